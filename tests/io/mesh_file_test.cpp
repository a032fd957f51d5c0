// read_file_bytes() and read_hex_mesh(): file access and format dispatch.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"
#include "io/error_text.h"
#include "io/temp_dir.h"

namespace hq {
namespace {

using test::error_text;
using test::TempDir;

const std::string kMedit =
    "MeshVersionFormatted 1\nDimension 3\nVertices 8\n"
    "0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n0 0 1 0\n1 0 1 0\n1 1 1 0\n0 1 1 0\n"
    "Hexahedra 1\n1 2 3 4 5 6 7 8 0\nEnd\n";
const std::string kVtk =
    "# vtk DataFile Version 3.0\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 float\n"
    "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\nCELLS 1 9\n8 0 1 2 3 4 5 6 7\nCELL_TYPES 1\n12\n";

TEST(ReadFileBytes, ReadsEveryByte) {
  TempDir dir("file");
  std::string bytes(200000, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7 % 256);
  EXPECT_EQ(read_file_bytes(dir.write("data.bin", bytes)), bytes);
  EXPECT_EQ(read_file_bytes(dir.write("empty", "")), "");
}

TEST(ReadFileBytes, Errors) {
  TempDir dir("file");
  const auto error = [](const std::filesystem::path& path) {
    return error_text<InputError>([&] { read_file_bytes(path); });
  };
  const auto missing = dir.path() / "missing.mesh";
  EXPECT_EQ(error(missing), missing.string() + ": cannot open: No such file or directory");
  EXPECT_EQ(error(dir.path()), dir.path().string() + ": not a regular file");
  const auto fifo = dir.path() / "fifo.mesh";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(error(fifo), fifo.string() + ": not a regular file");  // and does not block
  const auto in_file = dir.write("file", "x") / "child.mesh";
  EXPECT_EQ(error(in_file), in_file.string() + ": cannot open: Not a directory");
}

TEST(ReadFileBytes, Unreadable) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: permissions are not enforced";
  TempDir dir("file");
  const auto locked = dir.write("locked.mesh", kMedit);
  std::filesystem::permissions(locked, std::filesystem::perms::none);
  EXPECT_EQ(error_text<InputError>([&] { read_file_bytes(locked); }),
            locked.string() + ": cannot open: Permission denied");
}

TEST(ReadHexMesh, DispatchesOnTheExtensionInAnyCase) {
  TempDir dir("file");
  for (const char* name : {"a.mesh", "b.MESH", "c.Mesh"}) {
    const LoadedMesh loaded = read_hex_mesh(dir.write(name, kMedit));
    EXPECT_EQ(loaded.format, "medit");
    EXPECT_EQ(loaded.mesh.hexes.size(), 1u);
  }
  for (const char* name : {"a.vtk", "b.VTK"}) {
    const LoadedMesh loaded = read_hex_mesh(dir.write(name, kVtk));
    EXPECT_EQ(loaded.format, "vtk-legacy-ascii");
    EXPECT_EQ(loaded.mesh.points.size(), 8u);
    EXPECT_EQ(loaded.mesh.hexes.size(), 1u);
  }
}

TEST(ReadHexMesh, FromBytesAlreadyRead) {
  const LoadedMesh loaded = read_hex_mesh("not/read/from/disk.VTK", kVtk);
  EXPECT_EQ(loaded.format, "vtk-legacy-ascii");
  EXPECT_EQ(loaded.mesh.hexes.size(), 1u);
  EXPECT_EQ(read_hex_mesh("m.mesh", kMedit).format, "medit");
  EXPECT_EQ(error_text<InputError>([] { read_hex_mesh("m.obj", kMedit); }),
            "m.obj: unknown mesh format '.obj' (expected .mesh or .vtk)");
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh("dir/m.mesh", "MeshVersionFormatted 1\nVertices -3\n"); }),
            "dir/m.mesh:2: negative number of Vertices: -3");
}

TEST(ReadHexMesh, ExtensionErrors) {
  TempDir dir("file");
  const auto error = [](const std::filesystem::path& path) {
    return error_text<InputError>([&] { read_hex_mesh(path); });
  };
  const auto xyz = dir.write("m.xyz", kMedit);
  EXPECT_EQ(error(xyz), xyz.string() + ": unknown mesh format '.xyz' (expected .mesh or .vtk)");
  const auto meshb = dir.write("m.meshb", kMedit);
  EXPECT_EQ(error(meshb), meshb.string() + ": unknown mesh format '.meshb' (expected .mesh or .vtk)");
  const auto none = dir.write("mesh", kMedit);
  EXPECT_EQ(error(none), none.string() + ": no file extension (expected .mesh or .vtk)");
  const auto missing = dir.path() / "missing.vtk";
  EXPECT_EQ(error(missing), missing.string() + ": cannot open: No such file or directory");
}

TEST(ReadHexMesh, ContentMustMatchTheExtension) {
  TempDir dir("file");
  const auto vtk_as_mesh = dir.write("m.mesh", kVtk);
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(vtk_as_mesh); }),
            vtk_as_mesh.string() + ":1: a .mesh file with legacy VTK content");
  const auto mesh_as_vtk = dir.write("m.vtk", "# written by hand\n" + kMedit);
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(mesh_as_vtk); }),
            mesh_as_vtk.string() + ": a .vtk file with MEDIT (.mesh) content");
  const auto other = dir.write("o.mesh", "solid x\nendsolid x\n");
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(other); }),
            other.string() + ":1: expected MeshVersionFormatted, got 'solid'");
  const auto empty = dir.write("e.vtk", "");
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(empty); }),
            empty.string() + ":1: empty file, expected '# vtk DataFile Version X.Y'");
}

TEST(ReadHexMesh, ParseErrorsNameThePathAsGiven) {
  TempDir dir("file");
  const auto bad = dir.write("bad.mesh", "MeshVersionFormatted 1\nVertices -3\n");
  try {
    read_hex_mesh(bad);
    FAIL() << "no exception";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.path(), bad.string());
    EXPECT_EQ(e.line(), 2);
    EXPECT_EQ(std::string(e.what()), bad.string() + ":2: negative number of Vertices: -3");
  }
}

}  // namespace
}  // namespace hq
