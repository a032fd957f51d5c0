#pragma once
// Every Verdict 1.4.5 pyramid metric (verdict.h, V_PyramidMetric.cpp), as
// pure kernels on the 5 corners of one linear pyramid in VTK_PYRAMID order
// (= Verdict's: base 0-1-2-3 counter-clockwise seen from the apex 4;
// core/cell_kinds.h). Equal to Verdict 1.4.5 to 1e-12 relative on
// ../shared/data/verdict/cell_oracle_cases.json, its conventions kept
// (quirks.pyramid there):
//   - scaled_jacobian = sqrt(2) x the smallest scaled Jacobian of the tets
//     (0,1,2,4), (0,2,3,4), (0,1,3,4), (1,2,3,4), returned as 0 when that is
//     <= 0 (an inverted pyramid scores 0, never negative) and folded above 1
//     as 2 - x: an all-coincident pyramid gets -1.414e30; use
//     pyramid_validity() (cell_corner_jacobian.h) to tell inverted pyramids;
//   - jacobian stays signed; Verdict's ideal pyramid has equilateral
//     triangular faces (apex height = base edge / sqrt(2)).
// Units: volume and jacobian in model units cubed; the rest unitless.
// Never throws, never allocates.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "hqview/core/vec3.h"
#include "hqview/quality/cell_metric_info.h"

namespace hq {

// In verdict.h's order (the oracle's metrics_by_kind.pyramid).
enum class PyramidMetric : std::uint8_t {
  volume,
  jacobian,
  scaled_jacobian,
  shape,
  equiangle_skew,
};
inline constexpr int kNumPyramidMetrics = 5;

using PyramidCorners = std::array<Vec3, 5>;
using PyramidMetricValues = std::array<double, kNumPyramidMetrics>;

const CellMetricInfo& pyramid_metric_info(PyramidMetric m);
std::optional<PyramidMetric> pyramid_metric_from_name(std::string_view name);

// Every metric of one pyramid, in the enum's order. No pyramid metric of
// Verdict 1.4.5 is a size metric; `average_volume` is unused.
PyramidMetricValues pyramid_metrics(const PyramidCorners& p, double average_volume = 0);
double pyramid_metric(PyramidMetric m, const PyramidCorners& p, double average_volume = 0);

}  // namespace hq
