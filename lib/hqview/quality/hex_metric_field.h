#pragma once
// Every selected Verdict hex metric for every hex of a mesh (parallel over
// hexes, identical results for any thread count: each value is written by
// one task, the mean volume is summed sequentially in id order).

#include <array>
#include <vector>

#include "hqview/core/progress.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/quality/hex_metrics.h"

namespace hq {

struct HexMetricField {
  // The metrics that have values; scaled_jacobian always (the headline and
  // the inverted count need it).
  HexMetricSet computed;
  // Mean Verdict hex_volume over all hexes (inverted ones count negative, as
  // in VTK's vtkMeshQuality): the reference of the size metrics. 0 when no
  // size metric or volume was asked for.
  double average_volume = 0;
  // values[m][h]: metric m of hex h, Verdict's sentinels (+-1e30) kept;
  // empty for a metric not computed.
  std::array<std::vector<double>, kNumHexMetrics> values;

  const std::vector<double>& of(HexMetric m) const { return values[static_cast<std::size_t>(m)]; }
};

// Computes the metrics in `which` (plus scaled_jacobian) for every hex;
// `reporting`: whether it draws the progress bar (progress.h).
HexMetricField compute_hex_metrics(const HexMesh& mesh, HexMetricSet which = all_hex_metrics(),
                                   progress::Reporting reporting = progress::Reporting::report);

}  // namespace hq
