// Tie classes of ranked glyph clusters (issue 44 part T), from hand-made
// rankings: the tolerance's boundary, the sign rule, NaN, chaining.
#include "hqview/glyph/glyph_ties.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace hq {
namespace HQ_TEST_UNIT {

std::vector<AggregatedGlyph> ranked(const std::vector<double>& min_quality) {
  std::vector<AggregatedGlyph> clusters;
  for (std::size_t i = 0; i < min_quality.size(); ++i) {
    AggregatedGlyph g;
    g.id = static_cast<Index>(i);
    g.min_quality = min_quality[i];
    clusters.push_back(g);
  }
  return clusters;
}

TEST(GlyphTies, EqualWorstValuesFormOneClass) {
  // A Gmsh star's 96 clusters at one value: one class.
  const std::vector<Index> classes = glyph_tie_classes(ranked(std::vector<double>(96, 0.2105)));
  EXPECT_EQ(classes, std::vector<Index>(96, 0));
  EXPECT_EQ(tie_class_sizes(classes), std::vector<Index>{96});
}

TEST(GlyphTies, ToleranceIsMeasuredFromTheClassesFirstMember) {
  // 0.1000, 0.1009 tie (0.0009 <= 0.001); 0.1015 is 0.0015 from the first,
  // so it starts a class even though it is 0.0006 from the second (no
  // chaining: a class spans at most the tolerance).
  const std::vector<Index> classes = glyph_tie_classes(ranked({0.1, 0.1009, 0.1015, 0.1020, 0.3}));
  EXPECT_EQ(classes, (std::vector<Index>{0, 0, 1, 1, 2}));
  EXPECT_EQ(tie_class_sizes(classes), (std::vector<Index>{2, 2, 1}));
  // Just outside the tolerance: no tie.
  EXPECT_EQ(glyph_tie_classes(ranked({0.5, 0.5 + 1.5 * kGlyphTieTolerance})), (std::vector<Index>{0, 1}));
  // A tolerance of 0 ties exact equals only.
  EXPECT_EQ(glyph_tie_classes(ranked({0.2, 0.2, 0.2000001}), 0.0), (std::vector<Index>{0, 0, 1}));
}

TEST(GlyphTies, InvertedNeverTiesPoor) {
  // -0.0004 and 0.0003 are 0.0007 apart but on both sides of 0.
  EXPECT_EQ(glyph_tie_classes(ranked({-0.0004, 0.0003, 0.0005})), (std::vector<Index>{0, 1, 1}));
  // A mirrored mesh: every cluster at -0.999.
  EXPECT_EQ(glyph_tie_classes(ranked({-0.999, -0.999, -0.9989, -0.5})), (std::vector<Index>{0, 0, 0, 1}));
}

TEST(GlyphTies, NanNeverTiesAndNoClustersNoClasses) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(glyph_tie_classes(ranked({0.1, nan, nan})), (std::vector<Index>{0, 1, 2}));
  EXPECT_TRUE(glyph_tie_classes(ranked({})).empty());
  EXPECT_TRUE(tie_class_sizes({}).empty());
}

TEST(GlyphTies, ColouredClassesStopAtTheGlyphCap) {
  // The Gmsh star's classes (30, 6, 18, 2, 6, 1): only the first is coloured
  // (30 > 12 but the first always is); 1, 1, 1, ...: the palette's 6.
  EXPECT_EQ(coloured_tie_classes(std::vector<Index>{30, 6, 18, 2, 6, 1}, 6), 1);
  EXPECT_EQ(coloured_tie_classes(std::vector<Index>(10, 1), 6), 6);
  // 4 + 5 = 9 <= 12, + 4 = 13 > 12: two classes.
  EXPECT_EQ(coloured_tie_classes(std::vector<Index>{4, 5, 4, 1}, 6), 2);
  EXPECT_EQ(coloured_tie_classes(std::vector<Index>{4, 5, 3, 1}, 6), 3);  // exactly 12
  EXPECT_EQ(coloured_tie_classes(std::vector<Index>{2, 2}, 0), 0);
  EXPECT_EQ(coloured_tie_classes(std::vector<Index>{}, 6), 0);
  // Slots: the class when coloured, else -1.
  EXPECT_EQ(glyph_colour_slots(ranked({0.1, 0.1, 0.2, 0.3}), 2), (std::vector<Index>{0, 0, 1, -1}));
  std::vector<double> star(13, 0.21);
  star.push_back(0.3);
  std::vector<Index> expected(13, 0);  // 13 tied at 0.21: coloured (the first class), the next grey
  expected.push_back(-1);
  EXPECT_EQ(glyph_colour_slots(ranked(star), 6), expected);
}

}  // namespace
}  // namespace hq
