// read_surface(): reference surfaces through OpenMesh and the MEDIT reader.

#include <gtest/gtest.h>

#include <algorithm>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"
#include "io/error_text.h"
#include "io/temp_dir.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;
using test::TempDir;

void expect_valid(const TriSurface& surface) {
  for (const auto& triangle : surface.triangles)
    for (const Index id : triangle) {
      ASSERT_GE(id, 0);
      ASSERT_LT(id, static_cast<Index>(surface.points.size()));
    }
  for (const Vec3& p : surface.points) ASSERT_TRUE(is_finite(p));
}

// A unit square split in a triangle and a quad, plus an apex: 5 points.
const std::string kOff =
    "OFF\n5 3 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n"
    "4 0 1 2 3\n3 1 0 4\n3 2 1 4\n";  // consistently oriented

TEST(SurfaceReader, OffPolygonsAreTriangulatedAsFans) {
  TempDir dir("surface");
  const TriSurface surface = read_surface(dir.write("s.off", kOff));
  EXPECT_EQ(surface.points.size(), 5u);
  EXPECT_EQ(surface.triangles.size(), 4u);  // the quad gives 2
  EXPECT_EQ(surface.points[4], (Vec3{0.5, 0.5, 1}));
  expect_valid(surface);
}

TEST(SurfaceReader, ExtensionsInAnyCase) {
  TempDir dir("surface");
  EXPECT_EQ(read_surface(dir.write("S.OFF", kOff)).triangles.size(), 4u);
}

TEST(SurfaceReader, Obj) {
  TempDir dir("surface");
  const std::string obj =
      "# a pentagon and a triangle\n"
      "v 0 0 0\nv 1 0 0\nv 1.5 1 0\nv 0.5 1.5 0\nv -0.5 1 0\nv 0 0 -1\n"
      "vn 0 0 1\n"
      "f 1//1 2//1 3//1 4//1 5//1\n"
      "f 2 1 6\n";
  const TriSurface surface = read_surface(dir.write("s.obj", obj));
  EXPECT_EQ(surface.points.size(), 6u);
  EXPECT_EQ(surface.triangles.size(), 4u);
  expect_valid(surface);
}

TEST(SurfaceReader, StlMergesDuplicateVertices) {
  TempDir dir("surface");
  const std::string stl =
      "solid two\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n"
      "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\n"
      "endsolid two\n";
  const TriSurface surface = read_surface(dir.write("s.stl", stl));
  EXPECT_EQ(surface.points.size(), 4u);
  EXPECT_EQ(surface.triangles.size(), 2u);
  expect_valid(surface);
}

TEST(SurfaceReader, Ply) {
  TempDir dir("surface");
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
  const TriSurface surface = read_surface(dir.write("s.ply", ply));
  EXPECT_EQ(surface.points.size(), 4u);
  EXPECT_EQ(surface.triangles.size(), 2u);
  expect_valid(surface);
}

TEST(SurfaceReader, MeditTriangles) {
  TempDir dir("surface");
  const std::string mesh =
      "MeshVersionFormatted 2\nDimension 3\nVertices 3\n0 0 0 0\n1 0 0 0\n0 1 0 0\nTriangles 1\n1 2 3 0\nEnd\n";
  const TriSurface surface = read_surface(dir.write("s.Mesh", mesh));
  EXPECT_EQ(surface.points.size(), 3u);
  ASSERT_EQ(surface.triangles.size(), 1u);
  EXPECT_EQ(surface.triangles[0], (std::array<Index, 3>{0, 1, 2}));
}

TEST(SurfaceReader, Errors) {
  TempDir dir("surface");
  const auto error = [](const std::filesystem::path& path) {
    return error_text<InputError>([&] { read_surface(path); });
  };
  const auto missing = dir.path() / "missing.off";
  EXPECT_EQ(error(missing), missing.string() + ": cannot open: No such file or directory");
  const auto unknown = dir.write("s.xyz", "1 2 3\n");
  EXPECT_EQ(error(unknown),
            unknown.string() + ": unknown surface format '.xyz' (expected .obj, .off, .stl, .ply or .mesh)");
  const auto no_faces = dir.write("points.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_EQ(error(no_faces), no_faces.string() + ": empty surface (no faces)");
  const auto garbage = dir.write("garbage.off", "this is not an OFF file\n");
  EXPECT_EQ(error(garbage), garbage.string() + ": cannot read surface (OpenMesh could not parse it)");
  const auto empty = dir.write("empty.obj", "");
  EXPECT_EQ(error(empty), empty.string() + ": empty surface (no faces)");
  std::filesystem::create_directory(dir.path() / "dir.obj");
  EXPECT_EQ(error(dir.path() / "dir.obj"), (dir.path() / "dir.obj").string() + ": not a regular file");
  const auto medit = dir.write("s.mesh", "MeshVersionFormatted 2\nVertices 0\n");
  EXPECT_EQ(error_text<ParseError>([&] { read_surface(medit); }), medit.string() + ": no triangles");
}

TEST(SurfaceReader, OpenMeshDoesNotPrint) {
  TempDir dir("surface");
  const auto garbage = dir.write("garbage.off", "OFF\n2 1 0\n0 0 0\n1 0 0\n3 0 1 7\n");
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  try {
    read_surface(garbage);
  } catch (const InputError&) {
  }
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

// Files OpenMesh would read whole or allocate for from their headers are
// refused before it opens them (each message names what the file claims).
TEST(ReadSurface, HostileFilesAreRefusedBeforeOpenMeshReadsThem) {
  TempDir dir("surface_hostile");
  const auto off = dir.write("a.off", "OFF\n1000000000 1000000000 0\n0 0 0\n");
  EXPECT_EQ(error_text<ParseError>([&] { read_surface(off); }),
            off.string() + ": the header claims 2000000000 vertices and faces but the file has 34 bytes");
  const auto ply = dir.write("a.ply", "ply\nformat ascii 1.0\nelement vertex 500\nelement face 600\nend_header\n");
  EXPECT_EQ(error_text<ParseError>([&] { read_surface(ply); }),
            ply.string() + ": the header claims 1100 vertices and faces but the file has 68 bytes");
  std::string stl(84 + 50, '\0');
  stl[80] = 2;  // claims 2 triangles, holds 1
  const auto binary_stl = dir.write("a.stl", stl);
  EXPECT_EQ(error_text<ParseError>([&] { read_surface(binary_stl); }),
            binary_stl.string() + ": binary STL header claims 2 triangles (184 bytes) but the file has 134");
  for (const char* name : {"z.obj", "z.off", "z.mesh"}) {
    const auto zeros = dir.write(name, std::string(4096, '\0'));
    const std::string format = std::string(name) == "z.obj"   ? "OBJ"
                               : std::string(name) == "z.off" ? "OFF"
                                                              : "MEDIT (.mesh)";
    EXPECT_EQ(error_text<ParseError>([&] { read_surface(zeros); }),
              zeros.string() + ": binary data, expected " + format + " text (a NUL byte at offset 0)");
  }
  const auto big = dir.write("big.obj", std::string(2048, ' '));
  EXPECT_EQ(error_text<InputError>([&] { read_surface(big, ReadLimits{.max_memory = 1024}); }),
            big.string() + ": the file has 2048 bytes (2 KB), more than --max-memory (1 KB)");
}

}  // namespace
}  // namespace hq
