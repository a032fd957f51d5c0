#pragma once
// Which metrics say where the simulation is bad: Spearman's rank correlation
// over the hexes between the Poisson check's normalised error density and
// each computed metric (Gao et al., "Evaluating Hex-mesh Quality Metrics via
// Correlation Analysis", CGF 36(5), 2017, correlate across meshes; this is
// the per-mesh form). Ranks are averaged over ties; hexes where either value
// is NaN or a Verdict sentinel (|v| >= 1e30) are left out; rho is NaN (null
// in report.json) when fewer than 3 hexes remain or either side is constant.

#include <span>
#include <string>
#include <vector>

#include "hqview/fem/fem_element_field.h"
#include "hqview/quality/hex_metric_field.h"

namespace hq {

// Spearman's rho of the pairs (x_i, y_i), and how many pairs entered it.
struct RankCorrelation {
  double rho = 0;
  std::int64_t count = 0;
};
RankCorrelation spearman_correlation(std::span<const double> x, std::span<const double> y);

struct MetricCorrelation {
  std::string metric;  // a Verdict name, or fem_kappa / fem_lambda_max / fem_det_j_min
  RankCorrelation correlation;
};

// The computed Verdict metrics in HexMetric order, then the element
// conditioning's kappa, lambda_max and det_j_min; parallel over metrics.
std::vector<MetricCorrelation> correlate_metrics(std::span<const double> error_density, const HexMetricField& metrics,
                                                 const FemElementField& elements);

}  // namespace hq
