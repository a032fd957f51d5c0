// --max-memory: the estimate, and each reader refusing a file
// whose declared counts need more than the budget, before allocating.

#include "hqview/io/read_limits.h"

#include <gtest/gtest.h>

#include <string>

#include "error_text.h"
#include "hqview/io/gmsh_reader.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/io/ovm_reader.h"
#include "hqview/io/vtk_legacy_reader.h"
#include "hqview/io/vtu_reader.h"
#include "temp_dir.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;

TEST(ReadLimits, FormatsSizesWithThreeDigits) {
  EXPECT_EQ(format_memory_size(1), "1 byte");
  EXPECT_EQ(format_memory_size(1000), "1000 bytes");
  EXPECT_EQ(format_memory_size(kMiB), "1 MB");
  EXPECT_EQ(format_memory_size(1536 * kMiB), "1.5 GB");
  EXPECT_EQ(format_memory_size(12345 * kMiB), "12.1 GB");
  EXPECT_EQ(format_memory_size(std::uint64_t{3} << 40), "3 TB");
}

TEST(ReadLimits, EstimateGrowsWithEveryCountAndSaturates) {
  const std::uint64_t base = estimate_analysis_memory(0, 0, 0);
  EXPECT_GT(base, 100 * kMiB);  // the process and its libraries
  EXPECT_EQ(estimate_analysis_memory(1000, 0, 0), base + 1000);
  EXPECT_GT(estimate_analysis_memory(0, 1000, 0), base);
  EXPECT_GT(estimate_analysis_memory(0, 0, 1000), estimate_analysis_memory(0, 1000, 0));
  EXPECT_EQ(estimate_analysis_memory(UINT64_MAX, UINT64_MAX, UINT64_MAX), UINT64_MAX);
}

TEST(ReadLimits, DefaultIsAFractionOfThePhysicalMemory) {
  const std::uint64_t bytes = default_max_memory();
  EXPECT_GT(bytes, 0u);
  EXPECT_EQ(ReadLimits{}.max_memory, bytes);
}

const ReadLimits kOneMegabyte{.max_memory = kMiB};

std::string needs(std::uint64_t file_bytes, std::uint64_t vertices, std::uint64_t hexes) {
  return format_memory_size(estimate_analysis_memory(file_bytes, vertices, hexes));
}

TEST(ReadLimits, MeditChecksVerticesThenHexes) {
  const std::string vertices = "MeshVersionFormatted 2\nDimension 3\nVertices\n8\n" + std::string(8 * 8, ' ');
  EXPECT_EQ(error_text<ParseError>([&] { read_medit(vertices, "m.mesh", kOneMegabyte); }),
            "m.mesh:4: the file declares 8 vertices, which needs about " + needs(vertices.size(), 8, 0) +
                "; --max-memory is 1 MB");
  std::string hexes = "MeshVersionFormatted 2\nDimension 3\nVertices 1\n0 0 0 0\nHexahedra 3\n";
  hexes += std::string(3 * 18, ' ');
  const ReadLimits enough_for_vertices{.max_memory = estimate_analysis_memory(hexes.size(), 1, 2)};
  EXPECT_EQ(error_text<ParseError>([&] { read_medit(hexes, "m.mesh", enough_for_vertices); }),
            "m.mesh:5: the file declares 3 hexes, which needs about " + needs(hexes.size(), 1, 3) + " (" +
                std::to_string(estimate_analysis_memory(hexes.size(), 1, 3)) + " bytes); --max-memory is " +
                format_memory_size(enough_for_vertices.max_memory) + " (" +
                std::to_string(enough_for_vertices.max_memory) + " bytes)");  // rounded alike: exact bytes too
  // No limit: the same file gets as far as its (blank) entries.
  EXPECT_EQ(error_text<ParseError>([&] { read_medit(hexes, "m.mesh", ReadLimits{.max_memory = 0}); }),
            "m.mesh:6: unexpected end of file, expected 8 vertex ids and a reference (hexahedron 1 of 3)");
}

TEST(ReadLimits, SizesThatRoundAlikeAreShownInBytes) {
  const std::uint64_t needed = estimate_analysis_memory(100, 8, 1);
  const ReadLimits just_below{.max_memory = needed - 1};
  EXPECT_EQ(error_text<ParseError>([&] { check_mesh_memory(just_below, "m.mesh", 7, 100, 8, 1); }),
            "m.mesh:7: the file declares 1 hex, which needs about " + format_memory_size(needed) + " (" +
                std::to_string(needed) + " bytes); --max-memory is " + format_memory_size(needed - 1) + " (" +
                std::to_string(needed - 1) + " bytes)");
  EXPECT_NO_THROW(check_mesh_memory(ReadLimits{.max_memory = needed}, "m.mesh", 7, 100, 8, 1));
}

// A header claiming 10^9 hexes in a tiny file: the count is checked against
// the bytes left before the budget, so the message says the file is malformed.
TEST(ReadLimits, CountsBeyondTheFileComeBeforeTheBudget) {
  const std::string text = "MeshVersionFormatted 2\nDimension 3\nVertices 1\n0 0 0 0\nHexahedra 1000000000\n";
  const std::string message = "m.mesh:5: 1000000000 Hexahedra cannot fit in the 0 bytes left in the file";
  EXPECT_EQ(error_text<ParseError>([&] { read_medit(text, "m.mesh"); }), message);
  const ReadLimits enough_for_vertices{.max_memory = estimate_analysis_memory(text.size(), 1, 0)};
  EXPECT_EQ(error_text<ParseError>([&] { read_medit(text, "m.mesh", enough_for_vertices); }), message);
}

TEST(ReadLimits, EveryReaderWithCountsChecksThem) {
  const std::string vtk =
      "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 2 double\n0 0 0 1 1 1\n";
  EXPECT_EQ(
      error_text<ParseError>([&] { read_vtk_legacy(vtk, "m.vtk", kOneMegabyte); }),
      "m.vtk:5: the file declares 2 vertices, which needs about " + needs(vtk.size(), 2, 0) + "; --max-memory is 1 MB");
  const std::string vtu =
      "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid>\n<Piece NumberOfPoints=\"8\" NumberOfCells=\"1\">\n"
      "</Piece></UnstructuredGrid></VTKFile>\n";
  EXPECT_EQ(
      error_text<ParseError>([&] { read_vtu(vtu, "m.vtu", kOneMegabyte); }),
      "m.vtu:2: the file declares 1 cell, which needs about " + needs(vtu.size(), 8, 1) + "; --max-memory is 1 MB");
  const std::string msh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 1 1\n$EndNodes\n";
  EXPECT_EQ(
      error_text<ParseError>([&] { read_gmsh(msh, "m.msh", kOneMegabyte); }),
      "m.msh:5: the file declares 2 vertices, which needs about " + needs(msh.size(), 2, 0) + "; --max-memory is 1 MB");
  const std::string ovm = "OVM ASCII\nVertices\n2\n0 0 0\n1 1 1\n";
  EXPECT_NE(error_text<ParseError>([&] {
              read_ovm(ovm, "m.ovm", kOneMegabyte);
            }).find(": the file declares 2 vertices, which needs about "),
            std::string::npos);
}

TEST(ReadLimits, FileLargerThanTheBudgetIsNotRead) {
  test::TempDir dir("limits");
  const auto path = dir.write("m.mesh", std::string(2 * kMiB, '#'));
  EXPECT_EQ(error_text<InputError>([&] { read_hex_mesh(path, kOneMegabyte); }),
            path.string() + ": the file has 2097152 bytes (2 MB), more than --max-memory (1 MB)");
}

TEST(ReadLimits, BinaryGarbageIsRefusedFromItsFirstMegabyte) {
  test::TempDir dir("limits");
  std::string zeros(3 * kMiB, '\0');
  for (const char* name : {"m.mesh", "m.vtk", "m.e"}) {
    const auto path = dir.write(name, zeros);
    const std::string format = std::string(name) == "m.mesh"  ? "MEDIT (.mesh)"
                               : std::string(name) == "m.vtk" ? "legacy VTK"
                                                              : "Exodus II (netCDF)";
    const bool is_text_only = std::string(name) == "m.mesh";
    EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(path); }),
              path.string() + ": binary data, expected " + format + (is_text_only ? " text" : " content") +
                  " (a NUL byte at offset 0" + (is_text_only ? ")" : " and no mesh format's signature)"));
  }
  // A text-only format's signature, then zeros (a sparse file): still binary data.
  const auto late = dir.write("late.mesh", "MeshVersionFormatted 2\n" + std::string(3 * kMiB, '\0'));
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(late); }),
            late.string() + ": binary data, expected MEDIT (.mesh) text (a NUL byte at offset 23)");
  // Binary legacy VTK has a signature: left to its reader.
  const auto vtk = dir.write("b.vtk", std::string("# vtk DataFile Version 3.0\nx\nBINARY\n") + std::string(10, '\0'));
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(vtk); }).find("binary data"), std::string::npos);
}

}  // namespace
}  // namespace hq
