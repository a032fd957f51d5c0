// quality.metrics: statistics of each computed metric, acceptable fraction,
// Verdict's sentinels counted apart.

#include "hqview/quality/quality_summary.h"

#include <gtest/gtest.h>

#include "support/fixtures.h"

namespace hq {
namespace {

const MetricSummary* find(const std::vector<MetricSummary>& all, std::string_view name) {
  for (const MetricSummary& m : all)
    if (m.name == name) return &m;
  return nullptr;
}

TEST(MetricSummary, GridOfCubesIsPerfectAndComplete) {
  const HexMetricField field = compute_hex_metrics(test::grid(3));
  const auto all = summarize_hex_metrics(field);
  ASSERT_EQ(all.size(), static_cast<std::size_t>(kNumHexMetrics));
  for (int i = 0; i < kNumHexMetrics; ++i)
    EXPECT_EQ(all[static_cast<std::size_t>(i)].name, hex_metric_name(static_cast<HexMetric>(i)));
  const MetricSummary* sj = find(all, "scaled_jacobian");
  EXPECT_EQ(sj->stats.count, 27);
  EXPECT_EQ(sj->stats.min, 1.0);
  EXPECT_EQ(sj->stats.histogram.edges.front(), -1.0);
  EXPECT_EQ(sj->fraction_acceptable, 1.0);
  EXPECT_EQ(sj->acceptable_min, 0.5);
  EXPECT_NEAR(find(all, "skew")->stats.max, 0.0, 1e-15);
  EXPECT_EQ(find(all, "volume")->acceptable_max, std::numeric_limits<double>::infinity());
  EXPECT_NEAR(find(all, "relative_size_squared")->stats.mean, 1.0, 1e-15);
}

TEST(MetricSummary, DegenerateCellsAreCountedApart) {
  HexMesh mesh = test::grid(2);
  // Flatten hex 0 (top corners = bottom corners): Verdict's 1e30.
  for (int i = 4; i < 8; ++i) mesh.hexes[0][i] = mesh.hexes[0][i - 4];
  const HexMetricField field = compute_hex_metrics(mesh);
  EXPECT_EQ(field.of(HexMetric::scaled_jacobian)[0], kVerdictDegenerate);
  const auto all = summarize_hex_metrics(field);
  const MetricSummary* sj = find(all, "scaled_jacobian");
  EXPECT_EQ(sj->stats.num_degenerate, 1);
  EXPECT_EQ(sj->stats.count, 7);
  EXPECT_EQ(sj->stats.max, 1.0);  // the 1e30 is never averaged in
  EXPECT_EQ(sj->fraction_acceptable, 1.0);
}

TEST(MetricSummary, OnlyComputedMetrics) {
  HexMetricSet which;
  insert(which, HexMetric::taper);
  const auto all = summarize_hex_metrics(compute_hex_metrics(test::grid(2), which));
  ASSERT_EQ(all.size(), 2u);  // scaled_jacobian is always computed
  EXPECT_EQ(all[0].name, "taper");
  EXPECT_EQ(all[1].name, "scaled_jacobian");
}

}  // namespace
}  // namespace hq
