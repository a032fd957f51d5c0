#include "hqview/pipeline/metric_summary.h"

namespace hq {

std::vector<MetricSummary> summarize_hex_metrics(const HexMetricField& field) {
  std::vector<MetricSummary> out;
  for (int i = 0; i < kNumHexMetrics; ++i) {
    const auto m = static_cast<HexMetric>(i);
    if (!contains(field.computed, m)) continue;
    const HexMetricInfo& info = hex_metric_info(m);
    StatisticsOptions options;
    if (m == HexMetric::scaled_jacobian) {
      options.histogram_min = -1.0;
      options.histogram_max = 1.0;
    }
    MetricSummary s;
    s.name = std::string(info.name);
    s.stats = compute_statistics(field.of(m), options);
    s.acceptable_min = info.acceptable_min;
    s.acceptable_max = info.acceptable_max;
    std::int64_t inside = 0;
    for (double v : field.of(m))
      if (!is_verdict_sentinel(v) && v >= info.acceptable_min && v <= info.acceptable_max) ++inside;
    s.fraction_acceptable = s.stats.count > 0 ? static_cast<double>(inside) / static_cast<double>(s.stats.count) : 0.0;
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace hq
