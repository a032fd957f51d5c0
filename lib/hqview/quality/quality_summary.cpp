#include "hqview/quality/quality_summary.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "hqview/quality/corner_jacobian.h"

namespace hq {
namespace {

StatisticsOptions jacobian_histogram() {
  StatisticsOptions o;
  o.histogram_min = -1.0;
  o.histogram_max = 1.0;
  o.histogram_bins = 20;
  return o;
}

}  // namespace

QualitySummary summarize_quality(const HexMesh& mesh, const QualityField& field, int worst_count) {
  QualitySummary q;
  const auto options = jacobian_histogram();
  // A corner with a zero-length edge is degenerate: counted, kept out of the
  // distribution (its value 0 still reaches vertex quality).
  std::vector<std::uint8_t> corner_flags(field.corner_scaled_jacobian.size());
  for (std::size_t h = 0; h < field.corner_degenerate_mask.size(); ++h)
    for (int i = 0; i < 8; ++i)
      corner_flags[8 * h + static_cast<std::size_t>(i)] = (field.corner_degenerate_mask[h] >> i) & 1u;
  // Three independent sorts (the corners': 8 values per hex) run at once.
  tbb::parallel_invoke(
      [&] { q.scaled_jacobian = compute_statistics(field.cell_scaled_jacobian, options); },
      [&] { q.corner_scaled_jacobian = compute_statistics(field.corner_scaled_jacobian, options, corner_flags); },
      [&] { q.vertex_quality = compute_statistics(field.vertex_quality, options); });

  // The headline's cell counts (Verdict metrics: summarize_hex_metrics).
  q.num_inverted = q.scaled_jacobian.num_inverted;
  q.num_degenerate = q.scaled_jacobian.num_degenerate;

  // Worst vertices: lowest quality first, ties by id; unreferenced ones skipped.
  std::vector<Index> vertices;
  for (std::size_t v = 0; v < field.vertex_quality.size(); ++v)
    if (!std::isnan(field.vertex_quality[v])) vertices.push_back(static_cast<Index>(v));
  const std::size_t nv = std::min<std::size_t>(static_cast<std::size_t>(worst_count), vertices.size());
  std::partial_sort(vertices.begin(), vertices.begin() + static_cast<std::ptrdiff_t>(nv), vertices.end(),
                    [&](Index a, Index b) {
                      const double qa = field.vertex_quality[a], qb = field.vertex_quality[b];
                      return qa != qb ? qa < qb : a < b;
                    });
  for (std::size_t i = 0; i < nv; ++i)
    q.worst_vertices.push_back({vertices[i], field.vertex_quality[vertices[i]], mesh.points[vertices[i]]});

  // Worst cells: degenerate (1e30) cells first, they are the worst of all,
  // then ascending scaled Jacobian, ties by id.
  std::vector<Index> cells(field.cell_scaled_jacobian.size());
  std::iota(cells.begin(), cells.end(), 0);
  auto rank = [&](Index c) {
    const double v = field.cell_scaled_jacobian[c];
    return v >= kVerdictDegenerate ? -INFINITY : v;
  };
  const std::size_t nc = std::min<std::size_t>(static_cast<std::size_t>(worst_count), cells.size());
  std::partial_sort(cells.begin(), cells.begin() + static_cast<std::ptrdiff_t>(nc), cells.end(), [&](Index a, Index b) {
    const double ra = rank(a), rb = rank(b);
    return ra != rb ? ra < rb : a < b;
  });
  for (std::size_t i = 0; i < nc; ++i) q.worst_cells.push_back({cells[i], field.cell_scaled_jacobian[cells[i]]});
  return q;
}

std::vector<MetricSummary> summarize_hex_metrics(const HexMetricField& field) {
  std::vector<HexMetric> computed;
  for (int i = 0; i < kNumHexMetrics; ++i)
    if (contains(field.computed, static_cast<HexMetric>(i))) computed.push_back(static_cast<HexMetric>(i));
  // One task per metric, each summarised sequentially (statistics sort their
  // values): the same numbers for any thread count.
  std::vector<MetricSummary> out(computed.size());
  tbb::parallel_for(std::size_t{0}, computed.size(), [&](std::size_t k) {
    const HexMetric m = computed[k];
    const HexMetricInfo& info = hex_metric_info(m);
    StatisticsOptions options;
    if (m == HexMetric::scaled_jacobian) {
      options.histogram_min = -1.0;
      options.histogram_max = 1.0;
    }
    MetricSummary& s = out[k];
    s.name = std::string(info.name);
    s.stats = compute_statistics(field.of(m), options);
    s.acceptable_min = info.acceptable_min;
    s.acceptable_max = info.acceptable_max;
    std::int64_t inside = 0;
    for (double v : field.of(m))
      if (!is_verdict_sentinel(v) && v >= info.acceptable_min && v <= info.acceptable_max) ++inside;
    s.fraction_acceptable = s.stats.count > 0 ? static_cast<double>(inside) / static_cast<double>(s.stats.count) : 0.0;
  });
  return out;
}

}  // namespace hq
