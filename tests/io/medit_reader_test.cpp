#include "hqview/io/medit_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "io/error_text.h"

namespace hq {
namespace HQ_TEST_UNIT {

using hq::test::error_text;

// The unit cube as one hex, in the layout most writers use.
const std::string kCube =
    "MeshVersionFormatted 2\n"  // 1
    "Dimension 3\n"             // 2
    "Vertices\n"                // 3
    "8\n"                       // 4
    "0 0 0 0\n"                 // 5
    "1 0 0 0\n"                 // 6
    "1 1 0 0\n"                 // 7
    "0 1 0 0\n"                 // 8
    "0 0 1 0\n"                 // 9
    "1 0 1 0\n"                 // 10
    "1 1 1 0\n"                 // 11
    "0 1 1 0\n"                 // 12
    "Hexahedra 1\n"             // 13
    "1 2 3 4 5 6 7 8 0\n"       // 14
    "End\n";                    // 15

const std::string kHeader = "MeshVersionFormatted 1\nDimension 3\n";  // lines 1-2
const std::string kVertices =                                         // lines 3-12
    "Vertices 9\n"
    "0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n0 0 1 0\n1 0 1 0\n1 1 1 0\n0 1 1 0\n2 2 2 0\n";
const std::string kHex = "Hexahedra 1\n1 2 3 4 5 6 7 8 0\n";
// A last comment line: keeps the rest of a short test text large enough for
// its counts, so that the entry checks (not the count check) are reached.
const std::string kPad = "# padding: the end of the test file....\n";

std::string parse_error(const std::string& text) {
  return error_text<ParseError>([&] { read_medit(text, "m.mesh"); });
}

void expect_unit_cube(const LoadedMesh& loaded) {
  ASSERT_EQ(loaded.mesh.points.size(), 8u);
  ASSERT_EQ(loaded.mesh.hexes.size(), 1u);
  EXPECT_EQ(loaded.mesh.points[6], (Vec3{1, 1, 1}));
  EXPECT_EQ(loaded.mesh.hexes[0], (Hex{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(loaded.format, "medit");
}

// A grid of n^3 hexes, large enough (more than 2^15 vertices and hexes) for
// its sections to be read in parts on several threads. Its text has blank
// lines, comment lines, CRLF line ends and trailing comments between and
// after entries; `vertex_line[i]` / `hex_line[h]` is the line of each entry.
struct GridText {
  std::string text;
  std::vector<std::int64_t> vertex_line, hex_line;
  int n = 0;
  Index id(int i, int j, int k) const { return static_cast<Index>((k * (n + 1) + j) * (n + 1) + i); }
};

GridText grid_text(int n) {
  GridText g;
  g.n = n;
  const int m = n + 1;
  std::int64_t line = 1;
  auto add = [&](const std::string& s) {
    g.text += s;
    line += static_cast<std::int64_t>(std::count(s.begin(), s.end(), '\n'));
  };
  add("MeshVersionFormatted 2\nDimension 3\nVertices\n" + std::to_string(m * m * m) + "\n");
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const auto v = static_cast<std::size_t>(g.id(i, j, k));
        if (v % 997 == 5) add("\n");
        if (v % 1009 == 7) add("# a comment line\n");
        g.vertex_line.push_back(line);
        add(std::to_string(i) + ".5 " + std::to_string(-j) + " " + std::to_string(k) + "e-1 " + std::to_string(v % 3) +
            (v % 101 == 0 ? " # trailing\r\n" : v % 2 == 0 ? "\r\n" : "\n"));
      }
  add("Hexahedra\n" + std::to_string(n * n * n) + "\n");
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (g.hex_line.size() % 1013 == 11) add("  # between hexes\n\t\n");
        g.hex_line.push_back(line);
        std::string entry;
        for (const Index v : {g.id(i, j, k), g.id(i + 1, j, k), g.id(i + 1, j + 1, k), g.id(i, j + 1, k),
                              g.id(i, j, k + 1), g.id(i + 1, j, k + 1), g.id(i + 1, j + 1, k + 1), g.id(i, j + 1, k + 1)})
          entry += std::to_string(v + 1) + " ";
        add(entry + "0\n");
      }
  add("End\n");
  return g;
}

TEST(MeditReader, LargeSectionsReadInPartsGiveEveryEntryInOrder) {
  const GridText g = grid_text(34);  // 42,875 vertices, 39,304 hexes
  const LoadedMesh loaded = read_medit(g.text, "grid.mesh");
  ASSERT_EQ(loaded.mesh.points.size(), 42875u);
  ASSERT_EQ(loaded.mesh.hexes.size(), 39304u);
  const int m = g.n + 1;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        ASSERT_EQ(loaded.mesh.points[static_cast<std::size_t>(g.id(i, j, k))], (Vec3{i + 0.5, -1.0 * j, k / 10.0}))
            << i << " " << j << " " << k;
  std::size_t h = 0;
  for (int k = 0; k < g.n; ++k)
    for (int j = 0; j < g.n; ++j)
      for (int i = 0; i < g.n; ++i, ++h)
        ASSERT_EQ(loaded.mesh.hexes[h], (Hex{g.id(i, j, k), g.id(i + 1, j, k), g.id(i + 1, j + 1, k), g.id(i, j + 1, k),
                                             g.id(i, j, k + 1), g.id(i + 1, j, k + 1), g.id(i + 1, j + 1, k + 1),
                                             g.id(i, j + 1, k + 1)}))
            << h;
}

// An error anywhere in a large section is the one the entry-by-entry
// reading finds first, with its line, whichever part it falls in.
TEST(MeditReader, LargeSectionsReportTheFirstErrorWithItsLine) {
  const GridText g = grid_text(34);
  const auto line_start = [&](std::int64_t line) {
    std::size_t pos = 0;
    for (std::int64_t l = 1; l < line; ++l) pos = g.text.find('\n', pos) + 1;
    return pos;
  };
  const auto replace_line = [&](std::string text, std::int64_t line, const std::string& with) {
    const std::size_t begin = line_start(line);
    return text.replace(begin, text.find('\n', begin) - begin, with);
  };
  const auto error = [](const std::string& text) {
    return error_text<ParseError>([&] { read_medit(text, "grid.mesh"); });
  };
  // Two errors in different parts: the earlier one is reported.
  std::string two = replace_line(g.text, g.vertex_line[40000], "1 2 x 0");
  two = replace_line(two, g.vertex_line[30001], "1 2 3");
  EXPECT_EQ(error(two), "grid.mesh:" + std::to_string(g.vertex_line[30001]) +
                            ": expected 3 coordinates and a reference, got 3 values (vertex 30002 of 42875)");
  EXPECT_EQ(error(replace_line(g.text, g.vertex_line[40000], "1 2 x 0")),
            "grid.mesh:" + std::to_string(g.vertex_line[40000]) + ": expected a coordinate, got 'x' (vertex 40001 of 42875)");
  EXPECT_EQ(error(replace_line(g.text, g.hex_line[39303], "1 2 3 4 5 6 7 99999 0")),
            "grid.mesh:" + std::to_string(g.hex_line[39303]) +
                ": vertex id 99999 out of range [1, 42875] (hexahedron 39304 of 39304)");
  // An entry over two lines: the first line lacks values.
  EXPECT_EQ(error(replace_line(g.text, g.hex_line[20000], "1 2 3 4\n5 6 7 8 0")),
            "grid.mesh:" + std::to_string(g.hex_line[20000]) +
                ": expected 8 vertex ids and a reference, got 4 values (hexahedron 20001 of 39304)");
  // Fewer entries than the count: the Hexahedra keyword is read as a vertex.
  std::string short_text = g.text;
  const std::size_t last_vertex = line_start(g.vertex_line[42874]);
  short_text.erase(last_vertex, line_start(g.vertex_line[42874] + 1) - last_vertex);
  EXPECT_EQ(error(short_text), "grid.mesh:" + std::to_string(g.vertex_line[42874]) +
                                   ": expected a coordinate, got 'Hexahedra' (vertex 42875 of 42875)");
}

TEST(MeditReader, ReadsTheUnitCubeWithZeroBasedIds) {
  const LoadedMesh loaded = read_medit(kCube, "cube.mesh");
  expect_unit_cube(loaded);
  EXPECT_TRUE(loaded.warnings.empty());
}

TEST(MeditReader, CountsAndValuesOnTheKeywordLineOrTheNext) {
  const std::string text =
      "MeshVersionFormatted\n1\nDimension\n3\nVertices 8\n"
      "0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n0 0 1 0\n1 0 1 0\n1 1 1 0\n0 1 1 0\n"
      "Hexahedra\n\n1\n1 2 3 4 5 6 7 8 0\n";
  expect_unit_cube(read_medit(text, "m.mesh"));
}

TEST(MeditReader, LeadingSpacesCommentsCrlfAndNoFinalNewline) {
  // fandisk.mesh style: every line indented, Dimension on its own line.
  const std::string text =
      "# written by a tool\r\n"
      " MeshVersionFormatted 2\r\n"
      " Dimension\r\n 3\r\n"
      "  # the points\r\n"
      " Vertices\r\n 8\r\n"
      "   0.0  0.0  0.0   1\r\n   1.0  0.0  0.0   1\r\n   1.0  1.0  0.0   1\r\n   0.0  1.0  0.0   1\r\n"
      "   0.0  0.0  1.0   1\r\n   1.0  0.0  1.0   1\r\n   1e0  1.0  1.0   1 # a comment\r\n\r\n"
      "   0.0  +1.0  10E-1   1\r\n"
      " Hexahedra\r\n 1\r\n 1 2 3 4 5 6 7 8 1\r\n"
      " End";
  const LoadedMesh loaded = read_medit(text, "m.mesh");
  expect_unit_cube(loaded);
  EXPECT_EQ(loaded.mesh.points[7], (Vec3{0, 1, 1}));
}

TEST(MeditReader, KeywordsInAnyCaseAndTheOldHexaedraSpelling) {
  const std::string text =
      "meshversionformatted 1\nDIMENSION 3\nvertices 8\n"
      "0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n0 0 1 0\n1 0 1 0\n1 1 1 0\n0 1 1 0\n"
      "Hexaedra 1\n1 2 3 4 5 6 7 8 0\nend\n";
  expect_unit_cube(read_medit(text, "m.mesh"));
}

TEST(MeditReader, EndIsOptionalAndWhatFollowsItIsIgnored) {
  std::string without_end = kCube.substr(0, kCube.size() - 4);
  expect_unit_cube(read_medit(without_end, "m.mesh"));
  expect_unit_cube(read_medit(kCube + "garbage that is never read\n", "m.mesh"));
}

TEST(MeditReader, SkipsEveryOtherKnownSection) {
  const std::string text = kHeader + kVertices +
                           "Edges 2\n1 2 0\n2 3 0\n"
                           "Corners 1\n1\n"
                           "RequiredVertices 2\n1\n2\n"
                           "Ridges 1\n1\n"
                           "RequiredEdges 1\n2\n"
                           "Triangles 2\n1 2 3 0\n1 3 4 0\n"
                           "Quadrilaterals 1\n1 2 3 4 7\n"
                           "Quads\n1\n5 6 7 8 0\n"
                           "Normals 1\n0 0 1\n"
                           "NormalAtVertices 1\n1 1\n"
                           "Tangents 1\n1 0 0\n" +
                           kHex + "End\n";
  const LoadedMesh loaded = read_medit(text, "m.mesh");
  EXPECT_EQ(loaded.mesh.points.size(), 9u);
  EXPECT_EQ(loaded.mesh.hexes.size(), 1u);
  EXPECT_TRUE(loaded.warnings.empty());
}

TEST(MeditReader, ReadsOtherVolumeElementsAndWarnsAboutUnknownSections) {
  const std::string text = kHeader + kVertices +
                           "Tetrahedra 2\n1 2 3 5 0\n2 3 4 9 0\n"
                           "Prisms 1\n1 2 3 5 6 7 0\n"
                           "MyCustomData 2\nanything at all\n\n3 words here\n" +
                           kHex;
  const LoadedMesh loaded = read_medit(text, "m.mesh");
  EXPECT_EQ(loaded.mesh.hexes.size(), 1u);
  // Tetrahedra as listed; a prism's corners 1-2 and 4-5 swapped into VTK's order.
  EXPECT_EQ(loaded.mesh.tets, (std::vector<std::array<Index, 4>>{{0, 1, 2, 4}, {1, 2, 3, 8}}));
  EXPECT_EQ(loaded.mesh.wedges, (std::vector<std::array<Index, 6>>{{0, 2, 1, 4, 6, 5}}));
  EXPECT_TRUE(loaded.mesh.source_index[static_cast<std::size_t>(CellKind::tet)].empty());  // implicit: 1, 2
  EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::tet, 1), 2);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_EQ(loaded.warnings[0], "m.mesh: unknown section 'MyCustomData' (2 entries) skipped");
}

TEST(MeditReader, HexahedraBeforeVertices) {
  const std::string text = kHeader + kHex + kVertices;
  const LoadedMesh loaded = read_medit(text, "m.mesh");
  EXPECT_EQ(loaded.mesh.hexes[0], (Hex{0, 1, 2, 3, 4, 5, 6, 7}));
  // Ids are then checked at the end, reported at the Hexahedra line.
  const std::string bad = kHeader + "Hexahedra 1\n1 2 3 4 5 6 7 10 0\n" + kVertices;
  EXPECT_EQ(parse_error(bad), "m.mesh:3: vertex id 10 out of range [1, 9] (hexahedron 1 of 1)");
}

TEST(MeditReader, UnreferencedVerticesAreKept) {
  const LoadedMesh loaded = read_medit(kHeader + kVertices + kHex, "m.mesh");
  EXPECT_EQ(loaded.mesh.points.size(), 9u);
}

// --- errors -----------------------------------------------------------------

TEST(MeditReaderErrors, EmptyOrWrongFirstKeyword) {
  EXPECT_EQ(parse_error(""), "m.mesh:1: unexpected end of file, expected MeshVersionFormatted");
  EXPECT_EQ(parse_error("# only a comment\n\n"), "m.mesh:2: unexpected end of file, expected MeshVersionFormatted");
  EXPECT_EQ(parse_error("\nVertices 8\n"), "m.mesh:2: expected MeshVersionFormatted, got 'Vertices'");
  EXPECT_EQ(parse_error("MeshVersionFormatted 7\n"), "m.mesh:1: unsupported MeshVersionFormatted 7 (expected 1 to 4)");
  EXPECT_EQ(parse_error("MeshVersionFormatted two\n"),
            "m.mesh:1: expected the version number after MeshVersionFormatted, got 'two'");
  EXPECT_EQ(parse_error("MeshVersionFormatted"),
            "m.mesh:1: unexpected end of file, expected the version number after MeshVersionFormatted");
}

TEST(MeditReaderErrors, Dimension) {
  EXPECT_EQ(parse_error("MeshVersionFormatted 1\nDimension\n2\n"), "m.mesh:2: unsupported Dimension 2 (expected 3)");
  EXPECT_EQ(parse_error("MeshVersionFormatted 1\nDimension 3 4\n"), "m.mesh:2: unexpected '4' after the dimension");
}

TEST(MeditReaderErrors, UnknownKeywordOrStrayNumber) {
  EXPECT_EQ(parse_error(kHeader + "Vertexes\nHexahedra 1\n"), "m.mesh:3: unknown keyword 'Vertexes'");
  EXPECT_EQ(parse_error(kHeader + "Vertices 1\n0 0 0 0\n1 1 1 0\n"), "m.mesh:5: expected a keyword, got '1'");
  EXPECT_EQ(parse_error(kHeader + "Dimension 3\nMeshVersionFormatted 1\n"),
            "m.mesh:4: second MeshVersionFormatted keyword");
}

TEST(MeditReaderErrors, BadCounts) {
  EXPECT_EQ(parse_error(kHeader + "Vertices -5\n"), "m.mesh:3: negative number of Vertices: -5");
  EXPECT_EQ(parse_error(kHeader + "Vertices\n3000000000\n"),
            "m.mesh:4: number of Vertices 3000000000 exceeds the limit of 2147483647");
  // 1000 vertices need at least 8 bytes each; checked before allocating.
  EXPECT_EQ(parse_error(kHeader + "Vertices 1000\n0 0 0 0\n"),
            "m.mesh:3: 1000 Vertices cannot fit in the 8 bytes left in the file");
  EXPECT_EQ(parse_error(kHeader + "Vertices 2147483647\n"),
            "m.mesh:3: 2147483647 Vertices cannot fit in the 0 bytes left in the file");
  EXPECT_EQ(parse_error(kHeader + kVertices + "Hexahedra 99999\n1 2 3 4 5 6 7 8 0\n"),
            "m.mesh:13: 99999 Hexahedra cannot fit in the 18 bytes left in the file");
  EXPECT_EQ(parse_error(kHeader + "Vertices x\n"), "m.mesh:3: expected the number of Vertices after Vertices, got 'x'");
  EXPECT_EQ(parse_error(kHeader + "Vertices 2 0 0 0 0\n"), "m.mesh:3: unexpected '0' after the number of Vertices");
  EXPECT_EQ(parse_error(kHeader + "Vertices"),
            "m.mesh:3: unexpected end of file, expected the number of Vertices after Vertices");
  EXPECT_EQ(parse_error(kHeader + "Strange -1\n"), "m.mesh:3: negative number of Strange: -1");
}

TEST(MeditReaderErrors, VertexLines) {
  EXPECT_EQ(parse_error(kHeader + "Vertices 2\n0 0 0 0\n1 1 0\n" + kPad),
            "m.mesh:5: expected 3 coordinates and a reference, got 3 values (vertex 2 of 2)");
  EXPECT_EQ(parse_error(kHeader + "Vertices 2\n0 0 0 0\n1 1\n" + kPad),
            "m.mesh:5: expected 3 coordinates and a reference, got 2 values (vertex 2 of 2)");
  EXPECT_EQ(parse_error(kHeader + "Vertices 2\n0 0 0 0 0\n1 1 1 0\n"),
            "m.mesh:4: expected 3 coordinates and a reference, got 5 values (vertex 1 of 2)");
  EXPECT_EQ(parse_error(kHeader + "Vertices 2\n0 0 0 0\n1 1x 1 0\n"),
            "m.mesh:5: expected a coordinate, got '1x' (vertex 2 of 2)");
  EXPECT_EQ(parse_error(kHeader + "Vertices 2\n0 0 0 0\n1 1 1 0.5\n"),
            "m.mesh:5: expected an integer reference, got '0.5' (vertex 2 of 2)");
  EXPECT_EQ(parse_error(kHeader + "Vertices 2\n0 nan 0 0\n1 1 1 0\n"),
            "m.mesh:4: non-finite coordinate nan (vertex 1 of 2)");
  EXPECT_EQ(parse_error(kHeader + "Vertices 2\n0 0 0 0\n1 1 -inf 0\n"),
            "m.mesh:5: non-finite coordinate -inf (vertex 2 of 2)");
  // Count one too high: the next keyword stands where the last vertex should.
  EXPECT_EQ(parse_error(kHeader + "Vertices 2\n0 0 0 0\nHexahedra 1\n1 1 1 1 1 1 1 1 1\n"),
            "m.mesh:5: expected a coordinate, got 'Hexahedra' (vertex 2 of 2)");
}

TEST(MeditReaderErrors, HexLines) {
  const std::string head = kHeader + kVertices;  // Hexahedra keyword on line 13
  EXPECT_EQ(parse_error(head + "Hexahedra 1\n1 2 3 4 5 6 7 0\n" + kPad),
            "m.mesh:14: vertex id 0 out of range [1, 9] (hexahedron 1 of 1)");
  EXPECT_EQ(parse_error(head + "Hexahedra 1\n1 2 3 4 5 6 7 10 0\n"),
            "m.mesh:14: vertex id 10 out of range [1, 9] (hexahedron 1 of 1)");
  EXPECT_EQ(parse_error(head + "Hexahedra 1\n1 2 3 4 5 6 7 -3 0\n"),
            "m.mesh:14: vertex id -3 out of range [1, 9] (hexahedron 1 of 1)");
  EXPECT_EQ(parse_error(head + "Hexahedra 1\n1 2 3 4 5 6 7 8\n" + kPad),
            "m.mesh:14: expected 8 vertex ids and a reference, got 8 values (hexahedron 1 of 1)");
  EXPECT_EQ(parse_error(head + "Hexahedra 1\n1 2 3 4 5 6 7\n" + kPad),
            "m.mesh:14: expected 8 vertex ids and a reference, got 7 values (hexahedron 1 of 1)");
  EXPECT_EQ(parse_error(head + "Hexahedra 1\n1 2 3 4 5 6 7 8 0 0\n"),
            "m.mesh:14: expected 8 vertex ids and a reference, got 10 values (hexahedron 1 of 1)");
  EXPECT_EQ(parse_error(head + "Hexahedra 1\n1 2 3 4 5 6 7 8.0 0\n"),
            "m.mesh:14: expected an integer vertex id, got '8.0' (hexahedron 1 of 1)");
  EXPECT_EQ(parse_error(head + "Hexahedra 1\n1 2 3 4 5 6 7 8 x\n"),
            "m.mesh:14: expected an integer reference, got 'x' (hexahedron 1 of 1)");
  EXPECT_EQ(parse_error(head + "Hexahedra 2\n1 2 3 4 5 6 7 8 0\n1 2 3 4 5 6 2 8 0\n"),
            "m.mesh:15: vertex id 2 repeated (hexahedron 2 of 2)");
}

TEST(MeditReaderErrors, TruncatedFile) {
  EXPECT_EQ(parse_error(kHeader + kVertices + "Hexahedra 2\n1 2 3 4 5 6 7 8 0\n" + kPad),
            "m.mesh:15: unexpected end of file, expected 8 vertex ids and a reference (hexahedron 2 of 2)");
  EXPECT_EQ(parse_error(kHeader + kVertices + "Hexahedra 2\n1 2 3 4 5 6 7 8 0\n1          2          3"),
            "m.mesh:15: expected 8 vertex ids and a reference, got 3 values (hexahedron 2 of 2)");
  EXPECT_EQ(parse_error(kHeader + "Vertices 2\n0 0 0 0\n" + kPad),
            "m.mesh:5: unexpected end of file, expected 3 coordinates and a reference (vertex 2 of 2)");
  EXPECT_EQ(parse_error(kHeader + kVertices + "Triangles 3\n1 2 3 0\n" + kPad),
            "m.mesh:15: unexpected end of file, expected 3 vertex ids and a reference (Triangles entry 2 of 3)");
  EXPECT_EQ(parse_error(kHeader + kVertices + "Unknown 3\nx\n" + kPad),
            "m.mesh:15: unexpected end of file, expected 3 entries of 'Unknown', got 1");
}

TEST(MeditReaderErrors, SkippedSectionEntries) {
  const std::string head = kHeader + kVertices;  // next keyword on line 13
  EXPECT_EQ(parse_error(head + "Triangles 2\n1 2 3 0\n" + kHex),
            "m.mesh:15: expected 3 vertex ids and a reference, got 'Hexahedra' (Triangles entry 2 of 2)");
  EXPECT_EQ(parse_error(head + "Quads 1\n1 2 3 0\n" + kHex),
            "m.mesh:14: expected 4 vertex ids and a reference, got 4 values (Quads entry 1 of 1)");
  EXPECT_EQ(parse_error(head + "Corners 1\n1 2\n" + kHex),
            "m.mesh:14: expected a vertex id, got 2 values (Corners entry 1 of 1)");
}

TEST(MeditReaderErrors, MissingSectionsAndEmptyMeshes) {
  EXPECT_EQ(parse_error(kHeader + kHex), "m.mesh: no Vertices section");
  EXPECT_EQ(parse_error(kHeader + kVertices), "m.mesh: no volume cells (Hexahedra, Tetrahedra, Prisms or Pyramids)");
  EXPECT_EQ(parse_error(kHeader + kVertices + "Hexahedra 0\nEnd\n"),
            "m.mesh: no volume cells (Hexahedra, Tetrahedra, Prisms or Pyramids)");
  EXPECT_EQ(parse_error(kHeader + "Vertices 0\n" + kHex),
            "m.mesh:5: vertex id 1 out of range [1, 0] (hexahedron 1 of 1)");
  EXPECT_EQ(parse_error(kHeader + kVertices + kHex + kVertices),
            "m.mesh:15: second Vertices section (the first is at line 3)");
  EXPECT_EQ(parse_error(kHeader + kVertices + kHex + kHex),
            "m.mesh:15: second Hexahedra section (the first is at line 13)");
}

TEST(MeditReaderErrors, ErrorsAreParseErrorsWithPathAndLine) {
  try {
    read_medit(kHeader + "Vertices -1\n", "dir/m.mesh");
    FAIL() << "no exception";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.path(), "dir/m.mesh");
    EXPECT_EQ(e.line(), 3);
  }
}

// --- triangles (reference surfaces) -------------------------------------------

TEST(MeditTriangles, ReadsVerticesAndTrianglesSkippingHexahedra) {
  const std::string text = kHeader + kVertices + kHex + "Triangles 2\n1 2 3 0\n1 3 4 5\nEnd\n";
  const TriSurface surface = read_medit_triangles(text, "s.mesh");
  EXPECT_EQ(surface.points.size(), 9u);
  ASSERT_EQ(surface.triangles.size(), 2u);
  EXPECT_EQ(surface.triangles[1], (std::array<Index, 3>{0, 2, 3}));
}

TEST(MeditTriangles, Errors) {
  const auto error = [](const std::string& text) {
    return error_text<ParseError>([&] { read_medit_triangles(text, "s.mesh"); });
  };
  EXPECT_EQ(error(kHeader + kVertices + kHex), "s.mesh: no triangles");
  EXPECT_EQ(error(kHeader + kVertices + "Triangles 1\n1 2 12 0\n"),
            "s.mesh:14: vertex id 12 out of range [1, 9] (triangle 1 of 1)");
  EXPECT_EQ(error(kHeader + kVertices + "Triangles 1\n1 2 2 0\n"), "s.mesh:14: vertex id 2 repeated (triangle 1 of 1)");
  EXPECT_EQ(error(kHeader + "Triangles 1\n1 2 3 0\n"), "s.mesh: no Vertices section");
  // A Hexahedra section is still checked while it is skipped.
  EXPECT_EQ(error(kHeader + kVertices + "Hexahedra 1\n1 2 3 4 5 6 7 8\n" + kPad),
            "s.mesh:14: expected 8 vertex ids and a reference, got 8 values (Hexahedra entry 1 of 1)");
}

}  // namespace
}  // namespace hq
