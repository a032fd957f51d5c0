#pragma once
// Every Verdict hexahedron metric (ALGORITHMS.md §2), as pure kernels on the
// 8 corners of one hex in VTK_HEXAHEDRON order (core/hex_topology.h).
//
// Each kernel follows Verdict 1.4.5 (sandialabs/verdict, V_HexMetric.cpp,
// V_QuadMetric.cpp for the face angles, V_GaussIntegration.cpp for
// distortion; Knupp, SAND2007-1751) and agrees with it to 1e-12 relative on
// the oracle cases of ../shared/data/verdict, sentinels included:
//   +1e30 (kVerdictDegenerate) where Verdict reports a degenerate element,
//   -1e30 for nodal_jacobian_ratio of a fully inverted or collapsed hex.
// Verdict quirks kept on purpose (README "Metric definitions"):
//   - edge_ratio: longest of edges 0-5 over the shortest of all 12;
//   - size metrics (relative_size_squared, shape_and_size, shear_and_size)
//     compare with `average_volume`, the mesh's mean hex_volume;
//   - distortion and nodal_jacobian_ratio use raw coordinates (they lose
//     digits far from the origin, as Verdict does); the other metrics are
//     computed from coordinate differences or around the hex centre.
//
// The kernels never throw and never allocate. Units: lengths in model units,
// volume and jacobian in model units cubed, dimension in model units, the
// angles behind equiangle_skew in degrees; every other metric is unitless.

#include <array>
#include <bitset>
#include <cstdint>
#include <optional>
#include <string_view>

#include "hqview/core/vec3.h"
#include "hqview/quality/corner_jacobian.h"

namespace hq {

// In Verdict's order (ALGORITHMS.md §2); also the order of report.json
// `quality.metrics` and of the metric columns of data/cells.csv.
enum class HexMetric : std::uint8_t {
  edge_ratio,
  max_edge_ratio,
  max_aspect_frobenius,
  med_aspect_frobenius,
  skew,
  taper,
  volume,
  stretch,
  diagonal,
  dimension,
  oddy,
  condition,
  jacobian,
  scaled_jacobian,
  shear,
  shape,
  relative_size_squared,
  shape_and_size,
  shear_and_size,
  distortion,
  nodal_jacobian_ratio,
  equiangle_skew,
};
inline constexpr int kNumHexMetrics = 22;

struct HexMetricInfo {
  std::string_view name;  // Verdict's name, snake_case
  // Verdict's acceptable range (Verdict manual, SAND2007-2853; Cubit for
  // nodal_jacobian_ratio and equiangle_skew); +-infinity where unbounded.
  double acceptable_min;
  double acceptable_max;
  bool uses_average_volume;  // a size metric
};

const HexMetricInfo& hex_metric_info(HexMetric m);
inline std::string_view hex_metric_name(HexMetric m) { return hex_metric_info(m).name; }
// The metric called `name` (Verdict's snake_case name), or nullopt.
std::optional<HexMetric> hex_metric_from_name(std::string_view name);

// A set of metrics, bit i = HexMetric i.
using HexMetricSet = std::bitset<kNumHexMetrics>;
inline HexMetricSet all_hex_metrics() { return HexMetricSet().set(); }
inline bool contains(const HexMetricSet& s, HexMetric m) { return s.test(static_cast<std::size_t>(m)); }
inline void insert(HexMetricSet& s, HexMetric m) { s.set(static_cast<std::size_t>(m)); }

using HexCorners = std::array<Vec3, 8>;
using HexMetricValues = std::array<double, kNumHexMetrics>;

// All metrics in `which` for one hex; entries outside `which` are NaN.
// Shares the corner frames, determinants and lengths between metrics: this
// is the kernel the mesh-wide field uses. Equal to the single-metric kernels
// below.
HexMetricValues hex_metrics(const HexCorners& p, double average_volume, const HexMetricSet& which = all_hex_metrics());

// One kernel per metric (the reference for tests and for one-metric callers).
double hex_edge_ratio(const HexCorners& p);
double hex_max_edge_ratio(const HexCorners& p);
double hex_max_aspect_frobenius(const HexCorners& p);
double hex_med_aspect_frobenius(const HexCorners& p);
double hex_skew(const HexCorners& p);
double hex_taper(const HexCorners& p);
double hex_volume(const HexCorners& p);  // 24 tetrahedra through the face and cell centres
double hex_stretch(const HexCorners& p);
double hex_diagonal(const HexCorners& p);
double hex_dimension(const HexCorners& p);
double hex_oddy(const HexCorners& p);
double hex_condition(const HexCorners& p);  // = hex_max_aspect_frobenius
double hex_jacobian(const HexCorners& p);
// hex_scaled_jacobian(const HexCorners&) is in corner_jacobian.h.
double hex_shear(const HexCorners& p);
double hex_shape(const HexCorners& p);
double hex_relative_size_squared(const HexCorners& p, double average_volume);
double hex_shape_and_size(const HexCorners& p, double average_volume);
double hex_shear_and_size(const HexCorners& p, double average_volume);
double hex_distortion(const HexCorners& p);
double hex_nodal_jacobian_ratio(const HexCorners& p);
double hex_equiangle_skew(const HexCorners& p);

// One metric by its enum (dispatches to the kernels above).
double hex_metric(HexMetric m, const HexCorners& p, double average_volume);

// True for Verdict's sentinels: |v| >= 1e30 (degenerate element).
inline bool is_verdict_sentinel(double v) { return v >= kVerdictDegenerate || v <= -kVerdictDegenerate; }

}  // namespace hq
