// Hybrid meshes made by Debian's Gmsh (built-in kernel) in the test, read
// back in every format Gmsh writes them in: a recombined transfinite box
// next to an unstructured one (Gmsh puts pyramids on the quads the
// tetrahedra meet) and an extruded mixed quad/triangle surface (hexahedra
// and prisms). Each file reads to the element counts the .msh file lists
// (counted here by a parse of its own), and every cell has a positive volume
// by a split into tetrahedra (hybrid_mesh_files.h). Skipped without gmsh.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "hqview/io/mesh_reader.h"
#include "hybrid_mesh_files.h"
#include "io/gmsh_run.h"
#include "temp_dir.h"

namespace hq {
namespace {

using test::TempDir;

using test::msh22_type_counts;

bool run_gmsh(const TempDir& dir, const std::string& geo, const std::vector<std::string>& outputs) {
  return test::run_gmsh(HQ_GMSH, dir, geo, outputs);
}

void expect_counts_and_positive_volumes(const std::filesystem::path& path, const std::map<int, int>& counts) {
  SCOPED_TRACE(path.filename().string());
  const LoadedMesh loaded = read_hex_mesh(path);
  EXPECT_EQ(static_cast<int>(loaded.mesh.hexes.size()), counts.count(5) ? counts.at(5) : 0);
  EXPECT_EQ(static_cast<int>(loaded.mesh.tets.size()), counts.count(4) ? counts.at(4) : 0);
  EXPECT_EQ(static_cast<int>(loaded.mesh.wedges.size()), counts.count(6) ? counts.at(6) : 0);
  EXPECT_EQ(static_cast<int>(loaded.mesh.pyramids.size()), counts.count(7) ? counts.at(7) : 0);
  std::vector<std::array<double, 3>> points;
  for (const Vec3& p : loaded.mesh.points) points.push_back({p.x, p.y, p.z});
  int num_bad = 0;
  for_each_block(loaded.mesh, [&](auto kind, const auto& cells) {
    for (const auto& cell : cells) {
      const std::vector<int> corners(cell.begin(), cell.end());
      if (test::split_volume(points, cell_kind_vtk_type(kind()), corners).total <= 0) ++num_bad;
    }
  });
  EXPECT_EQ(num_bad, 0);
}

// A 4x4x4 recombined transfinite box [0,1]^3 and an unstructured box
// [1,2]x[0,1]^2 extruded from its x=1 face without layers.
constexpr const char* kHexTetGeo = R"(
Point(1) = {0, 0, 0, 0.25};
l[] = Extrude {0, 1, 0} { Point{1}; Layers{4}; };
s[] = Extrude {0, 0, 1} { Line{l[1]}; Layers{4}; Recombine; };
v[] = Extrude {1, 0, 0} { Surface{s[1]}; Layers{4}; Recombine; };
w[] = Extrude {1, 0, 0} { Surface{v[0]}; };
)";

// A transfinite recombined square next to a triangle, extruded in 3 layers.
constexpr const char* kExtrudedGeo = R"(
Point(1) = {0, 0, 0, 0.3}; Point(2) = {1, 0, 0, 0.3}; Point(3) = {1, 1, 0, 0.3};
Point(4) = {0, 1, 0, 0.3}; Point(5) = {2, 0.5, 0, 0.3};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1}; Line(5) = {2, 5}; Line(6) = {5, 3};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, -2}; Plane Surface(2) = {2};
Transfinite Curve{1, 2, 3, 4} = 4; Transfinite Surface{1}; Recombine Surface{1};
Extrude {0, 0, 1} { Surface{1, 2}; Layers{3}; Recombine; }
)";

TEST(GmshHybrid, HexTetBoxesGetPyramids) {
  const TempDir dir("gmsh_hex_tet");
  if (!run_gmsh(dir, kHexTetGeo, {"m22.msh", "m.msh", "m.vtk"})) GTEST_SKIP() << "gmsh failed or is missing";
  std::ifstream in(dir.path() / "m22.msh");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::map<int, int> counts = msh22_type_counts(text);
  EXPECT_EQ(counts.at(5), 64);  // the transfinite box
  EXPECT_GT(counts.at(4), 0);
  EXPECT_EQ(counts.at(7), 16);  // one pyramid on each quad of the shared face
  for (const char* file : {"m22.msh", "m.msh", "m.vtk"}) expect_counts_and_positive_volumes(dir.path() / file, counts);
}

TEST(GmshHybrid, ExtrudedMixedSurfaceGivesHexesAndPrisms) {
  const TempDir dir("gmsh_extruded");
  if (!run_gmsh(dir, kExtrudedGeo, {"m22.msh", "m.msh", "m.vtk"})) GTEST_SKIP() << "gmsh failed or is missing";
  std::ifstream in(dir.path() / "m22.msh");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::map<int, int> counts = msh22_type_counts(text);
  EXPECT_EQ(counts.at(5), 27);  // 3x3 quads x 3 layers
  EXPECT_GT(counts.at(6), 0);
  EXPECT_EQ(counts.at(6) % 3, 0);
  EXPECT_EQ(counts.count(4), 0u);
  for (const char* file : {"m22.msh", "m.msh", "m.vtk"}) expect_counts_and_positive_volumes(dir.path() / file, counts);
}

}  // namespace
}  // namespace hq
