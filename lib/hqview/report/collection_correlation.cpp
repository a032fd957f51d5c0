#include "hqview/report/collection_correlation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "hqview/fem/metric_correlation.h"

namespace hq {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool is_analysed(const BatchEntry& e) { return e.status == BatchStatus::ok || e.status == BatchStatus::gate_failed; }

double number_or_nan(const ReportDocument& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
}

std::size_t slot_of(std::string_view key) {
  std::size_t k = 0;
  while (k < kNumHeadlineKeys && key != kHeadlineKeys[k]) ++k;
  return k;
}

}  // namespace

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
  return out;
}

CollectionCorrelation correlate_collection(const std::vector<BatchEntry>& entries, const std::string& label) {
  static const std::size_t l2_slot = slot_of("fem.poisson.mean.l2_error");
  static const std::size_t h1_slot = slot_of("fem.poisson.mean.h1_error");
  CollectionCorrelation out;
  std::vector<const BatchEntry*> meshes;
  for (const BatchEntry& e : entries)
    if (is_analysed(e) && (label.empty() || e.label == label) && !e.metrics.empty() && e.headline[l2_slot] &&
        e.headline[h1_slot])
      meshes.push_back(&e);
  out.num_meshes = static_cast<int>(meshes.size());
  // The metric names in alphabetical order: index.json keeps a row's metrics
  // by name, so a merge of shards (rows read back) gives the same order as one run.
  std::vector<std::string> names;
  for (const BatchEntry* e : meshes)
    for (const MeshMetricRange& m : e->metrics)
      if (std::find(names.begin(), names.end(), m.metric) == names.end()) names.push_back(m.metric);
  std::sort(names.begin(), names.end());
  const auto add_row = [&](std::string metric, std::string stat, int direction, const std::vector<double>& value,
                           const std::vector<double>& l2, const std::vector<double>& h1) {
    CollectionCorrelationRow row;
    row.metric = std::move(metric);
    row.stat = std::move(stat);
    row.direction = direction;
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
  for (const std::string& name : names) {
    const int direction = metric_direction(name);
    for (const bool is_worst : {true, false}) {
      std::vector<double> value, l2, h1;
      for (const BatchEntry* e : meshes)
        for (const MeshMetricRange& m : e->metrics)
          if (m.metric == name) {
            value.push_back(!is_worst ? m.mean : direction < 0 ? m.max : m.min);
            l2.push_back(*e->headline[l2_slot]);
            h1.push_back(*e->headline[h1_slot]);
          }
      add_row(name, !is_worst ? "mean" : direction != 0 ? "worst" : "min", direction, value, l2, h1);
    }
  }
  static const std::size_t hexes_slot = slot_of("mesh.num_hexes");
  std::vector<double> value, l2, h1;
  for (const BatchEntry* e : meshes)
    if (e->headline[hexes_slot]) {
      value.push_back(*e->headline[hexes_slot]);
      l2.push_back(*e->headline[l2_slot]);
      h1.push_back(*e->headline[h1_slot]);
    }
  if (!meshes.empty()) add_row("num_hexes", "count", 0, value, l2, h1);
  // The family's false discovery rate: one q per p, per error.
  std::vector<double> p_l2, p_h1;
  for (const CollectionCorrelationRow& r : out.rows) {
    p_l2.push_back(r.p_l2);
    p_h1.push_back(r.p_h1);
  }
  const std::vector<double> q_l2 = benjamini_hochberg(p_l2), q_h1 = benjamini_hochberg(p_h1);
  for (std::size_t i = 0; i < out.rows.size(); ++i) {
    out.rows[i].q_l2 = q_l2[i];
    out.rows[i].q_h1 = q_h1[i];
  }
  return out;
}

}  // namespace hq
