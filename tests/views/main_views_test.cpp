// View A's scene and viewpoint choice, without OpenGL.
#include "hqview/views/main_views.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "hqview/glyph/glyphs.h"
#include "hqview/image/colormap.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

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
    glyphs.cluster_offsets = {0, 2};
    glyphs.cluster_vertices = {0, 1};
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

// Many more clusters than K: every vertex of a 4x4x4 grid is a cluster of
// its own (rank = vertex id), K = 3; the palette colours min(K, its size)
// = 3 of them.
TEST(MainScene, OnlyTheTopClustersAreColouredTheRestAreNeutral) {
  HexMesh mesh = test::grid(4);
  const Topology topology = build_topology(mesh);
  GlyphResult glyphs;
  glyphs.options.top_clusters = 3;
  const auto n = static_cast<Index>(mesh.points.size());
  glyphs.vertex_cluster.resize(mesh.points.size());
  glyphs.vertex_radius.assign(mesh.points.size(), 0.1);
  for (Index v = 0; v < n; ++v) {
    glyphs.vertex_cluster[v] = v;
    glyphs.cluster_offsets.push_back(v);
    glyphs.cluster_vertices.push_back(v);
    AggregatedGlyph g;
    g.id = v, g.size = 1, g.representative_vertex = v, g.position = mesh.points[v], g.radius = 0.1;
    g.min_quality = 0.01 * v;  // no ties (glyph_tie_classes)
    glyphs.clusters.push_back(g);
  }
  glyphs.cluster_offsets.push_back(n);
  const Camera camera = fit_camera_to_points(main_view_points(mesh, topology, glyphs), {-1, -2, -3}, 1.0);
  const Scene scene = build_main_scene(mesh, topology, glyphs, nullptr, camera, 600, {});
  const Rgba8 neutral = to_rgba8(neutral_cluster_color());
  const Index coloured = labelled_cluster_count(3);
  ASSERT_EQ(coloured, 3);
  // The coloured (ranked) glyphs in the set drawn over the grey ones; the grey
  // ones but those left out where they pile up on screen.
  const GlyphsDrawn shown = main_view_glyphs_drawn(
      glyphs, camera, 600, displayed_glyph_radii(glyphs, displayed_glyph_scale(glyphs, camera, 600, 1.0)));
  ASSERT_EQ(scene.spheres.size(), 3u);
  ASSERT_EQ(scene.spheres[1].colors.size(), static_cast<std::size_t>(coloured));
  EXPECT_TRUE(scene.spheres[2].colors.empty());  // no grey one below 0.01
  ASSERT_EQ(scene.spheres[0].colors.size(), static_cast<std::size_t>(n - coloured - shown.num_left_out));
  EXPECT_GT(scene.spheres[0].colors.size(), static_cast<std::size_t>(n) / 2);
  std::size_t grey = 0;
  for (Index v = 0; v < n; ++v) {
    if (!shown.drawn[static_cast<std::size_t>(v)]) continue;
    const Rgba8 expected = v < coloured ? to_rgba8(labelled_cluster_color(v)) : neutral;
    const Rgba8 drawn = v < coloured ? scene.spheres[1].colors[static_cast<std::size_t>(v)] : scene.spheres[0].colors[grey++];
    EXPECT_EQ(drawn, expected) << v;
  }
  // Edge colours: the lower-ranked endpoint's cluster decides; edges only
  // at the coloured clusters' vertices (issue 44's fifth round: the grey
  // clusters' edges veiled the model).
  std::size_t i = 0;
  for (const Edge& e : topology.edges) {
    const Index rank = std::min(e[0], e[1]);
    if (rank >= coloured) continue;
    ASSERT_LT(2 * i, scene.lines[1].colors.size());
    EXPECT_EQ(scene.lines[1].colors[2 * i], to_rgba8(labelled_cluster_color(rank))) << e[0] << "-" << e[1];
    ++i;
  }
  EXPECT_EQ(scene.lines[1].colors.size(), 2 * i);
}

// The distances between the cluster colours and the overlap markers' and
// wireframe's colours: tests/views/palette_test.cpp (CIEDE2000).

TEST(MainScene, ClusterEdgesCircleOnlyTheWorstVerticesOfABigCluster) {
  HexMesh mesh = test::grid(4);
  GlyphResult glyphs;
  glyphs.vertex_cluster.assign(mesh.points.size(), 0);
  glyphs.vertex_radius.resize(mesh.points.size());
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    glyphs.vertex_radius[v] = static_cast<double>((v * 37) % mesh.points.size());  // a permutation of 0..n-1
    glyphs.cluster_vertices.push_back(static_cast<Index>(v));
  }
  glyphs.cluster_offsets = {0, static_cast<Index>(mesh.points.size())};
  const std::vector<std::uint8_t> marked = worst_cluster_vertices(glyphs, 5);
  ASSERT_EQ(marked.size(), mesh.points.size());
  EXPECT_EQ(std::count(marked.begin(), marked.end(), 1), 5);
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    EXPECT_EQ(marked[v] != 0, glyphs.vertex_radius[v] >= static_cast<double>(mesh.points.size() - 5)) << v;
}

TEST(MainScene, LayersHoldWhatTheViewDraws) {
  Fixture f;
  const Scene scene = build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, {});
  ASSERT_EQ(scene.lines.size(), 3u);
  ASSERT_EQ(scene.spheres.size(), 3u);  // pale grey glyphs, the ranked ones over them, unfaded grey ones
  EXPECT_FALSE(scene.spheres[0].over_other_spheres);
  EXPECT_TRUE(scene.spheres[1].over_other_spheres);
  EXPECT_FALSE(scene.spheres[2].over_other_spheres);
  EXPECT_GT(scene.spheres[0].pale, 0.0f);
  EXPECT_EQ(scene.spheres[2].pale, 0.0f);
  ASSERT_TRUE(scene.triangles.empty());
  ASSERT_EQ(scene.overlay.size(), 1u);
  ASSERT_EQ(scene.translucent.size(), 1u);
  // Boundary wireframe of a 3x3x3 grid: 56 vertices, 54 quads, so 108 edges
  // (Euler), less the 4 of the intersecting cell's boundary face (cell 4,
  // the bottom centre: drawn in the intersection colour in lines[2]).
  EXPECT_EQ(scene.lines[0].indices.size() / 2, 104u);
  for (const Rgba8& c : scene.lines[0].colors) EXPECT_EQ((Rgba8{c.r, c.g, c.b, 255}), kWireframeColor);
  // Cluster edges: every edge at vertex 0 or 1, in cluster 0's colour.
  const Rgba8 cluster0 = to_rgba8(labelled_cluster_color(0));
  std::size_t expected = 0;
  for (const Edge& e : f.topology.edges) expected += (e[0] <= 1 || e[1] <= 1);
  EXPECT_EQ(scene.lines[1].indices.size() / 2, expected);
  for (const Rgba8& c : scene.lines[1].colors) EXPECT_EQ(c, cluster0);
  // One aggregated glyph, ranked: in the set drawn over the grey ones.
  EXPECT_TRUE(scene.spheres[0].centers.empty());
  ASSERT_EQ(scene.spheres[1].centers.size(), 1u);
  EXPECT_FLOAT_EQ(scene.spheres[1].radii[0], 0.4f);
  EXPECT_EQ(scene.spheres[1].colors[0], cluster0);
  // Three arrows (in the overlay), and one intersecting cell (6 quads, 12 triangles) with 12 edges.
  EXPECT_GT(scene.overlay[0].indices.size(), 0u);
  EXPECT_EQ(scene.translucent[0].indices.size(), 36u);
  EXPECT_LT(scene.translucent[0].colors[0].a, 255);
  EXPECT_EQ(scene.lines[2].indices.size() / 2, 12u);
}

TEST(MainScene, WithoutOverlapNoArrowsNoCells) {
  Fixture f;
  const Scene scene = build_main_scene(f.mesh, f.topology, f.glyphs, nullptr, camera_for(f), 600, {});
  EXPECT_TRUE(scene.overlay[0].indices.empty());
  EXPECT_TRUE(scene.translucent[0].indices.empty());
}

TEST(MainScene, ArrowCountFollowsTheMarker) {
  Fixture f;
  const Scene one = build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, {});
  f.overlap.markers[0].count = 6;
  const Scene two = build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, {});
  EXPECT_EQ(2 * one.overlay[0].indices.size(), two.overlay[0].indices.size());
}

// Looking down -z, orthographic, 100 model units over a 100-pixel-high view:
// one model unit per pixel, screen x = model x, screen y = model y.
Camera pixel_camera() {
  Camera camera;
  camera.eye = {0, 0, 10};
  camera.target = {0, 0, 0};
  camera.up = {0, 1, 0};
  camera.ortho_height = 100.0;
  camera.is_perspective = false;
  return camera;
}

TEST(MarkerMerge, CloseMarkersBecomeOneWithTheirCounts) {
  // Markers merge with the first anchor of their own kind within 25 pixels.
  // Coincident at pixel 0; intersections at 10 (10 from the coincident one:
  // another kind, so its own marker), 30 (20 from 10: merged), 40 (30 from
  // the anchor at 10: its own); coincident at 20 (merged with 0), 100.
  const std::vector<OverlapMarker> markers{{MarkerKind::coincident, {0, 0, 0}, 2},
                                           {MarkerKind::intersection, {10, 0, 5}, 3},
                                           {MarkerKind::intersection, {30, 0, 0}, 1},
                                           {MarkerKind::intersection, {40, 0, 0}, 6},
                                           {MarkerKind::coincident, {20, 0, 0}, 7},
                                           {MarkerKind::coincident, {100, 0, -5}, 4}};
  const auto drawn = merge_markers_on_screen(markers, pixel_camera(), 100, 25.0);
  ASSERT_EQ(drawn.size(), 4u);
  EXPECT_EQ(drawn[0].kind, MarkerKind::coincident);
  EXPECT_EQ(drawn[0].members, 2);
  EXPECT_EQ(drawn[0].coincident, 9);
  EXPECT_EQ(drawn[0].intersections, 0);
  EXPECT_EQ(drawn[0].position, markers[0].position) << "anchored at the first member";
  EXPECT_EQ(drawn[1].kind, MarkerKind::intersection);
  EXPECT_EQ(drawn[1].members, 2);
  EXPECT_EQ(drawn[1].intersections, 4);
  EXPECT_EQ(drawn[1].coincident, 0);
  EXPECT_EQ(drawn[2].intersections, 6);
  EXPECT_EQ(drawn[3].coincident, 4);
  // Depth does not matter in an orthographic view; no merging at 0 pixels.
  EXPECT_EQ(merge_markers_on_screen(markers, pixel_camera(), 100, 0.0).size(), 6u);
  // Half the pixels per unit: 30 units are 15 pixels, all intersections merge.
  EXPECT_EQ(merge_markers_on_screen(markers, pixel_camera(), 50, 25.0).size(), 3u);
}

TEST(MarkerMerge, DrawnMarkersAreApartAndKeepEveryFinding) {
  // A crowded pseudo-random cloud (fixed LCG): drawn anchors are pairwise at
  // least min_pixels apart, every marker lies within min_pixels of some
  // anchor, and the findings add up.
  std::vector<OverlapMarker> markers;
  std::uint32_t state = 12345;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24);
  };
  Index total = 0;
  for (int i = 0; i < 500; ++i) {
    const Index count = 1 + static_cast<Index>(next() * 5);
    total += count;
    markers.push_back({next() < 0.3 ? MarkerKind::coincident : MarkerKind::intersection,
                       {100 * next() - 50, 100 * next() - 50, 10 * next()},
                       count});
  }
  const double d = 12.0;
  const auto drawn = merge_markers_on_screen(markers, pixel_camera(), 100, d);
  ASSERT_LT(drawn.size(), markers.size());
  Index sum = 0, members = 0;
  for (const ScreenMarker& m : drawn) {
    sum += m.count();
    members += m.members;
  }
  EXPECT_EQ(sum, total);
  EXPECT_EQ(members, static_cast<Index>(markers.size()));
  for (const ScreenMarker& m : drawn)  // one kind per drawn marker
    EXPECT_EQ(m.kind == MarkerKind::coincident ? m.intersections : m.coincident, 0);
  for (std::size_t i = 0; i < drawn.size(); ++i)
    for (std::size_t j = i + 1; j < drawn.size(); ++j)
      if (drawn[i].kind == drawn[j].kind)
        EXPECT_GE(std::hypot(drawn[i].position.x - drawn[j].position.x, drawn[i].position.y - drawn[j].position.y),
                  d);
  for (const OverlapMarker& m : markers)
    EXPECT_TRUE(std::any_of(drawn.begin(), drawn.end(), [&](const ScreenMarker& a) {
      return a.kind == m.kind && std::hypot(a.position.x - m.position.x, a.position.y - m.position.y) < d;
    }));
}

// Triangles of the arrows in the scene that have the given colour.
std::size_t arrow_triangles(const Scene& scene, Rgba8 color) {
  const TriangleSet& set = scene.overlay[0];  // the arrows
  std::size_t n = 0;
  for (std::size_t t = 0; t + 2 < set.indices.size(); t += 3) n += set.colors[set.indices[t]] == color;
  return n;
}

TEST(MainScene, CrowdedMarkersShareOneFanOfArrows) {
  Fixture f;
  // One intersection marker of count 1 gives the triangles of one arrow.
  f.overlap.markers = {{MarkerKind::intersection, f.mesh.points[0], 1}};
  const std::size_t per_arrow =
      build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, {}).overlay[0].indices.size() / 3;
  ASSERT_GT(per_arrow, 0u);
  // Two markers of 8 a hair apart: one fan of at most 12 arrows, not 16.
  const Vec3 p = f.mesh.points[0];
  f.overlap.markers = {{MarkerKind::intersection, p, 8}, {MarkerKind::intersection, p + Vec3{1e-3, 0, 0}, 8}};
  const Scene merged = build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, {});
  EXPECT_EQ(merged.overlay[0].indices.size() / 3, 12 * per_arrow);
  MainViewOptions apart;
  apart.marker_merge_pixels = 0.0;
  const Scene separate = build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, apart);
  EXPECT_EQ(separate.overlay[0].indices.size() / 3, 16 * per_arrow);
  // Mixed kinds: 3 coincident and 1 intersection findings, 4 arrows, 3 of
  // them in the coincident colour.
  f.overlap.markers = {{MarkerKind::coincident, p, 3}, {MarkerKind::intersection, p + Vec3{1e-3, 0, 0}, 1}};
  const Scene mixed = build_main_scene(f.mesh, f.topology, f.glyphs, &f.overlap, camera_for(f), 600, {});
  EXPECT_EQ(arrow_triangles(mixed, kCoincidentArrowColor), 3 * per_arrow);
  EXPECT_EQ(arrow_triangles(mixed, kIntersectionArrowColor), per_arrow);
}

TEST(Viewpoints, NamesSayWhereTheEyeSits) {
  const Vec3 up{0, 1, 0};
  EXPECT_EQ(viewpoint_name(upright_view_direction(up, 30.0, 25.0), up), "azimuth 30, elevation 25 deg");
  EXPECT_EQ(viewpoint_name(upright_view_direction(up, -90.0, 15.0), up), "azimuth 270, elevation 15 deg");
  EXPECT_EQ(viewpoint_name({0, 1, 0}, up), "straight below");
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
  // z up: every candidate looks from 15-35 degrees above; from the side
  // both show.
  const Vec3 up{0, 0, 1};
  const auto chosen = choose_main_viewpoints(points, f.glyphs, 1.0, 2, up);
  ASSERT_EQ(chosen.size(), 2u);
  for (const Vec3& d : chosen) {
    EXPECT_GE(view_elevation_degrees(d, up), 15.0 - 1e-9);
    EXPECT_LE(view_elevation_degrees(d, up), 35.0 + 1e-9);
  }
  // The second view looks from the other side (90 degrees of azimuth or more).
  const double gap = std::abs(std::remainder(view_azimuth_degrees(chosen[0], up) - view_azimuth_degrees(chosen[1], up), 360.0));
  EXPECT_GE(gap, 90.0 - 1e-9);
  EXPECT_EQ(chosen, choose_main_viewpoints(points, f.glyphs, 1.0, 2, up)) << "deterministic";
  // x up: the glyphs' line (along z) is horizontal; the chosen view looks
  // across it (azimuth near +-90, where the eye is on the y axis), not along it.
  const Vec3 x_up{1, 0, 0};
  const Vec3 across = choose_main_viewpoints(points, f.glyphs, 1.0, 1, x_up).at(0);
  EXPECT_LT(std::abs(across.z), 0.6);
}

TEST(Viewpoints, WithoutSpheresTheThreeQuarterViews) {
  const Vec3 up{0, 0, 1};
  const std::vector<Vec3> points{{0, 0, 0}, {1, 1, 1}};
  const auto none = choose_viewpoints(points, {}, {}, 1.0, 2, up);
  ASSERT_EQ(none.size(), 2u);
  EXPECT_EQ(none[0], three_quarter_view(up));
  EXPECT_EQ(none[1], three_quarter_back_view(up));
  // One sphere: every upright view shows it; the choice is an upright one.
  const std::vector<Vec3> centers{{0.5, 0.5, 0.5}};
  const std::vector<double> radii{0.2};
  const Vec3 d = choose_viewpoints(points, centers, radii, 1.0, 1, up).at(0);
  EXPECT_GE(view_elevation_degrees(d, up), 15.0 - 1e-9);
  EXPECT_LE(view_elevation_degrees(d, up), 35.0 + 1e-9);
}

}  // namespace
}  // namespace hq
