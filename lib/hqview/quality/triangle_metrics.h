#pragma once
// Every Verdict 1.4.5 triangle metric (verdict.h, V_TriMetric.cpp), as pure
// kernels on the 3 corners of one linear triangle in 3-D (VTK_TRIANGLE order,
// core/cell_kinds.h). Equal to Verdict 1.4.5 to 1e-12 relative on
// ../shared/data/verdict/cell_oracle_cases.json, its conventions for
// degenerate triangles included (quirks.tri there):
//   - no orientation: a reversed triangle scores the same;
//   - shape = 1 / condition, so a degenerate triangle has shape 1e-30;
//   - distortion is 1 for every linear triangle;
//   - normalized_inradius is 0 for three collinear distinct corners but 1e30
//     when an edge has zero length.
// Size metrics (relative_size_squared, shape_and_size) compare the area with
// `average_area`, the mean triangle area of the mesh.
// Units: area in model units squared, angles in degrees; the rest unitless.
// The kernels never throw and never allocate.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "hqview/core/vec3.h"
#include "hqview/quality/cell_metric_info.h"

namespace hq {

// In verdict.h's order (the oracle's metrics_by_kind.tri).
enum class TriangleMetric : std::uint8_t {
  edge_ratio,
  aspect_ratio,
  radius_ratio,
  aspect_frobenius,
  area,
  minimum_angle,
  maximum_angle,
  condition,
  scaled_jacobian,
  shape,
  distortion,
  equiangle_skew,
  normalized_inradius,
  relative_size_squared,
  shape_and_size,
};
inline constexpr int kNumTriangleMetrics = 15;

using TriangleCorners = std::array<Vec3, 3>;
using TriangleMetricValues = std::array<double, kNumTriangleMetrics>;

const CellMetricInfo& triangle_metric_info(TriangleMetric m);
std::optional<TriangleMetric> triangle_metric_from_name(std::string_view name);

// Every metric of one triangle, in the enum's order.
TriangleMetricValues triangle_metrics(const TriangleCorners& p, double average_area);
// One metric by its enum.
double triangle_metric(TriangleMetric m, const TriangleCorners& p, double average_area);

// The kernels other kinds reuse (a wedge's and a pyramid's faces, a
// collapsed quad).
double triangle_area(const TriangleCorners& p);
double triangle_minimum_angle(const TriangleCorners& p);
double triangle_maximum_angle(const TriangleCorners& p);
double triangle_equiangle_skew(const TriangleCorners& p);
double triangle_condition(const TriangleCorners& p);
double triangle_scaled_jacobian(const TriangleCorners& p);

}  // namespace hq
