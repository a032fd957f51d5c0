// quality.metrics: statistics of each computed metric, acceptable fraction,
// Verdict's sentinels counted apart.

#include "hqview/quality/quality_summary.h"

#include <gtest/gtest.h>

#include <cstring>

#include "hqview/mesh/topology.h"
#include "support/fixtures.h"
#include "support/mixed_grid.h"

namespace hq {
namespace HQ_TEST_UNIT {

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

bool same_statistics(const Statistics& a, const Statistics& b) {
  const auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof(double)) == 0; };
  return a.count == b.count && a.num_degenerate == b.num_degenerate && a.num_inverted == b.num_inverted &&
         same(a.min, b.min) && same(a.max, b.max) && same(a.mean, b.mean) && same(a.std, b.std) &&
         same(a.p01, b.p01) && same(a.p05, b.p05) && same(a.p50, b.p50) && same(a.p95, b.p95) &&
         same(a.p99, b.p99) && a.histogram.edges == b.histogram.edges && a.histogram.counts == b.histogram.counts;
}

// The statistics shared between by_kind and the whole mesh (issue 46: the
// corner values sorted once): what single_kind_statistics points at, and
// summarize_quality taking them gives every number it computes itself.
TEST(QualitySummary, OneKindSharesItsStatisticsWithTheWholeMesh) {
  Mesh tets = test::mixed_grid(3, 0.2);  // its tets alone (with a flat-ish jitter: varied values)
  tets.hexes.clear();
  tets.wedges.clear();
  tets.pyramids.clear();
  tets.tets.pop_back();  // the repeated tet
  struct Case {
    const char* name;
    Mesh mesh;
    bool corners, scaled_jacobian;
  };
  const Case cases[] = {{"tets", tets, true, true},
                        {"hexes", test::grid(3), true, false},
                        {"every kind", test::mixed_grid(3, 0.2), false, false}};
  for (const Case& c : cases) {
    const Topology topo = build_topology(c.mesh);
    const QualityField field = compute_quality(c.mesh, topo);
    const auto keep = [](std::string_view) { return false; };
    const std::vector<SummarizedCellBlock> blocks = summarize_non_hex_blocks(c.mesh, field, keep);
    const std::vector<KindQualitySummary> by_kind =
        summarize_by_kind(c.mesh, field, summarize_hex_metrics(compute_hex_metrics(c.mesh)), blocks);
    const KnownQualityStatistics known = single_kind_statistics(c.mesh, field, by_kind);
    EXPECT_EQ(known.corner_scaled_jacobian != nullptr, c.corners) << c.name;
    EXPECT_EQ(known.scaled_jacobian != nullptr, c.scaled_jacobian) << c.name;
    const QualitySummary computed = summarize_quality(c.mesh, field, 5);
    const QualitySummary shared = summarize_quality(c.mesh, field, 5, known);
    EXPECT_TRUE(same_statistics(shared.corner_scaled_jacobian, computed.corner_scaled_jacobian)) << c.name;
    EXPECT_TRUE(same_statistics(shared.scaled_jacobian, computed.scaled_jacobian)) << c.name;
    EXPECT_GT(computed.corner_scaled_jacobian.count, 0) << c.name;
    // Taken as given, not computed again: other statistics come back as they are.
    Statistics marked;
    marked.count = -7;
    const QualitySummary taken = summarize_quality(c.mesh, field, 5, {&marked, &marked});
    EXPECT_EQ(taken.scaled_jacobian.count, -7);
    EXPECT_EQ(taken.corner_scaled_jacobian.count, -7);
  }
}

}  // namespace
}  // namespace hq
