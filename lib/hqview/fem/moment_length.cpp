#include "hqview/fem/moment_length.h"

#include <array>
#include <cmath>
#include <limits>

#include "hqview/fem/fixed_chunks.h"
#include "hqview/fem/q1_element.h"

namespace hq {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The six distinct (i, j) of a symmetric 3 x 3 and the ten (i, j, k) of a
// symmetric 3 x 3 x 3, i <= j <= k.
constexpr std::array<std::array<int, 2>, 6> kPairs{{{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}}};
constexpr std::array<std::array<int, 3>, 10> kTriples{
    {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 0, 1}, {0, 0, 2}, {0, 1, 1}, {1, 1, 2}, {0, 2, 2}, {1, 2, 2}, {0, 1, 2}}};

// Phase: f(x - o, det J) at a hex's 2 x 2 x 2 Gauss-Legendre points (weights
// 1), o a fixed point near the mesh. The map in monomial form x = a + b xi +
// c eta + d zeta + e xi eta + f eta zeta + g xi zeta + h xi eta zeta (from
// the corners' signs), so that position and Jacobian cost a few
// multiply-adds per point.
template <class F>
void for_gauss_points(const Q1Corners& p, const Vec3& o, F&& f) {
  std::array<Vec3, 8> m{};  // a, b, c, d, e, f, g, h
  for (std::size_t i = 0; i < 8; ++i) {
    const double s0 = kQ1CornerSigns[i][0], s1 = kQ1CornerSigns[i][1], s2 = kQ1CornerSigns[i][2];
    const Vec3 q = 0.125 * (p[i] - o);
    m[0] = m[0] + q;
    m[1] = m[1] + s0 * q;
    m[2] = m[2] + s1 * q;
    m[3] = m[3] + s2 * q;
    m[4] = m[4] + (s0 * s1) * q;
    m[5] = m[5] + (s1 * s2) * q;
    m[6] = m[6] + (s0 * s2) * q;
    m[7] = m[7] + (s0 * s1 * s2) * q;
  }
  const double g = 1.0 / std::sqrt(3.0);
  for (std::size_t k = 0; k < 8; ++k) {
    const double xi = g * kQ1CornerSigns[k][0], eta = g * kQ1CornerSigns[k][1], zeta = g * kQ1CornerSigns[k][2];
    const Vec3 x = m[0] + xi * m[1] + eta * m[2] + zeta * m[3] + (xi * eta) * m[4] + (eta * zeta) * m[5] +
                   (xi * zeta) * m[6] + (xi * eta * zeta) * m[7];
    const Vec3 dxi = m[1] + eta * m[4] + zeta * m[6] + (eta * zeta) * m[7];
    const Vec3 deta = m[2] + xi * m[4] + zeta * m[5] + (xi * zeta) * m[7];
    const Vec3 dzeta = m[3] + eta * m[5] + xi * m[6] + (xi * eta) * m[7];
    f(x, dot(dxi, cross(deta, dzeta)));
  }
}

// Phase: the sums over the hexes of K integrals, f(x - o, det J, sums) per Gauss point.
template <std::size_t K, class F>
std::array<double, K> sum_over_hexes(const HexMesh& mesh, const Vec3& o, F&& f) {
  return detail::sum_fem_chunks<K>(mesh.hexes.size(), [&](std::size_t lo, std::size_t hi) {
    std::array<double, K> s{};
    for (std::size_t h = lo; h < hi; ++h)
      for_gauss_points(hex_corners(mesh, static_cast<Index>(h)), o, [&](const Vec3& x, double det) { f(x, det, s); });
    return s;
  });
}

}  // namespace

VolumeMoments volume_moments(const HexMesh& mesh) {
  VolumeMoments m;
  // o: the first hex's first corner, so that |x - o| is of the mesh's size
  // wherever the mesh sits (no cancellation 1e3 diagonals away). No hexes:
  // no sums, volume 0.
  const Vec3 o = mesh.hexes.empty() ? Vec3{} : hex_corners(mesh, 0)[0];
  const std::array<double, 4> first = sum_over_hexes<4>(mesh, o, [](const Vec3& x, double det, auto& s) {
    s[0] += det;
    for (int i = 0; i < 3; ++i) s[static_cast<std::size_t>(1 + i)] += det * x[i];
  });
  m.volume = first[0];
  if (!(m.volume > 0)) {
    m.centroid = {kNaN, kNaN, kNaN};
    for (auto& row : m.second) row.fill(kNaN);
    for (auto& plane : m.third)
      for (auto& row : plane) row.fill(kNaN);
    return m;
  }
  const Vec3 offset{first[1] / m.volume, first[2] / m.volume, first[3] / m.volume};
  m.centroid = o + offset;
  // About the centroid: x - c = (x - o) - offset.
  const std::array<double, 16> central = sum_over_hexes<16>(mesh, o, [&](const Vec3& x, double det, auto& s) {
    const Vec3 y = x - offset;
    for (std::size_t p = 0; p < kPairs.size(); ++p) s[p] += det * y[kPairs[p][0]] * y[kPairs[p][1]];
    for (std::size_t t = 0; t < kTriples.size(); ++t)
      s[6 + t] += det * y[kTriples[t][0]] * y[kTriples[t][1]] * y[kTriples[t][2]];
  });
  for (std::size_t p = 0; p < kPairs.size(); ++p) {
    const auto i = static_cast<std::size_t>(kPairs[p][0]), j = static_cast<std::size_t>(kPairs[p][1]);
    m.second[i][j] = m.second[j][i] = central[p] / m.volume;
  }
  for (std::size_t t = 0; t < kTriples.size(); ++t) {
    const auto i = static_cast<std::size_t>(kTriples[t][0]), j = static_cast<std::size_t>(kTriples[t][1]),
               k = static_cast<std::size_t>(kTriples[t][2]);
    const double v = central[6 + t] / m.volume;
    m.third[i][j][k] = m.third[i][k][j] = m.third[j][i][k] = m.third[j][k][i] = m.third[k][i][j] = m.third[k][j][i] = v;
  }
  return m;
}

double third_moment_along(const VolumeMoments& m, const Vec3& e) {
  double sum = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        sum += m.third[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)][static_cast<std::size_t>(k)] * e[i] *
               e[j] * e[k];
  return sum;
}

double moment_length(const VolumeMoments& m) {
  if (!(m.volume > 0)) return kNaN;
  const double trace = m.second[0][0] + m.second[1][1] + m.second[2][2];
  return trace > 0 ? std::sqrt(12.0 * trace) : kNaN;
}

}  // namespace hq
