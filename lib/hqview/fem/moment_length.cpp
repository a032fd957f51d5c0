#include "hqview/fem/moment_length.h"

#include <array>
#include <cmath>
#include <limits>

#include "hqview/fem/fixed_chunks.h"
#include "hqview/fem/q1_element.h"

namespace hq {
namespace {

// Phase: one hex's integrals of 1, x - o and |x - o|^2 over its trilinear
// map by 2 x 2 x 2 Gauss-Legendre (weights 1), o a fixed point near the
// mesh. The map in monomial form x = a + b xi + c eta + d zeta + e xi eta +
// f eta zeta + g xi zeta + h xi eta zeta (from the corners' signs), so that
// position and Jacobian cost a few multiply-adds per point.
std::array<double, 5> hex_moments(const Q1Corners& p, const Vec3& o) {
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
  std::array<double, 5> s{};
  for (std::size_t k = 0; k < 8; ++k) {
    const double xi = g * kQ1CornerSigns[k][0], eta = g * kQ1CornerSigns[k][1], zeta = g * kQ1CornerSigns[k][2];
    const Vec3 x = m[0] + xi * m[1] + eta * m[2] + zeta * m[3] + (xi * eta) * m[4] + (eta * zeta) * m[5] +
                   (xi * zeta) * m[6] + (xi * eta * zeta) * m[7];
    const Vec3 dxi = m[1] + eta * m[4] + zeta * m[6] + (eta * zeta) * m[7];
    const Vec3 deta = m[2] + xi * m[4] + zeta * m[5] + (xi * zeta) * m[7];
    const Vec3 dzeta = m[3] + eta * m[5] + xi * m[6] + (xi * eta) * m[7];
    const double det = dot(dxi, cross(deta, dzeta));
    s[0] += det;
    s[1] += det * x.x;
    s[2] += det * x.y;
    s[3] += det * x.z;
    s[4] += det * dot(x, x);
  }
  return s;
}

}  // namespace

double moment_length(const HexMesh& mesh) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = mesh.hexes.size();
  if (n == 0) return nan;
  // o: the first hex's first corner, so that |x - o| is of the mesh's size
  // wherever the mesh sits (no cancellation 1e3 diagonals away).
  const Vec3 o = hex_corners(mesh, 0)[0];
  const std::array<double, 5> sum = detail::sum_fem_chunks<5>(n, [&](std::size_t lo, std::size_t hi) {
    std::array<double, 5> s{};
    for (std::size_t h = lo; h < hi; ++h) {
      const std::array<double, 5> e = hex_moments(hex_corners(mesh, static_cast<Index>(h)), o);
      for (std::size_t k = 0; k < 5; ++k) s[k] += e[k];
    }
    return s;
  });
  const double volume = sum[0];
  if (!(volume > 0)) return nan;
  // tr C = int |x - o|^2 dV / V - |c - o|^2.
  const Vec3 c{sum[1] / volume, sum[2] / volume, sum[3] / volume};
  const double trace = sum[4] / volume - dot(c, c);
  return trace > 0 ? std::sqrt(12.0 * trace) : nan;
}

}  // namespace hq
