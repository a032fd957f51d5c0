#include "hqview/io/vtk_legacy_reader.h"

#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "io/error_text.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

using hq::test::error_text;

// --- a small legacy VTK writer for the tests ----------------------------------

struct VtkCell {
  int type;
  std::vector<std::int64_t> ids;
};

struct VtkSpec {
  std::vector<Vec3> points;
  std::vector<VtkCell> cells;
  bool binary = false;
  bool version5 = false;                    // 5.1 OFFSETS/CONNECTIVITY layout, else 4.2
  std::string point_type = "double";        // double, float or int
  std::string index_type = "vtktypeint64";  // 5.1 OFFSETS and CONNECTIVITY: vtktypeint64 or vtktypeint32
  std::string before_points;                // text after the DATASET line
  std::string trailer;                      // text after CELL_TYPES
};

void put_big_endian(std::string& out, std::uint64_t bits, int size) {
  for (int i = size - 1; i >= 0; --i) out += static_cast<char>((bits >> (8 * i)) & 0xff);
}

void put_int(std::string& out, std::int64_t value, int size, bool binary) {
  if (binary) {
    put_big_endian(out, static_cast<std::uint64_t>(value), size);
  } else {
    out += std::to_string(value) + " ";
  }
}

std::string shortest(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

// The coordinate as stored by the given POINTS type (what a reader must return).
double stored(double value, const std::string& type) {
  if (type == "float") return static_cast<float>(value);
  if (type == "int") return static_cast<double>(static_cast<std::int32_t>(std::lround(value)));
  return value;
}

void put_coordinate(std::string& out, double value, const std::string& type, bool binary) {
  const double v = stored(value, type);
  if (!binary) {
    out += shortest(v) + " ";
  } else if (type == "float") {
    put_big_endian(out, std::bit_cast<std::uint32_t>(static_cast<float>(v)), 4);
  } else if (type == "int") {
    put_big_endian(out, static_cast<std::uint32_t>(static_cast<std::int32_t>(v)), 4);
  } else {
    put_big_endian(out, std::bit_cast<std::uint64_t>(v), 8);
  }
}

std::string write_vtk(const VtkSpec& spec) {
  const bool bin = spec.binary;
  std::string s = std::string("# vtk DataFile Version ") + (spec.version5 ? "5.1" : "4.2") + "\nwritten by a test\n" +
                  (bin ? "BINARY" : "ASCII") + "\nDATASET UNSTRUCTURED_GRID\n" + spec.before_points;
  s += "POINTS " + std::to_string(spec.points.size()) + " " + spec.point_type + "\n";
  for (const Vec3& p : spec.points) {
    for (int k = 0; k < 3; ++k) put_coordinate(s, p[k], spec.point_type, bin);
    if (!bin) s += "\n";
  }
  if (bin) s += "\n";
  std::size_t num_ids = 0;
  for (const VtkCell& cell : spec.cells) num_ids += cell.ids.size();
  if (spec.version5) {
    const int size = spec.index_type == "vtktypeint32" ? 4 : 8;
    s += "CELLS " + std::to_string(spec.cells.size() + 1) + " " + std::to_string(num_ids) + "\n";
    s += "OFFSETS " + spec.index_type + "\n";
    std::int64_t offset = 0;
    put_int(s, 0, size, bin);
    for (const VtkCell& cell : spec.cells) put_int(s, offset += static_cast<std::int64_t>(cell.ids.size()), size, bin);
    s += "\nCONNECTIVITY " + spec.index_type + "\n";
    for (const VtkCell& cell : spec.cells) {
      for (const std::int64_t id : cell.ids) put_int(s, id, size, bin);
      if (!bin) s += "\n";
    }
    if (bin) s += "\n";
  } else {
    s += "CELLS " + std::to_string(spec.cells.size()) + " " + std::to_string(num_ids + spec.cells.size()) + "\n";
    for (const VtkCell& cell : spec.cells) {
      put_int(s, static_cast<std::int64_t>(cell.ids.size()), 4, bin);
      for (const std::int64_t id : cell.ids) put_int(s, id, 4, bin);
      if (!bin) s += "\n";
    }
    if (bin) s += "\n";
  }
  s += "CELL_TYPES " + std::to_string(spec.cells.size()) + "\n";
  for (const VtkCell& cell : spec.cells) {
    put_int(s, cell.type, 4, bin);
    if (!bin) s += "\n";
  }
  if (bin) s += "\n";
  return s + spec.trailer;
}

VtkCell hex_cell(const Hex& hex) { return {12, {hex.begin(), hex.end()}}; }

VtkSpec spec_of(const HexMesh& mesh) {
  VtkSpec spec;
  spec.points = mesh.points;
  for (const Hex& hex : mesh.hexes) spec.cells.push_back(hex_cell(hex));
  return spec;
}

// A 2x2x2 grid with irregular coordinates (not exact in float or decimal).
HexMesh wobbly_grid() {
  HexMesh mesh = test::grid(2);
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    Vec3& p = mesh.points[i];
    p = {p.x + 0.1 * std::sin(1.0 + double(i)), p.y * 1.37 + 1e-7 * double(i), p.z - 0.3 * std::cos(double(i))};
  }
  return mesh;
}

std::string parse_error(const std::string& bytes) {
  return error_text<ParseError>([&] { read_vtk_legacy(bytes, "m.vtk"); });
}

// --- variants ------------------------------------------------------------------

TEST(VtkLegacyReader, ReadsEveryLayoutAndEncoding) {
  const HexMesh mesh = wobbly_grid();
  for (const bool binary : {false, true})
    for (const bool version5 : {false, true})
      for (const std::string point_type : {"double", "float", "int"}) {
        SCOPED_TRACE(std::string(binary ? "binary " : "ascii ") + (version5 ? "5.1 " : "4.2 ") + point_type);
        VtkSpec spec = spec_of(mesh);
        spec.binary = binary;
        spec.version5 = version5;
        spec.point_type = point_type;
        const LoadedMesh loaded = read_vtk_legacy(write_vtk(spec), "m.vtk");
        EXPECT_EQ(loaded.format, binary ? "vtk-legacy-binary" : "vtk-legacy-ascii");
        EXPECT_TRUE(loaded.warnings.empty());
        ASSERT_EQ(loaded.mesh.points.size(), mesh.points.size());
        for (std::size_t i = 0; i < mesh.points.size(); ++i)
          for (int k = 0; k < 3; ++k) ASSERT_EQ(loaded.mesh.points[i][k], stored(mesh.points[i][k], point_type));
        EXPECT_EQ(loaded.mesh.hexes, mesh.hexes);
      }
}

TEST(VtkLegacyReader, Version51WithInt32Indices) {
  const HexMesh mesh = wobbly_grid();
  for (const bool binary : {false, true}) {
    VtkSpec spec = spec_of(mesh);
    spec.binary = binary;
    spec.version5 = true;
    spec.index_type = "vtktypeint32";
    EXPECT_EQ(read_vtk_legacy(write_vtk(spec), "m.vtk").mesh.hexes, mesh.hexes);
  }
}

TEST(VtkLegacyReader, AsciiAndBinaryOfTheSameContentGiveIdenticalMeshes) {
  HexMesh mesh = wobbly_grid();
  mesh.points.push_back({0.1, 0.2, 0.3});  // unreferenced, kept
  for (const bool version5 : {false, true})
    for (const std::string point_type : {"double", "float"}) {
      VtkSpec spec = spec_of(mesh);
      spec.cells.push_back({10, {0, 1, 3, 9}});  // a tetrahedron in both
      spec.version5 = version5;
      spec.point_type = point_type;
      spec.trailer = "CELL_DATA 9\nSCALARS q float 1\nLOOKUP_TABLE default\n";
      const LoadedMesh ascii = read_vtk_legacy(write_vtk(spec), "m.vtk");
      spec.binary = true;
      const LoadedMesh binary = read_vtk_legacy(write_vtk(spec), "m.vtk");
      EXPECT_EQ(ascii.mesh.points, binary.mesh.points);
      EXPECT_EQ(ascii.mesh.hexes, binary.mesh.hexes);
      EXPECT_EQ(ascii.mesh.tets, binary.mesh.tets);
      EXPECT_EQ(ascii.mesh.tets, (std::vector<std::array<Index, 4>>{{0, 1, 3, 9}}));
      EXPECT_EQ(ascii.mesh.source_index, binary.mesh.source_index);
      EXPECT_EQ(ascii.warnings, binary.warnings);
      EXPECT_EQ(ascii.mesh.points.size(), 28u);
      EXPECT_EQ(ascii.mesh.hexes.size(), 8u);
    }
}

TEST(VtkLegacyReader, VoxelsAreReorderedToHexahedronOrder) {
  // Voxel corners: x fastest, then y, then z.
  VtkSpec spec;
  spec.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  spec.cells = {{11, {0, 1, 2, 3, 4, 5, 6, 7}}};
  for (const bool binary : {false, true}) {
    spec.binary = binary;
    const LoadedMesh loaded = read_vtk_legacy(write_vtk(spec), "m.vtk");
    ASSERT_EQ(loaded.mesh.hexes.size(), 1u);
    EXPECT_EQ(loaded.mesh.hexes[0], (Hex{0, 1, 3, 2, 4, 5, 7, 6}));
    EXPECT_EQ(hex_corners(loaded.mesh, 0), test::cube_corners());
    EXPECT_TRUE(loaded.warnings.empty());
  }
}

TEST(VtkLegacyReader, TetrahedraAreReadOtherCellsSkippedWithOneWarning) {
  VtkSpec spec = spec_of(test::unit_cube());
  spec.cells.push_back({10, {0, 1, 3, 4}});
  spec.cells.push_back({5, {0, 1, 2}});
  spec.cells.push_back({10, {1, 2, 3, 6}});
  spec.cells.push_back({23, {0, 1, 2, 3, 4, 5, 6, 7}});        // quadratic quad: really 8 points
  spec.cells.push_back({42, {2, 3, 0, 1, 2, 3, 4, 5, 6, 7}});  // polyhedron face stream, never checked as ids
  const LoadedMesh loaded = read_vtk_legacy(write_vtk(spec), "rockarm.vtk");
  EXPECT_EQ(loaded.mesh.hexes.size(), 1u);
  EXPECT_EQ(loaded.mesh.tets, (std::vector<std::array<Index, 4>>{{0, 1, 3, 4}, {1, 2, 3, 6}}));
  EXPECT_EQ(loaded.mesh.source_index[static_cast<std::size_t>(CellKind::tet)], (std::vector<std::int64_t>{1, 3}));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  // A polyhedron (42) among them: a warning (a volume cell not analysed);
  // the triangle and the quadratic quad, faces of a volume mesh, a note.
  EXPECT_EQ(loaded.warnings[0], "rockarm.vtk: 1 cell of unread types skipped (type 42)");
  EXPECT_EQ(loaded.notes, std::vector<std::string>{"rockarm.vtk: 2 cells of unread types skipped (types 5, 23)"});

  spec.cells.resize(2);
  EXPECT_TRUE(read_vtk_legacy(write_vtk(spec), "m.vtk").warnings.empty());
}

TEST(VtkLegacyReader, EightPointCellsWithAnotherTypeAreLoadedAsHexahedra) {
  // As hex_cube_coarse.vtk: 8-point cells labelled 10 (tetra); HexaLab loads them.
  const HexMesh mesh = test::grid(2);
  VtkSpec spec = spec_of(mesh);
  for (VtkCell& cell : spec.cells) cell.type = 10;
  spec.cells[3].type = 12;
  spec.cells[5].type = 13;
  const LoadedMesh loaded = read_vtk_legacy(write_vtk(spec), "cube.vtk");
  EXPECT_EQ(loaded.mesh.hexes, mesh.hexes);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_EQ(loaded.warnings[0],
            "cube.vtk: 7 cells with 8 points but a non-hexahedral type (10, 13) loaded as hexahedra: "
            "cells 0, 1, 2, 4, 5 and 2 more");

  spec.cells = {spec.cells[0], spec.cells[3]};
  EXPECT_EQ(read_vtk_legacy(write_vtk(spec), "m.vtk").warnings,
            std::vector<std::string>{
                "m.vtk: 1 cell with 8 points but a non-hexahedral type (10) loaded as hexahedra: cell 0"});
}

TEST(VtkLegacyReader, IgnoresDataSectionsAndSkipsFieldAndMetadata) {
  const HexMesh mesh = wobbly_grid();
  for (const bool binary : {false, true})
    for (const bool version5 : {false, true}) {
      SCOPED_TRACE(std::string(binary ? "binary " : "ascii ") + (version5 ? "5.1" : "4.2"));
      VtkSpec spec = spec_of(mesh);
      spec.binary = binary;
      spec.version5 = version5;
      // A FIELD block before POINTS (VTK writes TIME this way).
      spec.before_points = "FIELD FieldData 2\nTIME 1 1 double\n";
      if (binary) {
        put_big_endian(spec.before_points, std::bit_cast<std::uint64_t>(2.5), 8);
        spec.before_points += "\nCYCLE 1 1 int\n";
        put_big_endian(spec.before_points, 10, 4);
        spec.before_points += "\n";
      } else {
        spec.before_points += "2.5\nCYCLE 1 1 int\n10\n";
      }
      spec.trailer =
          "CELL_DATA 8\nSCALARS quality float 1\nLOOKUP_TABLE default\nthis is never parsed\n"
          "POINT_DATA 27\nFIELD f 1\n";
      std::string text = write_vtk(spec);
      // 5.1 files carry METADATA blocks after arrays.
      const std::string metadata = "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1\n\n";
      text.insert(text.find("CELLS"), metadata);
      if (version5) text.insert(text.find("CONNECTIVITY"), metadata);
      const LoadedMesh loaded = read_vtk_legacy(text, "m.vtk");
      EXPECT_EQ(loaded.mesh.hexes, mesh.hexes);
      EXPECT_EQ(loaded.mesh.points.size(), mesh.points.size());
    }
}

TEST(VtkLegacyReader, KeywordsInAnyCaseCrlfAndSectionsInAnyOrder) {
  const std::string text =
      "# vtk DataFile Version 3.0\r\n"
      "\r\n"  // empty title
      "ascii\r\n"
      "dataset unstructured_grid\r\n"
      "cells 1 9\r\n8 0 1 2 3 4 5 6 7\r\n"
      "cell_types 1\r\n12\r\n"
      "points 8 float\r\n0 0 0 1 0 0 1 1 0\r\n0 1 0 0 0 1 1 0 1\r\n1 1 1 0 1 1\r\n";
  const LoadedMesh loaded = read_vtk_legacy(text, "m.vtk");
  EXPECT_EQ(loaded.mesh.hexes, test::unit_cube().hexes);
  EXPECT_EQ(loaded.mesh.points, test::unit_cube().points);
}

// --- errors ----------------------------------------------------------------------

// The unit cube, ASCII 4.2; the line numbers are those in the comments.
const std::string kHead =
    "# vtk DataFile Version 4.2\n"  // 1
    "cube\n"                        // 2
    "ASCII\n"                       // 3
    "DATASET UNSTRUCTURED_GRID\n";  // 4
const std::string kPoints =
    "POINTS 8 float\n"                                           // 5
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n";  // 6-13
const std::string kCells = "CELLS 1 9\n8 0 1 2 3 4 5 6 7\n";     // 14-15
const std::string kTypes = "CELL_TYPES 1\n12\n";                 // 16-17

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(VtkLegacyReaderErrors, TheCubeItselfParses) {
  EXPECT_EQ(read_vtk_legacy(kHead + kPoints + kCells + kTypes, "m.vtk").mesh.hexes.size(), 1u);
}

TEST(VtkLegacyReaderErrors, Header) {
  EXPECT_EQ(parse_error(""), "m.vtk:1: empty file, expected '# vtk DataFile Version X.Y'");
  EXPECT_EQ(parse_error("# vtk DataFile\n"), "m.vtk:1: expected '# vtk DataFile Version X.Y', got '# vtk DataFile'");
  EXPECT_EQ(parse_error("# vtk DataFile Version x\n"),
            "m.vtk:1: expected '# vtk DataFile Version X.Y', got '# vtk DataFile Version x'");
  EXPECT_EQ(parse_error("# vtk DataFile Version 6.0\nt\nASCII\n"),
            "m.vtk:1: unsupported file version 6.0 (expected at most 5.1)");
  EXPECT_EQ(parse_error("# vtk DataFile Version 4.2\n"), "m.vtk:1: unexpected end of file, expected the title line");
  EXPECT_EQ(parse_error("# vtk DataFile Version 4.2\nt\n"),
            "m.vtk:2: unexpected end of file, expected ASCII or BINARY");
  EXPECT_EQ(parse_error("# vtk DataFile Version 4.2\nt\nTEXT\n"), "m.vtk:3: expected ASCII or BINARY, got 'TEXT'");
  EXPECT_EQ(parse_error("# vtk DataFile Version 4.2\nt\nASCII\nDATA SET\n"), "m.vtk:4: expected DATASET, got 'DATA'");
  EXPECT_EQ(parse_error("# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\nPOINTS 0 float\n"),
            "m.vtk:4: unsupported dataset type 'POLYDATA' (expected UNSTRUCTURED_GRID)");
  EXPECT_EQ(parse_error("# vtk DataFile Version 4.2\nt\nASCII\nDATASET\nUNSTRUCTURED_GRID\n"),
            "m.vtk:4: expected a dataset type after DATASET");
}

TEST(VtkLegacyReaderErrors, KeywordsAndMissingSections) {
  EXPECT_EQ(parse_error(kHead + "VERTICES 3 4\n"), "m.vtk:5: unknown keyword 'VERTICES' in an UNSTRUCTURED_GRID");
  EXPECT_EQ(parse_error(kHead + kPoints + kCells), "m.vtk:15: unexpected end of file: no CELL_TYPES section");
  EXPECT_EQ(parse_error(kHead + kPoints + kCells + "CELL_DATA 1\n"),
            "m.vtk:16: CELL_DATA before the CELL_TYPES section");
  EXPECT_EQ(parse_error(kHead + kCells + kTypes), "m.vtk:8: unexpected end of file: no POINTS section");
  EXPECT_EQ(parse_error(kHead + kPoints + kPoints), "m.vtk:14: second POINTS section (the first is at line 5)");
}

TEST(VtkLegacyReaderErrors, Points) {
  const std::string tail = kCells + kTypes;
  EXPECT_EQ(parse_error(kHead + "POINTS -1 float\n" + tail), "m.vtk:5: negative number of points in POINTS: -1");
  EXPECT_EQ(parse_error(kHead + "POINTS 3000000000 float\n" + tail),
            "m.vtk:5: number of points in POINTS 3000000000 exceeds the limit of 2147483647");
  const std::string rest = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n" + tail;
  EXPECT_EQ(parse_error(kHead + "POINTS 1000 float\n" + rest),
            "m.vtk:5: 3000 POINTS values cannot fit in the " + std::to_string(rest.size()) + " bytes left in the file");
  EXPECT_EQ(parse_error(kHead + "POINTS 8 quaternion\n" + rest), "m.vtk:5: unknown data type 'quaternion' for POINTS");
  EXPECT_EQ(parse_error(kHead + "POINTS 8\n" + rest), "m.vtk:5: expected a data type after POINTS");
  EXPECT_EQ(parse_error(kHead + "POINTS eight float\n" + rest),
            "m.vtk:5: expected the number of points after POINTS, got 'eight'");
  EXPECT_EQ(parse_error(kHead + "POINTS 8 float extra\n" + rest),
            "m.vtk:5: unexpected 'extra' after the POINTS header");
  const std::string points = kHead + kPoints + tail;
  EXPECT_EQ(parse_error(replaced(points, "1 1 0\n", "1 nan 0\n")), "m.vtk:8: non-finite coordinate nan (point 2)");
  EXPECT_EQ(parse_error(replaced(points, "1 1 0\n", "1 1 inf\n")), "m.vtk:8: non-finite coordinate inf (point 2)");
  EXPECT_EQ(parse_error(replaced(points, "1 1 0\n", "1 x 0\n")),
            "m.vtk:8: expected a number, got 'x' (POINTS value 8 of 24)");
  // Count one too high: CELLS stands where a coordinate should.
  EXPECT_EQ(parse_error(replaced(points, "POINTS 8", "POINTS 9")),
            "m.vtk:14: expected a number, got 'CELLS' (POINTS value 25 of 27)");
}

TEST(VtkLegacyReaderErrors, LegacyCells) {
  const std::string head = kHead + kPoints;  // CELLS on line 14
  EXPECT_EQ(parse_error(head + "CELLS -1 9\n8 0 1 2 3 4 5 6 7\n" + kTypes),
            "m.vtk:14: negative number of cells in CELLS: -1");
  EXPECT_EQ(parse_error(head + "CELLS 2 1\n8 0 1 2 3 4 5 6 7\n" + kTypes),
            "m.vtk:14: cell list size 1 cannot hold 2 cells");
  EXPECT_EQ(parse_error(head + "CELLS 1 90\n8 0 1 2 3 4 5 6 7\n" + kTypes),
            "m.vtk:14: 90 CELLS values cannot fit in the 34 bytes left in the file");
  EXPECT_EQ(parse_error(head + "CELLS 1 8\n8 0 1 2 3 4 5 6 7\n" + kTypes),
            "m.vtk:15: cell 0 claims 8 points, but 7 values are left in the cell list");
  EXPECT_EQ(parse_error(head + "CELLS 1 10\n8 0 1 2 3 4 5 6 7\n" + kTypes),
            "m.vtk:14: cell list size 10 does not match the 9 values of its 1 cells");
  EXPECT_EQ(parse_error(head + "CELLS 2 9\n8 0 1 2 3 4 5 6 7\n" + kTypes),
            "m.vtk:15: cell list size 9 ends after 1 of 2 cells");
  EXPECT_EQ(parse_error(head + "CELLS 1 9\n8 0 1 2 3 4 5 6 8\n" + kTypes),
            "m.vtk:15: point id 8 out of range [0, 8) (cell 0)");
  EXPECT_EQ(parse_error(head + "CELLS 1 9\n8 0 1 2 3 4 5 6 -1\n" + kTypes),
            "m.vtk:15: point id -1 out of range (cell 0)");
  EXPECT_EQ(parse_error(head + "CELLS 1 9\n8 0 1 2 3 4 5 6 6\n" + kTypes), "m.vtk:15: point id 6 repeated (cell 0)");
  EXPECT_EQ(parse_error(head + "CELLS 1 8\n7 0 1 2 3 4 5 6\n" + kTypes),
            "m.vtk:15: cell 0 has type 12 (hexahedron) but 7 points, expected 8");
  EXPECT_EQ(parse_error(head + "CELLS 1 8\n7 0 1 2 3 4 5 6\nCELL_TYPES 1\n11\n"),
            "m.vtk:15: cell 0 has type 11 (voxel) but 7 points, expected 8");
}

TEST(VtkLegacyReaderErrors, CellTypes) {
  const std::string head = kHead + kPoints + kCells;  // CELL_TYPES on line 16
  EXPECT_EQ(parse_error(head + "CELL_TYPES 2\n12\n12\n"),
            "m.vtk:16: CELL_TYPES has 2 entries but CELLS (line 14) has 1 cells");
  EXPECT_EQ(parse_error(head + "CELL_TYPES 1\n300\n"), "m.vtk:17: invalid cell type 300 (cell 0)");
  EXPECT_EQ(parse_error(head + "CELL_TYPES 2\n12\n"),
            "m.vtk:17: unexpected end of file, expected 2 values in CELL_TYPES, got 1");
  // Only surface cells: a surface mesh (surface_mesh_reading_test); a line
  // is neither.
  EXPECT_EQ(read_vtk_legacy(kHead + kPoints + "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n", "m.vtk").mesh.triangles.size(), 1u);
  EXPECT_EQ(parse_error(kHead + kPoints + "CELLS 2 7\n2 0 1\n3 0 1 2\nCELL_TYPES 2\n3\n4\n"),
            "m.vtk: no volume cells (2 cells of types 3, 4)");
  EXPECT_EQ(parse_error(kHead + kPoints + "CELLS 0 0\nCELL_TYPES 0\n"), "m.vtk: no volume cells");
  EXPECT_EQ(parse_error(kHead + kPoints + "CELLS 1 6\n5 0 1 2 3 4\nCELL_TYPES 1\n10\n"),
            "m.vtk:15: cell 0 has type 10 (tetra) but 5 points, expected 4");
}

// The unit cube, ASCII 5.1.
const std::string kHead51 = replaced(kHead, "4.2", "5.1");
const std::string kCells51 =
    "CELLS 2 8\n"                  // 14
    "OFFSETS vtktypeint64\n"       // 15
    "0 8\n"                        // 16
    "CONNECTIVITY vtktypeint64\n"  // 17
    "0 1 2 3 4 5 6 7\n";           // 18

TEST(VtkLegacyReaderErrors, Version51Cells) {
  const std::string good = kHead51 + kPoints + kCells51 + kTypes;
  EXPECT_EQ(read_vtk_legacy(good, "m.vtk").mesh.hexes.size(), 1u);
  EXPECT_EQ(parse_error(replaced(good, "\n0 8\n", "\n1 8\n")), "m.vtk:16: first offset is 1, expected 0");
  EXPECT_EQ(parse_error(replaced(good, "\n0 8\n", "\n0 9\n")), "m.vtk:16: offset 9 exceeds the connectivity size 8");
  EXPECT_EQ(parse_error(replaced(good, "\n0 8\n", "\n0 7\n")),
            "m.vtk:16: last offset 7 does not match the connectivity size 8");
  EXPECT_EQ(parse_error(replaced(replaced(good, "\n0 8\n", "\n0 8 4\n"), "CELLS 2 8", "CELLS 3 8")),
            "m.vtk:16: offsets decrease: offset 2 is 4, offset 1 is 8");
  EXPECT_EQ(parse_error(replaced(good, "CONNECTIVITY vtktypeint64", "CONNECTIVITY float")),
            "m.vtk:17: expected an integer data type for CONNECTIVITY, got 'float'");
  EXPECT_EQ(parse_error(replaced(good, "OFFSETS vtktypeint64\n0 8\n", "")),
            "m.vtk:15: expected OFFSETS, got 'CONNECTIVITY'");
  EXPECT_EQ(parse_error(replaced(good, "5 6 7\n", "5 6 8\n")), "m.vtk:18: point id 8 out of range [0, 8) (cell 0)");
  EXPECT_EQ(parse_error(replaced(good, "CELLS 2 8", "CELLS -2 8")),
            "m.vtk:14: negative number of offsets in CELLS: -2");
  EXPECT_EQ(parse_error(replaced(good, "CELLS 2 8", "CELLS 2 800")),
            "m.vtk:16: last offset 8 does not match the connectivity size 800");
}

// --- binary errors: the section keyword's line and a byte offset ------------------------

VtkSpec binary_cube(bool version5) {
  VtkSpec spec = spec_of(test::unit_cube());
  spec.binary = true;
  spec.version5 = version5;
  spec.point_type = "float";  // no 0x0A byte in 0.0f and 1.0f: POINTS on line 5, CELLS on line 7
  return spec;
}

TEST(VtkLegacyReaderErrors, BinaryTruncatedData) {
  const std::string text = write_vtk(binary_cube(false));
  const std::size_t data = text.find("POINTS 8 float\n") + 15;
  EXPECT_EQ(parse_error(text.substr(0, data + 10)),
            "m.vtk:5: binary POINTS data truncated: 24 float values need 96 bytes, 10 left");
  const std::size_t cells = text.find("CELLS 1 9\n") + 10;
  EXPECT_EQ(parse_error(text.substr(0, cells + 35)),
            "m.vtk:7: binary CELLS data truncated: 9 int values need 36 bytes, 35 left");
}

TEST(VtkLegacyReaderErrors, BinaryValuesAreLocatedByByteOffset) {
  VtkSpec spec = binary_cube(false);
  spec.points[2].y = std::numeric_limits<double>::quiet_NaN();
  std::string text = write_vtk(spec);
  const std::size_t points = text.find("POINTS 8 float\n") + 15;
  EXPECT_EQ(parse_error(text), "m.vtk:5: non-finite coordinate nan (point 2) (POINTS data at byte offset " +
                                   std::to_string(points + 7 * 4) + ")");

  spec = binary_cube(false);
  spec.cells[0].ids[7] = 8;
  text = write_vtk(spec);
  const std::size_t cells = text.find("CELLS 1 9\n") + 10;
  EXPECT_EQ(parse_error(text), "m.vtk:7: point id 8 out of range [0, 8) (cell 0) (CELLS data at byte offset " +
                                   std::to_string(cells + 8 * 4) + ")");

  spec = binary_cube(true);
  spec.cells[0].ids[5] = 3;
  text = write_vtk(spec);
  // 5.1: CELLS line 7, OFFSETS line 8, its data on line 9, CONNECTIVITY line 10.
  const std::size_t ids = text.find("CONNECTIVITY vtktypeint64\n") + 26;
  EXPECT_EQ(parse_error(text), "m.vtk:10: point id 3 repeated (cell 0) (CONNECTIVITY data at byte offset " +
                                   std::to_string(ids + 5 * 8) + ")");

  spec = binary_cube(false);
  spec.cells[0].ids[1] = -4;
  text = write_vtk(spec);
  EXPECT_EQ(parse_error(text), "m.vtk:7: point id -4 out of range (cell 0) (CELLS data at byte offset " +
                                   std::to_string(cells + 2 * 4) + ")");
}

TEST(VtkLegacyReaderErrors, BinaryLineNumbersCountNewlineBytesInTheData) {
  VtkSpec spec = binary_cube(false);
  spec.points[1].x = std::bit_cast<float>(std::uint32_t{0x0A0A0A0A});  // four newline bytes
  spec.cells[0].ids[0] = 99;
  EXPECT_EQ(parse_error(write_vtk(spec)).substr(0, 9), "m.vtk:11:");
}

TEST(VtkLegacyReaderErrors, ErrorsAreParseErrors) {
  try {
    read_vtk_legacy(kHead + "POINTS -1 float\n", "dir/m.vtk");
    FAIL() << "no exception";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.path(), "dir/m.vtk");
    EXPECT_EQ(e.line(), 5);
  }
}

}  // namespace
}  // namespace hq
