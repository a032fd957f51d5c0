// Property: whatever the bytes, the readers return or throw ParseError; they
// never crash, hang, throw anything else or allocate from absurd counts.
// Deterministic mutations (fixed seed) of small valid inputs; a sanitizer
// build of this test is a cheap fuzzer.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <typeinfo>
#include <vector>

#include "hqview/io/abaqus_reader.h"
#include "hqview/io/gmsh_reader.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/io/ovm_reader.h"
#include "hqview/io/polygon_reader.h"
#include "hqview/io/vtk_legacy_reader.h"
#include "hqview/io/vtu_reader.h"

namespace hq {
namespace HQ_TEST_UNIT {

const std::string kMedit =
    "MeshVersionFormatted 2\nDimension\n3\n# comment\nVertices 9\n"
    "0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n0 0 1 0\n1 0 1 0\n1 1 1 0\n0 1 1 0\n2 2 2 1\n"
    "Triangles 1\n1 2 3 0\nQuads 1\n1 2 3 4 0\nTetrahedra 1\n1 2 3 9 0\nFoo 1\nbar\n"
    "Hexahedra 1\n1 2 3 4 5 6 7 8 0\nEnd\n";

const std::string kVtkAscii =
    "# vtk DataFile Version 4.2\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 float\n"
    "0 0 0 1 0 0 1 1 0\n0 1 0 0 0 1 1 0 1\n1 1 1 0 1 1\n"
    "CELLS 2 14\n8 0 1 2 3 4 5 6 7\n4 0 1 2 4\nCELL_TYPES 2\n12\n10\nCELL_DATA 2\n";

const std::string kVtk51Ascii =
    "# vtk DataFile Version 5.1\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n"
    "0 0 0 1 0 0 1 1 0\n0 1 0 0 0 1 1 0 1\n1 1 1 0 1 1\nMETADATA\nINFORMATION 0\n\n"
    "CELLS 3 12\nOFFSETS vtktypeint64\n0 8 12\nCONNECTIVITY vtktypeint64\n0 1 2 3 4 5 6 7 0 1 2 4\n"
    "CELL_TYPES 2\n11\n10\n";

void put_be(std::string& out, std::uint64_t bits, int size) {
  for (int i = size - 1; i >= 0; --i) out += static_cast<char>((bits >> (8 * i)) & 0xff);
}

std::string binary_vtk(bool version5) {
  std::string s = std::string("# vtk DataFile Version ") + (version5 ? "5.1" : "3.0") +
                  "\ncube\nBINARY\nDATASET UNSTRUCTURED_GRID\nFIELD FieldData 1\nTIME 1 1 double\n";
  put_be(s, 0x4004000000000000u, 8);  // 2.5
  s += "\nPOINTS 8 float\n";
  const float corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& p : corners)
    for (const float c : p) put_be(s, std::bit_cast<std::uint32_t>(c), 4);
  if (version5) {
    s += "\nCELLS 2 8\nOFFSETS vtktypeint32\n";
    put_be(s, 0, 4);
    put_be(s, 8, 4);
    s += "\nCONNECTIVITY vtktypeint32\n";
    for (int i = 0; i < 8; ++i) put_be(s, static_cast<std::uint64_t>(i), 4);
  } else {
    s += "\nCELLS 1 9\n";
    put_be(s, 8, 4);
    for (int i = 0; i < 8; ++i) put_be(s, static_cast<std::uint64_t>(i), 4);
  }
  s += "\nCELL_TYPES 1\n";
  put_be(s, 12, 4);
  return s + "\n";
}

// A unit cube written by meshio as .vtu, binary (header and data in one
// base64 string) and zlib-compressed (header and blocks encoded apart).
const std::string kVtuBinary =
    "<?xml version=\"1.0\"?>\n"
    "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    "<UnstructuredGrid>\n"
    "<Piece NumberOfPoints=\"8\" NumberOfCells=\"1\">\n"
    "<Points>\n"
    "<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"binary\">\n"
    "wAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAPA/AAAAAAAAAAAAAAAAAAAAAAAAAAAAAPA/"
    "AAAAAAAA8D8AAAAAAAAAAAAAAAAAAAAAAAAAAAAA8D8AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAADwPwAAAAAAAPA/"
    "AAAAAAAAAAAAAAAAAADwPwAAAAAAAPA/AAAAAAAA8D8AAAAAAADwPwAAAAAAAAAAAAAAAAAA8D8AAAAAAADwPw==\n"
    "</DataArray>\n"
    "</Points>\n"
    "<Cells>\n"
    "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"binary\">\n"
    "QAAAAAAAAAAAAAAAAQAAAAAAAAACAAAAAAAAAAMAAAAAAAAABAAAAAAAAAAFAAAAAAAAAAYAAAAAAAAABwAAAAAAAAA=\n"
    "</DataArray>\n"
    "<DataArray type=\"Int64\" Name=\"offsets\" format=\"binary\">\n"
    "CAAAAAgAAAAAAAAA\n"
    "</DataArray>\n"
    "<DataArray type=\"Int64\" Name=\"types\" format=\"binary\">\n"
    "CAAAAAwAAAAAAAAA\n"
    "</DataArray>\n"
    "</Cells>\n"
    "</Piece>\n"
    "</UnstructuredGrid>\n"
    "</VTKFile>\n";
const std::string kVtuZlib =
    "<?xml version=\"1.0\"?>\n"
    "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\" "
    "compressor=\"vtkZLibDataCompressor\">\n"
    "<UnstructuredGrid>\n"
    "<Piece NumberOfPoints=\"8\" NumberOfCells=\"1\">\n"
    "<Points>\n"
    "<DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"binary\">\n"
    "AQAAAACAAADAAAAAGwAAAA==eJxjYMAHPtjjFyckT8hcdHXo4oTVAQDgMQ41\n"
    "</DataArray>\n"
    "</Points>\n"
    "<Cells>\n"
    "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"binary\">\n"
    "AQAAAACAAABAAAAAHgAAAA==eJxjYIAARijNBKWZoTQLlGaF0mxQmh1KAwAC4AAd\n"
    "</DataArray>\n"
    "<DataArray type=\"Int64\" Name=\"offsets\" format=\"binary\">\n"
    "AQAAAACAAAAIAAAACwAAAA==eJzjYIAAAABIAAk=\n"
    "</DataArray>\n"
    "<DataArray type=\"Int64\" Name=\"types\" format=\"binary\">\n"
    "AQAAAACAAAAIAAAACwAAAA==eJzjYYAAAABoAA0=\n"
    "</DataArray>\n"
    "</Cells>\n"
    "</Piece>\n"
    "</UnstructuredGrid>\n"
    "</VTKFile>\n";
const std::string kVtuAppended = [] {
  std::string appended;
  const auto block = [&](const std::string& data) {
    const auto size = static_cast<std::uint32_t>(data.size());
    appended.append(reinterpret_cast<const char*>(&size), 4);
    appended += data;
  };
  const double xyz[24] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  const std::int32_t ids[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  const std::int32_t offset = 8;
  const std::uint8_t type = 12;
  block(std::string(reinterpret_cast<const char*>(xyz), sizeof xyz));
  block(std::string(reinterpret_cast<const char*>(ids), sizeof ids));
  block(std::string(reinterpret_cast<const char*>(&offset), 4));
  block(std::string(reinterpret_cast<const char*>(&type), 1));
  return "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"8\" NumberOfCells=\"1\">\n"
         "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/></Points>\n"
         "<Cells><DataArray type=\"Int32\" Name=\"connectivity\" format=\"appended\" offset=\"196\"/>\n"
         "<DataArray type=\"Int32\" Name=\"offsets\" format=\"appended\" offset=\"232\"/>\n"
         "<DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"240\"/></Cells>\n"
         "</Piece></UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_" +
         appended + "\n</AppendedData></VTKFile>\n";
}();

const std::string kGmsh22 =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n9\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n"
    "7 1 1 1\n8 0 1 1\n19 2 2 2\n$EndNodes\n$Elements\n2\n1 3 2 0 1 1 2 3 4\n2 5 2 0 1 1 2 3 4 5 6 7 8\n$EndElements\n";
const std::string kGmsh41 =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 8 1 8\n3 1 0 8\n1\n2\n3\n4\n5\n6\n7\n8\n0 0 0\n1 0 0\n"
    "1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n$EndNodes\n$Elements\n2 2 1 2\n2 1 3 1\n1 1 2 3 4\n3 1 5 1\n"
    "2 1 2 3 4 5 6 7 8\n$EndElements\n";

std::string binary_gmsh22() {
  std::string s = "$MeshFormat\n2.2 1 8\n";
  const auto put_int = [&](std::int32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); };
  const auto put_double = [&](double v) { s.append(reinterpret_cast<const char*>(&v), 8); };
  put_int(1);
  s += "\n$EndMeshFormat\n$Nodes\n8\n";
  const double corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < 8; ++i) {
    put_int(i + 1);
    for (const double c : corners[i]) put_double(c);
  }
  s += "\n$EndNodes\n$Elements\n1\n";
  for (const std::int32_t v : {5, 1, 1, 1, 0}) put_int(v);
  for (int i = 1; i <= 8; ++i) put_int(i);
  return s + "\n$EndElements\n";
}

const std::string kAbaqus =
    "*HEADING\ncube\n*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n5, 0, 0, 1\n6, 1, 0, 1\n7, 1, 1, 1\n"
    "8, 0, 1, 1\n*ELEMENT, TYPE=S4\n2, 1, 2, 3, 4\n*ELEMENT, TYPE=C3D8R\n1, 1, 2, 3, 4,\n5, 6, 7, 8\n";

const std::string kOvm =
    "OVM ASCII\nVertices\n8\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\nEdges\n12\n3 2\n2 1\n"
    "1 0\n0 3\n5 6\n6 7\n7 4\n4 5\n2 6\n5 1\n7 3\n0 4\nFaces\n6\n4 0 2 4 6\n4 8 10 12 14\n4 3 16 9 18\n"
    "4 13 20 7 22\n4 19 15 23 5\n4 1 21 11 17\nPolyhedra\n1\n6 0 2 4 6 8 10\n";

// Replaces, inserts, deletes, truncates or duplicates a few bytes.
std::string mutate(std::string s, std::mt19937_64& rng) {
  static constexpr std::string_view kInteresting = " \n0123456789-+.eE#";
  const int count = 1 + static_cast<int>(rng() % 4);
  for (int m = 0; m < count; ++m) {
    const std::size_t pos = rng() % (s.size() + 1);
    switch (rng() % 6) {
      case 0:
        if (pos < s.size()) s[pos] = static_cast<char>(rng());
        break;
      case 1:
        s.insert(pos, 1, kInteresting[rng() % kInteresting.size()]);
        break;
      case 2:
        if (pos < s.size()) s.erase(pos, 1 + rng() % 20);
        break;
      case 3:
        s.resize(pos);
        break;
      case 4:
        if (pos < s.size()) s[pos] = "0123456789\n -"[rng() % 13];
        break;
      default: {
        const std::size_t from = rng() % (s.size() + 1);
        const std::size_t length = rng() % 50;
        if (from + length <= s.size()) s.insert(pos, s.substr(from, length));
      }
    }
  }
  return s;
}

template <class Read>
void check_mutations(const std::string& valid, Read read, std::uint64_t seed) {
  ASSERT_NO_THROW(read(valid));
  std::mt19937_64 rng(seed);
  int num_parsed = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::string input = mutate(valid, rng);
    try {
      read(input);
      ++num_parsed;
    } catch (const ParseError&) {
    } catch (const std::exception& e) {
      FAIL() << "mutation " << i << " threw " << typeid(e).name() << ": " << e.what();
    }
  }
  EXPECT_GT(num_parsed, 0);  // the mutations are not all fatal
}

TEST(ParserRobustness, Medit) {
  check_mutations(
      kMedit, [](const std::string& s) { read_medit(s, "m.mesh"); }, 1);
}

TEST(ParserRobustness, MeditTriangles) {
  check_mutations(
      kMedit, [](const std::string& s) { read_medit_triangles(s, "m.mesh"); }, 2);
}

TEST(ParserRobustness, VtkAscii) {
  check_mutations(
      kVtkAscii, [](const std::string& s) { read_vtk_legacy(s, "m.vtk"); }, 3);
  check_mutations(
      kVtk51Ascii, [](const std::string& s) { read_vtk_legacy(s, "m.vtk"); }, 4);
}

TEST(ParserRobustness, VtkBinary) {
  check_mutations(
      binary_vtk(false), [](const std::string& s) { read_vtk_legacy(s, "m.vtk"); }, 5);
  check_mutations(
      binary_vtk(true), [](const std::string& s) { read_vtk_legacy(s, "m.vtk"); }, 6);
}

TEST(ParserRobustness, Vtu) {
  const auto read = [](const std::string& s) { read_vtu(s, "m.vtu"); };
  check_mutations(kVtuBinary, read, 7);
  check_mutations(kVtuAppended, read, 8);
  if (has_zlib_support()) check_mutations(kVtuZlib, read, 9);
}

TEST(ParserRobustness, Gmsh) {
  const auto read = [](const std::string& s) { read_gmsh(s, "m.msh"); };
  check_mutations(kGmsh22, read, 10);
  check_mutations(kGmsh41, read, 11);
  check_mutations(binary_gmsh22(), read, 12);
}

TEST(ParserRobustness, AbaqusAndOvm) {
  check_mutations(
      kAbaqus, [](const std::string& s) { read_abaqus(s, "m.inp"); }, 13);
  check_mutations(
      kOvm, [](const std::string& s) { read_ovm(s, "m.ovm"); }, 14);
}

// A quad, a triangle, a pentagon: every corner form of OBJ, colours in OFF,
// extra properties and elements in PLY (ASCII and binary).
const std::string kObj =
    "# c\nv 0 0 0\nv 1 0 0\nv 1 1 0 1 0 0\nv 0 1 0\nv 2 0 0\nvt 0 0\nvn 0 0 1\n"
    "f 1 2/1 3//1 4/1/1\nf -4 5 -3\nf 1 2 5 \\\n 3 4\nl 1 2\n";
const std::string kOff = "COFF\n5 3 0\n0 0 0 1 0 0 1\n1 0 0 1 0 0 1\n1 1 0 1 0 0 1\n0 1 0 1 0 0 1\n2 0 0 1 0 0 1\n"
                         "4 0 1 2 3\n3 1 4 2 0.5 0.5 0.5\n5 0 1 4 2 3\n";
std::string ply(bool binary) {
  std::string s = std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
                  " 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                  "property uchar red\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  const float xyz[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
  const std::vector<std::vector<std::int32_t>> faces = {{0, 1, 2, 3}, {1, 4, 2}};
  for (const auto& p : xyz) {
    if (binary) {
      s.append(reinterpret_cast<const char*>(p), sizeof p);
      s += '\x07';
    } else {
      s += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + " 7\n";
    }
  }
  for (const auto& f : faces) {
    if (binary) {
      s += static_cast<char>(f.size());
      s.append(reinterpret_cast<const char*>(f.data()), f.size() * 4);
    } else {
      s += std::to_string(f.size());
      for (const auto v : f) s += " " + std::to_string(v);
      s += "\n";
    }
  }
  return s;
}

TEST(ParserRobustness, PolygonMeshes) {
  check_mutations(
      kObj, [](const std::string& s) { read_obj(s, "m.obj"); }, 15);
  check_mutations(
      kOff, [](const std::string& s) { read_off(s, "m.off"); }, 16);
  check_mutations(
      ply(false), [](const std::string& s) { read_ply(s, "m.ply"); }, 17);
  check_mutations(
      ply(true), [](const std::string& s) { read_ply(s, "m.ply"); }, 18);
}

}  // namespace
}  // namespace hq
