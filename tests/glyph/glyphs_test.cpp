// The glyph rules of ALGORITHMS.md §3: ratio and threshold, the size bonus,
// the aggregated glyph's position and ratio, ranking and ids.

#include "hqview/glyph/glyphs.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <limits>
#include <random>

#include "hqview/core/error.h"

namespace hq {
namespace HQ_TEST_UNIT {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(GlyphSizeBonus, PointOnePerTenMembersAtMostOne) {
  EXPECT_EQ(glyph_size_bonus(0), 0.0);
  EXPECT_EQ(glyph_size_bonus(1), 0.0);
  EXPECT_EQ(glyph_size_bonus(9), 0.0);
  EXPECT_EQ(glyph_size_bonus(10), 0.1);
  EXPECT_EQ(glyph_size_bonus(19), 0.1);
  EXPECT_EQ(glyph_size_bonus(20), 0.2);
  EXPECT_EQ(glyph_size_bonus(30), 0.3);  // the double of 0.3, not 3 * 0.1
  EXPECT_EQ(glyph_size_bonus(99), 0.9);
  EXPECT_EQ(glyph_size_bonus(100), 1.0);
  EXPECT_EQ(glyph_size_bonus(101), 1.0);
  EXPECT_EQ(glyph_size_bonus(1'000'000), 1.0);
}

TEST(GlyphRadii, RatioAboveThresholdTimesRmax) {
  const std::vector<double> quality{1.0, 0.9, 0.5, 0.25, 0.0, -1.0, kNaN, 0.5000000000000001};
  const std::vector<double> r = glyph_radii(quality, 2.0, 0.5);
  // c = 0, 0.1, 0.5 (at the threshold: no glyph), 0.75, 1, 2, NaN, just below 0.5.
  EXPECT_EQ(r, (std::vector<double>{0, 0, 0, 1.5, 2.0, 4.0, 0, 0}));
  const std::vector<double> all = glyph_radii(quality, 1.0, 0.0);
  EXPECT_EQ(all[0], 0.0);  // c = 0 is at the threshold 0
  EXPECT_DOUBLE_EQ(all[1], 1.0 - 0.9);
}

TEST(ResolveRmax, ModelUnitsOrMeanEdgeLength) {
  GlyphOptions o;
  EXPECT_EQ(o.rmax_unit, RmaxUnit::kMeanEdgeLength);
  o.rmax = 1.5;
  EXPECT_EQ(resolve_rmax(o, 2.0), 3.0);
  o.rmax_unit = RmaxUnit::kModel;
  EXPECT_EQ(resolve_rmax(o, 2.0), 1.5);
}

TEST(AggregateGlyph, PaperPositionAtTheMemberNearestTheMean) {
  const std::vector<Vec3> points{{0, 0, 0}, {10, 0, 0}, {1, 0, 0}, {4, 0, 0}, {20, 0, 0}};
  const std::vector<double> quality{0.4, 0.1, 0.3, 0.2, 0.0};
  // Members 0, 1, 2, 3: mean x = 3.75, nearest is vertex 3 (x = 4).
  const std::vector<Index> members{0, 1, 2, 3};
  const AggregatedGlyph g = aggregate_glyph(members, points, quality, 2.0, GlyphSizeRule::kPaper);
  EXPECT_EQ(g.size, 4);
  EXPECT_EQ(g.representative_vertex, 3);
  EXPECT_EQ(g.position, (Vec3{4, 0, 0}));
  EXPECT_EQ(g.min_quality, 0.1);
  EXPECT_EQ(g.ratio, 0.9);  // 1 − 0.1, no bonus below 10 members
  EXPECT_EQ(g.radius, 1.8);
}

TEST(AggregateGlyph, SeverityPositionAtTheWorstMember) {
  // The default rule: the glyph sits on the worst member (issue 44: a glyph
  // at the members' middle can sit where there is no defect), vertex 1
  // (quality 0.1) of the same members; ties: the smallest id.
  const std::vector<Vec3> points{{0, 0, 0}, {10, 0, 0}, {1, 0, 0}, {4, 0, 0}, {20, 0, 0}};
  const std::vector<double> quality{0.4, 0.1, 0.3, 0.2, 0.1};
  const std::vector<Index> members{0, 1, 2, 3};
  const AggregatedGlyph g = aggregate_glyph(members, points, quality, 2.0);
  EXPECT_EQ(g.representative_vertex, 1);
  EXPECT_EQ(g.position, (Vec3{10, 0, 0}));
  EXPECT_EQ(g.ratio, 0.9);
  const std::vector<Index> with_tie{1, 2, 3, 4};  // 1 and 4 tie at 0.1
  EXPECT_EQ(aggregate_glyph(with_tie, points, quality, 2.0).representative_vertex, 1);
}

TEST(AggregateGlyph, TiesGoToTheSmallestId) {
  // Two members equally far from the mean, listed so that the larger id comes first in space.
  const std::vector<Vec3> points{{5, 5, 5}, {2, 0, 0}, {0, 0, 0}};
  const std::vector<double> quality{0.0, 0.3, 0.3};
  const std::vector<Index> members{1, 2};
  constexpr GlyphSizeRule kPaper = GlyphSizeRule::kPaper;
  EXPECT_EQ(aggregate_glyph(members, points, quality, 1.0, kPaper).representative_vertex, 1);
  // Four corners of a square around the mean: the smallest id wins.
  const std::vector<Vec3> square{{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}};
  const std::vector<double> q4(4, 0.2);
  const std::vector<Index> ids{0, 1, 2, 3};
  EXPECT_EQ(aggregate_glyph(ids, square, q4, 1.0, kPaper).representative_vertex, 0);
  const std::vector<Index> last_three{1, 2, 3};  // mean (−1/3, −1/3): vertex 2 nearest
  EXPECT_EQ(aggregate_glyph(last_three, square, q4, 1.0, kPaper).representative_vertex, 2);
  // Severity: equal qualities, the smallest id.
  EXPECT_EQ(aggregate_glyph(last_three, square, q4, 1.0).representative_vertex, 1);
}

TEST(AggregateGlyph, PaperRuleAddsTheSizeBonusToTheLargestRatio) {
  std::vector<Vec3> points;
  std::vector<double> quality;
  for (int i = 0; i < 250; ++i) {
    points.push_back({double(i), 0, 0});
    quality.push_back(i == 7 ? 0.2 : 0.4);
  }
  auto aggregate = [&](int size) {
    std::vector<Index> members;
    for (int i = 0; i < size; ++i) members.push_back(i);
    return aggregate_glyph(members, points, quality, 0.5, GlyphSizeRule::kPaper);
  };
  EXPECT_EQ(aggregate(9).ratio, 0.8);
  EXPECT_EQ(aggregate(10).ratio, 0.8 + 0.1);
  EXPECT_EQ(aggregate(25).ratio, 0.8 + 0.2);
  EXPECT_EQ(aggregate(100).ratio, 0.8 + 1.0);
  EXPECT_EQ(aggregate(250).ratio, 0.8 + 1.0);  // the bonus is capped, not the ratio
  EXPECT_EQ(aggregate(250).radius, (0.8 + 1.0) * 0.5);
  EXPECT_EQ(aggregate(25).min_quality, 0.2);
}

TEST(AggregateGlyph, SeverityRuleIgnoresTheMemberCount) {
  // The default rule: radius = (1 − min quality) · rmax whatever the size, so
  // 250 members at min 0.4 are drawn smaller than 9 at min 0.2.
  std::vector<Vec3> points;
  std::vector<double> quality;
  for (int i = 0; i < 250; ++i) {
    points.push_back({double(i), 0, 0});
    quality.push_back(i == 7 ? 0.2 : 0.4);
  }
  auto aggregate = [&](int first, int size) {
    std::vector<Index> members;
    for (int i = first; i < first + size; ++i) members.push_back(i);
    return aggregate_glyph(members, points, quality, 0.5);
  };
  for (int size : {1, 9, 10, 25, 100, 250}) {
    EXPECT_EQ(aggregate(0, size).ratio, size > 7 ? 0.8 : 0.6) << size;
    EXPECT_EQ(aggregate(0, size).radius, (size > 7 ? 0.8 : 0.6) * 0.5) << size;
    EXPECT_EQ(aggregate(0, size).size, size);
  }
  EXPECT_LT(aggregate(8, 242).radius, aggregate(0, 9).radius);  // 242 at 0.4 < 9 with a 0.2
  EXPECT_STREQ(glyph_size_rule_name(GlyphSizeRule::kSeverity), "severity");
  EXPECT_STREQ(glyph_size_rule_name(GlyphSizeRule::kPaper), "paper");
}

// Three groups on a line with unit spacing, rmax = 1 model unit.
struct Line {
  std::vector<Vec3> points;
  std::vector<double> quality;
};

Line three_groups() {
  Line l;
  auto add = [&](double x, double q) {
    l.points.push_back({x, 0, 0});
    l.quality.push_back(q);
  };
  // Group A (ids 0-2): c = 0.6 each, spacing 1: 0.6 + 0.6 > 1, merged; min Jm 0.4.
  add(0, 0.4), add(1, 0.4), add(2, 0.4);
  add(10, 0.9);  // good vertex: no glyph
  // Group B (ids 4-5): min Jm 0.4, size 2.
  add(20, 0.4), add(21, 0.45);
  // Singleton C (id 6): Jm −0.5, the worst.
  add(40, -0.5);
  add(50, kNaN);  // unused vertex
  return l;
}

TEST(ComputeGlyphs, ClustersRankedByMinQualityThenSize) {
  const Line l = three_groups();
  GlyphOptions o;
  o.rmax = 1.0;
  o.rmax_unit = RmaxUnit::kModel;
  // The default (severity): bounded clusters. Group A is one component but
  // not one cluster: seed 0 (r 0.6, the smallest id of equals) has the ball
  // radius 1.2, which holds vertex 1 (1.0) but not 2 (2.0): {0, 1} and {2}.
  // Ranks: {6} (Jm −0.5), then {0, 1} and {4, 5} (min 0.4, size 2; smallest
  // member first), then {2}. Each glyph at its worst member (ties: smallest id).
  const GlyphResult b = compute_glyphs(l.points, l.quality, 123.0, o);
  ASSERT_EQ(b.clusters.size(), 4u);
  EXPECT_EQ(b.vertex_cluster, (std::vector<Index>{1, 1, 3, kNoIndex, 2, 2, 0, kNoIndex}));
  EXPECT_EQ(b.clusters[1].representative_vertex, 0);
  EXPECT_EQ(b.clusters[2].representative_vertex, 4);
  EXPECT_EQ(b.clusters[3].representative_vertex, 2);
  EXPECT_EQ(b.clusters[3].size, 1);
  EXPECT_EQ(b.cluster_vertices, (std::vector<Index>{6, 0, 1, 4, 5, 2}));
  // Paper: HQViewer's clusters, the components, each at the member nearest the mean.
  o.size_rule = GlyphSizeRule::kPaper;
  const GlyphResult g = compute_glyphs(l.points, l.quality, 123.0, o);
  EXPECT_EQ(g.rmax, 1.0);
  EXPECT_EQ(g.num_glyphs, 6);
  ASSERT_EQ(g.clusters.size(), 3u);
  // Rank 0: the singleton with Jm −0.5; rank 1: A (min 0.4, size 3); rank 2: B (min 0.4, size 2).
  EXPECT_EQ(g.clusters[0].representative_vertex, 6);
  EXPECT_EQ(g.clusters[0].ratio, 1.5);  // no bonus for 1 member
  EXPECT_EQ(g.clusters[1].size, 3);
  EXPECT_EQ(g.clusters[1].representative_vertex, 1);
  EXPECT_EQ(g.clusters[2].size, 2);
  EXPECT_EQ(g.clusters[2].representative_vertex, 4);  // tie at the mean: smallest id
  for (Index i = 0; i < 3; ++i) EXPECT_EQ(g.clusters[static_cast<std::size_t>(i)].id, i);
  EXPECT_EQ(g.vertex_cluster, (std::vector<Index>{1, 1, 1, kNoIndex, 2, 2, 0, kNoIndex}));
  EXPECT_DOUBLE_EQ(g.vertex_radius[0], 0.6);
  EXPECT_EQ(g.vertex_radius[3], 0.0);
  EXPECT_EQ(g.vertex_radius[7], 0.0);
  EXPECT_EQ(g.cluster_offsets, (std::vector<Index>{0, 1, 4, 6}));
  EXPECT_EQ(g.cluster_vertices, (std::vector<Index>{6, 0, 1, 2, 4, 5}));
}

TEST(ComputeGlyphs, EqualMinQualityAndSizeRankBySmallestMember) {
  Line l;
  for (double x : {30.0, 0.0, 60.0}) {  // ids 0, 1, 2: three equal singletons
    l.points.push_back({x, 0, 0});
    l.quality.push_back(0.2);
  }
  const GlyphResult g = compute_glyphs(l.points, l.quality, 1.0, GlyphOptions{});
  ASSERT_EQ(g.clusters.size(), 3u);
  EXPECT_EQ(g.clusters[0].representative_vertex, 0);
  EXPECT_EQ(g.clusters[1].representative_vertex, 1);
  EXPECT_EQ(g.clusters[2].representative_vertex, 2);
}

TEST(ComputeGlyphs, RelativeRmaxAndDefaults) {
  const Line l = three_groups();
  const GlyphOptions defaults;
  EXPECT_EQ(defaults.threshold, 0.5);
  EXPECT_EQ(defaults.rmax, 1.0);
  EXPECT_EQ(defaults.top_clusters, 8);
  // Default threshold 0.5: c = 0.6 and 0.55 and 1.5 pass; rmax = 1 × mean edge 0.5.
  const GlyphResult g = compute_glyphs(l.points, l.quality, 0.5, defaults);
  EXPECT_EQ(g.rmax, 0.5);
  EXPECT_EQ(g.num_glyphs, 6);
  // With rmax 0.5, A's glyphs (0.3 each, spacing 1) no longer overlap.
  EXPECT_EQ(g.clusters.size(), 6u);
}

TEST(ComputeGlyphs, NothingBadNothingShown) {
  std::vector<Vec3> points(5);
  std::vector<double> quality{1.0, 0.99, 0.8, 0.5, kNaN};
  const GlyphResult g = compute_glyphs(points, quality, 1.0, GlyphOptions{});
  EXPECT_EQ(g.num_glyphs, 0);
  EXPECT_TRUE(g.clusters.empty());
  EXPECT_EQ(g.cluster_offsets, std::vector<Index>{0});
  EXPECT_EQ(g.vertex_cluster, std::vector<Index>(5, kNoIndex));
  EXPECT_THROW(compute_glyphs(points, std::vector<double>(4, 0.0), 1.0, GlyphOptions{}), Error);
}

TEST(ComputeGlyphs, ZeroRmaxMeansNoGlyphs) {
  std::vector<Vec3> points(3);
  std::vector<double> quality{0.0, -1.0, 0.2};
  const GlyphResult g = compute_glyphs(points, quality, 0.0, GlyphOptions{});
  EXPECT_EQ(g.num_glyphs, 0);
  EXPECT_EQ(g.vertex_radius, std::vector<double>(3, 0.0));
}

TEST(ComputeGlyphs, IdenticalForEveryThreadCount) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coord(0.0, 40.0), q(-1.0, 1.0);
  std::vector<Vec3> points;
  std::vector<double> quality;
  for (int i = 0; i < 50000; ++i) {
    points.push_back({coord(rng), coord(rng), coord(rng)});
    quality.push_back(q(rng));
  }
  GlyphOptions o;
  o.rmax = 0.8;
  o.threshold = 0.3;
  tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 8);  // more threads than cores
  GlyphResult one;
  tbb::task_arena(1).execute([&] { one = compute_glyphs(points, quality, 1.0, o); });
  ASSERT_GT(one.clusters.size(), 10u);
  for (int threads : {2, 4, 7}) {
    GlyphResult many;
    tbb::task_arena(threads).execute([&] { many = compute_glyphs(points, quality, 1.0, o); });
    EXPECT_EQ(many.vertex_cluster, one.vertex_cluster);
    EXPECT_EQ(many.vertex_radius, one.vertex_radius);
    EXPECT_EQ(many.cluster_vertices, one.cluster_vertices);
    ASSERT_EQ(many.clusters.size(), one.clusters.size());
    for (std::size_t c = 0; c < one.clusters.size(); ++c) {
      EXPECT_EQ(many.clusters[c].representative_vertex, one.clusters[c].representative_vertex);
      EXPECT_EQ(many.clusters[c].ratio, one.clusters[c].ratio);
      EXPECT_EQ(many.clusters[c].size, one.clusters[c].size);
    }
  }
}

// The size rules on a random cloud: under severity (the default) a worse
// cluster is never drawn smaller than a better one (radius non-increasing
// with rank, equal min quality equal radius); under paper every radius is
// the severity radius plus the size bonus, and clusters and ranks agree.
TEST(ComputeGlyphs, SeverityRadiusFollowsRankAndPaperAddsTheBonus) {
  // Scattered vertices of any badness, and 6 dense blobs of 60 mildly bad
  // ones (the paper's bonus makes those outgrow worse small clusters).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(0.0, 80.0), q(-1.0, 0.6), mild(0.3, 0.45), blob(-1.5, 1.5);
  std::vector<Vec3> points;
  std::vector<double> quality;
  for (int i = 0; i < 15000; ++i) {
    points.push_back({coord(rng), coord(rng), coord(rng)});
    quality.push_back(q(rng));
  }
  for (int b = 0; b < 6; ++b) {
    const Vec3 centre{coord(rng), coord(rng), coord(rng)};
    for (int i = 0; i < 60; ++i) {
      points.push_back(centre + Vec3{blob(rng), blob(rng), blob(rng)});
      quality.push_back(mild(rng));
    }
  }
  GlyphOptions o;
  o.rmax = 0.7;
  o.rmax_unit = RmaxUnit::kModel;
  const GlyphResult severity = compute_glyphs(points, quality, 1.0, o);
  o.size_rule = GlyphSizeRule::kPaper;
  const GlyphResult paper = compute_glyphs(points, quality, 1.0, o);
  ASSERT_GT(severity.clusters.size(), paper.clusters.size());  // the blobs' chains are split
  ASSERT_GT(paper.clusters.size(), 100u);
  for (std::size_t i = 0; i < severity.clusters.size(); ++i) {
    const AggregatedGlyph& s = severity.clusters[i];
    EXPECT_EQ(s.ratio, 1.0 - s.min_quality);
    EXPECT_EQ(s.radius, (1.0 - s.min_quality) * 0.7);
    EXPECT_EQ(quality[static_cast<std::size_t>(s.representative_vertex)], s.min_quality);  // at the worst member
    if (i > 0) {
      EXPECT_GE(severity.clusters[i - 1].radius, s.radius) << i;
    }
  }
  int paper_inversions = 0;
  for (std::size_t i = 0; i < paper.clusters.size(); ++i) {
    const AggregatedGlyph& p = paper.clusters[i];
    EXPECT_EQ(p.ratio, 1.0 - p.min_quality + glyph_size_bonus(p.size));
    if (i > 0) paper_inversions += paper.clusters[i - 1].radius < p.radius;
  }
  EXPECT_GT(paper_inversions, 0);  // the cloud has big mild clusters: the paper rule inverts some pairs
  EXPECT_EQ(severity.vertex_radius, paper.vertex_radius);  // the member glyphs do not change
  // Each bounded cluster lies inside one of paper's (the components).
  for (std::size_t c = 0; c < severity.clusters.size(); ++c) {
    const Index first = severity.cluster_vertices[static_cast<std::size_t>(severity.cluster_offsets[c])];
    for (Index k = severity.cluster_offsets[c]; k < severity.cluster_offsets[c + 1]; ++k)
      EXPECT_EQ(paper.vertex_cluster[static_cast<std::size_t>(severity.cluster_vertices[static_cast<std::size_t>(k)])],
                paper.vertex_cluster[static_cast<std::size_t>(first)]);
  }
}

}  // namespace
}  // namespace hq
