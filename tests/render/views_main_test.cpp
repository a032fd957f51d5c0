// View A's scene and viewpoint choice, without OpenGL.
#include "hqview/render/views_main.h"

#include <gtest/gtest.h>

#include "hqview/glyph/glyphs.h"
#include "hqview/render/colormap.h"
#include "support/fixtures.h"

namespace hq {
namespace {

// A 3x3x3 grid with one cluster of two glyph vertices (0 and 1) and one
// overlap marker of count 3 at vertex 0.
struct Fixture {
  HexMesh mesh = test::grid(3);
  Topology topology = build_topology(mesh);
  GlyphResult glyphs;
  OverlapReport overlap;
  Fixture() {
    glyphs.vertex_cluster.assign(mesh.points.size(), kNoIndex);
    glyphs.vertex_radius.assign(mesh.points.size(), 0.0);
    glyphs.vertex_cluster[0] = glyphs.vertex_cluster[1] = 0;
    AggregatedGlyph g;
    g.id = 0;
    g.size = 2;
    g.representative_vertex = 0;
    g.position = mesh.points[0];
    g.radius = 0.4;
    glyphs.clusters.push_back(g);
    overlap.markers.push_back({MarkerKind::coincident, mesh.points[0], 3});
    overlap.cell_intersecting.assign(mesh.hexes.size(), 0);
    overlap.cell_intersecting[4] = 1;
  }
};

Camera camera_for(const Fixture& f) {
  return fit_camera_to_points(main_view_points(f.mesh, f.topology, f.glyphs), {-1, -1, -1}, 1.0);
}

TEST(MainScene, LayersHoldWhatTheViewDraws) {
  Fixture f;
  const Scene scene = build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, {});
  ASSERT_EQ(scene.lines.size(), 3u);
  ASSERT_EQ(scene.spheres.size(), 1u);
  ASSERT_EQ(scene.triangles.size(), 1u);
  ASSERT_EQ(scene.translucent.size(), 1u);
  // Boundary wireframe of a 3x3x3 grid: 56 vertices, 54 quads, so 108 edges (Euler).
  EXPECT_EQ(scene.lines[0].indices.size() / 2, 108u);
  for (const Rgba8& c : scene.lines[0].colors) EXPECT_EQ((Rgba8{c.r, c.g, c.b, 255}), kWireframeColor);
  // Cluster edges: every edge at vertex 0 or 1, in cluster 0's colour.
  const Rgba8 cluster0 = to_rgba8(qualitative_color(0));
  std::size_t expected = 0;
  for (const Edge& e : f.topology.edges) expected += (e[0] <= 1 || e[1] <= 1);
  EXPECT_EQ(scene.lines[1].indices.size() / 2, expected);
  for (const Rgba8& c : scene.lines[1].colors) EXPECT_EQ(c, cluster0);
  // One aggregated glyph.
  ASSERT_EQ(scene.spheres[0].centers.size(), 1u);
  EXPECT_FLOAT_EQ(scene.spheres[0].radii[0], 0.4f);
  EXPECT_EQ(scene.spheres[0].colors[0], cluster0);
  // Three arrows, and one intersecting cell (6 quads, 12 triangles) with 12 edges.
  EXPECT_GT(scene.triangles[0].indices.size(), 0u);
  EXPECT_EQ(scene.translucent[0].indices.size(), 36u);
  EXPECT_LT(scene.translucent[0].colors[0].a, 255);
  EXPECT_EQ(scene.lines[2].indices.size() / 2, 12u);
}

TEST(MainScene, WithoutOverlapNoArrowsNoCells) {
  Fixture f;
  const Scene scene = build_main_scene(f.mesh, f.topology, f.glyphs, nullptr, camera_for(f), 600, {});
  EXPECT_TRUE(scene.triangles[0].indices.empty());
  EXPECT_TRUE(scene.translucent[0].indices.empty());
}

TEST(MainScene, ArrowCountFollowsTheMarker) {
  Fixture f;
  const Scene one = build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, {});
  f.overlap.markers[0].count = 6;
  const Scene two = build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, {});
  EXPECT_EQ(2 * one.triangles[0].indices.size(), two.triangles[0].indices.size());
}

TEST(Viewpoints, TwentySixDirections) {
  const auto d = candidate_view_directions();
  ASSERT_EQ(d.size(), 26u);
  for (const Vec3& v : d) EXPECT_NEAR(norm(v), 1.0, 1e-12);
  EXPECT_EQ(viewpoint_name({-1, 0, 0}), "+x");
  EXPECT_EQ(viewpoint_name(normalized(Vec3{-1, 1, -1})), "+x-y+z");
}

TEST(Viewpoints, CoverageGrowsWithSphereSize) {
  Camera camera;
  camera.eye = {0, 0, 10};
  camera.target = {0, 0, 0};
  camera.up = {0, 1, 0};
  const std::vector<Vec3> c{{0, 0, 0}};
  const double small = glyph_coverage(c, std::vector<double>{0.5}, camera, 1.0);
  const double large = glyph_coverage(c, std::vector<double>{1.0}, camera, 1.0);
  EXPECT_GT(small, 0.0);
  EXPECT_NEAR(large / small, 4.0, 0.3);
  // Two spheres one behind the other cover what the front one covers.
  const std::vector<Vec3> stacked{{0, 0, 0}, {0, 0, -3}};
  EXPECT_NEAR(glyph_coverage(stacked, std::vector<double>{1.0, 0.5}, camera, 1.0), large, 1e-12);
}

TEST(Viewpoints, PrefersTheViewThatSeparatesGlyphs) {
  // Two glyphs on a line along z: looking along z they hide each other, from
  // the side both show; the best viewpoint is not along z.
  Fixture f;
  f.glyphs.clusters.clear();
  for (int i = 0; i < 2; ++i) {
    AggregatedGlyph g;
    g.id = i;
    g.position = {1.5, 1.5, 0.5 + 2.0 * i};
    g.radius = 0.5;
    f.glyphs.clusters.push_back(g);
  }
  const auto points = main_view_points(f.mesh, f.topology, f.glyphs);
  const auto chosen = choose_main_viewpoints(points, f.glyphs, 1.0, 2);
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_LT(std::abs(chosen[0].z), 0.99);
  EXPECT_EQ(chosen, choose_main_viewpoints(points, f.glyphs, 1.0, 2)) << "deterministic";
}

}  // namespace
}  // namespace hq
