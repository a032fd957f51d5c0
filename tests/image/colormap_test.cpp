#include "hqview/image/colormap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <tuple>

namespace hq {
namespace HQ_TEST_UNIT {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool same(const Color& a, const Color& b) { return to_rgba8(a) == to_rgba8(b); }

double distance(const Color& a, const Color& b) {
  return std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
}

TEST(QualityMap, EndpointsAreCalmAndStriking) {
  const Color best = sample_quality_map(1.0), worst = sample_quality_map(0.0);
  // Perfect elements: light and nearly grey; the worst: dark-ish saturated red.
  EXPECT_GT(cie_lightness(best), 88.0);
  EXPECT_LT(std::max({best.r, best.g, best.b}) - std::min({best.r, best.g, best.b}), 0.1f);
  EXPECT_LT(cie_lightness(worst), 50.0);
  EXPECT_GT(worst.r, 0.7f);
  EXPECT_LT(worst.g, 0.2f);
  EXPECT_LT(worst.b, 0.2f);
}

TEST(QualityMap, LightnessIsStrictlyMonotone) {
  double previous = -1.0;
  for (int i = 0; i <= 200; ++i) {
    const double l = cie_lightness(sample_quality_map(i / 200.0));
    EXPECT_GT(l, previous) << "t = " << i / 200.0;
    previous = l;
  }
}

TEST(QualityMap, ClampsOutsideTheUnitInterval) {
  EXPECT_TRUE(same(sample_quality_map(-3.0), sample_quality_map(0.0)));
  EXPECT_TRUE(same(sample_quality_map(7.0), sample_quality_map(1.0)));
}

TEST(QualityColor, MapsRangesSpecialValuesAndRounding) {
  EXPECT_TRUE(same(quality_color(1.0), sample_quality_map(1.0)));
  EXPECT_TRUE(same(quality_color(0.0), sample_quality_map(0.0)));
  EXPECT_TRUE(same(quality_color(0.37), sample_quality_map(0.37)));
  EXPECT_TRUE(same(quality_color(1.0 + 1e-12), sample_quality_map(1.0)));
  EXPECT_TRUE(same(quality_color(-1e-9), kInvertedColor));
  EXPECT_TRUE(same(quality_color(-1.0), kInvertedColor));
  EXPECT_TRUE(same(quality_color(kNaN), kUndefinedColor));
}

TEST(QualityColor, SpecialColoursStandApart) {
  // Grey for NaN, and inverted far from every colour of the map.
  EXPECT_FLOAT_EQ(kUndefinedColor.r, kUndefinedColor.g);
  EXPECT_FLOAT_EQ(kUndefinedColor.g, kUndefinedColor.b);
  for (int i = 0; i <= 100; ++i) {
    EXPECT_GT(distance(kInvertedColor, sample_quality_map(i / 100.0)), 0.9) << i;
    EXPECT_GT(distance(kUndefinedColor, sample_quality_map(i / 100.0)), 0.25) << i;
  }
}

TEST(DivergingColor, BlueWhiteRed) {
  const Color low = diverging_color(-1.0), mid = diverging_color(0.0), high = diverging_color(1.0);
  EXPECT_GT(low.b, low.r);
  EXPECT_GT(high.r, high.b);
  EXPECT_GT(cie_lightness(mid), 95.0);
  EXPECT_TRUE(same(diverging_color(-5.0), low));
  EXPECT_TRUE(same(diverging_color(5.0), high));
  EXPECT_TRUE(same(diverging_color(kNaN), kUndefinedColor));
  // Lightness rises to the middle and falls after it.
  for (int i = 0; i < 50; ++i) {
    EXPECT_LT(cie_lightness(diverging_color(-1.0 + i / 50.0)), cie_lightness(diverging_color(-1.0 + (i + 1) / 50.0)));
    EXPECT_GT(cie_lightness(diverging_color(i / 50.0)), cie_lightness(diverging_color((i + 1) / 50.0)));
  }
}

// The perceptual rules (CIEDE2000 between the palette, the neutral grey,
// the special colours and the quality map; colour vision deficiency) are
// checked in tests/views/palette_test.cpp, which also knows the overlap
// markers' colours; here: the palette is distinct opaque colours, none
// the neutral grey.
TEST(ClusterColor, LabelledColoursAreDistinctAndNotNeutral) {
  std::set<std::tuple<int, int, int>> seen;
  for (int i = 0; i < kLabelledClusterPaletteSize; ++i) {
    const Rgba8 c = to_rgba8(labelled_cluster_color(i));
    EXPECT_EQ(c.a, 255);
    EXPECT_TRUE(seen.insert({c.r, c.g, c.b}).second) << i;
    EXPECT_FALSE(same(labelled_cluster_color(i), neutral_cluster_color())) << i;
  }
}

TEST(ClusterColor, OnlyTheTopClustersWearAColour) {
  // K = 1: rank 0 its own colour, every other rank the neutral tone.
  EXPECT_TRUE(same(cluster_color(0, 1), labelled_cluster_color(0)));
  for (int rank : {1, 2, 9, 500}) EXPECT_TRUE(same(cluster_color(rank, 1), neutral_cluster_color())) << rank;
  // K = 3: ranks 0..2 their own colours, then the neutral tone.
  for (int rank = 0; rank < 3; ++rank) EXPECT_TRUE(same(cluster_color(rank, 3), labelled_cluster_color(rank)));
  for (int rank : {3, 4, 9, 10, 500}) EXPECT_TRUE(same(cluster_color(rank, 3), neutral_cluster_color())) << rank;
  // K = 8 (the default): the palette's 3 (issue 44 part R), then the neutral tone.
  for (int rank = 0; rank < 3; ++rank) EXPECT_TRUE(same(cluster_color(rank, 8), labelled_cluster_color(rank)));
  for (int rank : {3, 4, 5, 6, 7, 8, 500}) EXPECT_TRUE(same(cluster_color(rank, 8), neutral_cluster_color())) << rank;
  EXPECT_TRUE(same(cluster_color(-1, 3), neutral_cluster_color()));
  // K beyond the palette: the palette's first are labelled, never a repeat.
  EXPECT_EQ(labelled_cluster_count(25), kLabelledClusterPaletteSize);
  EXPECT_TRUE(same(cluster_color(kLabelledClusterPaletteSize, 25), neutral_cluster_color()));
  EXPECT_EQ(labelled_cluster_count(0), 0);
}

TEST(CieLightness, KnownValues) {
  EXPECT_NEAR(cie_lightness({0, 0, 0, 1}), 0.0, 1e-9);
  EXPECT_NEAR(cie_lightness({1, 1, 1, 1}), 100.0, 1e-3);
  EXPECT_NEAR(cie_lightness({0.5f, 0.5f, 0.5f, 1}), 53.39, 0.05);
}

}  // namespace
}  // namespace hq
