// read_gmsh on inline strings: MSH 2.2 and 4.1, ASCII and binary (both byte
// orders), non-contiguous node tags, skipped element types, skipped
// sections, and the error paths.

#include "hqview/io/gmsh_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "error_text.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;

// The unit cube, node tags 10, 20, ..., 80 in file order 80, 10, 20, ..., 70.
const std::int64_t kTags[8] = {80, 10, 20, 30, 40, 50, 60, 70};
const double kXyz[8][3] = {{0, 1, 1}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}};
// Hex corners by tag: 10 20 30 40 50 60 70 80 -> file indices 1..7, 0.
const Hex kHex = {1, 2, 3, 4, 5, 6, 7, 0};

void expect_cube(const LoadedMesh& loaded, const std::string& format) {
  EXPECT_EQ(loaded.format, format);
  ASSERT_EQ(loaded.mesh.points.size(), 8u);
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(loaded.mesh.points[static_cast<std::size_t>(i)].x, kXyz[i][0]);
    EXPECT_EQ(loaded.mesh.points[static_cast<std::size_t>(i)].y, kXyz[i][1]);
    EXPECT_EQ(loaded.mesh.points[static_cast<std::size_t>(i)].z, kXyz[i][2]);
  }
  ASSERT_EQ(loaded.mesh.hexes.size(), 1u);
  EXPECT_EQ(loaded.mesh.hexes[0], kHex);
}

std::string nodes22_ascii() {
  std::string s = "$Nodes\n8\n";
  for (int i = 0; i < 8; ++i)
    s += std::to_string(kTags[i]) + " " + std::to_string(kXyz[i][0]) + " " + std::to_string(kXyz[i][1]) + " " +
         std::to_string(kXyz[i][2]) + "\n";
  return s + "$EndNodes\n";
}

const std::string kFormat22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";

TEST(GmshReader, Ascii22) {
  const std::string text = kFormat22 + "$PhysicalNames\n1\n3 1 \"vol\"\n$EndPhysicalNames\n" + nodes22_ascii() +
                           "$Elements\n3\n1 15 2 0 1 10\n2 5 2 0 1 10 20 30 40 50 60 70 80\n3 3 2 0 1 10 20 30 "
                           "40\n$EndElements\n$NodeData\nwhatever\n$EndNodeData\n";
  const LoadedMesh loaded = read_gmsh(text, "a.msh");
  expect_cube(loaded, "gmsh-2.2-ascii");
  // Lower-dimensional elements (boundary quads, lines, points): a note, not a warning.
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_EQ(loaded.notes.size(), 1u);
  EXPECT_EQ(loaded.notes[0], "a.msh: 2 elements of unread types skipped (types 3, 15)");
}

TEST(GmshReader, Ascii41) {
  std::string text =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n$EndEntities\n"
      "$Nodes\n2 8 10 80\n3 1 0 1\n80\n0 1 1\n3 1 1 7\n";
  for (int i = 1; i < 8; ++i) text += std::to_string(kTags[i]) + "\n";
  for (int i = 1; i < 8; ++i)
    text += std::to_string(kXyz[i][0]) + " " + std::to_string(kXyz[i][1]) + " " + std::to_string(kXyz[i][2]) +
            " 0.5 0.5 0.5\n";
  text += "$EndNodes\n$Elements\n2 2 1 2\n2 1 3 1\n1 10 20 30 40\n3 1 5 1\n2 10 20 30 40 50 60 70 80\n$EndElements\n";
  const LoadedMesh loaded = read_gmsh(text, "a.msh");
  expect_cube(loaded, "gmsh-4.1-ascii");
  // Lower-dimensional elements (boundary quads, lines, points): a note, not a warning.
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_EQ(loaded.notes.size(), 1u);
  EXPECT_EQ(loaded.notes[0], "a.msh: 1 element of unread types skipped (type 3)");
}

// Binary values in either byte order.
struct Bytes {
  bool big_endian = false;
  std::string out;
  template <class T>
  Bytes& put(T value) {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (big_endian) std::reverse(b, b + sizeof(T));
    out.append(b, sizeof(T));
    return *this;
  }
};

std::string binary22(bool big_endian) {
  Bytes b{big_endian, "$MeshFormat\n2.2 1 8\n"};
  b.put<std::int32_t>(1);
  b.out += "\n$EndMeshFormat\n$Nodes\n8\n";
  for (int i = 0; i < 8; ++i) {
    b.put<std::int32_t>(static_cast<std::int32_t>(kTags[i]));
    for (const double c : kXyz[i]) b.put<double>(c);
  }
  b.out += "\n$EndNodes\n$Elements\n3\n";
  // A block of 2 lines (type 1, 2 tags), then a hexahedron (type 5, 2 tags).
  b.put<std::int32_t>(1).put<std::int32_t>(2).put<std::int32_t>(2);
  for (int e = 0; e < 2; ++e)
    b.put<std::int32_t>(e + 1).put<std::int32_t>(0).put<std::int32_t>(1).put<std::int32_t>(10).put<std::int32_t>(20);
  b.put<std::int32_t>(5).put<std::int32_t>(1).put<std::int32_t>(2);
  b.put<std::int32_t>(3).put<std::int32_t>(0).put<std::int32_t>(1);
  for (int t = 10; t <= 80; t += 10) b.put<std::int32_t>(t);
  b.out += "\n$EndElements\n";
  return b.out;
}

TEST(GmshReader, Binary22BothByteOrders) {
  for (const bool big_endian : {false, true}) {
    const LoadedMesh loaded = read_gmsh(binary22(big_endian), "b.msh");
    expect_cube(loaded, "gmsh-2.2-binary");
    // Lower-dimensional elements (boundary quads, lines, points): a note, not a warning.
    EXPECT_TRUE(loaded.warnings.empty());
    ASSERT_EQ(loaded.notes.size(), 1u);
    EXPECT_EQ(loaded.notes[0], "b.msh: 2 elements of unread types skipped (type 1)");
  }
}

std::string binary41() {
  Bytes b{false, "$MeshFormat\n4.1 1 8\n"};
  b.put<std::int32_t>(1);
  b.out += "\n$EndMeshFormat\n$Nodes\n";
  b.put<std::uint64_t>(1).put<std::uint64_t>(8).put<std::uint64_t>(10).put<std::uint64_t>(80);
  b.put<std::int32_t>(3).put<std::int32_t>(1).put<std::int32_t>(0).put<std::uint64_t>(8);
  for (const std::int64_t tag : kTags) b.put<std::uint64_t>(static_cast<std::uint64_t>(tag));
  for (const auto& xyz : kXyz)
    for (const double c : xyz) b.put<double>(c);
  b.out += "\n$EndNodes\n$Elements\n";
  b.put<std::uint64_t>(2).put<std::uint64_t>(2).put<std::uint64_t>(1).put<std::uint64_t>(2);
  b.put<std::int32_t>(0).put<std::int32_t>(1).put<std::int32_t>(15).put<std::uint64_t>(1);
  b.put<std::uint64_t>(1).put<std::uint64_t>(10);
  b.put<std::int32_t>(3).put<std::int32_t>(1).put<std::int32_t>(5).put<std::uint64_t>(1);
  b.put<std::uint64_t>(2);
  for (int t = 10; t <= 80; t += 10) b.put<std::uint64_t>(static_cast<std::uint64_t>(t));
  b.out += "\n$EndElements\n";
  return b.out;
}

TEST(GmshReader, Binary41) {
  const LoadedMesh loaded = read_gmsh(binary41(), "b.msh");
  expect_cube(loaded, "gmsh-4.1-binary");
  // Lower-dimensional elements (boundary quads, lines, points): a note, not a warning.
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_EQ(loaded.notes.size(), 1u);
  EXPECT_EQ(loaded.notes[0], "b.msh: 1 element of unread types skipped (type 15)");
}

TEST(GmshReader, Detection) {
  EXPECT_TRUE(looks_like_gmsh("\n$MeshFormat\n2.2 0 8\n"));
  EXPECT_FALSE(looks_like_gmsh("MeshVersionFormatted 1\n"));
}

TEST(GmshReader, Errors) {
  const auto error = [](const std::string& text) { return error_text<ParseError>([&] { read_gmsh(text, "e.msh"); }); };
  EXPECT_EQ(error(""), "e.msh:1: empty file, expected $MeshFormat");
  EXPECT_EQ(error("$Nodes\n"), "e.msh:1: expected $MeshFormat, got '$Nodes'");
  EXPECT_EQ(error("$MeshFormat\n4.0 0 8\n$EndMeshFormat\n"),
            "e.msh:2: unsupported MSH version '4.0' (expected 2.2 or 4.1)");
  EXPECT_EQ(error("$MeshFormat\n2.2 2 8\n$EndMeshFormat\n"), "e.msh:2: file type 2, expected 0 (ASCII) or 1 (binary)");
  EXPECT_EQ(error("$MeshFormat\n2.2 1 8\nabcd\n$EndMeshFormat\n"),
            "e.msh:3: binary format check: expected the integer 1, got bytes 'abcd'");
  EXPECT_EQ(error(kFormat22), "e.msh:3: unexpected end of file: no $Nodes section");
  EXPECT_EQ(error(kFormat22 + "$Comments\nnever closed\n"),
            "e.msh:4: unexpected end of file: $Comments without $EndComments");
  EXPECT_EQ(error(kFormat22 + "$Elements\n0\n$EndElements\n"), "e.msh:4: $Elements before $Nodes");
  EXPECT_EQ(error(kFormat22 + "$Nodes\n-1\n"), "e.msh:5: negative number of nodes -1");
  EXPECT_EQ(error(kFormat22 + "$Nodes\n1000\n1 0 0 0\n"),
            "e.msh:5: 1000 nodes cannot fit in the 9 bytes left in the file");
  EXPECT_EQ(error(kFormat22 + "$Nodes\n2\n1 0 0 0\n1 1 1 1\n$EndNodes\n"), "e.msh:7: node tag 1 defined twice");
  EXPECT_EQ(error(kFormat22 + "$Nodes\n1\n1 0 nan 0\n$EndNodes\n"), "e.msh:6: non-finite coordinate nan (node 1)");
  EXPECT_EQ(error(kFormat22 + "$Nodes\n1\n1 0 0 0\n$EndNode\n"), "e.msh:7: expected $EndNodes, got '$EndNode'");
  EXPECT_EQ(error(kFormat22 + nodes22_ascii() + "$Elements\n1\n1 5 0 10 20 30 40 50 60 70 90\n$EndElements\n"),
            "e.msh:17: node tag 90 is not defined (element 1)");
  EXPECT_EQ(error(kFormat22 + nodes22_ascii() + "$Elements\n1\n1 5 0 10 20 30 40 50 60 70 10\n$EndElements\n"),
            "e.msh:17: node tag 10 repeated (element 1)");
  EXPECT_EQ(error(kFormat22 + nodes22_ascii() + "$Elements\n1\n1 5 0 10 20 30 40 50 60 70\n$EndElements\n"),
            "e.msh:17: expected 8 node tags for hexahedron 1, got 7");
  EXPECT_EQ(error(kFormat22 + nodes22_ascii() + "$Elements\n1\n1 5 0 10 20 30 40 50 60 70 80 90\n$EndElements\n"),
            "e.msh:17: expected 8 node tags for hexahedron 1, got 9");
  EXPECT_EQ(error(kFormat22 + nodes22_ascii() + "$Elements\n1\n1 1 0 10 20\n$EndElements\n"),
            "e.msh:15: no volume elements (types 4, 5, 6, 7) among 1 element of type 1");
  EXPECT_EQ(error("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n3 1 0 3\n1\n2\n3\n"),
            "e.msh:6: node block 0 claims 3 nodes, 2 are left of the 2 in the header");
  // Binary: truncated data, at the section's line with the byte offset.
  const std::string b22 = binary22(false);
  EXPECT_EQ(error(b22.substr(0, b22.find("$EndNodes") - 20)),
            "e.msh:6: 8 nodes cannot fit in the 206 bytes left in the file");
  // A hexahedron's node data cut short.
  EXPECT_EQ(error(b22.substr(0, b22.size() - 30)).substr(0, 47), "e.msh:10: element block of 1 elements truncated");
  std::string bad_type = b22;
  const std::size_t elements = bad_type.find("$Elements\n3\n") + 12;
  bad_type[elements] = 99;
  EXPECT_EQ(error(bad_type), "e.msh:10: unknown element type 99 (byte offset " + std::to_string(elements) + ")");
}

}  // namespace
}  // namespace hq
