// --compare-align auto and --reference-align auto: the 24 axis rotations,
// the identity's margin, ICP, mirrors (docs/analysis.md "Compare alignment").
#include "hqview/analysis/compare_alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "hqview/io/mesh_reader.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::box_grid;
using test::cube_corners;
using test::shared_data_dir;

double determinant(const Matrix3& m) {
  return det(Vec3{m[0][0], m[0][1], m[0][2]}, Vec3{m[1][0], m[1][1], m[1][2]}, Vec3{m[2][0], m[2][1], m[2][2]});
}

bool same(const Matrix3& a, const Matrix3& b, double tolerance = 1e-9) {
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      if (std::abs(a[i][j] - b[i][j]) > tolerance) return false;
  return true;
}

const Matrix3 kTurnX90{{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}};  // y -> z, z -> -y
const Matrix3 kTurnZ180{{{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}}};

// The mesh with every point mapped by p -> m p + offset.
HexMesh transformed(const HexMesh& mesh, const Matrix3& m, const Vec3& offset) {
  HexMesh copy = mesh;
  for (Vec3& p : copy.points) p = m * p + offset;
  return copy;
}

// An asymmetric part built by hand: an L of unit hexes (4 x 1 x 1 along x,
// 1 x 3 x 1 up y from its first hex, a 1 x 1 x 2 post on the far end), so
// that no axis rotation but the identity maps it onto itself.
HexMesh l_part() {
  HexMesh mesh;
  auto add = [&](int x, int y, int z) {
    const Index base = static_cast<Index>(mesh.points.size());
    for (const Vec3& c : cube_corners()) mesh.points.push_back(c + Vec3{double(x), double(y), double(z)});
    mesh.hexes.push_back({base, base + 1, base + 2, base + 3, base + 4, base + 5, base + 6, base + 7});
  };
  for (int x = 0; x < 4; ++x) add(x, 0, 0);
  for (int y = 1; y < 4; ++y) add(0, y, 0);
  add(3, 0, 1);
  add(3, 0, 2);
  return mesh;
}

CompareAlignment align(const HexMesh& fixed, const HexMesh& moving) {
  return align_compare_mesh(fixed, build_topology(fixed), moving, build_topology(moving), CompareAlign::auto_);
}

// Every point of `moving` lands within tolerance (of the diagonal) of where
// it came from in `fixed` (same point ids).
double worst_landing(const HexMesh& fixed, const HexMesh& moving, const CompareAlignment& a) {
  double worst = 0;
  for (std::size_t i = 0; i < fixed.points.size(); ++i)
    worst = std::max(worst, norm(aligned_point(moving.points[i], a) - fixed.points[i]));
  return worst / bounding_box(fixed.points).diagonal();
}

std::optional<HexMesh> shared_mesh(const char* relative) {
  const auto dir = shared_data_dir();
  if (!dir) return std::nullopt;
  return read_hex_mesh(*dir / "meshes" / relative).mesh;
}

TEST(CompareAlignment, TheAxisRotationsAreTheTwentyFourProperOnes) {
  const auto rotations = axis_rotations();
  EXPECT_TRUE(same(rotations[0], kIdentity3));
  std::set<std::string> names;
  for (const Matrix3& r : rotations) {
    EXPECT_DOUBLE_EQ(determinant(r), 1.0);
    EXPECT_TRUE(same(r * transposed(r), kIdentity3));
    names.insert(rotation_name(r));
  }
  EXPECT_EQ(names.size(), 24u);  // distinct, so distinct matrices
  EXPECT_EQ(rotation_name(kTurnX90), "90 deg about +x");
  EXPECT_EQ(rotation_name(transposed(kTurnX90)), "90 deg about -x");
  EXPECT_EQ(rotation_name(kTurnZ180), "180 deg about +z");
  EXPECT_EQ(rotation_name(Matrix3{{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}}), "120 deg about +x+y+z");
  EXPECT_EQ(rotation_name(Matrix3{{{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}}), "180 deg about +x+y");
  EXPECT_NEAR(rotation_angle_degrees(kTurnX90), 90.0, 1e-12);
}

// A copy turned (about the origin, then moved) is found: the inverse turn,
// every point back where it was.
void expect_turn_found(const HexMesh& mesh, const Matrix3& turn, const std::string& what) {
  const HexMesh copy = transformed(mesh, turn, {0.3, -2.0, 5.0});
  const CompareAlignment a = align(mesh, copy);
  SCOPED_TRACE(what);
  EXPECT_TRUE(a.searched);
  EXPECT_TRUE(a.aligned);
  EXPECT_TRUE(same(a.axis_rotation, transposed(turn))) << rotation_name(a.axis_rotation);
  EXPECT_FALSE(a.mirrored);
  EXPECT_LT(a.distance, 1e-4);
  EXPECT_GT(a.identity_distance, 0.01);
  EXPECT_NEAR(a.scale, 1.0, 1e-9);
  EXPECT_LT(worst_landing(mesh, copy, a), 1e-4);
  EXPECT_NE(alignment_description(a).find("turned " + rotation_name(transposed(turn))), std::string::npos)
      << alignment_description(a);
}

TEST(CompareAlignment, FindsTheTurnOfAHandBuiltPart) {
  const HexMesh part = l_part();
  expect_turn_found(part, kTurnX90, "90 about x");
  expect_turn_found(part, kTurnZ180, "180 about z");
  expect_turn_found(part, Matrix3{{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}}, "120 about the diagonal");
}

TEST(CompareAlignment, FindsTheTurnOfSharedMeshes) {
  for (const char* name : {"gao2016_sweeping/kitten_1.mesh", "livesu2016_skeleton/armadillo.mesh"}) {
    const auto mesh = shared_mesh(name);
    if (!mesh) GTEST_SKIP() << "../shared/data is absent";
    expect_turn_found(*mesh, kTurnX90, std::string(name) + " 90 about x");
    expect_turn_found(*mesh, kTurnZ180, std::string(name) + " 180 about z");
  }
}

TEST(CompareAlignment, AScaledTurnedCopyIsFoundAtItsScale) {
  const HexMesh part = l_part();
  HexMesh copy = transformed(part, kTurnX90, {100, 0, 0});
  for (Vec3& p : copy.points) p = 40.0 * p;
  const CompareAlignment a = align(part, copy);
  EXPECT_NEAR(a.scale, 1.0 / 40.0, 1e-9);
  EXPECT_TRUE(same(a.axis_rotation, transposed(kTurnX90)));
  EXPECT_LT(worst_landing(part, copy, a), 1e-4);
}

TEST(CompareAlignment, TheSameMeshStaysWhereItIs) {
  const HexMesh part = l_part();
  const CompareAlignment a = align(part, part);
  EXPECT_TRUE(a.searched);
  EXPECT_FALSE(a.aligned);
  EXPECT_TRUE(same(a.axis_rotation, kIdentity3));
  EXPECT_LT(a.distance, 1e-12);
  EXPECT_FALSE(a.icp_applied);
  EXPECT_EQ(alignment_description(a), "");
  const auto fandisk = shared_mesh("li2012_srf/fandisk.mesh");
  if (!fandisk) GTEST_SKIP() << "../shared/data is absent";
  const CompareAlignment f = align(*fandisk, *fandisk);
  EXPECT_FALSE(f.aligned);
  EXPECT_TRUE(same(f.axis_rotation, kIdentity3));
  EXPECT_FALSE(f.mirrored);
}

TEST(CompareAlignment, BunnyInAndOutStayAtTheIdentity) {
  const auto in = shared_mesh("livesu2015_edgecone/bunny_in.mesh");
  if (!in) GTEST_SKIP() << "../shared/data is absent";
  const auto out = shared_mesh("livesu2015_edgecone/bunny_out.mesh");
  const CompareAlignment a = align(*in, *out);
  EXPECT_FALSE(a.aligned);
  EXPECT_TRUE(same(a.axis_rotation, kIdentity3));
  EXPECT_FALSE(a.mirrored);
  EXPECT_LT(a.distance, 0.01);
  EXPECT_FALSE(a.icp_applied);  // they share a frame: never moved
}

TEST(CompareAlignment, AMirroredCopyIsReportedAsMirrored) {
  const Matrix3 mirror_x{{{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  std::vector<HexMesh> meshes{l_part()};
  if (const auto kitten = shared_mesh("gao2016_sweeping/kitten_1.mesh")) meshes.push_back(*kitten);
  for (const HexMesh& mesh : meshes) {
    const HexMesh copy = transformed(mesh, mirror_x, {0, 0, 0});
    const CompareAlignment a = align(mesh, copy);
    EXPECT_TRUE(a.mirrored);
    EXPECT_LT(a.mirror_distance, 1e-4);
    EXPECT_GT(a.axis_rotation_distance, 2 * a.mirror_distance);
    EXPECT_NEAR(std::abs(a.mirror_normal.x), 1.0, 1e-9);
    EXPECT_NE(alignment_description(a).find("mirror image"), std::string::npos);
  }
  // A mirror image that a rotation also fits (a symmetric box) is no mirror.
  const HexMesh box = box_grid(3, 2, 1);
  EXPECT_FALSE(align(box, transformed(box, mirror_x, {0, 0, 0})).mirrored);
}

TEST(CompareAlignment, IcpRefinesASmallTurn) {
  // Turned 90 degrees about x and then 4 more about z: the axis rotation
  // leaves a residue that ICP removes.
  const HexMesh part = l_part();
  const double t = 4.0 * M_PI / 180.0;
  const Matrix3 small{{{std::cos(t), -std::sin(t), 0}, {std::sin(t), std::cos(t), 0}, {0, 0, 1}}};
  const HexMesh copy = transformed(part, small * kTurnX90, {10, 0, 0});
  const CompareAlignment a = align(part, copy);
  EXPECT_TRUE(same(a.axis_rotation, transposed(kTurnX90)));
  EXPECT_TRUE(a.icp_applied);
  EXPECT_LT(a.distance, 0.5 * a.axis_rotation_distance);
  EXPECT_NEAR(a.scale, 1.0, 1e-3);  // the box fit's scale (the turned box is larger) corrected
  EXPECT_LT(worst_landing(part, copy, a), 1e-3) << a.icp_iterations << " iterations";
}

TEST(CompareAlignment, NoneAndBboxNeverTurn) {
  const HexMesh part = l_part();
  const HexMesh copy = transformed(part, kTurnX90, {100, 0, 0});
  for (CompareAlign mode : {CompareAlign::none, CompareAlign::bbox}) {
    const CompareAlignment a =
        align_compare_mesh(part, build_topology(part), copy, build_topology(copy), mode);
    EXPECT_FALSE(a.searched);
    EXPECT_TRUE(same(a.rotation, kIdentity3));
  }
}

}  // namespace
}  // namespace hq
