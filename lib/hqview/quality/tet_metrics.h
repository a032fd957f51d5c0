#pragma once
// Every Verdict 1.4.5 tetrahedron metric but timestep (verdict.h,
// V_TetMetric.cpp), as pure kernels on the 4 corners of one linear tet in
// VTK_TETRA order (= Verdict's: (P1-P0) x (P2-P0) . (P3-P0) > 0 when valid;
// core/cell_kinds.h). Equal to Verdict 1.4.5 to 1e-12 relative on
// ../shared/data/verdict/cell_oracle_cases.json, its conventions for
// degenerate and inverted tets kept (quirks.tet there):
//   - an inverted tet keeps its sign in volume, jacobian, scaled_jacobian,
//     inradius, mean_ratio, normalized_inradius, collapse_ratio and
//     condition; shape, relative_size_squared and shape_and_size are 0;
//     squish_index exceeds 1;
//   - scaled_jacobian is 1e30 when every edge product is below 2.2e-15
//     (all corners at one point), 0 for a flat tet; minimum_angle is 1e30
//     for a flat or degenerate tet; inradius of an all-coincident tet is NaN;
//   - distortion is 1 for every linear tet;
//   - relative_size_squared and shape_and_size compare the weighted mean
//     volume with the absolute 2.2e-15, so a mesh whose mean tet volume is
//     below ~2e-15 scores 0 (VTK 9.1 does not).
// Size metrics compare with `average_volume`, the mean tet volume of the mesh.
// Units: volume and jacobian in model units cubed, inradius in model units,
// angles in degrees; the rest unitless. Never throws, never allocates.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "hqview/core/vec3.h"
#include "hqview/quality/cell_metric_info.h"

namespace hq {

// In verdict.h's order (the oracle's metrics_by_kind.tet, without timestep).
enum class TetMetric : std::uint8_t {
  inradius,
  edge_ratio,
  radius_ratio,
  aspect_ratio,
  aspect_gamma,
  aspect_frobenius,
  minimum_angle,
  collapse_ratio,
  volume,
  condition,
  jacobian,
  scaled_jacobian,
  mean_ratio,
  normalized_inradius,
  shape,
  distortion,
  equivolume_skew,
  squish_index,
  equiangle_skew,
  relative_size_squared,
  shape_and_size,
};
inline constexpr int kNumTetMetrics = 21;

using TetCorners = std::array<Vec3, 4>;
using TetMetricValues = std::array<double, kNumTetMetrics>;

const CellMetricInfo& tet_metric_info(TetMetric m);
std::optional<TetMetric> tet_metric_from_name(std::string_view name);

// The block-wide part of the size metrics (relative_size_squared,
// shape_and_size): the mean tet volume and the volume of Verdict's regular
// weight tet of that volume (a cube root), computed once per block.
struct TetSizeReference {
  double average_volume = 0;
  double regular_volume = 0;
};
TetSizeReference tet_size_reference(double average_volume);

// The metrics listed (any order) of every tet of `tets`: out[j][i] is
// tet_metric(metrics[j], tets[i], reference.average_volume), bit for bit,
// the tet's size computed once for all its metrics, a few tets
// at a time, one per SIMD lane (the same IEEE operations in every lane, libm
// called lane by lane). out.size() == metrics.size(), each out[j] with room
// for tets.size() values.
void tet_metric_list_many(std::span<const TetMetric> metrics, std::span<const TetCorners> tets,
                          const TetSizeReference& reference, std::span<double* const> out);

// Every metric of one tet, in the enum's order.
TetMetricValues tet_metrics(const TetCorners& p, double average_volume);
// One metric by its enum.
double tet_metric(TetMetric m, const TetCorners& p, double average_volume);

// The kernels other kinds reuse (the wedge's corner tets, the pyramid's
// split tets).
double tet_volume(const TetCorners& p);
double tet_jacobian(const TetCorners& p);
double tet_scaled_jacobian(const TetCorners& p);
double tet_aspect_frobenius(const TetCorners& p);

}  // namespace hq
