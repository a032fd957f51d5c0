#pragma once
// report.json `quality.metrics`: the statistics of every computed Verdict hex
// metric, with Verdict's acceptable range and the fraction of cells in it.

#include <vector>

#include "hqview/quality/hex_metric_field.h"
#include "hqview/report/report_model.h"

namespace hq {

// One MetricSummary per computed metric, in HexMetric order. Verdict's
// sentinels (|v| >= 1e30) are counted in num_degenerate and kept out of
// every other number, fraction_acceptable included (its denominator is the
// non-degenerate count). Histograms: 20 bins over [-1, 1] for
// scaled_jacobian, over [min, max] otherwise.
std::vector<MetricSummary> summarize_hex_metrics(const HexMetricField& field);

}  // namespace hq
