// read_file_bytes() and read_hex_mesh(): file access and format dispatch.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"
#include "io/error_text.h"
#include "io/temp_dir.h"

namespace hq {
namespace HQ_TEST_UNIT {

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
  EXPECT_EQ(error_text<InputError>([] { read_hex_mesh("m.stl", kMedit); }),
            "m.stl: unknown mesh format '.stl' (expected .mesh, .vtk, .vtu, .msh, .ovm, .inp, .e or .exo, or a surface "
            ".obj, .off or .ply)");
  // A .obj is a surface mesh now (polygon_reader.h): MEDIT content in it is refused as such.
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh("m.obj", kMedit); }),
            "m.obj: a .obj file with MEDIT (.mesh) content (expected the extension .mesh)");
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh("dir/m.mesh", "MeshVersionFormatted 1\nVertices -3\n"); }),
            "dir/m.mesh:2: negative number of Vertices: -3");
}

TEST(ReadHexMesh, ExtensionErrors) {
  TempDir dir("file");
  const auto error = [](const std::filesystem::path& path) {
    return error_text<InputError>([&] { read_hex_mesh(path); });
  };
  const auto xyz = dir.write("m.xyz", kMedit);
  EXPECT_EQ(error(xyz),
            xyz.string() + ": unknown mesh format '.xyz' (expected .mesh, .vtk, .vtu, .msh, .ovm, .inp, .e or .exo, or a surface .obj, .off or .ply)");
  const auto meshb = dir.write("m.meshb", kMedit);
  EXPECT_EQ(
      error(meshb),
      meshb.string() + ": unknown mesh format '.meshb' (expected .mesh, .vtk, .vtu, .msh, .ovm, .inp, .e or .exo, or a surface .obj, .off or .ply)");
  const auto none = dir.write("mesh", kMedit);
  EXPECT_EQ(error(none),
            none.string() + ": no file extension (expected .mesh, .vtk, .vtu, .msh, .ovm, .inp, .e or .exo, or a surface .obj, .off or .ply)");
  const auto missing = dir.path() / "missing.vtk";
  EXPECT_EQ(error(missing), missing.string() + ": cannot open: No such file or directory");
}

TEST(ReadHexMesh, ContentMustMatchTheExtension) {
  TempDir dir("file");
  const auto vtk_as_mesh = dir.write("m.mesh", kVtk);
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(vtk_as_mesh); }),
            vtk_as_mesh.string() + ": a .mesh file with legacy VTK content (expected the extension .vtk)");
  const auto mesh_as_vtk = dir.write("m.vtk", "# written by hand\n" + kMedit);
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(mesh_as_vtk); }),
            mesh_as_vtk.string() + ": a .vtk file with MEDIT (.mesh) content (expected the extension .mesh)");
  const auto other = dir.write("o.mesh", "solid x\nendsolid x\n");
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(other); }),
            other.string() + ":1: expected MeshVersionFormatted, got 'solid'");
  const auto empty = dir.write("e.vtk", "");
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(empty); }),
            empty.string() + ":1: empty file, expected '# vtk DataFile Version X.Y'");
}

// Minimal files of the other formats: one unit cube each.
const std::string kVtu =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid>\n"
    "<Piece NumberOfPoints=\"8\" NumberOfCells=\"1\"><Points>\n"
    "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
    "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1</DataArray></Points><Cells>\n"
    "<DataArray type=\"Int32\" Name=\"connectivity\">0 1 2 3 4 5 6 7</DataArray>\n"
    "<DataArray type=\"Int32\" Name=\"offsets\">8</DataArray>\n"
    "<DataArray type=\"UInt8\" Name=\"types\">12</DataArray>\n"
    "</Cells></Piece></UnstructuredGrid></VTKFile>\n";
const std::string kGmsh =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n"
    "7 1 1 1\n8 0 1 1\n$EndNodes\n$Elements\n1\n1 5 0 1 2 3 4 5 6 7 8\n$EndElements\n";
const std::string kAbaqus =
    "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n5, 0, 0, 1\n6, 1, 0, 1\n7, 1, 1, 1\n8, 0, 1, 1\n"
    "*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4, 5, 6, 7, 8\n";

TEST(ReadHexMesh, TheOtherFormats) {
  EXPECT_EQ(read_hex_mesh("m.vtu", kVtu).format, "vtu-ascii");
  EXPECT_EQ(read_hex_mesh("m.MSH", kGmsh).format, "gmsh-2.2-ascii");
  EXPECT_EQ(read_hex_mesh("m.inp", kAbaqus).format, "abaqus");
  for (const char* name : {"m.vtu", "m.msh", "m.inp"}) {
    const LoadedMesh loaded = read_hex_mesh(name, std::string(name) == "m.vtu"   ? kVtu
                                                  : std::string(name) == "m.msh" ? kGmsh
                                                                                 : kAbaqus);
    EXPECT_EQ(loaded.mesh.points.size(), 8u);
    ASSERT_EQ(loaded.mesh.hexes.size(), 1u);
    EXPECT_EQ(loaded.mesh.hexes[0], (Hex{0, 1, 2, 3, 4, 5, 6, 7}));
  }
  // Exodus goes to netCDF (or is refused without it).
  EXPECT_NE(error_text<InputError>([] { read_hex_mesh("m.exo", "CDF\x01junk"); }).find("m.exo: "), std::string::npos);
}

TEST(ReadHexMesh, ContentIsCheckedAgainstTheExtension) {
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh("m.vtu", kGmsh); }),
            "m.vtu: a .vtu file with Gmsh content (expected the extension .msh)");
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh("m.msh", kVtu); }),
            "m.msh: a .msh file with VTK XML content (expected the extension .vtu)");
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh("m.inp", kMedit); }),
            "m.inp: a .inp file with MEDIT (.mesh) content (expected the extension .mesh)");
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh("m.ovm", kAbaqus); }),
            "m.ovm: a .ovm file with Abaqus content (expected the extension .inp)");
}

TEST(ReadHexMesh, FormatOverride) {
  // --format wins over the extension, which may be anything or absent.
  EXPECT_EQ(read_hex_mesh_as("mesh.txt", kGmsh, "msh").format, "gmsh-2.2-ascii");
  EXPECT_EQ(read_hex_mesh_as("noextension", kVtu, "vtu").format, "vtu-ascii");
  EXPECT_EQ(read_hex_mesh_as("m.vtk", kMedit, "mesh").format, "medit");
  EXPECT_EQ(read_hex_mesh_as("m.vtk", kVtk, "").format, "vtk-legacy-ascii");  // empty: by the extension
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh_as("m.vtu", kMedit, "vtu"); }),
            "m.vtu:1: text before the root element");  // the chosen reader's own error
  EXPECT_EQ(error_text<ValueError>([] { read_hex_mesh_as("m.vtk", kVtk, "stl"); }),
            "unknown mesh format 'stl' (expected mesh, vtk, vtu, msh, ovm, exodus, inp, obj, off, ply)");
  TempDir dir("file");
  EXPECT_EQ(read_hex_mesh_as(dir.write("cube.dat", kAbaqus), "inp").format, "abaqus");
  EXPECT_EQ(mesh_format_names(), "mesh, vtk, vtu, msh, ovm, exodus, inp, obj, off, ply");
}

TEST(ReadHexMesh, DetectsFormatsByContent) {
  EXPECT_EQ(detect_mesh_format(kMedit), "mesh");
  EXPECT_EQ(detect_mesh_format(kVtk), "vtk");
  EXPECT_EQ(detect_mesh_format(kVtu), "vtu");
  EXPECT_EQ(detect_mesh_format(kGmsh), "msh");
  EXPECT_EQ(detect_mesh_format(kAbaqus), "inp");
  EXPECT_EQ(detect_mesh_format("OVM ASCII\n"), "ovm");
  EXPECT_EQ(detect_mesh_format(std::string("CDF\x01", 4)), "exodus");
  EXPECT_EQ(detect_mesh_format("\x89HDF\r\n\x1a\n"), "exodus");
  EXPECT_EQ(detect_mesh_format("solid x\n"), "");
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
