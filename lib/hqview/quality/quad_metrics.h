#pragma once
// Every Verdict 1.4.5 quadrilateral metric (verdict.h, V_QuadMetric.cpp), as
// pure kernels on the 4 corners of one linear quad in 3-D (VTK_QUAD order,
// core/cell_kinds.h). Equal to Verdict 1.4.5 to 1e-12 relative on
// ../shared/data/verdict/cell_oracle_cases.json, its conventions kept
// (quirks.quad there):
//   - no orientation of its own: Verdict measures signed corner areas against
//     the quad's own centre normal ((e0 - e2) x (e1 - e3), e_i = P(i+1) - P(i)),
//     so a reversed quad scores the same; a concave or bow-tie quad has a
//     negative corner;
//   - condition is 1e30 (and shear, shape and their size products 0) as soon
//     as one corner's signed area is below 2.2e-15 after scaling;
//   - P3 == P2 exactly makes minimum_angle, maximum_angle, condition,
//     jacobian, scaled_jacobian (and so shear) those of triangle (P0,P1,P2);
//   - equiangle_skew exceeds 1 and maximum_angle reports reflex angles
//     (360 - largest) when a corner is reflex;
//   - warpage is a cosine cubed: 1 when planar, 2.2e-15 for a degenerate quad.
// Size metrics (relative_size_squared, shape_and_size, shear_and_size)
// compare the area with `average_area`, the mean quad area of the mesh.
// Units: area and jacobian in model units squared, angles in degrees; the
// rest unitless. The kernels never throw and never allocate.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "hqview/core/vec3.h"
#include "hqview/quality/cell_metric_info.h"

namespace hq {

// In verdict.h's order (the oracle's metrics_by_kind.quad).
enum class QuadMetric : std::uint8_t {
  edge_ratio,
  max_edge_ratio,
  aspect_ratio,
  radius_ratio,
  med_aspect_frobenius,
  max_aspect_frobenius,
  skew,
  taper,
  warpage,
  area,
  stretch,
  minimum_angle,
  maximum_angle,
  oddy,
  condition,
  jacobian,
  scaled_jacobian,
  shear,
  shape,
  distortion,
  equiangle_skew,
  relative_size_squared,
  shape_and_size,
  shear_and_size,
};
inline constexpr int kNumQuadMetrics = 24;

using QuadCorners = std::array<Vec3, 4>;
using QuadMetricValues = std::array<double, kNumQuadMetrics>;

const CellMetricInfo& quad_metric_info(QuadMetric m);
std::optional<QuadMetric> quad_metric_from_name(std::string_view name);

// Every metric of one quad, in the enum's order.
QuadMetricValues quad_metrics(const QuadCorners& p, double average_area);
// One metric by its enum.
double quad_metric(QuadMetric m, const QuadCorners& p, double average_area);
// out[j] = quad_metric(metrics[j], p, average_area), bit for bit, the pieces
// the metrics share (edges, size, corner areas, angles) computed once.
void quad_metric_list(std::span<const QuadMetric> metrics, const QuadCorners& p, double average_area,
                      std::span<double> out);

// Verdict's signed corner areas: (e(i-1) x e(i)) . n at corner i, n the unit
// centre normal described above (0 when the quad has no centre normal).
std::array<double, 4> quad_signed_corner_areas(const QuadCorners& p);

// The kernels other kinds reuse (a wedge's and a pyramid's quad faces).
double quad_stretch(const QuadCorners& p);
double quad_shape(const QuadCorners& p);
double quad_equiangle_skew(const QuadCorners& p);

}  // namespace hq
