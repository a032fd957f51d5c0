// Views C and D of a surface mesh (issue 47 item 7): a hand-built planar
// 4 x 4 quad grid whose vertex (2, 2) is pushed through the opposite corner
// (3, 3) of its quad, folding the quads around it. D of that vertex labels
// each of its four quads' corners with the corner's signed scaled Jacobian
// (computed here by hand against the grid's normal), each label next to
// its corner's disc, the disc where the corner is on screen; the camera
// looks along the plane's normal. C of cluster #0 draws the cluster's
// faces, filled by their cell scaled Jacobian.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "hqview/image/colormap.h"
#include "hqview/pipeline/analyze.h"
#include "hqview/render/camera.h"
#include "hqview/render/label_layout.h"
#include "hqview/render/osmesa_renderer.h"
#include "hqview/views/detail_views.h"
#include "hqview/views/main_views.h"
#include "hqview/views/surface_views.h"
#include "hqview/views/views.h"
#include "io/temp_dir.h"

namespace hq {
namespace HQ_TEST_UNIT {

constexpr int kN = 4;  // quads a side
constexpr Index kPushed = 2 + (kN + 1) * 2;

// pushed: where the vertex (2, 2) goes; by default through (3, 3).
std::vector<Vec3> grid_points(const Vec3& pushed = {3.4, 3.3, 0.0}) {
  std::vector<Vec3> p;
  for (int j = 0; j <= kN; ++j)
    for (int i = 0; i <= kN; ++i) p.push_back({double(i), double(j), 0.0});
  p[static_cast<std::size_t>(kPushed)] = pushed;
  return p;
}

// turn: each quad's corner list starts `turn` corners on (the same quads).
std::string grid_obj(const std::vector<Vec3>& p, int turn = 0) {
  std::ostringstream out;
  for (const Vec3& x : p) out << "v " << x.x << ' ' << x.y << ' ' << x.z << '\n';
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const int a = 1 + i + (kN + 1) * j;
      const std::array<int, 4> f{a, a + 1, a + kN + 2, a + kN + 1};
      out << 'f';
      for (int k = 0; k < 4; ++k) out << ' ' << f[static_cast<std::size_t>((k + turn) % 4)];
      out << '\n';
    }
  return out.str();
}

// By hand: the corner at a of the planar quad (prev, a, next), against +z
// (the majority of the grid's quads turn counter-clockwise about +z).
double corner_by_hand(const Vec3& prev, const Vec3& a, const Vec3& next) {
  const Vec3 e1 = next - a, e2 = prev - a;
  return (e1.x * e2.y - e1.y * e2.x) / (norm(e1) * norm(e2));
}

struct Fixture {
  Analysis a;
  DetailViewOptions options;
};

Fixture folded_grid(const test::TempDir& dir, int turn = 0, const Vec3& pushed = {3.4, 3.3, 0.0}) {
  AnalyzeOptions run;
  run.mesh_path = dir.write("fold.obj", grid_obj(grid_points(pushed), turn));
  run.tool_version = "test";
  Fixture f{analyze_mesh(run), {}};
  f.options.width = 800, f.options.height = 600;
  f.options.view_direction = planar_view_direction(f.a);
  f.options.cell_quality = f.a.field.cell_scaled_jacobian;
  return f;
}

TEST(SurfaceDetailViews, PlanarFoldOneRingLabelsEachCornerAtItsCorner) {
  const test::TempDir dir("surface_detail_views");
  // Through (3, 3), and just past it: there quad 10's reflex corner (3, 3)
  // is 0.14 from the vertex and 45% of the way to its centre lies outside it.
  for (const Vec3& pushed : {Vec3{3.4, 3.3, 0.0}, Vec3{3.1, 3.1, 0.0}}) {
    SCOPED_TRACE("pushed to (" + std::to_string(pushed.x) + ", " + std::to_string(pushed.y) + ")");
    const Fixture f = folded_grid(dir, 0, pushed);
    const Analysis& a = f.a;
    ASSERT_TRUE(a.mesh_summary.planarity && a.mesh_summary.planarity->is_planar);
    ASSERT_TRUE(f.options.view_direction);
    EXPECT_NEAR(std::abs(f.options.view_direction->z), 1.0, 1e-12);  // flat, from above

    const LocalShot shot = local_shot(a.mesh, a.topology, a.field.corner_scaled_jacobian, kPushed, f.options);
    // The camera: orthographic, along the normal.
    EXPECT_FALSE(shot.camera.is_perspective);
    const Vec3 look = normalized(shot.camera.target - shot.camera.eye);
    EXPECT_NEAR(std::abs(look.z), 1.0, 1e-9);

    // The four quads at the vertex, each corner's value by hand.
    const std::vector<Vec3> p = grid_points(pushed);
    const std::vector<VertexCorner> corners = vertex_corners(a.mesh, a.topology, a.field.corner_scaled_jacobian, kPushed);
    ASSERT_EQ(corners.size(), 4u);
    ASSERT_EQ(shot.labels.size(), 4u);
    int inverted = 0;
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const VertexCorner& c = corners[i];
      SCOPED_TRACE("quad " + std::to_string(c.hex));
      EXPECT_EQ(c.kind, CellKind::quad);
      const auto& q = a.mesh.quads.at(static_cast<std::size_t>(c.hex));
      ASSERT_EQ(q[static_cast<std::size_t>(c.local)], kPushed);
      const auto at = [&](int k) { return p[static_cast<std::size_t>(q[static_cast<std::size_t>((k + 4) % 4)])]; };
      const double expected = corner_by_hand(at(c.local - 1), at(c.local), at(c.local + 1));
      EXPECT_NEAR(c.value, expected, 1e-12);
      const LocalLabel& l = shot.labels[i];
      EXPECT_NEAR(l.value, expected, 1e-12);
      EXPECT_EQ(l.is_inverted, expected < 0.0);
      inverted += expected < 0.0;
      // A ring of 4: every corner labelled in full, "-0.873  quad 10".
      ASSERT_TRUE(l.placed);
      EXPECT_EQ(l.number, 0);
      char value[32];
      std::snprintf(value, sizeof value, "%.3f", expected);
      EXPECT_EQ(l.text, std::string(value) + "  quad " + std::to_string(c.hex));
      // Its disc where its corner is: inside its own quad as projected (even-odd
      // rule, so a folded quad's own region), nearer its corner than the
      // corner's shorter edge is long (47g review #2: a reversed quad's disc
      // 45% of the way to the centre lay outside the quad).
      const PixelRect& view = shot.layout.view;
      const auto screen = [&](const Vec3& at_model) {
        const Vec3 ndc = project_to_ndc(shot.camera, double(view.width) / view.height, at_model);
        return std::array<double, 2>{view.x + 0.5 * (ndc.x + 1.0) * view.width, view.y + 0.5 * (1.0 - ndc.y) * view.height};
      };
      const double x = l.marker.x, y = l.marker.y;
      bool inside = false;
      for (int k = 0; k < 4; ++k) {
        const auto [x0, y0] = screen(at(k));
        const auto [x1, y1] = screen(at(k + 1));
        if ((y0 > y) != (y1 > y) && x < x0 + (y - y0) / (y1 - y0) * (x1 - x0)) inside = !inside;
      }
      EXPECT_TRUE(inside) << "disc at (" << x << ", " << y << ")";
      const auto [vx, vy] = screen(at(c.local));
      const auto edge = [&](int k) {
        const auto [ex, ey] = screen(at(k));
        return std::hypot(ex - vx, ey - vy);
      };
      EXPECT_LT(std::hypot(x - vx, y - vy), std::min(edge(c.local - 1), edge(c.local + 1)));
      // The label within its disc's rim plus the leader cap of it.
      const double dx = std::max({l.box.x - x, 0.0, x - (l.box.x + l.box.width)});
      const double dy = std::max({l.box.y - y, 0.0, y - (l.box.y + l.box.height)});
      EXPECT_LE(std::hypot(dx, dy), l.marker.radius + shot.max_leader);
    }
    // The pushed vertex turns two of its quads over (their corners there
    // negative) and keeps two convex-or-concave ones positive.
    EXPECT_GE(inverted, 1);
    EXPECT_LT(inverted, 4);
  }
}

TEST(SurfaceDetailViews, PlanarFoldClusterViewFillsTheClustersFaces) {
  const test::TempDir dir("surface_detail_views");
  const Fixture f = folded_grid(dir);
  const Analysis& a = f.a;
  ASSERT_TRUE(a.glyphs && !a.glyphs->clusters.empty());
  const ClusterRegion region = cluster_region(a.mesh, a.topology, *a.glyphs, 0);
  ASSERT_FALSE(region.cells.empty());
  // The pushed vertex is #0's, so are its four quads.
  for (const auto& q : a.mesh.quads)
    if (std::find(q.begin(), q.end(), kPushed) != q.end()) {
      const Index id = static_cast<Index>(&q - a.mesh.quads.data());
      EXPECT_TRUE(std::binary_search(region.cells.begin(), region.cells.end(), id)) << id;
    }
  const ClusterShot shot =
      cluster_shot(a.mesh, a.topology, a.field.vertex_quality, *a.glyphs, 0, f.options);
  // Two opaque sets, the faces of positive then of negative cell scaled
  // Jacobian, each face's triangles in quality_color of that value (two
  // triangles a quad); the negative ones lifted towards the eye (a fold
  // stacks faces in the plane: the inverted ones drawn over the others).
  ASSERT_EQ(shot.scene.triangles.size(), 2u);
  const Vec3 look = normalized(shot.camera.target - shot.camera.eye);
  EXPECT_NEAR(std::abs(look.z), 1.0, 1e-9);
  std::size_t k = 0, num_inverted = 0;
  for (std::size_t set = 0; set < 2; ++set) {
    const TriangleSet& faces = shot.scene.triangles[set];
    EXPECT_EQ(faces.indices.size(), 6 * (faces.colors.size() / 4));
    for (std::size_t i = 0; i < faces.colors.size(); i += 4) {
      Index cell = kNoIndex;  // the next region cell of this set's sign
      while (k < region.cells.size() && cell == kNoIndex) {
        const double q = a.field.cell_scaled_jacobian[static_cast<std::size_t>(region.cells[k])];
        if ((q < 0.0) == (set == 1)) cell = region.cells[k];
        ++k;
      }
      ASSERT_NE(cell, kNoIndex);
      EXPECT_EQ(faces.colors[i], to_rgba8(quality_color(a.field.cell_scaled_jacobian[static_cast<std::size_t>(cell)])));
      const Vec3f& p = faces.positions[i];
      const double depth = dot(shot.scene.origin + Vec3{p.x, p.y, p.z} - shot.camera.eye, look);
      const double plane = dot(Vec3{0, 0, 0} - shot.camera.eye, look);  // the grid's plane z = 0
      if (set == 0) EXPECT_NEAR(depth, plane, 1e-6);
      else EXPECT_LT(depth, plane - 1e-4);
      num_inverted += set;
    }
    if (set == 0) k = 0;
  }
  EXPECT_GE(num_inverted, 1u);
  std::size_t faces_drawn = 0;
  for (const TriangleSet& set : shot.scene.triangles) faces_drawn += set.colors.size() / 4;
  EXPECT_EQ(faces_drawn, region.cells.size());
  EXPECT_NE(shot.cell_kinds.find(kClusterFaceFillLegend), std::string::npos);
  // The legend says what a sphere is and what its size says, and its ring
  // swatch is drawn as the ring (47i review #7: a dark ring with no band).
  EXPECT_NE(shot.cell_kinds.find("sphere: a vertex below the threshold\nsize: how far below"), std::string::npos);
  const auto ring = std::find_if(shot.swatches.begin(), shot.swatches.end(),
                                 [](const ColorBarSwatch& s) { return s.label == "ring: its worst vertex"; });
  ASSERT_NE(ring, shot.swatches.end());
  EXPECT_EQ(ring->shape, SwatchShape::solid_ring);
  ASSERT_TRUE(ring->ring_band);
  EXPECT_EQ(*ring->ring_band, kWorstBandColor);
}

// Each quad's two triangles in view C lie inside the quad (the centroid of
// each, even-odd in the plane): with the corner lists turned by one, the
// folded quads' reflex corners are corners 1 and 3, where the diagonal 0-2
// ran outside the quad (47g review #1: a fill with no edge line).
TEST(SurfaceDetailViews, PlanarFoldClusterViewFillsEachQuadInsideItsEdges) {
  const test::TempDir dir("surface_detail_views");
  for (int turn = 0; turn < 2; ++turn) {
    SCOPED_TRACE("turn " + std::to_string(turn));
    const Fixture f = folded_grid(dir, turn);
    ASSERT_TRUE(f.a.glyphs && !f.a.glyphs->clusters.empty());
    const ClusterShot shot = cluster_shot(f.a.mesh, f.a.topology, f.a.field.vertex_quality, *f.a.glyphs, 0, f.options);
    std::size_t checked = 0;
    for (const TriangleSet& faces : shot.scene.triangles)
      for (std::size_t t = 0; t + 2 < faces.indices.size(); t += 3) {
        const std::size_t base = faces.indices[t] / 4 * 4;  // the quad's first position
        double x = 0.0, y = 0.0;
        for (std::size_t k = 0; k < 3; ++k) {
          EXPECT_EQ(faces.indices[t + k] / 4 * 4, base);
          x += faces.positions[faces.indices[t + k]].x / 3.0, y += faces.positions[faces.indices[t + k]].y / 3.0;
        }
        bool inside = false;
        for (std::size_t k = 0; k < 4; ++k) {
          const Vec3f& p0 = faces.positions[base + k];
          const Vec3f& p1 = faces.positions[base + (k + 1) % 4];
          if ((p0.y > y) != (p1.y > y) && x < p0.x + (y - p0.y) / (p1.y - p0.y) * (p1.x - p0.x)) inside = !inside;
        }
        EXPECT_TRUE(inside) << "triangle " << t / 3 << " at (" << x << ", " << y << ")";
        ++checked;
      }
    EXPECT_GE(checked, 8u);
  }
}

// View C's glyphs and marks on the fold (47g review #3, #4, #6, #8): size is
// severity (one factor times each vertex's glyph radius, 1 - quality times
// rmax, so the fold's inverted vertices rank), the largest within 0.35 of the
// cluster's shortest edge (by hand from the grid's points); the worst
// vertex's glyph first and ringed (an overlay annulus about it, facing the
// camera, outside the glyph); the cluster's edges nearer the eye than
// every glyph's front (the vertex where the folded edges meet stays in
// sight); the faces lit as view A's (kSurfaceFillAmbient); and a legend
// entry for each line colour and the neighbours' fill.
TEST(SurfaceDetailViews, PlanarFoldClusterGlyphsRankAndLeaveTheFoldInSight) {
  const test::TempDir dir("surface_detail_views");
  const Fixture f = folded_grid(dir);
  const Analysis& a = f.a;
  ASSERT_TRUE(a.glyphs && !a.glyphs->clusters.empty());
  const ClusterShot shot = cluster_shot(a.mesh, a.topology, a.field.vertex_quality, *a.glyphs, 0, f.options);
  const SphereSet& spheres = shot.scene.spheres.at(0);
  ASSERT_GE(spheres.centers.size(), 2u);
  // Each sphere's vertex (by position) and the ratio of its radius to the
  // vertex's glyph radius: one for all.
  const std::vector<Vec3> p = grid_points();
  std::vector<Index> vertex;
  for (const Vec3f& c : spheres.centers) {
    const Vec3 at = shot.scene.origin + Vec3{c.x, c.y, c.z};
    Index found = kNoIndex;
    for (std::size_t v = 0; v < p.size(); ++v)
      if (norm(p[v] - at) < 1e-6) found = static_cast<Index>(v);
    ASSERT_NE(found, kNoIndex);
    vertex.push_back(found);
  }
  int inverted = 0;
  for (std::size_t i = 0; i < vertex.size(); ++i) {
    const auto v = static_cast<std::size_t>(vertex[i]);
    SCOPED_TRACE("vertex " + std::to_string(v));
    inverted += a.field.vertex_quality[v] < 0.0;
    EXPECT_NEAR(a.glyphs->vertex_radius[v], (1.0 - a.field.vertex_quality[v]) * a.glyphs->rmax, 1e-9);
    EXPECT_NEAR(spheres.radii[i] / a.glyphs->vertex_radius[v],
                spheres.radii[0] / a.glyphs->vertex_radius[static_cast<std::size_t>(vertex[0])], 1e-5);
    // The first is the worst.
    EXPECT_LE(a.field.vertex_quality[static_cast<std::size_t>(vertex[0])], a.field.vertex_quality[v]);
  }
  EXPECT_GE(inverted, 2) << "the fold's inverted glyphs, which must rank";
  EXPECT_EQ(vertex[0], kPushed);
  // The shortest edge of the cluster's quads, by hand.
  const ClusterRegion region = cluster_region(a.mesh, a.topology, *a.glyphs, 0);
  double shortest = HUGE_VAL;
  for (Index c : region.cells) {
    const auto& q = a.mesh.quads.at(static_cast<std::size_t>(c));
    for (int k = 0; k < 4; ++k) shortest = std::min(shortest, norm(p[static_cast<std::size_t>(q[k])] - p[static_cast<std::size_t>(q[(k + 1) % 4])]));
  }
  EXPECT_LE(*std::max_element(spheres.radii.begin(), spheres.radii.end()), 0.35 * shortest + 1e-6);
  // The cluster's edges (the second line set) nearer the eye than every
  // glyph's front where they meet its vertex.
  const Vec3 look = normalized(shot.camera.target - shot.camera.eye);
  const auto depth = [&](const Vec3f& q) { return dot(shot.scene.origin + Vec3{q.x, q.y, q.z} - shot.camera.eye, look); };
  const LineSet& own = shot.scene.lines.at(1);
  std::size_t at_glyphs = 0;
  for (const Vec3f& q : own.positions)
    for (std::size_t i = 0; i < spheres.centers.size(); ++i) {
      const Vec3f& c = spheres.centers[i];
      const Vec3 d{q.x - c.x, q.y - c.y, q.z - c.z};
      if (norm(d - dot(d, look) * look) > 1e-6) continue;  // not at this glyph's vertex
      EXPECT_LT(depth(q), depth(c) - spheres.radii[i]);
      ++at_glyphs;
    }
  EXPECT_GE(at_glyphs, 2 * spheres.centers.size());
  // The ring: in the overlay, about the first glyph, in the plane facing the
  // camera, from its rim to a few pixels out (1200 px frame of the fold).
  ASSERT_EQ(shot.scene.overlay.size(), 1u);
  const Vec3f& c0 = spheres.centers[0];
  for (const Vec3f& q : shot.scene.overlay[0].positions) {
    const Vec3 d{q.x - c0.x, q.y - c0.y, q.z - c0.z};
    EXPECT_NEAR(dot(d, look), 0.0, 1e-6);
    EXPECT_GT(norm(d), spheres.radii[0]);
    EXPECT_LT(norm(d), spheres.radii[0] + 0.1 * shot.camera.ortho_height);
  }
  // Lit as view A's faces, each quad shaded by one normal (its Newell
  // normal, by hand: a planar grid's is +-z), so a non-planar quad's two
  // triangles shade alike (47g review #11).
  for (const TriangleSet& faces : shot.scene.triangles) {
    EXPECT_EQ(faces.ambient, kSurfaceFillAmbient);
    ASSERT_EQ(faces.normals.size(), faces.positions.size());
    for (const Vec3f& n : faces.normals) EXPECT_NEAR(std::abs(n.z), 1.0, 1e-6);
  }
  // A legend entry for each line colour drawn and for the neighbours' fill
  // as drawn over the white background.
  const auto has_swatch = [&](Rgba8 c) {
    return std::any_of(shot.swatches.begin(), shot.swatches.end(),
                       [&](const ColorBarSwatch& s) { return to_rgba8(s.color) == c; });
  };
  for (const LineSet& lines : shot.scene.lines)
    for (const Rgba8& c : lines.colors) EXPECT_TRUE(has_swatch(c));
  ASSERT_FALSE(shot.scene.translucent.empty());
  ASSERT_FALSE(shot.scene.translucent[0].colors.empty());
  const Rgba8 fill = shot.scene.translucent[0].colors[0];
  const auto over_white = [&](std::uint8_t v) {
    return static_cast<std::uint8_t>(std::lround((v * fill.a + 255 * (255 - fill.a)) / 255.0));
  };
  EXPECT_TRUE(has_swatch({over_white(fill.r), over_white(fill.g), over_white(fill.b), 255}));
}

// The analysis of a planar 4 x 4 quad grid whose second column is 0.01
// wide (vertex (1, 2) is 1 + 5 * 2), each grid point (x, y, 0) written
// where `place` puts it.
template <class Place>
Analysis sliver_grid(const test::TempDir& dir, const std::string& name, Place place) {
  const std::array<double, 5> xs{0.0, 1.0, 1.01, 2.0, 3.0};
  std::ostringstream obj;
  for (int j = 0; j <= 4; ++j)
    for (double x : xs) {
      const Vec3 q = place(Vec3{x, double(j), 0.0});
      obj << "v " << q.x << ' ' << q.y << ' ' << q.z << '\n';
    }
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int a = 1 + i + 5 * j;
      obj << "f " << a << ' ' << a + 1 << ' ' << a + 6 << ' ' << a + 5 << '\n';
    }
  AnalyzeOptions run;
  run.mesh_path = dir.write(name, obj.str());
  run.tool_version = "test";
  return analyze_mesh(run);
}

// View D (800 x 600, along the plane's normal) of vertex v of sliver_grid.
LocalShot sliver_grid_shot(const Analysis& a, Index v) {
  DetailViewOptions options;
  options.width = 800, options.height = 600;
  options.view_direction = planar_view_direction(a);
  options.cell_quality = a.field.cell_scaled_jacobian;
  return local_shot(a.mesh, a.topology, a.field.corner_scaled_jacobian, v, options);
}

// A ring of slivers (47g review #6, Dolphin_padded's corner between edges
// 3 px apart): a planar 4 x 4 grid whose second column is 0.01 wide. D of
// the vertex (1, 2): in the view a sliver's disc has no room in its quad
// (its anchor 0.4 x 0.01 from the vertex on the right angle's bisector, so
// 0.004 / sqrt 2 from the quad's edges: under a pixel), so D gets an inset
// zoomed on the vertex in which every disc (all four corners right angles,
// SJ 1: one size) is 10 px in radius at scale 1
// (0.5 for the 800 x 600 figure: 5 px, its rim 1.12 times that; the
// tightest room takes 0.8 of it, by hand); every corner disc in the inset
// lies inside its own quad as the inset projects it (centre and rim,
// even-odd) and no two discs overlap; the inset covers no label.
TEST(SurfaceDetailViews, SliverRingGetsAnInsetWithEachDiscInsideItsQuad) {
  const test::TempDir dir("surface_detail_views");
  const Analysis a = sliver_grid(dir, "slivers.obj", [](const Vec3& q) { return q; });
  const Index v = 1 + 5 * 2;  // (1, 2)
  const LocalShot shot = sliver_grid_shot(a, v);
  ASSERT_TRUE(shot.inset);
  const DetailInset& inset = *shot.inset;
  const double aspect = double(inset.rect.width) / inset.rect.height;
  const auto screen = [&](const Vec3& q) {
    const Vec3 ndc = project_to_ndc(inset.camera, aspect, q);
    return std::array<double, 2>{0.5 * (ndc.x + 1.0) * inset.rect.width, 0.5 * (1.0 - ndc.y) * inset.rect.height};
  };
  for (const LocalLabel& l : shot.labels)
    if (l.placed) EXPECT_FALSE(boxes_overlap(l.box, inset.rect));
  // The discs: triangle fans of 33 positions (centre, 32 on the rim), each
  // corner's rim then its colour, then the vertex's two.
  ASSERT_EQ(inset.scene.overlay.size(), 1u);
  const TriangleSet& fans = inset.scene.overlay[0];
  const std::size_t n = vertex_corners(a.mesh, a.topology, a.field.corner_scaled_jacobian, v).size();
  ASSERT_EQ(n, 4u);
  ASSERT_EQ(fans.positions.size(), 33 * (2 * n + 2));
  std::vector<std::array<double, 3>> discs;  // x, y, radius on screen
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t base = 33 * 2 * k;  // the rim's fan
    const auto at = [&](std::size_t i) {
      const Vec3f& q = fans.positions[base + i];
      return screen(inset.scene.origin + Vec3{q.x, q.y, q.z});
    };
    const auto [cx, cy] = at(0);
    const auto [rx, ry] = at(1);
    discs.push_back({cx, cy, std::hypot(rx - cx, ry - cy)});
    EXPECT_NEAR(discs.back()[2], 1.12 * 10.0 * 0.5, 0.3);
    // Inside one quad at the vertex, centre and rim.
    int holding = 0;
    for (const auto& q : a.mesh.quads) {
      if (std::find(q.begin(), q.end(), v) == q.end()) continue;
      const auto inside = [&](double x, double y) {
        bool in = false;
        for (int e = 0; e < 4; ++e) {
          const auto [x0, y0] = screen(a.mesh.points[static_cast<std::size_t>(q[e])]);
          const auto [x1, y1] = screen(a.mesh.points[static_cast<std::size_t>(q[(e + 1) % 4])]);
          if ((y0 > y) != (y1 > y) && x < x0 + (y - y0) / (y1 - y0) * (x1 - x0)) in = !in;
        }
        return in;
      };
      bool all = inside(cx, cy);
      for (std::size_t i = 1; i <= 32 && all; ++i) {
        const auto [x, y] = at(i);
        all = inside(x, y);
      }
      holding += all;
    }
    EXPECT_EQ(holding, 1) << "disc " << k << " at (" << cx << ", " << cy << ")";
  }
  for (std::size_t i = 0; i < discs.size(); ++i)
    for (std::size_t j = i + 1; j < discs.size(); ++j)
      EXPECT_GT(std::hypot(discs[i][0] - discs[j][0], discs[i][1] - discs[j][1]), discs[i][2] + discs[j][2]);
}

// The sliver grid above turned 35 degrees about x and 20 about z, its
// corner (0, 4) pulled out to (-1.5, 4.8) so the ring's bounding-box centre
// is off its plane (47i review #1: the inset's camera moved along the view
// to the vertex's depth kept the view's near and far planes, which enclose
// the planar ring's single depth with 1% slack, and the inset came out
// blank white): every ring point lies between the inset camera's near and
// far planes, the inset's rendered pixels hold the faces' fill (not only
// white), and the box it shows lies inside the view.
TEST(SurfaceDetailViews, TiltedSliverRingsInsetShowsItsFacesAndItsBoxIsInTheView) {
  const test::TempDir dir("surface_detail_views");
  const double a = 35.0 * 3.14159265358979323846 / 180.0, b = 20.0 * 3.14159265358979323846 / 180.0;
  const Analysis an = sliver_grid(dir, "tilted_slivers.obj", [&](Vec3 q) {
    if (q.x == 0.0 && q.y == 3.0) q = {-1.5, 3.8, 0.0};
    const Vec3 r{q.x, std::cos(a) * q.y - std::sin(a) * q.z, std::sin(a) * q.y + std::cos(a) * q.z};
    return Vec3{std::cos(b) * r.x - std::sin(b) * r.y, std::sin(b) * r.x + std::cos(b) * r.y, r.z};
  });
  const Index v = 1 + 5 * 2;  // (1, 2)
  const LocalShot shot = sliver_grid_shot(an, v);
  ASSERT_TRUE(shot.inset);
  const DetailInset& inset = *shot.inset;
  const Vec3 ahead = normalized(inset.camera.target - inset.camera.eye);
  for (const auto& q : an.mesh.quads) {
    if (std::find(q.begin(), q.end(), v) == q.end()) continue;
    for (Index c : q) {
      const double depth = dot(an.mesh.points[static_cast<std::size_t>(c)] - inset.camera.eye, ahead);
      EXPECT_GE(depth, inset.camera.near_plane);
      EXPECT_LE(depth, inset.camera.far_plane);
    }
  }
  const PixelRect& view = shot.layout.view;
  EXPECT_GE(inset.box.x, view.x);
  EXPECT_GE(inset.box.y, view.y);
  EXPECT_LE(inset.box.x + inset.box.width, view.x + view.width);
  EXPECT_LE(inset.box.y + inset.box.height, view.y + view.height);
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  ASSERT_TRUE(renderer);
  const Image image = renderer->render(inset.scene, inset.camera, inset.rect.width, inset.rect.height);
  std::size_t drawn = 0;
  for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4)
    drawn += image.rgba[i] < 250 || image.rgba[i + 1] < 250 || image.rgba[i + 2] < 250;
  // The ring's faces fill most of a zoom on their vertex.
  EXPECT_GT(drawn, image.rgba.size() / 4 / 4);
}

// `--views clusters,local,corners` on a quad mesh draws C of each top
// cluster, D and E of each worst vertex (the pushed one first) and nothing
// else; D's file names the pushed vertex.
TEST(SurfaceDetailViews, TheirViewIdsDrawThemForAQuadMesh) {
  const test::TempDir dir("surface_detail_views");
  const Fixture f = folded_grid(dir);
  ViewOptions views;
  views.width = 320, views.height = 240;
  views.views = {"clusters", "local", "corners"};
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  ASSERT_TRUE(renderer);
  const std::vector<RenderedView> drawn = render_views(f.a, views, *renderer);
  std::vector<std::string> ids, paths;
  for (const RenderedView& v : drawn)
    for (const ViewFile& file : v.files) {
      if (ids.empty() || ids.back() != v.id) ids.push_back(v.id);
      paths.push_back(file.relative_path);
    }
  EXPECT_EQ(ids, (std::vector<std::string>{"clusters", "local", "corners"}));
  EXPECT_EQ(paths.at(0), "views/cluster_0.png");
  EXPECT_NE(std::find(paths.begin(), paths.end(), "views/local_v" + std::to_string(kPushed) + ".png"), paths.end());
  EXPECT_NE(std::find(paths.begin(), paths.end(), "views/corners_v" + std::to_string(kPushed) + ".svg"), paths.end());
}

}  // namespace
}  // namespace hq
