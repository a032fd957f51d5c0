// read_abaqus on inline strings: *NODE, *ELEMENT of the C3D8 family with
// continuation lines, skipped element types and keywords, and the errors.

#include "hqview/io/abaqus_reader.h"

#include <gtest/gtest.h>

#include <string>

#include "error_text.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;

const std::string kNodes =
    "*Node, nset=all\n"
    "  101, 0., 0., 0.\n102, 1., 0., 0.\n103, 1., 1., 0.\n104, 0., 1., 0.\n"
    "105, 0., 0., 1.\n106, 1., 0., 1.\n107, 1., 1., 1.\n108, 0., 1.\n";

TEST(AbaqusReader, NodesElementsAndContinuations) {
  const std::string text = "** a comment\n*HEADING\nsome title, with commas\n" + kNodes +
                           "*ELEMENT, TYPE=C3D8R, ELSET=solid\n1, 101, 102, 103, 104,\n   105, 106, 107, 108\n"
                           "*element,type=c3d8i\n2,105,106,107,108,101,102,103,104\n"
                           "*ELEMENT, TYPE=S4R\n3, 101, 102, 103, 104\n4, 105, 106,\n107, 108\n"
                           "*ELEMENT, TYPE=C3D4\n5, 101, 102, 103, 105\n"
                           "*NSET, NSET=top\n105, 106, 107, 108\n*MATERIAL, NAME=steel\n*ELASTIC\n2e11, 0.3\n";
  const LoadedMesh loaded = read_abaqus(text, "a.inp");
  EXPECT_EQ(loaded.format, "abaqus");
  ASSERT_EQ(loaded.mesh.points.size(), 8u);
  EXPECT_EQ(loaded.mesh.points[6].x, 1.0);
  EXPECT_EQ(loaded.mesh.points[7].z, 0.0);  // missing z
  ASSERT_EQ(loaded.mesh.hexes.size(), 2u);
  EXPECT_EQ(loaded.mesh.hexes[0], (Hex{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(loaded.mesh.hexes[1], (Hex{4, 5, 6, 7, 0, 1, 2, 3}));
  EXPECT_EQ(loaded.mesh.tets, (std::vector<std::array<Index, 4>>{{0, 1, 2, 4}}));
  EXPECT_EQ(loaded.mesh.source_index[static_cast<std::size_t>(CellKind::hex)], (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(loaded.mesh.source_index[static_cast<std::size_t>(CellKind::tet)], (std::vector<std::int64_t>{5}));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_EQ(loaded.warnings[0], "a.inp: 2 elements of unread types skipped (type S4R)");
}

TEST(AbaqusReader, Detection) {
  EXPECT_TRUE(looks_like_abaqus("** comment\n\n*Heading\n"));
  EXPECT_FALSE(looks_like_abaqus("$MeshFormat\n"));
  EXPECT_FALSE(looks_like_abaqus("** only comments\n"));
}

TEST(AbaqusReader, Errors) {
  const auto error = [](const std::string& text) {
    return error_text<ParseError>([&] { read_abaqus(text, "e.inp"); });
  };
  EXPECT_EQ(error("1, 0, 0, 0\n"), "e.inp:1: data line before any keyword: '1, 0, 0, 0'");
  EXPECT_EQ(error("*NODE\n1, 0, x, 0\n"), "e.inp:2: expected a coordinate, got 'x'");
  EXPECT_EQ(error("*NODE\n1, 0, 0, 0, 0\n"), "e.inp:2: expected a node id and 1 to 3 coordinates, got 5 fields");
  EXPECT_EQ(error("*NODE\n1, 0, 0, 0\n1, 1, 1, 1\n"), "e.inp:3: node id 1 defined twice");
  EXPECT_EQ(error("*NODE\n0, 0, 0, 0\n"), "e.inp:2: node id 0 is not positive");
  EXPECT_EQ(error("*NODE\n1, 0, 0, inf\n"), "e.inp:2: non-finite coordinate (node 1)");
  EXPECT_EQ(error("*ELEMENT\n"), "e.inp:1: *ELEMENT without TYPE=");
  EXPECT_EQ(error("*INCLUDE, INPUT=mesh.inp\n"),
            "e.inp:1: *INCLUDE is not supported: merge the included file into this one");
  EXPECT_EQ(error(kNodes + "*ELEMENT, TYPE=C3D8\n1, 101, 102, 103, 104, 105, 106, 107\n"),
            "e.inp:11: expected an element id and 8 node ids, got 8 fields");
  EXPECT_EQ(error(kNodes + "*ELEMENT, TYPE=C3D8\n1, 101, 102, 103, 104, 105, 106, 107, 109\n"),
            "e.inp:11: node 109 is not defined (element 1)");
  EXPECT_EQ(error(kNodes + "*ELEMENT, TYPE=C3D8\n1, 101, 102, 103, 104, 105, 106, 107, 101\n"),
            "e.inp:11: node 101 repeated (element 1)");
  EXPECT_EQ(error(kNodes + "*ELEMENT, TYPE=C3D8\n1, 101, 102, 103, 104,\n"),
            "e.inp:11: unexpected end of file in an element continued on the next line");
  EXPECT_EQ(error(kNodes + "*ELEMENT, TYPE=B31\n1, 101, 102\n"),
            "e.inp: no volume elements (*ELEMENT, TYPE=C3D8, C3D8R, C3D4, C3D6, C3D5 ...): 1 element of type B31");
}

}  // namespace
}  // namespace hq
