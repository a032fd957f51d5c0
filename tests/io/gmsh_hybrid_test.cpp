// Hybrid meshes made by Debian's Gmsh (built-in kernel) in the test, read
// back in every format Gmsh writes them in: a recombined transfinite box
// next to an unstructured one (Gmsh puts pyramids on the quads the
// tetrahedra meet) and an extruded mixed quad/triangle surface (hexahedra
// and prisms). Each file reads to the element counts the .msh file lists
// (counted here by a parse of its own), and every cell has a positive volume
// by a split into tetrahedra (hybrid_mesh_files.h). Skipped without gmsh.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "gmsh_run.h"
#include "hqview/io/mesh_reader.h"
#include "hybrid_mesh_files.h"
#include "support/gmsh_hybrid.h"
#include "temp_dir.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::kHexTetGeo;
using test::run_gmsh;
using test::TempDir;

using test::msh22_type_counts;

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

using test::kExtrudedGeo;

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

// Each cell of a kind as the sorted coordinates of its corners (rounded to
// 1e-9: Gmsh's Abaqus export prints 14 digits), the cells sorted: the same
// for two files of one mesh whatever their numbering.
std::vector<std::vector<std::array<double, 3>>> cells_by_coordinates(const Mesh& mesh, CellKind kind) {
  std::vector<std::vector<std::array<double, 3>>> out;
  for_each_block(mesh, [&](auto k, const auto& cells) {
    if (k() != kind) return;
    for (const auto& cell : cells) {
      std::vector<std::array<double, 3>> corners;
      for (const Index v : cell) {
        const Vec3& p = mesh.points[static_cast<std::size_t>(v)];
        const auto round = [](double x) { return std::round(x * 1e9) / 1e9; };
        corners.push_back({round(p.x), round(p.y), round(p.z)});
      }
      std::sort(corners.begin(), corners.end());
      out.push_back(corners);
    }
  });
  std::sort(out.begin(), out.end());
  return out;
}

// The hex-tet boxes made second order by Gmsh (-order 2: 27-node hexahedra,
// 10-node tetrahedra, 14-node pyramids) read, in MSH 2.2, MSH 4.1, VTK (its
// pyramids as 14-point VTK_PYRAMIDs), Abaqus (C3D27, C3D10) and MEDIT
// (27-vertex Hexahedra, TetrahedraP2; Gmsh writes no pyramids in these two),
// to the linear mesh's cells, all with positive volumes.
TEST(GmshHybrid, SecondOrderMeshReadsToTheLinearMeshsCells) {
  const TempDir dir("gmsh_second_order");
  if (!run_gmsh(dir, kHexTetGeo, {"lin22.msh"}) ||
      !run_gmsh(dir, kHexTetGeo, {"q22.msh", "q.msh", "q.vtk", "q.inp", "q.mesh"}, "-order 2"))
    GTEST_SKIP() << "gmsh failed or is missing";
  std::ifstream in(dir.path() / "q22.msh");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::map<int, int> counts = msh22_type_counts(text);
  EXPECT_EQ(counts.at(12), 64);  // MSH_HEX_27
  EXPECT_EQ(counts.at(14), 16);  // MSH_PYR_14
  EXPECT_GT(counts.at(11), 0);   // MSH_TET_10
  EXPECT_EQ(counts.count(4) + counts.count(5) + counts.count(7), 0u);
  const LoadedMesh linear = read_hex_mesh(dir.path() / "lin22.msh");
  for (const char* file : {"q22.msh", "q.msh", "q.vtk", "q.inp", "q.mesh"}) {
    SCOPED_TRACE(file);
    const LoadedMesh loaded = read_hex_mesh(dir.path() / file);
    const bool has_pyramids = std::string(file) != "q.inp" && std::string(file) != "q.mesh";
    for (const CellKind kind : {CellKind::hex, CellKind::tet, CellKind::pyramid}) {
      if (kind == CellKind::pyramid && !has_pyramids) continue;
      EXPECT_EQ(cells_by_coordinates(loaded.mesh, kind), cells_by_coordinates(linear.mesh, kind))
          << cell_kind_name(kind);
    }
    EXPECT_EQ(loaded.mesh.pyramids.size(), has_pyramids ? 16u : 0u);
    std::vector<std::array<double, 3>> points;
    for (const Vec3& p : loaded.mesh.points) points.push_back({p.x, p.y, p.z});
    int num_bad = 0;
    for_each_block(loaded.mesh, [&](auto kind, const auto& cells) {
      for (const auto& cell : cells)
        if (test::split_volume(points, cell_kind_vtk_type(kind()), std::vector<int>(cell.begin(), cell.end())).min_tet <= 0)
          ++num_bad;
    });
    EXPECT_EQ(num_bad, 0);
    const auto warned = std::count_if(loaded.warnings.begin(), loaded.warnings.end(), [](const std::string& w) {
      return w.find("higher-order") != std::string::npos;
    });
    EXPECT_EQ(warned, 1);
  }
}

}  // namespace
}  // namespace hq
