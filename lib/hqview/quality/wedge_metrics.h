#pragma once
// Every Verdict 1.4.5 wedge (triangular prism) metric (verdict.h,
// V_WedgeMetric.cpp), as pure kernels on the 6 corners of one linear wedge
// in VTK_WEDGE order (core/cell_kinds.h: the right-hand normal of (0,1,2)
// points AWAY from (3,4,5)). Verdict wants the other order (Exodus/Gmsh:
// towards); the kernels permute with kWedgeVtkToVerdict before Verdict's
// formulas, so a valid VTK wedge has positive volume and scaled Jacobian 1
// when ideal. Equal to Verdict 1.4.5 on the permuted corners to 1e-12
// relative on ../shared/data/verdict/cell_oracle_cases.json, its conventions
// kept (quirks.wedge there):
//   - edge_ratio, max/mean_aspect_frobenius, condition, max_stretch and
//     equiangle_skew ignore orientation (an inverted prism has condition 1);
//   - a tangled wedge can have volume 0 and distortion 1e30; a zero-height or
//     all-coincident wedge has scaled_jacobian -1e30;
//   - distortion of the ideal prism is 1.0000011547 (Verdict's 6-digit
//     constants).
// Units: volume and jacobian in model units cubed; the rest unitless.
// Never throws, never allocates.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "hqview/core/vec3.h"
#include "hqview/quality/cell_metric_info.h"

namespace hq {

// In verdict.h's order (the oracle's metrics_by_kind.wedge).
enum class WedgeMetric : std::uint8_t {
  volume,
  edge_ratio,
  max_aspect_frobenius,
  mean_aspect_frobenius,
  jacobian,
  distortion,
  max_stretch,
  scaled_jacobian,
  shape,
  condition,
  equiangle_skew,
};
inline constexpr int kNumWedgeMetrics = 11;

using WedgeCorners = std::array<Vec3, 6>;  // VTK order
using WedgeMetricValues = std::array<double, kNumWedgeMetrics>;

const CellMetricInfo& wedge_metric_info(WedgeMetric m);
std::optional<WedgeMetric> wedge_metric_from_name(std::string_view name);

// Every metric of one wedge given in VTK order, in the enum's order. No
// wedge metric of Verdict 1.4.5 is a size metric; `average_volume` is
// accepted for symmetry with the other kinds and unused.
WedgeMetricValues wedge_metrics(const WedgeCorners& p, double average_volume = 0);
// One metric by its enum (VTK order).
double wedge_metric(WedgeMetric m, const WedgeCorners& p, double average_volume = 0);

// The corners in Verdict's (Exodus/Gmsh) order.
WedgeCorners wedge_to_verdict_order(const WedgeCorners& vtk);

}  // namespace hq
