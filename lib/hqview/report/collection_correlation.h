#pragma once
// Across a collection: which geometric metrics predict the simulation error
// of a mesh (Gao et al., "Evaluating Hex-mesh Quality Metrics via
// Correlation Analysis", CGF 36(5), 2017). Over the meshes of a batch whose
// finite-element check was solved (--simulate), Spearman's rank correlation
// between each mesh's error figure (fem.poisson.mean.l2_error and .h1_error)
// and its worst and its mean of each metric (report.json quality.metrics.<m>,
// and the element conditioning fem.element.kappa / lambda_max / det_j_min):
// the worst is the min of a higher-is-better metric and the max of a
// lower-is-better one (metric_direction); a metric with no direction (a
// size) gives its min, divided by L^k (CollectionCorrelationRow::length_power)
// so that meshes in different units compare. A baseline row correlates the hex count
// (mesh.num_hexes): a metric that ranks the meshes no better than their
// resolution says little. Each rho has its two-sided p-value (spearman_test:
// exact permutation up to 8 meshes, the t approximation above) and its
// Benjamini-Hochberg q over the table's rows (metric_correlation.h). Null (NaN)
// when fewer than kMinCorrelationMeshes meshes have both values or either
// side is constant over them. A second baseline row correlates h/L (the
// cube root of the mean hex volume over L = fem.poisson.mesh_length, the
// diagonal of the box with the mesh's second moments of volume
// (fem/moment_length.h: the same for a turned or mirrored copy): its
// resolution relative to its size; BatchEntry::metrics "h_over_l"). Duplicates are detected by geometry, not by name
// (same_mesh_geometry): a mesh whose geometry equals an earlier one's (by
// path) is counted once and listed in `duplicates`, with how much its errors
// differ (the problem's placement: same mesh, other errors). With few meshes
// no correlation can be significant: min_p and critical_rho say how far.
// Pure; the entries' order (index.json, sorted by path) does not change the
// result.

#include <string>
#include <string_view>
#include <vector>

#include "hqview/report/batch_index.h"

namespace hq {

// Fewer meshes with both values: no correlation (rank correlations of a
// handful of meshes say little; Gao et al. used dozens per dataset).
inline constexpr int kMinCorrelationMeshes = 5;

struct CollectionCorrelationRow {
  std::string metric;  // a Verdict name, or fem_kappa, fem_lambda_max, fem_det_j_min; num_hexes (the baseline)
  std::string stat;    // "worst", "min" (no direction), "mean", or "count" (num_hexes)
  int direction = 0;   // metric_direction: +1 higher is better, -1 lower, 0 neither
  double rho_l2 = 0;   // Spearman's rho with the mean relative L2 error; NaN: null
  double p_l2 = 0;     // its two-sided p-value; NaN: null
  double rho_h1 = 0;   // with the mean relative H1 semi-norm error
  double p_h1 = 0;
  // Benjamini-Hochberg q of p_l2 (p_h1) over the table's rows (the baseline
  // included); NaN: null.
  double q_l2 = 0, q_h1 = 0;
  int num_meshes = 0;  // meshes that entered (both errors and this value)
  // k > 0: a size correlated in units of the mesh's length, value / L^k
  // (size_length_power; L = fem.poisson.mesh_length, placement-free): raw
  // sizes rank the meshes' units, not their quality.
  int length_power = 0;
  // Not its own hypothesis: the row it restates by definition (its values
  // are a monotone function of that row's, so the same ranks, rho and p).
  // "h_over_l" for the mean volume / L^3 = (h/L)^3; empty otherwise. Such a
  // row is not in the Benjamini-Hochberg family (it would count one test
  // twice) and carries the restated row's q.
  std::string restates;
  // The partial rank correlation given h/L (partial_rank_correlation of this
  // row's rho, its rho with h_over_l over the same meshes, and h_over_l's
  // rho): what the row says beyond the meshes' resolution. NaN for the
  // baselines, without h/L, or where h/L ranks the errors (or the row) almost
  // exactly (|rho| >= kPartialMaxAbsRho: nothing is left to explain).
  double rho_l2_given_h = 0, rho_h1_given_h = 0;
};

// The power of length a size metric (no better direction) carries:
// dimension and fem_lambda_max 1, volume, jacobian and fem_det_j_min 3;
// 0 for any other name.
int size_length_power(std::string_view metric);

// One mesh left out as the duplicate of another.
struct CollectionDuplicate {
  std::string path;     // left out
  std::string same_as;  // the one counted (the first by path)
  // |e_a - e_b| / max(e_a, e_b) of the mean L2 (H1) errors: 0 when the
  // check does not depend on where the mesh sits.
  double l2_difference = 0, h1_difference = 0;
};

struct CollectionCorrelation {
  int num_meshes = 0;  // distinct analysed meshes with a solved check (duplicates left out)
  std::vector<CollectionDuplicate> duplicates;
  // Meshes left out because they have inverted hexes (mesh quality
  // num_inverted > 0: a corner whose Jacobian is <= 0): the trilinear map
  // folds there, so the check is no valid finite-element discretisation of
  // the problem and its error is not that of the mesh's quality (issue 48h:
  // were counted). By path.
  std::vector<std::string> inverted;
  // The paths of the num_meshes counted meshes (by path): every count over
  // "the counted meshes" (the batch page's ties) runs over these only.
  std::vector<std::string> counted;
  // The smallest two-sided p any rho can reach over num_meshes meshes
  // (2 / n!: the two perfect orders among the n! permutations), and the
  // smallest |rho| whose p is at most 0.05 (exact permutation distribution
  // up to kExactSpearmanMaxCount meshes, the t approximation above); NaN
  // below kMinCorrelationMeshes. With m rows, one row alone reaches
  // q <= 0.05 only when m * min_p <= 0.05.
  double min_p = 0;
  double critical_rho = 0;
  int min_meshes = kMinCorrelationMeshes;
  // The Benjamini-Hochberg family: the rows that are their own hypothesis
  // (restates empty) with a p, for the H1 (L2) error; the baselines are in it.
  int num_hypotheses_h1 = 0, num_hypotheses_l2 = 0;
  // Per metric (alphabetical: the same after a merge of shards), worst (or
  // min) then mean; then the baseline num_hexes.
  std::vector<CollectionCorrelationRow> rows;
};

// Whether two meshes have the same geometry up to a rotation, reflection,
// uniform scale, translation or renumbering: the same numbers of vertices
// and hexes, and the same min, mean and max (to 1e-9 relative) of every
// scale-invariant metric both computed (the ones with a better direction,
// fem_kappa included), at least three of them. Needs solved checks (metrics).
bool same_mesh_geometry(const BatchEntry& a, const BatchEntry& b);

// The metric summaries a batch row keeps for this (BatchEntry::metrics),
// read from a report document: empty unless its fem.poisson was solved.
// Also "h_over_l" (min = mean = max): cbrt(quality.metrics.volume.mean) /
// fem.poisson.mesh_length, when both are there.
std::vector<MeshMetricRange> metric_summaries_from_report(const ReportDocument& report);

// Over the analysed (ok, gate_failed) entries with a solved check. `label`:
// only that method's meshes; empty: all.
CollectionCorrelation correlate_collection(const std::vector<BatchEntry>& entries, const std::string& label = "");

}  // namespace hq
