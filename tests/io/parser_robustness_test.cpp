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

#include "hqview/io/medit_reader.h"
#include "hqview/io/vtk_legacy_reader.h"

namespace hq {
namespace {

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

}  // namespace
}  // namespace hq
