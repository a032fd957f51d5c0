// --up auto: the resting up axis (docs/analysis.md "Up axis: auto") on
// hand-built solids whose resting pose is known, under every axis rotation
// and mirror, and on the two shared meshes earlier rules got wrong.
#include "hqview/analysis/resting_up.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <string>

#include "hqview/analysis/compare_alignment.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/render/upright.h"
#include "support/fixtures.h"

namespace hq {
namespace {

using Cell = std::array<int, 3>;

// Unit voxels as hexes (VTK order), points shared between neighbours.
HexMesh voxels(const std::vector<Cell>& cells) {
  HexMesh mesh;
  std::map<Cell, Index> ids;
  const auto point = [&](int x, int y, int z) {
    const auto [it, added] = ids.try_emplace(Cell{x, y, z}, static_cast<Index>(mesh.points.size()));
    if (added) mesh.points.push_back({double(x), double(y), double(z)});
    return it->second;
  };
  for (const auto& [i, j, k] : cells)
    mesh.hexes.push_back({point(i, j, k), point(i + 1, j, k), point(i + 1, j + 1, k), point(i, j + 1, k),
                          point(i, j, k + 1), point(i + 1, j, k + 1), point(i + 1, j + 1, k + 1),
                          point(i, j + 1, k + 1)});
  return mesh;
}

// A lamp: a 6 x 6 x 1 slab with a 2 x 2 x 7 column on its middle. It rests
// on the slab (upside down on the column's end it would rest too, on a
// ninth of the area; on a side its centre falls outside the slab's edge).
HexMesh lamp() {
  std::vector<Cell> cells;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) cells.push_back({i, j, 0});
  for (int k = 1; k < 8; ++k)
    for (int i = 2; i < 4; ++i)
      for (int j = 2; j < 4; ++j) cells.push_back({i, j, k});
  return voxels(cells);
}

// A dustpan: an L lying on its long leg, a 12 x 6 x 1 plate with a 1 x 6 x 3
// lip along one short edge. On the lip's top or the far edge it tips over
// or barely rests on a sliver (6); on its back (the lip's outer face, 24) or
// on a side (the L's profile, 31.5) it rests on less than 72 / 1.5.
HexMesh dustpan() {
  std::vector<Cell> cells;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 6; ++j) cells.push_back({i, j, 0});
  for (int k = 1; k < 4; ++k)
    for (int j = 0; j < 6; ++j) cells.push_back({0, j, k});
  return voxels(cells);
}

HexMesh transformed(const HexMesh& mesh, const Matrix3& m) {
  HexMesh copy = mesh;
  for (Vec3& p : copy.points) p = m * p;
  return copy;
}

Vec3 choose(const HexMesh& mesh) { return choose_resting_up(mesh, build_topology(mesh)).up; }

// Rounded to exact axis components (m * (0, 0, 1) of an axis rotation).
Vec3 exact(const Vec3& v) { return {std::round(v.x), std::round(v.y), std::round(v.z)}; }

TEST(RestingUp, ALampRestsOnItsSlab) {
  const HexMesh mesh = lamp();
  const RestingUp r = choose_resting_up(mesh, build_topology(mesh));
  EXPECT_EQ(r.up, (Vec3{0, 0, 1}));
  EXPECT_TRUE(r.from_data);
  ASSERT_EQ(r.candidates.size(), 6u);
  // +z: the slab's 6 x 6 underside; the centre (3, 3, 2.25) is 3 from its
  // edges (tip 3 / 2.25). -z: the column's 2 x 2 end, 1 from its edges and
  // 5.75 below (tip 1 / 5.75). The sides: the slab's 6 x 1 edge face, the
  // centre 1.25 above it.
  EXPECT_DOUBLE_EQ(r.candidates[0].support_area, 36.0);
  EXPECT_NEAR(r.candidates[0].tip, 3.0 / 2.25, 1e-12);
  EXPECT_DOUBLE_EQ(r.candidates[3].support_area, 4.0);
  EXPECT_NEAR(r.candidates[3].tip, 1.0 / 5.75, 1e-12);
  EXPECT_TRUE(r.candidates[3].rests);
  for (int side : {1, 2, 4, 5}) {
    EXPECT_DOUBLE_EQ(r.candidates[side].support_area, 6.0) << side;
    EXPECT_NEAR(r.candidates[side].tip, -1.25 / 3.0, 1e-12) << side;
    EXPECT_FALSE(r.candidates[side].rests) << side;
  }
}

TEST(RestingUp, EveryRotationAndMirrorOfTheLampAndTheDustpanGivesTheTurnedAxis) {
  for (const auto& [name, mesh] : {std::pair{"lamp", lamp()}, std::pair{"dustpan", dustpan()}}) {
    for (const Matrix3& rotation : axis_rotations()) {
      for (const double mirror : {1.0, -1.0}) {
        Matrix3 m = rotation;
        for (double& a : m[0]) a *= mirror;  // x -> -x after the turn
        const Vec3 expected = exact(m * Vec3{0, 0, 1});
        const HexMesh copy = transformed(mesh, m);
        EXPECT_EQ(choose(copy), expected) << name << " turned to " << up_axis_name(expected) << " mirror " << mirror;
      }
    }
  }
}

TEST(RestingUp, ACubeCannotTellAndKeepsTheFilesAxes) {
  const HexMesh cube = test::box_grid(3, 3, 3);
  const RestingUp r = choose_resting_up(cube, build_topology(cube));
  EXPECT_EQ(r.up, (Vec3{0, 0, 1}));
  // A 4 x 3 x 4 box: +y rests on 16, +z on 12, within the margin (12 x 1.5
  // >= 16), so +z, the first; a 4 x 3 x 2 one: +z's 12 is 1.5 x +y's 8.
  EXPECT_EQ(choose(test::box_grid(4, 3, 4)), (Vec3{0, 0, 1}));
  EXPECT_EQ(choose(test::box_grid(4, 3, 2)), (Vec3{0, 0, 1}));
  // A 4 x 2 x 4 one: +y's 16 over +z's 8 is more than the margin.
  EXPECT_EQ(choose(test::box_grid(4, 2, 4)), (Vec3{0, 1, 0}));
}

TEST(RestingUp, NoBoundaryOrNoVolumeIsTheDefault) {
  const RestingUp none = choose_resting_up(HexMesh{}, build_topology(HexMesh{}));
  EXPECT_EQ(none.up, (Vec3{0, 0, 1}));
  EXPECT_FALSE(none.from_data);
  EXPECT_TRUE(none.candidates.empty());
  HexMesh squashed = test::box_grid(2, 2, 2);
  for (Vec3& p : squashed.points) p.z = 0.0;
  EXPECT_FALSE(choose_resting_up(squashed, build_topology(squashed)).from_data);
}

// bunny_in (z-up) and armadillo (y-up): "longest axis" and "heavier side
// down" both got them wrong. Also turned 90 degrees about x.
TEST(RestingUp, SharedMeshesEarlierRulesGotWrong) {
  const auto dir = test::shared_data_dir();
  if (!dir) GTEST_SKIP() << "no shared data";
  const Matrix3 turn_x{{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}};  // y -> z, z -> -y
  for (const auto& [file, up] : {std::pair{"livesu2015_edgecone/bunny_in.mesh", Vec3{0, 0, 1}},
                                 std::pair{"livesu2016_skeleton/armadillo.mesh", Vec3{0, 1, 0}}}) {
    const HexMesh mesh = read_hex_mesh(*dir / "meshes" / file).mesh;
    EXPECT_EQ(choose(mesh), up) << file;
    EXPECT_EQ(choose(transformed(mesh, turn_x)), exact(turn_x * up)) << file << " turned about x";
  }
}

}  // namespace
}  // namespace hq
