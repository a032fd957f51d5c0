#pragma once
// Which metrics say where the simulation is bad: Spearman's rank correlation
// over the hexes between the Poisson check's normalised error density and
// each computed metric (Gao et al., "Evaluating Hex-mesh Quality Metrics via
// Correlation Analysis", CGF 36(5), 2017, correlate across meshes; this is
// the per-mesh form). Ranks are averaged over ties; hexes where either value
// is NaN or a Verdict sentinel (|v| >= 1e30) are left out; rho is NaN (null
// in report.json) when fewer than 3 hexes remain or either side is constant.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
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

// Spearman's rho with its two-sided p-value under the null of no
// association: exact (every arrangement of the y ranks against the x ranks,
// ties kept) for count <= kExactSpearmanMaxCount; above, the t
// approximation t = rho sqrt((n - 2) / (1 - rho^2)) with n - 2 degrees of
// freedom (Zar, "Significance testing of the Spearman rank correlation
// coefficient", JASA 67, 1972: close to the exact value from n of about 10).
// p is NaN when rho is.
inline constexpr int kExactSpearmanMaxCount = 8;
struct RankCorrelationTest {
  RankCorrelation correlation;
  double p_value = 0;
};
RankCorrelationTest spearman_test(std::span<const double> x, std::span<const double> y);

// Benjamini-Hochberg adjusted p-values (q-values; Benjamini and Hochberg,
// JRSS B 57, 1995) of a family of tests: with the m finite p sorted
// ascending, q_(i) = min over j >= i of m p_(j) / j, at most 1; NaN stays
// NaN and does not count in m. A row with q <= 0.05 is a discovery at a false
// discovery rate of 5 % over the family.
std::vector<double> benjamini_hochberg(std::span<const double> p);

// Which way a metric's value is better (+1 higher, -1 lower, 0 neither: a
// size), from Verdict's acceptable ranges (hex_metric_info): a range ending at
// 1 (scaled Jacobian, shape, stretch, diagonal, distortion, the size-weighted
// shape metrics, nodal_jacobian_ratio) has its ideal there, higher is better;
// an unbounded one (volume, dimension, jacobian) is a size, neither; every
// other (edge and aspect ratios, skews, taper, oddy, condition) is lower is
// better. fem_kappa: lower; fem_lambda_max and fem_det_j_min: neither (they
// scale with the size: across meshes they rank resolution). 0 for other names.
int metric_direction(std::string_view metric);

// A size metric: one with no better direction (metric_direction 0: volume,
// dimension, jacobian, fem_lambda_max, fem_det_j_min) or one that Verdict
// builds from the hex's size relative to the mesh's mean
// (relative_size_squared = min(D, 1/D)^2 with D = volume / mean volume, and
// the size-weighted shape_and_size and shear_and_size). Their correlation with
// the error density mixes the mesh's resolution into it: the charts tag them.
bool metric_is_size(std::string_view metric);

// The metric-direction normalisation of a rho against the error density:
// agreement = -direction * rho (direction = metric_direction), so that
// agreement > 0 says "the metric's worse side has the higher error" (a
// higher-is-better metric with rho < 0, a lower-is-better one with rho > 0)
// and its size how strongly. NaN when the metric has no direction or rho is
// NaN. The correlation chart colours and sorts by it.
double metric_agreement(int direction, double rho);

// A two-sided confidence interval for Spearman's rho over n pairs: Fisher's
// z = atanh(rho) with the standard error of Bonett and Wright ("Sample size
// requirements for estimating Pearson, Kendall and Spearman correlations",
// Psychometrika 65, 2000) sqrt((1 + rho^2 / 2) / (n - 3)); the interval
// tanh(z -+ z_(1 - alpha/2) se) (z_0.975 = 1.959963984540054). It treats the
// n pairs as independent: over the hexes of one mesh, whose neighbours are
// correlated, it is too narrow (docs/analysis.md). NaN ends for n < 4 or a
// NaN rho; rho = +-1 gives [rho, rho].
struct RankCorrelationInterval {
  double lo = 0, hi = 0;
};
inline constexpr double kCorrelationIntervalZ = 1.959963984540054;  // 95 %
// z: the normal quantile of the level (kCorrelationIntervalZ: 95 %, one interval).
RankCorrelationInterval spearman_interval(double rho, std::int64_t count, double z = kCorrelationIntervalZ);

// The normal quantile z_(1 - 0.05 / (2 m)) that makes m intervals
// simultaneous at 95 % (Bonferroni: each at level 1 - 0.05 / m; any one
// misses its rho with probability at most 0.05 / m, so all hold together
// with probability at least 0.95). m <= 1: kCorrelationIntervalZ.
double bonferroni_interval_z(int m);

struct MetricCorrelation {
  std::string metric;  // a Verdict name, or fem_kappa / fem_lambda_max / fem_det_j_min
  RankCorrelation correlation;
  // The partial Spearman correlation given the hex size (partial_rank_correlation
  // with z = the size's ranks, over the hexes where all three are usable):
  // what the metric says about the density beyond what the size says. NaN
  // without sizes, or when the metric or the density ranks exactly as the size.
  double rho_given_size = 0;
  // The 95 % interval of correlation.rho (spearman_interval over its count).
  RankCorrelationInterval interval;
  // The interval the verdicts (agrees / disagrees / undecided) rest on:
  // simultaneous 95 % over the verdict family, the metrics with a better
  // direction and a rho (bonferroni_interval_z of their number), so that
  // deciding many signs at once does not find one by chance.
  RankCorrelationInterval adjusted_interval;
};

// The number of metrics in the verdict family of correlate_metrics' output:
// those with a better direction (metric_direction != 0) and a finite rho.
int verdict_family_size(std::span<const MetricCorrelation> correlations);

// The partial correlation of x and y given z from the three pairwise
// correlations: (r_xy - r_xz r_yz) / sqrt((1 - r_xz^2)(1 - r_yz^2)) (on
// ranks: the partial Spearman correlation; Conover, "Practical
// Nonparametric Statistics", 3rd ed., 5.4). NaN when |r_xz| or |r_yz| is
// at least kPartialMaxAbsRho (a side that ranks almost as z: the volume
// against the size) or any is NaN.
inline constexpr double kPartialMaxAbsRho = 0.999;
double partial_rank_correlation(double r_xy, double r_xz, double r_yz);

// The computed Verdict metrics in HexMetric order, then the element
// conditioning's kappa, lambda_max and det_j_min; parallel over metrics.
// `cell_size` (per hex, may be empty): the size the partial correlations
// control for (the Poisson check's h_e = |e|^(1/3)).
std::vector<MetricCorrelation> correlate_metrics(std::span<const double> error_density, const HexMetricField& metrics,
                                                 const FemElementField& elements,
                                                 std::span<const double> cell_size = {});

// Spearman's rho between the error density and the hex size (NaN without sizes).
RankCorrelation size_correlation(std::span<const double> error_density, std::span<const double> cell_size);

}  // namespace hq
