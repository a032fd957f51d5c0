#include "hqview/quality/wedge_metrics.h"

#include <cmath>
#include <limits>

#include "hqview/core/cell_kinds.h"
#include "hqview/quality/quad_metrics.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/triangle_metrics.h"
#include "hqview/quality/verdict_support.h"

// Follows V_WedgeMetric.cpp of Verdict 1.4.5 (6-node wedges). Every formula
// below reads the corners in Verdict's order (c = wedge_to_verdict_order).

namespace hq {
namespace {

using namespace verdict_support;

constexpr std::array<CellMetricInfo, kNumWedgeMetrics> kInfo = {{
    {"volume", false},
    {"edge_ratio", false},
    {"max_aspect_frobenius", false},
    {"mean_aspect_frobenius", false},
    {"jacobian", false},
    {"distortion", false},
    {"max_stretch", false},
    {"scaled_jacobian", false},
    {"shape", false},
    {"condition", false},
    {"equiangle_skew", false},
}};

// Verdict's corner frames (Verdict order): corner i, then the corners of
// (vec1, vec2, vec3) with the Jacobian vec2 . (vec1 x vec3).
constexpr int kFrames[6][4] = {{0, 1, 3, 2}, {1, 2, 4, 0}, {2, 0, 5, 1}, {3, 0, 4, 5}, {4, 1, 5, 3}, {5, 3, 4, 2}};

double volume_of(const WedgeCorners& c) {
  const Vec3 q0 = {(c[0].x + c[1].x + c[3].x + c[4].x) / 4, (c[0].y + c[1].y + c[3].y + c[4].y) / 4,
                   (c[0].z + c[1].z + c[3].z + c[4].z) / 4};
  const Vec3 q1 = {(c[1].x + c[2].x + c[4].x + c[5].x) / 4, (c[1].y + c[2].y + c[4].y + c[5].y) / 4,
                   (c[1].z + c[2].z + c[4].z + c[5].z) / 4};
  const Vec3 q2 = {(c[2].x + c[0].x + c[3].x + c[5].x) / 4, (c[2].y + c[0].y + c[3].y + c[5].y) / 4,
                   (c[2].z + c[0].z + c[3].z + c[5].z) / 4};
  // Verdict's 11 tetrahedra through the quad-face centres.
  const TetCorners tets[11] = {{c[0], c[3], q0, q2}, {c[1], c[4], q1, q0},   {c[2], c[5], q2, q1}, {q0, q2, q1, c[0]},
                               {c[1], q0, q1, c[0]}, {c[2], c[1], q1, c[0]}, {c[2], q1, q2, c[0]}, {q0, q1, q2, c[3]},
                               {c[5], q2, q1, c[3]}, {c[4], c[5], q1, c[3]}, {c[4], q1, q0, c[3]}};
  double volume = 0.0;
  for (const auto& t : tets) volume += tet_volume(t);
  return volume;
}

double edge_ratio_of(const WedgeCorners& c) {
  const Vec3 e[9] = {c[1] - c[0], c[2] - c[1], c[0] - c[2], c[4] - c[3], c[5] - c[4],
                     c[3] - c[5], c[3] - c[0], c[4] - c[1], c[5] - c[2]};
  double max = squared_norm(e[0]), min = max;
  for (int i = 1; i < 9; ++i) {
    const double l2 = squared_norm(e[i]);
    if (max <= l2) max = l2;
    if (l2 <= min) min = l2;
  }
  const double edge_ratio = std::sqrt(max / min);
  if (std::isnan(edge_ratio)) return kDblMax;
  if (edge_ratio < 1.) return 1.;
  return std::fmin(edge_ratio, kDblMax);
}

// Verdict's six corner tets' aspect Frobenius.
std::array<double, 6> aspects(const WedgeCorners& c) {
  return {tet_aspect_frobenius({c[0], c[1], c[2], c[3]}), tet_aspect_frobenius({c[1], c[2], c[0], c[4]}),
          tet_aspect_frobenius({c[2], c[0], c[1], c[5]}), tet_aspect_frobenius({c[3], c[5], c[4], c[0]}),
          tet_aspect_frobenius({c[4], c[3], c[5], c[1]}), tet_aspect_frobenius({c[5], c[4], c[3], c[2]})};
}

double max_aspect_frobenius_of(const WedgeCorners& c) {
  const auto a = aspects(c);
  double largest = std::fmax(a[0], std::fmax(a[1], std::fmax(a[2], std::fmax(a[3], std::fmax(a[4], a[5])))));
  if (largest >= kDblMax) return kDblMax;
  largest /= 1.16477;
  return std::fmax(largest, 1.);
}

double mean_aspect_frobenius_of(const WedgeCorners& c) {
  const auto a = aspects(c);
  double mean = (a[0] + a[1] + a[2] + a[3] + a[4] + a[5]);
  if (mean >= kDblMax) return kDblMax;
  mean /= (6. * 1.16477);
  return std::fmax(mean, 1.);
}

double jacobian_of(const WedgeCorners& c) {
  double smallest = 0;
  for (int i = 0; i < 6; ++i) {
    const auto& f = kFrames[i];
    const Vec3 v1 = c[f[1]] - c[f[0]], v2 = c[f[2]] - c[f[0]], v3 = c[f[3]] - c[f[0]];
    const double j = dot(v2, cross(v1, v3));
    smallest = i == 0 ? j : std::fmin(j, smallest);
  }
  return clamp_signed(smallest);
}

double scaled_jacobian_of(const WedgeCorners& c) {
  double smallest = 0;
  for (int i = 0; i < 6; ++i) {
    const auto& f = kFrames[i];
    const Vec3 v1 = c[f[1]] - c[f[0]], v2 = c[f[2]] - c[f[0]], v3 = c[f[3]] - c[f[0]];
    const double lengths = std::sqrt(squared_norm(v1) * squared_norm(v2) * squared_norm(v3));
    const double j = dot(v2, cross(v1, v3)) / lengths;
    smallest = i == 0 ? j : std::fmin(j, smallest);
  }
  smallest *= 2 / kSqrt3;
  return clamp_signed(smallest);
}

double distortion_of(const WedgeCorners& c) {
  const double jacobian = jacobian_of(c);
  const double volume = volume_of(c);
  double distortion = kDblMax;
  if (std::fabs(volume) > 0.0) distortion = jacobian * 0.433013 / volume / 0.866025;
  if (std::isnan(distortion)) return kDblMax;
  if (distortion >= kDblMax) return kDblMax;
  if (distortion <= -kDblMax) return -kDblMax;
  return distortion;
}

double max_stretch_of(const WedgeCorners& c) {
  const double s1 = quad_stretch({c[0], c[1], c[4], c[3]});
  const double s2 = quad_stretch({c[1], c[2], c[5], c[4]});
  const double s3 = quad_stretch({c[2], c[0], c[3], c[5]});
  return clamp_signed(std::fmax(s1, std::fmax(s2, s3)));
}

double shape_of(const WedgeCorners& c) {
  const double size = char_size(c);
  double smallest = 1.0;
  for (const auto& f : kFrames) {
    const Vec3 v1 = (c[f[1]] - c[f[0]]) / size, v2 = (c[f[2]] - c[f[0]]) / size, v3 = (c[f[3]] - c[f[0]]) / size;
    const double j = dot(v2, cross(v1, v3));
    if (!(j > kDblMin)) return 0;
    const double normalised = j * 2.0 / kSqrt3;
    const double shape =
        3. * std::pow(normalised, 2.0 / 3.0) / (squared_norm(v1) + squared_norm(v2) + squared_norm(v3));
    smallest = std::fmin(shape, smallest);
  }
  if (smallest < kDblMin) return 0;
  return smallest;
}

double equiangle_skew_of(const WedgeCorners& c) {
  double skew = triangle_equiangle_skew({c[0], c[1], c[2]});
  for (double s : {triangle_equiangle_skew({c[3], c[4], c[5]}), quad_equiangle_skew({c[0], c[1], c[4], c[3]}),
                   quad_equiangle_skew({c[1], c[2], c[5], c[4]}), quad_equiangle_skew({c[2], c[0], c[3], c[5]})})
    skew = skew > s ? skew : s;
  return skew;
}

double metric_in_verdict_order(WedgeMetric m, const WedgeCorners& c) {
  using M = WedgeMetric;
  switch (m) {
    case M::volume:
      return volume_of(c);
    case M::edge_ratio:
      return edge_ratio_of(c);
    case M::max_aspect_frobenius:
    case M::condition:
      return max_aspect_frobenius_of(c);
    case M::mean_aspect_frobenius:
      return mean_aspect_frobenius_of(c);
    case M::jacobian:
      return jacobian_of(c);
    case M::distortion:
      return distortion_of(c);
    case M::max_stretch:
      return max_stretch_of(c);
    case M::scaled_jacobian:
      return scaled_jacobian_of(c);
    case M::shape:
      return shape_of(c);
    case M::equiangle_skew:
      return equiangle_skew_of(c);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

const CellMetricInfo& wedge_metric_info(WedgeMetric m) { return kInfo[static_cast<std::size_t>(m)]; }

std::optional<WedgeMetric> wedge_metric_from_name(std::string_view name) {
  for (int i = 0; i < kNumWedgeMetrics; ++i)
    if (kInfo[static_cast<std::size_t>(i)].name == name) return static_cast<WedgeMetric>(i);
  return std::nullopt;
}

WedgeCorners wedge_to_verdict_order(const WedgeCorners& vtk) {
  WedgeCorners c;
  for (int i = 0; i < 6; ++i) c[i] = vtk[kWedgeVtkToVerdict[i]];
  return c;
}

double wedge_metric(WedgeMetric m, const WedgeCorners& p, double /*average_volume*/) {
  return metric_in_verdict_order(m, wedge_to_verdict_order(p));
}

WedgeMetricValues wedge_metrics(const WedgeCorners& p, double /*average_volume*/) {
  const WedgeCorners c = wedge_to_verdict_order(p);
  WedgeMetricValues out;
  for (int m = 0; m < kNumWedgeMetrics; ++m)
    out[static_cast<std::size_t>(m)] = metric_in_verdict_order(static_cast<WedgeMetric>(m), c);
  return out;
}

}  // namespace hq
