#include "hqview/quality/pyramid_metrics.h"

#include <cmath>
#include <limits>

#include "hqview/quality/quad_metrics.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/triangle_metrics.h"
#include "hqview/quality/verdict_support.h"

// Follows V_PyramidMetric.cpp of Verdict 1.4.5 (5-node pyramids).

namespace hq {
namespace {

using namespace verdict_support;

constexpr std::array<CellMetricInfo, kNumPyramidMetrics> kInfo = {{
    {"volume", false},
    {"jacobian", false},
    {"scaled_jacobian", false},
    {"shape", false},
    {"equiangle_skew", false},
}};

// Verdict's make_pyramid_tets: the base split both ways, each half with the apex.
std::array<TetCorners, 4> split_tets(const PyramidCorners& p) {
  return {{{p[0], p[1], p[2], p[4]}, {p[0], p[2], p[3], p[4]}, {p[0], p[1], p[3], p[4]}, {p[1], p[2], p[3], p[4]}}};
}

double volume_of(const PyramidCorners& p) {
  const Vec3 centre = {(p[0].x + p[1].x + p[2].x + p[3].x) / 4, (p[0].y + p[1].y + p[2].y + p[3].y) / 4,
                       (p[0].z + p[1].z + p[2].z + p[3].z) / 4};
  double volume = 0.0;
  for (int i = 0; i < 4; ++i) volume += tet_volume({p[i], p[(i + 1) % 4], centre, p[4]});
  return volume;
}

double jacobian_of(const PyramidCorners& p) {
  const auto t = split_tets(p);
  const double j1 = tet_jacobian(t[0]), j2 = tet_jacobian(t[1]), j3 = tet_jacobian(t[2]), j4 = tet_jacobian(t[3]);
  const double p1 = j1 < j2 ? j1 : j2;
  const double p2 = j3 < j4 ? j3 : j4;
  return p1 < p2 ? p1 : p2;
}

double scaled_jacobian_of(const PyramidCorners& p) {
  const auto t = split_tets(p);
  const double smallest =
      std::fmin(tet_scaled_jacobian(t[0]),
                std::fmin(tet_scaled_jacobian(t[1]), std::fmin(tet_scaled_jacobian(t[2]), tet_scaled_jacobian(t[3]))));
  if (smallest <= 0.0) return 0.0;
  const double j = smallest * 2.0 / kSqrt2;
  return j < 1.0 ? j : 1.0 - (j - 1.0);
}

// Verdict's largest_pyramid_edge, with its quirk: it starts from the
// SHORTER of the first two base edges.
double largest_edge(const PyramidCorners& p) {
  const double l[8] = {squared_norm(p[1] - p[0]), squared_norm(p[2] - p[1]), squared_norm(p[3] - p[2]),
                       squared_norm(p[0] - p[3]), squared_norm(p[4] - p[0]), squared_norm(p[4] - p[1]),
                       squared_norm(p[4] - p[2]), squared_norm(p[4] - p[3])};
  double max = std::fmin(l[0], l[1]);
  for (int i = 2; i < 8; ++i) max = std::fmax(max, l[i]);
  return std::sqrt(max);
}

double shape_of(const PyramidCorners& p) {
  const double base_shape = quad_shape({p[0], p[1], p[2], p[3]});
  if (base_shape == 0.0) return 0.0;
  // Height of the apex over the base centroid along the normal at corner 0.
  const Vec3 centroid = (p[0] + p[1] + p[2] + p[3]) / 4.0;
  const Vec3 normal = cross(p[1] - p[0], p[3] - p[0]);
  const Vec3 to_apex = p[4] - centroid;
  double distance = dot(to_apex, normal) / norm(normal);
  const double cos_angle = distance / norm(to_apex);
  if (distance <= 0 || cos_angle <= 0.0) return 0.0;
  const double ideal = largest_edge(p) * (kSqrt2 / 2.0);
  distance = distance < ideal ? distance / ideal : ideal / distance;
  return base_shape * cos_angle * distance;
}

double equiangle_skew_of(const PyramidCorners& p) {
  double skew = quad_equiangle_skew({p[0], p[1], p[2], p[3]});
  for (int i = 0; i < 4; ++i) {
    const double s = triangle_equiangle_skew({p[i], p[(i + 1) % 4], p[4]});
    skew = skew > s ? skew : s;
  }
  return skew;
}

}  // namespace

const CellMetricInfo& pyramid_metric_info(PyramidMetric m) { return kInfo[static_cast<std::size_t>(m)]; }

std::optional<PyramidMetric> pyramid_metric_from_name(std::string_view name) {
  for (int i = 0; i < kNumPyramidMetrics; ++i)
    if (kInfo[static_cast<std::size_t>(i)].name == name) return static_cast<PyramidMetric>(i);
  return std::nullopt;
}

double pyramid_metric(PyramidMetric m, const PyramidCorners& p, double /*average_volume*/) {
  using M = PyramidMetric;
  switch (m) {
    case M::volume:
      return volume_of(p);
    case M::jacobian:
      return jacobian_of(p);
    case M::scaled_jacobian:
      return scaled_jacobian_of(p);
    case M::shape:
      return shape_of(p);
    case M::equiangle_skew:
      return equiangle_skew_of(p);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

PyramidMetricValues pyramid_metrics(const PyramidCorners& p, double average_volume) {
  PyramidMetricValues out;
  for (int m = 0; m < kNumPyramidMetrics; ++m)
    out[static_cast<std::size_t>(m)] = pyramid_metric(static_cast<PyramidMetric>(m), p, average_volume);
  return out;
}

}  // namespace hq
