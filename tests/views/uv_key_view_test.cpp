// The UV key (issue 45): one number per chart, on its own chart in 3D and in
// the atlas, the tints distinct; the figure drawn with the mock renderer.
#include "hqview/views/uv_key_view.h"

#include <gtest/gtest.h>

#include <set>

#include "hqview/uv/uv_atlas.h"
#include "support/surface_fixtures.h"

namespace hq {
namespace {

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

}  // namespace
}  // namespace hq
