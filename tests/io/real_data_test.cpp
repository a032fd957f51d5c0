// The real meshes of ../shared/data (HexaLab's dataset; see its README.md):
// every one loads with the vertex and hex counts of the README's table.
// Skipped when the data is absent.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "hqview/io/mesh_reader.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

struct MeshCase {
  const char* path;  // under meshes/
  Index num_vertices;
  Index num_hexes;
};

// /work/shared/data/README.md, the table.
constexpr MeshCase kMeshes[] = {
    {"gao2016_sweeping/kitten_1.mesh", 425, 300},
    {"gao2016_sweeping/bunny_1.mesh", 404, 264},
    {"gao2016_sweeping/hand7_1.mesh", 1362, 956},
    {"gao2016_sweeping/Dolphin_padded.mesh", 48794, 45440},
    {"livesu2016_skeleton/armadillo.mesh", 5137, 3856},
    {"livesu2016_skeleton/warrior.mesh", 24699, 19392},
    {"livesu2015_edgecone/bunny_in.mesh", 41749, 37734},
    {"livesu2015_edgecone/bunny_out.mesh", 41749, 37734},
    {"li2012_srf/fandisk.mesh", 614, 357},
    {"dualsheet2019/rockarm.vtk", 2651, 1858},
    {"smf2019/hex_cube_coarse.vtk", 136, 68},
};

constexpr const char* kSurfaces[] = {
    "gao2016_sweeping/kitten.off",  "gao2016_sweeping/bunny.off",        "gao2016_sweeping/hand.off",
    "gao2016_sweeping/dolphin.off", "livesu2016_skeleton/armadillo.obj",
};

std::filesystem::path meshes_dir() { return *test::shared_data_dir() / "meshes"; }

TEST(RealData, EveryMeshLoadsWithTheDocumentedCounts) {
  if (!test::shared_data_dir()) GTEST_SKIP() << "../shared/data (or $HQVIEW_DATA) not found";
  for (const MeshCase& c : kMeshes) {
    SCOPED_TRACE(c.path);
    const LoadedMesh loaded = read_hex_mesh(meshes_dir() / c.path);
    EXPECT_EQ(loaded.mesh.num_vertices(), c.num_vertices);
    EXPECT_EQ(loaded.mesh.num_hexes(), c.num_hexes);
    EXPECT_EQ(loaded.format, std::string(c.path).ends_with(".vtk") ? "vtk-legacy-ascii" : "medit");
    for (const Vec3& p : loaded.mesh.points) ASSERT_TRUE(is_finite(p));
    for (const Hex& hex : loaded.mesh.hexes)
      for (const Index id : hex) {
        ASSERT_GE(id, 0);
        ASSERT_LT(id, loaded.mesh.num_vertices());
      }
    if (std::string(c.path) != "smf2019/hex_cube_coarse.vtk") {
      EXPECT_TRUE(loaded.warnings.empty());
    }
  }
}

TEST(RealData, MislabelledCubeWarns) {
  if (!test::shared_data_dir()) GTEST_SKIP() << "../shared/data (or $HQVIEW_DATA) not found";
  const auto path = meshes_dir() / "smf2019/hex_cube_coarse.vtk";
  const LoadedMesh loaded = read_hex_mesh(path);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_EQ(loaded.warnings[0], path.string() +
                                    ": 68 cells with 8 points but a non-hexahedral type (10) loaded as hexahedra: "
                                    "cells 0, 1, 2, 3, 4 and 63 more");
}

TEST(RealData, ReferenceSurfacesLoad) {
  if (!test::shared_data_dir()) GTEST_SKIP() << "../shared/data (or $HQVIEW_DATA) not found";
  for (const char* name : kSurfaces) {
    SCOPED_TRACE(name);
    const TriSurface surface = read_surface(meshes_dir() / name);
    EXPECT_GT(surface.points.size(), 1000u);
    EXPECT_GT(surface.triangles.size(), 1000u);
    // Closed triangle meshes: F = 2V - 4 for genus 0, close to it otherwise.
    EXPECT_NEAR(double(surface.triangles.size()) / double(surface.points.size()), 2.0, 0.1);
    for (const auto& triangle : surface.triangles)
      for (const Index id : triangle) {
        ASSERT_GE(id, 0);
        ASSERT_LT(id, static_cast<Index>(surface.points.size()));
      }
  }
}

TEST(RealData, MeshAsSurfaceNeedsTriangles) {
  if (!test::shared_data_dir()) GTEST_SKIP() << "../shared/data (or $HQVIEW_DATA) not found";
  // A hex .mesh has no Triangles section: it is not a reference surface.
  const auto path = meshes_dir() / "gao2016_sweeping/kitten_1.mesh";
  EXPECT_THROW(read_surface(path), ParseError);
}

}  // namespace
}  // namespace hq
