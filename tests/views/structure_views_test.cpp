// The structure views' scenes, palette and viewpoints, built without OpenGL.
#include "hqview/views/overview_views.h"
#include "hqview/views/structure_views.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "hqview/image/colormap.h"
#include "hqview/render/upright.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

int channel_distance(Rgba8 a, Rgba8 b) {
  return std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
}

TEST(StructureViews, TheSixClassesHaveDistinctColoursNoneGrey) {
  for (int i = 0; i < kNumSingularClasses; ++i) {
    const Rgba8 c = singular_class_color(static_cast<SingularClass>(i));
    const int spread = std::max({c.r, c.g, c.b}) - std::min({c.r, c.g, c.b});
    EXPECT_GT(spread, 80) << singular_class_label(static_cast<SingularClass>(i)) << " is greyish";
    for (int j = 0; j < i; ++j)
      EXPECT_GT(channel_distance(c, singular_class_color(static_cast<SingularClass>(j))), 80) << i << " vs " << j;
  }
  StructureEdge e;
  e.singular = true;
  const std::pair<Index, SingularClass> interior[] = {{1, SingularClass::interior_other}, {2, SingularClass::interior_other},
                                                      {3, SingularClass::interior_3},     {5, SingularClass::interior_5},
                                                      {6, SingularClass::interior_6_plus}, {9, SingularClass::interior_6_plus}};
  for (auto [valence, expected] : interior) {
    e.valence = valence;
    EXPECT_EQ(singular_class(e), expected) << valence;
  }
  e.kind = EdgeKind::boundary;
  e.valence = 1;
  EXPECT_EQ(singular_class(e), SingularClass::boundary_1);
  e.valence = 4;
  EXPECT_EQ(singular_class(e), SingularClass::boundary_3_plus);
}

// One hex: a fifth of its edge would be a fifth of the model; the radius is
// capped at 0.02 of the boundary's diagonal (sqrt 3).
TEST(StructureViews, NodeSpheresOfACoarseMeshAreCappedByItsSize) {
  const HexMesh mesh = test::unit_cube();
  const Topology topology = build_topology(mesh);
  const Scene scene = build_singularity_scene(mesh, topology, compute_structure(mesh, topology), {});
  ASSERT_EQ(sphere_count(scene), 8u);
  EXPECT_FLOAT_EQ(scene.spheres[0].radii[0], static_cast<float>(0.02 * std::sqrt(3.0)));
}

// One unit hex and two tets splitting its x = 1 face (non-conforming): the
// 4 hex edges along x are singular (boundary, valence 1) and end at the
// face's 4 corners, which touch the tets: 4 curve ends there, each drawn as a
// ring facing the camera; the brown face is half transparent, unlit and
// after the veil, so nothing opaque hides a node (46q review Q-M3, Q-M4).
TEST(StructureViews, CurveEndsAtTetsGetRingsAndTheNonConformingFaceIsSeeThrough) {
  HexMesh mesh = test::unit_cube();
  std::vector<Index> x1;
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if (std::abs(mesh.points[i].x - 1.0) < 1e-12) x1.push_back(static_cast<Index>(i));
  ASSERT_EQ(x1.size(), 4u);
  const auto at = [&](double y, double z) {
    for (Index v : x1)
      if (std::abs(mesh.points[static_cast<std::size_t>(v)].y - y) < 1e-12 && std::abs(mesh.points[static_cast<std::size_t>(v)].z - z) < 1e-12) return v;
    return kNoIndex;
  };
  mesh.points.push_back({2.0, 0.5, 0.5});
  const Index apex = static_cast<Index>(mesh.points.size() - 1);
  const auto positive = [&](std::array<Index, 4> t) {
    const auto p = [&](int i) { return mesh.points[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])]; };
    if (dot(cross(p(1) - p(0), p(2) - p(0)), p(3) - p(0)) < 0) std::swap(t[1], t[2]);
    return t;
  };
  mesh.tets.push_back(positive({at(0, 0), at(1, 0), at(1, 1), apex}));
  mesh.tets.push_back(positive({at(0, 0), at(1, 1), at(0, 1), apex}));
  const Topology topology = build_topology(mesh);
  ASSERT_EQ(topology.non_conforming_faces.size(), 1u);
  const HexStructure s = compute_structure(mesh, topology);
  std::vector<Index> expected = x1;
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(interface_curve_ends(s), expected);
  EXPECT_EQ(s.num_interface_ends, 4);
  // Rings: 4, each 24 segments of 2 triangles, unlit, centred on its vertex, facing the camera.
  Camera camera;
  camera.eye = {5, -3, 2};
  camera.target = {0, 0, 0};
  camera.up = {0, 0, 1};
  const double r = 0.1;
  const std::vector<Index> ends = interface_curve_ends(s);
  const TriangleSet rings = curve_end_rings(mesh, ends, Vec3{}, camera, r);
  EXPECT_FALSE(rings.is_lit);
  ASSERT_EQ(rings.positions.size(), 4u * 48u);
  EXPECT_EQ(rings.indices.size(), 4u * 24u * 6u);
  const Vec3 d = normalized(camera.target - camera.eye);
  for (std::size_t k = 0; k < ends.size(); ++k) {
    const Vec3 c = mesh.points[static_cast<std::size_t>(ends[k])];
    for (std::size_t i = 48 * k; i < 48 * (k + 1); ++i) {
      const Vec3 q = Vec3{rings.positions[i].x, rings.positions[i].y, rings.positions[i].z} - c;
      EXPECT_NEAR(dot(q, d), 0.0, 1e-6);
      EXPECT_NEAR(norm(q), i % 2 == 0 ? r : kCurveEndRingInner * r, 1e-6);
    }
  }
  const Scene scene = build_singularity_scene(mesh, topology, s, {});
  EXPECT_TRUE(scene.triangles.empty());  // nothing opaque
  ASSERT_EQ(scene.translucent.size(), 2u);
  EXPECT_FALSE(scene.translucent[1].is_lit);
  ASSERT_FALSE(scene.translucent[1].colors.empty());
  for (const Rgba8& c : scene.translucent[1].colors) {
    EXPECT_EQ((Rgba8{c.r, c.g, c.b, 255}), kNonConformingColor);
    EXPECT_EQ(c.a, kNonConformingFaceAlpha);
  }
}

TEST(StructureViews, AGridShowsItsTwelveBoxEdgesAndEightNodes) {
  const HexMesh mesh = test::grid(3);
  const Topology topology = build_topology(mesh);
  const HexStructure s = compute_structure(mesh, topology);
  const Scene scene = build_singularity_scene(mesh, topology, s, {});
  ASSERT_EQ(scene.lines.size(), 1u);
  EXPECT_EQ(segment_count(scene), 36u);
  for (const Rgba8& c : scene.lines[0].colors)
    EXPECT_EQ(channel_distance(c, singular_class_color(SingularClass::boundary_1)), 0);
  // Every segment lies on an edge of the box [0, 3]^3: two coordinates at 0 or 3.
  const auto& p = scene.lines[0].positions;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 m = scene.origin + Vec3{p[i].x, p[i].y, p[i].z};
    int on_faces = 0;
    for (double c : {m.x, m.y, m.z}) on_faces += std::abs(c) < 1e-6 || std::abs(c - 3.0) < 1e-6;
    EXPECT_GE(on_faces, 2) << i;
  }
  ASSERT_EQ(sphere_count(scene), 8u);
  // 0.2 of the unit edge, capped at 0.02 of the diagonal 3 sqrt 3 (a coarse grid).
  EXPECT_FLOAT_EQ(scene.spheres[0].radii[0], static_cast<float>(std::min(0.2, 0.02 * 3 * std::sqrt(3.0))));
  ASSERT_EQ(scene.translucent.size(), 1u);
  EXPECT_EQ(scene.translucent[0].indices.size(), 54u * 6u);
  for (const Rgba8& c : scene.translucent[0].colors) EXPECT_LT(c.a, 128);
  EXPECT_TRUE(scene.triangles.empty());  // nothing opaque hides an interior edge
}

TEST(StructureViews, ACavityDrawsItsTwelveConcaveEdgesInTheValenceThreeColour) {
  HexMesh mesh = test::grid(3);
  mesh.hexes.erase(mesh.hexes.begin() + 13);
  const Topology topology = build_topology(mesh);
  const Scene scene = build_singularity_scene(mesh, topology, compute_structure(mesh, topology), {});
  int concave = 0;
  for (std::size_t i = 0; i < scene.lines[0].colors.size(); i += 2)
    concave += channel_distance(scene.lines[0].colors[i], singular_class_color(SingularClass::boundary_3_plus)) == 0;
  EXPECT_EQ(concave, 12);
  EXPECT_EQ(sphere_count(scene), 16u);
}

TEST(StructureViews, ViewpointsAreUprightAndApart) {
  for (const Vec3 up : {Vec3{0, 0, 1}, Vec3{0, 1, 0}}) {
    HexMesh mesh = test::box_grid(2, 3, 4);
    const Topology topology = build_topology(mesh);
    const HexStructure s = compute_structure(mesh, topology);
    StructureViewOptions options;
    options.up = up;
    const std::vector<Vec3> d = choose_singularity_viewpoints(mesh, topology, s, 2, options);
    ASSERT_EQ(d.size(), 2u);
    for (const Vec3& v : d) {
      const double elevation = view_elevation_degrees(v, up);
      EXPECT_GE(elevation, 15.0 - 1e-9);
      EXPECT_LE(elevation, 35.0 + 1e-9);
    }
    double gap = std::abs(view_azimuth_degrees(d[0], up) - view_azimuth_degrees(d[1], up));
    EXPECT_GE(gap > 180 ? 360 - gap : gap, 90.0 - 1e-9);
  }
}

// The size gradation view (46r review M4): from one of the four upright
// three-quarter poses (azimuth 30 + k 90, elevation 25), never head-on; a
// mesh grading evenly: the overview's pose; a grid with a thin first layer
// along x and y at one corner (length ratio 5^(1/3) > 1.5 there): the pose
// whose eye sees both of that corner's sides.
TEST(StructureViews, GradationViewIsTheThreeQuarterPoseFacingTheJump) {
  for (const Vec3 up : {Vec3{0, 0, 1}, Vec3{0, 1, 0}}) {
    StructureViewOptions options;
    options.up = up;
    const HexMesh even = test::box_grid(3, 3, 3);
    const Topology even_topology = build_topology(even);
    const Vec3 plain = choose_gradation_viewpoint(even, even_topology, compute_structure(even, even_topology), options);
    EXPECT_LT(norm(plain - three_quarter_view(up)), 1e-12);
  }
  StructureViewOptions options;  // up +z
  for (const double side : {-1.0, 1.0}) {
    HexMesh mesh = test::box_grid(4, 4, 4);
    // Layers 0.2, 1, 1, 1 thick along x and y, the thin one at x, y = 0 (side
    // -1) or mirrored to x, y = 4 (side +1).
    const auto graded = [side](double t) {
      const double g = t < 0.5 ? 0.2 * t : 0.2 + (t - 1.0);
      return side < 0 ? g : 3.2 - g;
    };
    for (Vec3& p : mesh.points) p = {graded(p.x), graded(p.y), p.z};
    const Topology topology = build_topology(mesh);
    const HexStructure s = compute_structure(mesh, topology);
    ASSERT_GT(s.gradation.max, kGradationOfInterest);
    const Vec3 d = choose_gradation_viewpoint(mesh, topology, s, options);
    EXPECT_NEAR(view_elevation_degrees(d, options.up), 25.0, 1e-9);
    EXPECT_NEAR(std::fmod(view_azimuth_degrees(d, options.up) + 360.0, 90.0), 30.0, 1e-9);
    // The eye (-d) on the thin layers' side in x and in y.
    EXPECT_GT(-d.x * side, 0.0) << side;
    EXPECT_GT(-d.y * side, 0.0) << side;
  }
}

// The gradation view marks the max cell (46t2 review: the title's max was
// hidden and unmarked): the largest finite value, the first on a tie, none
// without a finite value; its label names value, kind and id.
TEST(StructureViews, GradationMaxCellIsTheFirstLargestFiniteValue) {
  const double nan = std::nan("");
  EXPECT_EQ(gradation_max_cell(std::vector<double>{1.0, 1.7, nan, 1.2, 1.7}), 1);
  EXPECT_EQ(gradation_max_cell(std::vector<double>{nan, 1.0, HUGE_VAL}), 1);
  EXPECT_EQ(gradation_max_cell(std::vector<double>{nan, nan}), kNoIndex);
  EXPECT_EQ(gradation_max_cell(std::vector<double>{}), kNoIndex);
  HexMesh mesh = test::box_grid(2, 1, 1);
  const Topology topology = build_topology(mesh);
  const HexStructure s = compute_structure(mesh, topology);
  ASSERT_EQ(s.cell_gradation.size(), 2u);
  EXPECT_EQ(gradation_max_label(std::vector<double>{1.0, 1.714}, mesh, 1), "max 1.71  hex 1");
}

// Whether the max cell is in sight (46w review C4: cyl's max cell was on
// the far side, its solid outline over nearer cells): two unit cubes apart
// on the x axis seen from +x: the near one is seen, the far one (its front
// face behind the near cube, its other faces turned away) is on the far
// side; from higher up in y the far cube's top face shows; a 3 x 3 x 3
// grid's centre cell is inside, a corner cell seen or on the far side.
TEST(StructureViews, GradationMaxCellSightFromTheCamera) {
  HexMesh apart = test::box_grid(3, 1, 1);
  apart.hexes.erase(apart.hexes.begin() + 1);  // cubes x in [0, 1] and [2, 3]
  const std::vector<BoundaryPolygon> faces = boundary_polygons(build_topology(apart));
  ASSERT_EQ(faces.size(), 12u);
  Camera camera;
  camera.eye = {10.0, 0.5, 0.5}, camera.target = {0.0, 0.5, 0.5}, camera.up = {0, 0, 1};
  EXPECT_EQ(cell_sight(apart, faces, 1, camera), CellSight::seen);
  EXPECT_EQ(cell_sight(apart, faces, 0, camera), CellSight::far_side);
  camera.is_perspective = false;  // along the view direction: the same
  EXPECT_EQ(cell_sight(apart, faces, 0, camera), CellSight::far_side);
  camera.is_perspective = true;
  camera.eye = {10.0, 4.0, 0.5};
  EXPECT_EQ(cell_sight(apart, faces, 0, camera), CellSight::seen);
  const HexMesh cube = test::box_grid(3, 3, 3);
  const std::vector<BoundaryPolygon> cube_faces = boundary_polygons(build_topology(cube));
  camera.eye = {10.0, 9.0, 8.0}, camera.target = {1.5, 1.5, 1.5};
  EXPECT_EQ(cell_sight(cube, cube_faces, 13, camera), CellSight::inside);
  EXPECT_EQ(cell_sight(cube, cube_faces, 26, camera), CellSight::seen);     // (2, 2, 2): the near corner
  EXPECT_EQ(cell_sight(cube, cube_faces, 0, camera), CellSight::far_side);  // (0, 0, 0): the far corner
}

TEST(StructureViews, GradationColoursRunFromPaleToRedOnALogScale) {
  EXPECT_EQ(to_rgba8(gradation_color(1.0)).r, to_rgba8(sample_quality_map(1.0)).r);
  EXPECT_EQ(channel_distance(to_rgba8(gradation_color(2.0)), to_rgba8(sample_quality_map(0.5))), 0);
  EXPECT_EQ(channel_distance(to_rgba8(gradation_color(4.0)), to_rgba8(sample_quality_map(0.0))), 0);
  EXPECT_EQ(channel_distance(to_rgba8(gradation_color(40.0)), to_rgba8(sample_quality_map(0.0))), 0);
  EXPECT_EQ(channel_distance(to_rgba8(gradation_color(std::nan(""))), to_rgba8(kUndefinedColor)), 0);
  double previous = 101.0;
  for (double g = 1.0; g <= 4.0; g += 0.25) {
    const double l = cie_lightness(gradation_color(g));
    EXPECT_LT(l, previous) << g;  // darker as the jump grows
    previous = l;
  }
}

}  // namespace
}  // namespace hq
