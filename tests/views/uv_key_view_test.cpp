// The UV key (issue 45): one number per chart, on its own chart in 3D and in
// the atlas, the tints distinct; the figure drawn with the mock renderer.
#include "hqview/views/uv_key_view.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "hqview/render/label_layout.h"
#include "hqview/render/osmesa_renderer.h"
#include "support/fixtures.h"
#include <memory>

#include "hqview/uv/uv_atlas.h"
#include "support/surface_fixtures.h"
#include "uv_key_checks.h"

namespace hq {
namespace HQ_TEST_UNIT {

// Is point p inside triangle (a, b, c) of the plane (either orientation)?
bool inside(const std::array<double, 2>& p, const Uv& a, const Uv& b, const Uv& c) {
  const auto side = [&](const Uv& u, const Uv& v) { return (v[0] - u[0]) * (p[1] - u[1]) - (v[1] - u[1]) * (p[0] - u[0]); };
  const double d1 = side(a, b), d2 = side(b, c), d3 = side(c, a);
  return (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
}

TEST(UvKey, EveryChartHasOneLabelOnItsOwnChart) {
  const TriSurface surface = test::icosphere(3);
  const UvAtlas atlas = build_uv_atlas(surface, UvOptions{});
  ASSERT_GT(atlas.num_charts, 3);
  const std::vector<UvChartLabel> labels = uv_chart_labels(surface, atlas);
  ASSERT_EQ(labels.size(), static_cast<std::size_t>(atlas.num_charts));
  std::set<Index> charts;
  for (const UvChartLabel& l : labels) {
    charts.insert(l.chart);
    // The 3D anchor is the centroid of a triangle of that chart.
    ASSERT_NE(l.triangle, kNoIndex);
    EXPECT_EQ(atlas.triangle_chart[static_cast<std::size_t>(l.triangle)], l.chart);
    const auto& t = surface.triangles[static_cast<std::size_t>(l.triangle)];
    const Vec3 centroid = (surface.points[static_cast<std::size_t>(t[0])] + surface.points[static_cast<std::size_t>(t[1])] +
                           surface.points[static_cast<std::size_t>(t[2])]) / 3.0;
    EXPECT_LT(norm(centroid - l.position), 1e-12);
    EXPECT_NEAR(norm(l.normal), 1.0, 1e-9);
    // The UV anchor lies inside a UV triangle of that chart.
    const std::size_t u = static_cast<std::size_t>(l.uv_triangle);
    EXPECT_EQ(atlas.triangle_chart[u], l.chart);
    EXPECT_TRUE(inside(l.uv, atlas.uvs[3 * u], atlas.uvs[3 * u + 1], atlas.uvs[3 * u + 2]));
  }
  EXPECT_EQ(charts.size(), labels.size());  // one each
}

TEST(UvKey, NeighbouringChartIdsGetDistinctTints) {
  std::set<std::uint32_t> seen;
  for (Index c = 0; c < 12; ++c) {
    const Rgba8 t = chart_tint(c);
    EXPECT_GT(int(t.r) + t.g + t.b, 3 * 150) << c;  // light
    seen.insert(std::uint32_t(t.r) << 16 | std::uint32_t(t.g) << 8 | t.b);
  }
  EXPECT_EQ(seen.size(), 12u);
}

// Chart numbers never overlap (issue 45: on the hand's fingers 9, 10 and 11
// were drawn on top of each other): each sits centred on its anchor when
// that is free, else next to it (within the leader distance) or joined to
// it by a leader line; the boxes are pairwise disjoint and inside the frame.
void expect_disjoint_and_near(const std::vector<UvKeyNumberAnchor>& anchors, const std::vector<UvKeyNumber>& numbers,
                              const PixelRect& frame, const AnnotationStyle& style) {
  ASSERT_EQ(numbers.size(), anchors.size());
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    const UvKeyNumber& n = numbers[i];
    EXPECT_EQ(n.chart, anchors[i].chart);
    ASSERT_TRUE(n.placed) << "chart " << n.chart;
    EXPECT_GE(n.box.x, frame.x);
    EXPECT_GE(n.box.y, frame.y);
    EXPECT_LE(n.box.x + n.box.width, frame.x + frame.width);
    EXPECT_LE(n.box.y + n.box.height, frame.y + frame.height);
    for (std::size_t j = 0; j < i; ++j) {
      if (numbers[j].placed) {
        EXPECT_FALSE(boxes_overlap(n.box, numbers[j].box)) << n.chart << " and " << numbers[j].chart;
      }
    }
    const ScreenDisc anchor{double(n.anchor_x), double(n.anchor_y), 1.0};
    const bool on_anchor = box_meets_disc(n.box, anchor);
    if (!on_anchor && !n.has_leader) {
      EXPECT_LE(disc_box_gap(anchor, n.box), 10.0 * style.scale) << n.chart;
    }
  }
}

TEST(UvKey, NumbersOfACrowdedFrameAreDisjointAndNextToTheirCharts) {
  const AnnotationStyle style = annotation_style_for(1200);
  const PixelRect frame{100, 50, 400, 300};
  std::vector<UvKeyNumberAnchor> anchors;
  for (Index c = 0; c < 30; ++c) anchors.push_back({c, 290 + static_cast<int>(c % 6) * 5, 190 + static_cast<int>(c / 6) * 5});
  anchors.push_back({30, 498, 52});  // at the frame's corner: its box is moved inside
  const std::vector<UvKeyNumber> numbers = place_uv_key_numbers(anchors, frame, 22, style);
  expect_disjoint_and_near(anchors, numbers, frame, style);
  // The first is centred on its anchor (nothing was in its way).
  EXPECT_NEAR(numbers[0].box.x + numbers[0].box.width / 2.0, 290, 1.0);
  EXPECT_NEAR(numbers[0].box.y + numbers[0].box.height / 2.0, 190, 1.0);
  EXPECT_FALSE(numbers[0].has_leader);
  int leaders = 0;
  for (const UvKeyNumber& n : numbers) leaders += n.has_leader;
  EXPECT_GT(leaders, 0);  // 30 numbers in a 25 x 20 px patch cannot all sit next to it
}

TEST(UvKey, NumbersOfARealAtlasInASmallFrameAreDisjoint) {
  const TriSurface surface = test::icosphere(3);
  const UvAtlas atlas = build_uv_atlas(surface, UvOptions{});
  const AnnotationStyle style = annotation_style_for(1200);
  const PixelRect frame{0, 0, 160, 160};
  std::vector<UvKeyNumberAnchor> anchors;
  for (const UvChartLabel& l : uv_chart_labels(surface, atlas))
    anchors.push_back({l.chart, static_cast<int>(std::lround(l.uv[0] * 160)), static_cast<int>(std::lround((1 - l.uv[1]) * 160))});
  ASSERT_GT(anchors.size(), 3u);
  expect_disjoint_and_near(anchors, place_uv_key_numbers(anchors, frame, 22, style), frame, style);
}

}  // namespace
}  // namespace hq

namespace hq {
namespace HQ_TEST_UNIT {

TEST(UvKeyFigure, NumbersLieOnTheirChartsOrLeadToThem) {
  const TriSurface surface = test::icosphere(3);
  const UvAtlas atlas = build_uv_atlas(surface, UvOptions{});
  expect_numbers_on_their_charts(surface, atlas, atlas.num_charts);
}

}  // namespace
}  // namespace hq

namespace hq {
namespace HQ_TEST_UNIT {

// Issue 45d: a chart in several pieces in the atlas is numbered on each:
// two 100 x 100 squares of chart 3 joined by a 4-pixel neck (lobes), a
// third square apart (an island), and a 2 x 2 speck (under 2 %: none).
TEST(UvKeyAnchors, EveryIslandAndLobeOfAChartInTheAtlasIsNumbered) {
  ChartIdImage ids;
  ids.width = 400;
  ids.height = 150;
  ids.ids.assign(static_cast<std::size_t>(ids.width) * ids.height, kNoIndex);
  auto fill = [&](int x0, int y0, int w, int h) {
    for (int y = y0; y < y0 + h; ++y)
      for (int x = x0; x < x0 + w; ++x) ids.ids[static_cast<std::size_t>(y) * ids.width + x] = 3;
  };
  fill(10, 20, 100, 100);
  fill(110, 68, 20, 4);  // the neck
  fill(130, 20, 100, 100);
  fill(260, 20, 100, 100);
  fill(380, 140, 2, 2);
  const std::vector<UvKeyNumberAnchor> one = visible_chart_anchors(ids, 0, 0, 1);
  ASSERT_EQ(one.size(), 1u) << "without islands: one number per chart";
  const std::vector<UvKeyNumberAnchor> all = visible_chart_anchors(ids, 0, 0, 1, true);
  ASSERT_EQ(all.size(), 3u);
  std::set<int> squares;
  for (const UvKeyNumberAnchor& a : all) {
    EXPECT_EQ(a.chart, 3);
    EXPECT_GE(a.room, 40) << "anchored inside a square, not on the neck";
    squares.insert(a.x < 110 ? 0 : a.x < 240 ? 1 : 2);
  }
  EXPECT_EQ(squares.size(), 3u) << "one number on each square";
}

}  // namespace
}  // namespace hq
