#include "hqview/report/collection_correlation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>

#include <boost/math/distributions/students_t.hpp>

#include "hqview/fem/metric_correlation.h"

namespace hq {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool is_analysed(const BatchEntry& e) { return e.status == BatchStatus::ok || e.status == BatchStatus::gate_failed; }

double number_or_nan(const ReportDocument& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
}


constexpr const char* kHOverL = "h_over_l";

bool close(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)}); }

double relative_difference(double a, double b) {
  const double m = std::max(std::abs(a), std::abs(b));
  return m > 0 ? std::abs(a - b) / m : 0.0;
}

// The smallest |rho| over n distinct ranks whose two-sided p is at most 0.05.
double critical_rho_for(int n) {
  if (n < kMinCorrelationMeshes) return kNaN;
  if (n <= kExactSpearmanMaxCount) {
    // Every permutation's |rho| (no ties): rho = 1 - 6 sum d^2 / (n (n^2 - 1)).
    std::vector<int> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::vector<double> all;
    do {
      double d2 = 0;
      for (int i = 0; i < n; ++i) d2 += static_cast<double>((order[static_cast<std::size_t>(i)] - i) * (order[static_cast<std::size_t>(i)] - i));
      all.push_back(std::abs(1.0 - 6.0 * d2 / (n * (static_cast<double>(n) * n - 1.0))));
    } while (std::next_permutation(order.begin(), order.end()));
    std::sort(all.begin(), all.end(), std::greater<>());
    // The smallest value v with #{|rho| >= v} / n! <= 0.05.
    double critical = kNaN;
    for (std::size_t i = 0; i < all.size();) {
      std::size_t j = i;
      while (j < all.size() && all[j] >= all[i] - 1e-12) ++j;
      if (static_cast<double>(j) / static_cast<double>(all.size()) > 0.05) break;
      critical = all[i];
      i = j;
    }
    return critical;
  }
  const double df = n - 2.0;
  const double t = boost::math::quantile(boost::math::students_t(df), 0.975);
  return t / std::sqrt(df + t * t);
}

}  // namespace

int size_length_power(std::string_view metric) {
  if (metric == "dimension" || metric == "fem_lambda_max") return 1;
  if (metric == "volume" || metric == "jacobian" || metric == "fem_det_j_min") return 3;
  return 0;
}

bool same_mesh_geometry(const BatchEntry& a, const BatchEntry& b) {
  static const std::size_t vertices_slot = headline_slot("mesh.num_vertices"), hexes_slot = headline_slot("mesh.num_hexes");
  for (const std::size_t slot : {vertices_slot, hexes_slot})
    if (!a.headline[slot] || !b.headline[slot] || *a.headline[slot] != *b.headline[slot]) return false;
  int compared = 0;
  for (const MeshMetricRange& m : a.metrics) {
    if (metric_direction(m.metric) == 0) continue;  // a size: changes with the scale
    const auto other = std::find_if(b.metrics.begin(), b.metrics.end(),
                                    [&](const MeshMetricRange& x) { return x.metric == m.metric; });
    if (other == b.metrics.end()) continue;
    if (!close(m.min, other->min) || !close(m.mean, other->mean) || !close(m.max, other->max)) return false;
    ++compared;
  }
  return compared >= 3;
}

std::vector<MeshMetricRange> metric_summaries_from_report(const ReportDocument& report) {
  std::vector<MeshMetricRange> out;
  if (!report.contains("fem") || !report["fem"].is_object()) return out;
  const ReportDocument& fem = report["fem"];
  if (!fem.contains("poisson") || !fem["poisson"].is_object() || !fem["poisson"]["skipped"].is_null()) return out;
  if (report.contains("quality") && report["quality"].contains("metrics") && report["quality"]["metrics"].is_object())
    for (const auto& [name, stats] : report["quality"]["metrics"].items())
      if (stats.is_object())
        out.push_back({name, number_or_nan(stats, "min"), number_or_nan(stats, "mean"), number_or_nan(stats, "max")});
  if (fem.contains("element") && fem["element"].is_object())
    for (const char* name : {"kappa", "lambda_max", "det_j_min"})
      if (fem["element"].contains(name) && fem["element"][name].is_object())
        out.push_back({std::string("fem_") + name, number_or_nan(fem["element"][name], "min"),
                       number_or_nan(fem["element"][name], "mean"), number_or_nan(fem["element"][name], "max")});
  const auto volume = std::find_if(out.begin(), out.end(), [](const MeshMetricRange& m) { return m.metric == "volume"; });
  // L: the placement-free length (fem.poisson.mesh_length; issue 48h, was
  // the bounding-box diagonal, which changes when the mesh is turned).
  const double length = number_or_nan(fem["poisson"], "mesh_length");
  if (volume != out.end() && volume->mean > 0 && length > 0) {
    const double h_over_l = std::cbrt(volume->mean) / length;
    out.push_back({kHOverL, h_over_l, h_over_l, h_over_l});
  }
  return out;
}

CollectionCorrelation correlate_collection(const std::vector<BatchEntry>& entries, const std::string& label) {
  static const std::size_t l2_slot = headline_slot("fem.poisson.mean.l2_error");
  static const std::size_t h1_slot = headline_slot("fem.poisson.mean.h1_error");
  CollectionCorrelation out;
  std::vector<const BatchEntry*> candidates, meshes;
  static const std::size_t inverted_slot = headline_slot("quality.num_inverted");
  for (const BatchEntry& e : entries)
    if (is_analysed(e) && (label.empty() || e.label == label) && !e.metrics.empty() && e.headline[l2_slot] &&
        e.headline[h1_slot]) {
      if (e.headline[inverted_slot] && *e.headline[inverted_slot] > 0)
        out.inverted.push_back(e.path);
      else
        candidates.push_back(&e);
    }
  std::sort(out.inverted.begin(), out.inverted.end());
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const BatchEntry* a, const BatchEntry* b) { return a->path < b->path; });
  // Each mesh once: a later one with the geometry of a kept one is a duplicate.
  for (const BatchEntry* e : candidates) {
    const auto same = std::find_if(meshes.begin(), meshes.end(),
                                   [&](const BatchEntry* kept) { return same_mesh_geometry(*kept, *e); });
    if (same == meshes.end()) {
      meshes.push_back(e);
      continue;
    }
    out.duplicates.push_back({e->path, (*same)->path,
                              relative_difference(*e->headline[l2_slot], *(*same)->headline[l2_slot]),
                              relative_difference(*e->headline[h1_slot], *(*same)->headline[h1_slot])});
  }
  out.num_meshes = static_cast<int>(meshes.size());
  for (const BatchEntry* e : meshes) out.counted.push_back(e->path);
  out.critical_rho = critical_rho_for(out.num_meshes);
  out.min_p = kNaN;
  if (out.num_meshes >= kMinCorrelationMeshes) {
    double factorial = 1;
    for (int i = 2; i <= out.num_meshes; ++i) factorial *= i;
    out.min_p = 2.0 / factorial;
  }
  // The metric names in alphabetical order: index.json keeps a row's metrics
  // by name, so a merge of shards (rows read back) gives the same order as one run.
  std::vector<std::string> names;
  for (const BatchEntry* e : meshes)
    for (const MeshMetricRange& m : e->metrics)
      if (m.metric != kHOverL && std::find(names.begin(), names.end(), m.metric) == names.end())
        names.push_back(m.metric);
  std::sort(names.begin(), names.end());
  const auto add_row = [&](std::string metric, std::string stat, int direction, const std::vector<double>& value,
                           const std::vector<double>& l2, const std::vector<double>& h1, int length_power = 0) {
    CollectionCorrelationRow row;
    row.metric = std::move(metric);
    row.stat = std::move(stat);
    row.direction = direction;
    row.length_power = length_power;
    const RankCorrelationTest a = spearman_test(std::span<const double>(value), std::span<const double>(l2));
    const RankCorrelationTest b = spearman_test(std::span<const double>(value), std::span<const double>(h1));
    row.num_meshes = static_cast<int>(a.correlation.count);
    const bool enough_l2 = a.correlation.count >= out.min_meshes, enough_h1 = b.correlation.count >= out.min_meshes;
    row.rho_l2 = enough_l2 ? a.correlation.rho : kNaN;
    row.p_l2 = enough_l2 ? a.p_value : kNaN;
    row.rho_h1 = enough_h1 ? b.correlation.rho : kNaN;
    row.p_h1 = enough_h1 ? b.p_value : kNaN;
    out.rows.push_back(std::move(row));
  };
  // A size (no better direction) in units of the mesh's length L^k: L =
  // fem.poisson.mesh_length, cbrt(volume.mean) / h_over_l; a mesh without L leaves such a row (NaN, so not counted).
  const auto length_of = [](const BatchEntry& e) {
    double volume = kNaN, h_over_l = kNaN;
    for (const MeshMetricRange& m : e.metrics) {
      if (m.metric == "volume") volume = m.mean;
      if (m.metric == kHOverL) h_over_l = m.mean;
    }
    return volume > 0 && h_over_l > 0 ? std::cbrt(volume) / h_over_l : kNaN;
  };
  for (const std::string& name : names) {
    const int direction = metric_direction(name);
    const int power = direction == 0 ? size_length_power(name) : 0;
    for (const bool is_worst : {true, false}) {
      std::vector<double> value, l2, h1;
      for (const BatchEntry* e : meshes)
        for (const MeshMetricRange& m : e->metrics)
          if (m.metric == name) {
            const double v = !is_worst ? m.mean : direction < 0 ? m.max : m.min;
            const double length = power > 0 ? length_of(*e) : 1.0;
            if (!std::isfinite(length)) continue;
            value.push_back(power > 0 ? v / std::pow(length, power) : v);
            l2.push_back(*e->headline[l2_slot]);
            h1.push_back(*e->headline[h1_slot]);
          }
      add_row(name, !is_worst ? "mean" : direction != 0 ? "worst" : "min", direction, value, l2, h1, power);
      // mean volume / L^3 = (cbrt(mean volume) / L)^3 = (h/L)^3.
      if (name == "volume" && !is_worst) out.rows.back().restates = kHOverL;
    }
  }
  static const std::size_t hexes_slot = headline_slot("mesh.num_hexes");
  std::vector<double> value, l2, h1;
  for (const BatchEntry* e : meshes)
    if (e->headline[hexes_slot]) {
      value.push_back(*e->headline[hexes_slot]);
      l2.push_back(*e->headline[l2_slot]);
      h1.push_back(*e->headline[h1_slot]);
    }
  if (!meshes.empty()) add_row("num_hexes", "count", 0, value, l2, h1);
  // The second baseline: h/L.
  value.clear(), l2.clear(), h1.clear();
  for (const BatchEntry* e : meshes)
    for (const MeshMetricRange& m : e->metrics)
      if (m.metric == kHOverL) {
        value.push_back(m.mean);
        l2.push_back(*e->headline[l2_slot]);
        h1.push_back(*e->headline[h1_slot]);
      }
  if (!value.empty()) add_row(kHOverL, "value", 0, value, l2, h1);
  // Given h/L: each row's rho with h/L over the meshes that have both.
  std::vector<double> hl_values;
  std::vector<const BatchEntry*> hl_meshes;
  for (const BatchEntry* e : meshes)
    for (const MeshMetricRange& m : e->metrics)
      if (m.metric == kHOverL) {
        hl_values.push_back(m.mean);
        hl_meshes.push_back(e);
      }
  const auto hl_row = std::find_if(out.rows.begin(), out.rows.end(),
                                   [](const CollectionCorrelationRow& r) { return r.metric == kHOverL; });
  for (std::size_t i = 0; i < out.rows.size(); ++i) {
    CollectionCorrelationRow& r = out.rows[i];
    r.rho_l2_given_h = r.rho_h1_given_h = kNaN;
    if (hl_row == out.rows.end() || r.metric == kHOverL || r.metric == "num_hexes") continue;
    // The row's values again, paired with h/L.
    std::vector<double> value, hl;
    const int direction = r.direction;
    const bool is_worst = r.stat != "mean";
    for (std::size_t k = 0; k < hl_meshes.size(); ++k)
      for (const MeshMetricRange& m : hl_meshes[k]->metrics)
        if (m.metric == r.metric) {
          const double v = !is_worst ? m.mean : direction < 0 ? m.max : m.min;
          const double length = r.length_power > 0 ? length_of(*hl_meshes[k]) : 1.0;
          if (!std::isfinite(length)) continue;
          value.push_back(r.length_power > 0 ? v / std::pow(length, r.length_power) : v);
          hl.push_back(hl_values[k]);
        }
    if (static_cast<int>(value.size()) < out.min_meshes) continue;
    const double with_h = spearman_correlation(std::span<const double>(value), std::span<const double>(hl)).rho;
    r.rho_l2_given_h = partial_rank_correlation(r.rho_l2, with_h, hl_row->rho_l2);
    r.rho_h1_given_h = partial_rank_correlation(r.rho_h1, with_h, hl_row->rho_h1);
  }
  // The family's false discovery rate: one q per p, per error, over the rows
  // that are their own hypothesis; a restating row takes its row's q.
  std::vector<double> p_l2, p_h1;
  for (const CollectionCorrelationRow& r : out.rows) {
    p_l2.push_back(r.restates.empty() ? r.p_l2 : kNaN);
    p_h1.push_back(r.restates.empty() ? r.p_h1 : kNaN);
    out.num_hypotheses_l2 += r.restates.empty() && std::isfinite(r.p_l2);
    out.num_hypotheses_h1 += r.restates.empty() && std::isfinite(r.p_h1);
  }
  const std::vector<double> q_l2 = benjamini_hochberg(p_l2), q_h1 = benjamini_hochberg(p_h1);
  for (std::size_t i = 0; i < out.rows.size(); ++i) {
    out.rows[i].q_l2 = q_l2[i];
    out.rows[i].q_h1 = q_h1[i];
  }
  for (CollectionCorrelationRow& r : out.rows) {
    if (r.restates.empty()) continue;
    const auto of = std::find_if(out.rows.begin(), out.rows.end(),
                                 [&](const CollectionCorrelationRow& x) { return x.metric == r.restates; });
    r.q_l2 = of != out.rows.end() && std::isfinite(r.p_l2) ? of->q_l2 : kNaN;
    r.q_h1 = of != out.rows.end() && std::isfinite(r.p_h1) ? of->q_h1 : kNaN;
  }
  return out;
}

}  // namespace hq
