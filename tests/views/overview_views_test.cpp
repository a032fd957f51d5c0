// The overview's scene, built without OpenGL.
#include "hqview/views/overview_views.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "hqview/core/error.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/surface_boundary.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

Vec3 model(const Scene& scene, const Vec3f& p) { return scene.origin + Vec3{p.x, p.y, p.z}; }

TEST(QualityOverviewScene, Grid2CountsFacesAndUniqueBoundaryEdges) {
  const HexMesh mesh = test::grid(2);
  const Topology topology = build_topology(mesh);
  ASSERT_EQ(topology.boundary_faces.size(), 24u);
  const Scene scene = build_quality_overview_scene(mesh, topology, std::vector<double>(mesh.points.size(), 1.0), {});

  ASSERT_EQ(scene.triangles.size(), 1u);
  EXPECT_EQ(triangle_count(scene), 24u * 4u);  // 4 triangles around each quad's centre
  EXPECT_EQ(scene.triangles[0].positions.size(), 24u * 5u);
  EXPECT_EQ(scene.triangles[0].normals.size(), 24u * 5u);
  EXPECT_EQ(scene.triangles[0].colors.size(), 24u * 5u);
  // The surface of a 2x2x2 grid: V = 26, F = 24, so E = V + F - 2 = 48.
  ASSERT_EQ(scene.lines.size(), 1u);
  EXPECT_EQ(segment_count(scene), 48u);
  EXPECT_EQ(scene.lines[0].positions.size(), 26u);
  std::set<std::pair<std::uint32_t, std::uint32_t>> unique;
  const auto& idx = scene.lines[0].indices;
  for (std::size_t i = 0; i < idx.size(); i += 2)
    unique.insert({std::min(idx[i], idx[i + 1]), std::max(idx[i], idx[i + 1])});
  EXPECT_EQ(unique.size(), 48u);
}

TEST(QualityOverviewScene, Grid3CountsAndOutwardFaces) {
  const HexMesh mesh = test::grid(3);
  const Topology topology = build_topology(mesh);
  const Scene scene = build_quality_overview_scene(mesh, topology, std::vector<double>(mesh.points.size(), 1.0), {});
  EXPECT_EQ(triangle_count(scene), 54u * 4u);
  // The surface of a 3x3x3 grid: V = 4^3 - 2^3 = 56, F = 54, E = V + F - 2 = 108.
  EXPECT_EQ(segment_count(scene), 108u);
  const TriangleSet& faces = scene.triangles[0];
  for (std::size_t v = 0; v < faces.positions.size(); v += 5) {
    const Vec3 centre = model(scene, faces.positions[v + 4]);
    const Vec3 n{faces.normals[v].x, faces.normals[v].y, faces.normals[v].z};
    EXPECT_GT(dot(n, centre - Vec3{1.5, 1.5, 1.5}), 0.0) << "face " << v / 5 << " is not outward";
  }
}

TEST(QualityOverviewScene, PositionsAreRelativeToTheBoxCentreAndNormalsPointOut) {
  HexMesh mesh = test::grid(2);
  for (Vec3& p : mesh.points) p = p + Vec3{1000.0, -2000.0, 5.0};
  const Topology topology = build_topology(mesh);
  const Scene scene = build_quality_overview_scene(mesh, topology, std::vector<double>(mesh.points.size(), 0.5), {});
  EXPECT_EQ(scene.origin, (Vec3{1001.0, -1999.0, 6.0}));
  const TriangleSet& faces = scene.triangles[0];
  for (std::size_t v = 0; v < faces.positions.size(); ++v) {
    const Vec3 p = model(scene, faces.positions[v]);
    const Vec3 n{faces.normals[v].x, faces.normals[v].y, faces.normals[v].z};
    EXPECT_NEAR(norm(n), 1.0, 1e-6);
    EXPECT_GT(dot(n, p - scene.origin), 0.0) << "normal " << v << " points into the grid";
  }
}

TEST(QualityOverviewScene, ColoursFollowVertexQuality) {
  const HexMesh mesh = test::unit_cube();
  const Topology topology = build_topology(mesh);
  std::vector<double> quality(8, 1.0);
  quality[0] = -0.5;  // an inverted corner
  quality[6] = 0.0;
  const Scene scene = build_quality_overview_scene(mesh, topology, quality, {});
  const TriangleSet& faces = scene.triangles[0];
  ASSERT_EQ(faces.positions.size(), 6u * 5u);
  int inverted = 0, worst = 0;
  for (std::size_t v = 0; v < faces.positions.size(); ++v) {
    const Vec3 p = model(scene, faces.positions[v]);
    const Rgba8 c = faces.colors[v];
    if (p == Vec3{0, 0, 0}) {
      EXPECT_EQ(c, to_rgba8(kInvertedColor));
      ++inverted;
    } else if (p == Vec3{1, 1, 1}) {
      EXPECT_EQ(c, to_rgba8(quality_color(0.0)));
      ++worst;
    } else if (v % 5 == 4) {
      // A face centre: the colour of its corners' mean quality.
      // Every face holds exactly one of the corners 0 (quality -0.5) and 6 (0).
      const double x = p.x, y = p.y, z = p.z;
      const bool touches_0 = x == 0.0 || y == 0.0 || z == 0.0;
      const double mean = (3.0 + (touches_0 ? -0.5 : 0.0)) / 4.0;
      EXPECT_EQ(c, to_rgba8(quality_color(mean))) << "centre " << x << " " << y << " " << z;
    } else {
      EXPECT_EQ(c, to_rgba8(quality_color(1.0)));
    }
  }
  EXPECT_EQ(inverted, 3);  // corner 0 lies on 3 faces
  EXPECT_EQ(worst, 3);
}

TEST(QualityOverviewScene, EdgesUseTheOptionsColourAndWidth) {
  const HexMesh mesh = test::unit_cube();
  const Topology topology = build_topology(mesh);
  OverviewOptions options;
  options.edge_color = {10, 20, 30, 200};
  options.edge_width = 2.5f;
  const Scene scene = build_quality_overview_scene(mesh, topology, std::vector<double>(8, 1.0), options);
  EXPECT_EQ(segment_count(scene), 12u);
  EXPECT_FLOAT_EQ(scene.lines[0].width, 2.5f);
  for (const Rgba8& c : scene.lines[0].colors) EXPECT_EQ(c, options.edge_color);
}

TEST(QualityOverviewScene, RejectsAQualityFieldOfTheWrongSize) {
  const HexMesh mesh = test::unit_cube();
  const Topology topology = build_topology(mesh);
  EXPECT_THROW(build_quality_overview_scene(mesh, topology, std::vector<double>(7, 1.0), {}), Error);
}

TEST(QualityOverviewScene, EmptyMeshGivesAnEmptyScene) {
  const HexMesh mesh;
  const Topology topology;
  const Scene scene = build_quality_overview_scene(mesh, topology, {}, {});
  EXPECT_EQ(triangle_count(scene), 0u);
  EXPECT_EQ(segment_count(scene), 0u);
}

// The 2nd-pass review B #5: on a curved surface (inverted_are_reversed) a
// face that is not reversed kept no corner below 0, though the colour bar
// says a concave face's reflex corner is drawn there. A 4 x 4 grid of
// quads: quad (0, 0) reversed (its corners at -0.9 by hand), quad (2, 2)
// concave, its corner 2 (vertex (3, 3)) pushed to (2.3, 2.3), past the
// diagonal between its neighbours (at -0.5 by hand); every other vertex 1.
// Below 0 in the scene: the reversed face's 4 corners and the concave
// face's reflex corner, nothing else (the 3 other faces at (3, 3) and the
// reversed face's neighbours take their lowest corner at or above 0).
TEST(QualityOverviewScene, CurvedSurfaceKeepsReversedAndReflexCornersBelowZero) {
  HexMesh mesh;
  const auto id = [](int i, int j) { return static_cast<Index>(i + 5 * j); };
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) mesh.points.push_back({static_cast<double>(i), static_cast<double>(j), 0.0});
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) mesh.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  std::swap(mesh.quads[0][1], mesh.quads[0][3]);  // quad (0, 0) reversed
  const Index reflex = id(3, 3);
  mesh.points[static_cast<std::size_t>(reflex)] = {2.3, 2.3, 0.0};
  const std::size_t concave = 2 + 4 * 2, reversed = 0;
  std::vector<double> quality(mesh.points.size(), 1.0);
  for (Index v : mesh.quads[reversed]) quality[static_cast<std::size_t>(v)] = -0.9;
  quality[static_cast<std::size_t>(reflex)] = -0.5;
  Topology topology = build_topology(mesh);
  add_surface_faces_as_boundary(mesh, topology);  // as the pipeline draws a surface
  OverviewOptions options;
  options.inverted_are_reversed = true;
  options.inverted_cells = {static_cast<Index>(reversed)};
  const Scene scene = build_quality_overview_scene(mesh, topology, quality, options);
  const std::vector<BoundaryPolygon> polygons = boundary_polygons(topology);
  ASSERT_EQ(polygons.size(), 16u);
  const TriangleSet& fill = scene.triangles.at(0);
  ASSERT_EQ(fill.scalars.size(), 5u * polygons.size());  // 4 corners and a centre a quad, in face order
  int below = 0, lifted = 0;
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto cell = static_cast<std::size_t>(polygons[f].cell);
    for (std::size_t k = 0; k < 4; ++k) {
      const Index v = polygons[f].v[k];
      const bool expected = cell == reversed || (cell == concave && v == reflex);
      const float value = fill.scalars[5 * f + k];
      EXPECT_EQ(value < 0.0f, expected) << "quad " << cell << " corner " << k;
      below += value < 0.0f;
      lifted += !expected && quality[static_cast<std::size_t>(v)] < 0.0 && value == 1.0f;
    }
  }
  EXPECT_EQ(below, 5);
  // At the reflex vertex 3 other faces, at the reversed face's 3 outer
  // corners 2 + 2 + 1 more (6): each lifted to its lowest corner, 1.
  EXPECT_EQ(lifted, 3 + 5);
}

TEST(BoundaryBoundingBox, SpansTheBoundaryVertices) {
  HexMesh mesh = test::grid(2);
  mesh.points.push_back({50, 50, 50});  // unreferenced: not part of the boundary
  const Topology topology = build_topology(mesh);
  const Box3 box = boundary_bounding_box(mesh, topology);
  EXPECT_EQ(box.lo, (Vec3{0, 0, 0}));
  EXPECT_EQ(box.hi, (Vec3{2, 2, 2}));
}

}  // namespace
}  // namespace hq
