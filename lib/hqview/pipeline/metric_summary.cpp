#include "hqview/pipeline/metric_summary.h"

#include <tbb/parallel_for.h>

namespace hq {

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
