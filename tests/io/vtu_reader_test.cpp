// read_vtu on inline strings: every DataArray encoding (ascii, binary
// base64 with the header encoded with the data or apart, appended raw and
// base64), zlib or not, UInt32 and UInt64 headers, both byte orders, cell
// types 12 and 11, several pieces, and the error paths.

#include "hqview/io/vtu_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#ifdef HQ_HAVE_ZLIB
#include <zlib.h>
#endif

#include "error_text.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;

const std::vector<double> kCube = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
const Hex kIdentity = {0, 1, 2, 3, 4, 5, 6, 7};

template <class T>
std::string bytes_of(const std::vector<T>& values, bool big_endian = false) {
  std::string out(values.size() * sizeof(T), '\0');
  std::memcpy(out.data(), values.data(), out.size());
  if (big_endian)
    for (std::size_t i = 0; i < values.size(); ++i)
      std::reverse(out.begin() + static_cast<std::ptrdiff_t>(i * sizeof(T)),
                   out.begin() + static_cast<std::ptrdiff_t>((i + 1) * sizeof(T)));
  return out;
}

std::string header_value(std::uint64_t v, bool is_uint64, bool big_endian = false) {
  return is_uint64 ? bytes_of(std::vector<std::uint64_t>{v}, big_endian)
                   : bytes_of(std::vector<std::uint32_t>{static_cast<std::uint32_t>(v)}, big_endian);
}

std::string base64(const std::string& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

// Uncompressed: byte count header, then the data.
std::string raw_block(const std::string& data, bool is_uint64, bool big_endian = false) {
  return header_value(data.size(), is_uint64, big_endian) + data;
}

#ifdef HQ_HAVE_ZLIB
// zlib: [#blocks, block size, last block size, compressed sizes...] and the
// compressed blocks, returned apart (VTK base64-encodes them separately).
std::pair<std::string, std::string> zlib_blocks(const std::string& data, std::size_t block_size, bool is_uint64) {
  std::vector<std::string> blocks;
  for (std::size_t i = 0; i < data.size(); i += block_size) {
    const std::string chunk = data.substr(i, block_size);
    uLongf length = compressBound(chunk.size());
    std::string out(length, '\0');
    compress(reinterpret_cast<Bytef*>(out.data()), &length, reinterpret_cast<const Bytef*>(chunk.data()), chunk.size());
    out.resize(length);
    blocks.push_back(out);
  }
  std::string header = header_value(blocks.size(), is_uint64) + header_value(block_size, is_uint64) +
                       header_value(data.size() % block_size, is_uint64);
  std::string body;
  for (const std::string& b : blocks) {
    header += header_value(b.size(), is_uint64);
    body += b;
  }
  return {header, body};
}
#endif

std::string data_array(const std::string& type, const std::string& name, const std::string& format,
                       const std::string& content, int components = 1) {
  return "<DataArray type=\"" + type + "\" Name=\"" + name + "\"" +
         (components != 1 ? " NumberOfComponents=\"" + std::to_string(components) + "\"" : std::string()) +
         " format=\"" + format + "\">" + content + "</DataArray>\n";
}

std::string appended_array(const std::string& type, const std::string& name, std::size_t offset, int components = 1) {
  return "<DataArray type=\"" + type + "\" Name=\"" + name + "\"" +
         (components != 1 ? " NumberOfComponents=\"" + std::to_string(components) + "\"" : std::string()) +
         " format=\"appended\" offset=\"" + std::to_string(offset) + "\"/>\n";
}

std::string piece(int num_points, int num_cells, const std::string& points, const std::string& cells) {
  return "<Piece NumberOfPoints=\"" + std::to_string(num_points) + "\" NumberOfCells=\"" + std::to_string(num_cells) +
         "\">\n<Points>\n" + points + "</Points>\n<Cells>\n" + cells + "</Cells>\n</Piece>\n";
}

std::string vtu(const std::string& pieces, const std::string& attributes = "", const std::string& appended = "") {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\"" + attributes +
         ">\n<UnstructuredGrid>\n" + pieces + "</UnstructuredGrid>\n" + appended + "</VTKFile>\n";
}

std::string ascii_list(const std::vector<double>& values) {
  std::string out = "\n";
  for (const double v : values) out += std::to_string(v) + " ";
  return out + "\n";
}

// One cube, ASCII: the fixture most error tests start from.
std::string ascii_cube(const std::string& connectivity = "0 1 2 3 4 5 6 7", const std::string& offsets = "8",
                       const std::string& types = "12") {
  return vtu(piece(8, 1, data_array("Float64", "Points", "ascii", ascii_list(kCube), 3),
                   data_array("Int32", "connectivity", "ascii", connectivity) +
                       data_array("Int32", "offsets", "ascii", offsets) +
                       data_array("UInt8", "types", "ascii", types)));
}

void expect_cube(const LoadedMesh& loaded, const std::string& format) {
  EXPECT_EQ(loaded.format, format);
  ASSERT_EQ(loaded.mesh.points.size(), 8u);
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(loaded.mesh.points[i].x, kCube[3 * i]);
    EXPECT_EQ(loaded.mesh.points[i].y, kCube[3 * i + 1]);
    EXPECT_EQ(loaded.mesh.points[i].z, kCube[3 * i + 2]);
  }
  ASSERT_EQ(loaded.mesh.hexes.size(), 1u);
  EXPECT_EQ(loaded.mesh.hexes[0], kIdentity);
  EXPECT_TRUE(loaded.warnings.empty());
}

TEST(VtuReader, AsciiHexahedron) { expect_cube(read_vtu(ascii_cube(), "c.vtu"), "vtu-ascii"); }

// VTK 9 writes range attributes and <InformationKey> children before the values.
TEST(VtuReader, InformationKeysBeforeTheValues) {
  const std::string keys =
      "\n  <InformationKey name=\"L2_NORM_RANGE\" location=\"vtkDataArray\" length=\"2\">\n"
      "    <Value index=\"0\">0</Value>\n    <Value index=\"1\">1.73</Value>\n  </InformationKey>\n";
  const std::string text =
      vtu(piece(8, 1, data_array("Float64", "Points", "ascii", keys + ascii_list(kCube), 3),
                data_array("Int32", "connectivity", "ascii", "0 1 2 3 4 5 6 7") +
                    data_array("Int32", "offsets", "ascii", "8") + data_array("UInt8", "types", "ascii", "12")));
  expect_cube(read_vtu(text, "k.vtu"), "vtu-ascii");
  const std::string binary =
      vtu(piece(8, 1, data_array("Float64", "Points", "binary", keys + base64(raw_block(bytes_of(kCube), false)), 3),
                data_array("Int32", "connectivity", "ascii", "0 1 2 3 4 5 6 7") +
                    data_array("Int32", "offsets", "ascii", "8") + data_array("UInt8", "types", "ascii", "12")));
  expect_cube(read_vtu(binary, "k.vtu"), "vtu-binary");
}

TEST(VtuReader, VoxelIsReorderedAndOtherCellsSkipped) {
  // A voxel (x fastest) of the same cube, a triangle and a quad.
  const std::string text = vtu(piece(8, 3, data_array("Float32", "Points", "ascii", ascii_list(kCube), 3),
                                     data_array("Int64", "connectivity", "ascii", "0 1 2  0 1 3 2 4 5 7 6  0 1 2 3") +
                                         data_array("Int64", "offsets", "ascii", "3 11 15") +
                                         data_array("UInt8", "types", "ascii", "5 11 9")));
  const LoadedMesh loaded = read_vtu(text, "v.vtu");
  ASSERT_EQ(loaded.mesh.hexes.size(), 1u);
  EXPECT_EQ(loaded.mesh.hexes[0], kIdentity);
  // A triangle and a quad: lower-dimensional, a note.
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_EQ(loaded.notes.size(), 1u);
  EXPECT_EQ(loaded.notes[0], "v.vtu: 2 cells of unread types skipped (types 5, 9)");
}

// The cube's arrays as binary blocks, through `encode` (inline base64 or appended).
struct CubeArrays {
  std::string points, connectivity, offsets, types;
};
CubeArrays cube_arrays(bool big_endian = false) {
  return {bytes_of(kCube, big_endian), bytes_of(std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6, 7}, big_endian),
          bytes_of(std::vector<std::int32_t>{8}, big_endian), bytes_of(std::vector<std::uint8_t>{12}, big_endian)};
}

std::string inline_cube(const std::function<std::string(const std::string&)>& encode, const std::string& attributes,
                        bool big_endian = false) {
  const CubeArrays a = cube_arrays(big_endian);
  return vtu(piece(8, 1, data_array("Float64", "Points", "binary", encode(a.points), 3),
                   data_array("Int64", "connectivity", "binary", encode(a.connectivity)) +
                       data_array("Int32", "offsets", "binary", encode(a.offsets)) +
                       data_array("UInt8", "types", "binary", encode(a.types))),
             attributes);
}

TEST(VtuReader, BinaryUncompressed) {
  // Header and data in one base64 string (VTK), UInt32 header.
  expect_cube(read_vtu(inline_cube([](const std::string& d) { return base64(raw_block(d, false)); }, ""), "b.vtu"),
              "vtu-binary");
  // Encoded apart, UInt64 header, line breaks inside the base64.
  expect_cube(read_vtu(inline_cube(
                           [](const std::string& d) {
                             return "\n  " + base64(header_value(d.size(), true)) + "\n  " + base64(d) + "\n";
                           },
                           " header_type=\"UInt64\""),
                       "b.vtu"),
              "vtu-binary");
  // Big-endian file: values and header.
  expect_cube(read_vtu(inline_cube([](const std::string& d) { return base64(raw_block(d, false, true)); },
                                   " byte_order=\"BigEndian\"", true),
                       "b.vtu"),
              "vtu-binary");
}

TEST(VtuReader, AppendedRawAndBase64) {
  const CubeArrays a = cube_arrays();
  for (const bool is_base64 : {false, true}) {
    SCOPED_TRACE(is_base64 ? "base64" : "raw");
    std::string appended;
    std::vector<std::size_t> offsets;
    for (const std::string* d : {&a.points, &a.connectivity, &a.offsets, &a.types}) {
      offsets.push_back(appended.size());
      appended += is_base64 ? base64(raw_block(*d, true)) : raw_block(*d, true);
    }
    const std::string text =
        vtu(piece(8, 1, appended_array("Float64", "Points", offsets[0], 3),
                  appended_array("Int64", "connectivity", offsets[1]) + appended_array("Int32", "offsets", offsets[2]) +
                      appended_array("UInt8", "types", offsets[3])),
            " header_type=\"UInt64\"",
            std::string("<AppendedData encoding=\"") + (is_base64 ? "base64" : "raw") + "\">\n   _" + appended +
                "\n</AppendedData>\n");
    expect_cube(read_vtu(text, "a.vtu"), "vtu-appended");
  }
}

#ifdef HQ_HAVE_ZLIB
TEST(VtuReader, ZlibInlineAndAppended) {
  for (const bool is_uint64 : {false, true}) {
    SCOPED_TRACE(is_uint64 ? "UInt64" : "UInt32");
    const std::string attributes =
        std::string(" compressor=\"vtkZLibDataCompressor\"") + (is_uint64 ? " header_type=\"UInt64\"" : "");
    // 40-byte blocks: the points take 5 blocks, the last one partial.
    expect_cube(read_vtu(inline_cube(
                             [&](const std::string& d) {
                               const auto [header, body] = zlib_blocks(d, 40, is_uint64);
                               return base64(header) + base64(body);
                             },
                             attributes),
                         "z.vtu"),
                "vtu-binary");
    const CubeArrays a = cube_arrays();
    std::string appended;
    std::vector<std::size_t> offsets;
    for (const std::string* d : {&a.points, &a.connectivity, &a.offsets, &a.types}) {
      offsets.push_back(appended.size());
      const auto [header, body] = zlib_blocks(*d, 64, is_uint64);
      appended += header + body;
    }
    const std::string text =
        vtu(piece(8, 1, appended_array("Float64", "Points", offsets[0], 3),
                  appended_array("Int64", "connectivity", offsets[1]) + appended_array("Int32", "offsets", offsets[2]) +
                      appended_array("UInt8", "types", offsets[3])),
            attributes, "<AppendedData encoding=\"raw\">_" + appended + "</AppendedData>\n");
    expect_cube(read_vtu(text, "z.vtu"), "vtu-appended");
  }
}

TEST(VtuReader, ZlibErrors) {
  const std::string attributes = " compressor=\"vtkZLibDataCompressor\"";
  // A corrupt block.
  const auto corrupt = [](const std::string& d) {
    auto [header, body] = zlib_blocks(d, 1 << 15, false);
    body[body.size() / 2] ^= 0x55;
    body[body.size() / 2 + 1] ^= 0x55;
    return base64(header) + base64(body);
  };
  EXPECT_EQ(error_text<ParseError>([&] { read_vtu(inline_cube(corrupt, attributes), "z.vtu"); }).substr(0, 54),
            "z.vtu:6: zlib block 0 does not decompress to 192 bytes");
  // A header claiming far more blocks than the data holds: refused before allocating.
  const std::string huge =
      base64(header_value(1u << 30, false) + header_value(1u << 15, false) + header_value(0, false));
  EXPECT_EQ(error_text<ParseError>(
                [&] { read_vtu(inline_cube([&](const std::string&) { return huge; }, attributes), "z.vtu"); }),
            "z.vtu:6: compression header claims 1073741824 blocks, more than the data holds, data at byte offset 257 "
            "(DataArray of the Points)");
  // Blocks that would expand more than zlib can.
  const std::string bomb =
      base64(header_value(1, false) + header_value(192, false) + header_value(0, false) + header_value(0, false));
  EXPECT_EQ(error_text<ParseError>(
                [&] { read_vtu(inline_cube([&](const std::string&) { return bomb; }, attributes), "z.vtu"); }),
            "z.vtu:6: compression header claims 192 bytes from 0 compressed bytes, more than zlib can expand, data at "
            "byte offset 257 (DataArray of the Points)");
}
#endif

TEST(VtuReader, SeveralPiecesAreConcatenated) {
  const std::string one =
      piece(8, 1, data_array("Float64", "Points", "ascii", ascii_list(kCube), 3),
            data_array("Int32", "connectivity", "ascii", "0 1 2 3 4 5 6 7") +
                data_array("Int32", "offsets", "ascii", "8") + data_array("UInt8", "types", "ascii", "12"));
  const LoadedMesh loaded = read_vtu(vtu(one + one), "p.vtu");
  ASSERT_EQ(loaded.mesh.points.size(), 16u);
  ASSERT_EQ(loaded.mesh.hexes.size(), 2u);
  EXPECT_EQ(loaded.mesh.hexes[1], (Hex{8, 9, 10, 11, 12, 13, 14, 15}));
}

TEST(VtuReader, Detection) {
  EXPECT_TRUE(looks_like_vtu(ascii_cube()));
  EXPECT_TRUE(looks_like_vtu("\xEF\xBB\xBF<!-- a > b -->\n<VTKFile type=\"UnstructuredGrid\">"));
  EXPECT_FALSE(looks_like_vtu("<?xml version=\"1.0\"?><svg/>"));
  EXPECT_FALSE(looks_like_vtu("# vtk DataFile Version 3.0"));
}

TEST(VtuReader, Errors) {
  const auto error = [](const std::string& text) { return error_text<ParseError>([&] { read_vtu(text, "e.vtu"); }); };
  EXPECT_EQ(error("<Other/>"), "e.vtu:1: expected a <VTKFile> root element, got <Other>");
  EXPECT_EQ(error("<VTKFile type=\"PolyData\"></VTKFile>"),
            "e.vtu:1: unsupported VTK XML type 'PolyData' (expected UnstructuredGrid)");
  EXPECT_EQ(error(vtu("", " header_type=\"UInt16\"")),
            "e.vtu:2: unsupported header_type 'UInt16' (expected UInt32 or UInt64)");
  EXPECT_EQ(error(vtu("", " compressor=\"vtkLZ4DataCompressor\"")),
            "e.vtu:2: unsupported compressor 'vtkLZ4DataCompressor' (expected vtkZLibDataCompressor)");
  EXPECT_EQ(error(vtu("", " byte_order=\"Middle\"")),
            "e.vtu:2: unknown byte_order 'Middle' (expected LittleEndian or BigEndian)");
  EXPECT_EQ(error(vtu("")), "e.vtu:3: <UnstructuredGrid> has no <Piece>");
  EXPECT_EQ(error(vtu("<Piece NumberOfCells=\"1\"/>")), "e.vtu:4: <Piece> has no NumberOfPoints attribute");
  EXPECT_EQ(error(vtu("<Piece NumberOfPoints=\"-1\" NumberOfCells=\"1\"/>")), "e.vtu:4: negative NumberOfPoints -1");
  EXPECT_EQ(error(vtu("<Piece NumberOfPoints=\"x\" NumberOfCells=\"1\"/>")),
            "e.vtu:4: expected an integer NumberOfPoints, got 'x'");
  EXPECT_EQ(error(vtu("<Piece NumberOfPoints=\"8\" NumberOfCells=\"1\"/>")), "e.vtu:4: <Piece> has no <Points>");
  // Points: components, counts, values.
  EXPECT_EQ(error(vtu(piece(8, 1, data_array("Float64", "Points", "ascii", "0 0", 2), ""))),
            "e.vtu:6: points have 2 components, expected 3 (DataArray of the Points)");
  EXPECT_EQ(error(vtu(piece(2, 1, data_array("Float64", "Points", "ascii", "0.0 0.0 0.0", 3), ""))),
            "e.vtu:6: 3 values, expected 6 (DataArray of the Points)");
  EXPECT_EQ(error(vtu(piece(1, 1, data_array("Float64", "Points", "ascii", "\n0 0\nzero\n", 3), ""))),
            "e.vtu:8: expected a number, got 'zero' (DataArray of the Points value 2)");
  EXPECT_EQ(error(vtu(piece(1, 1, data_array("Float64", "Points", "ascii", "0 0 0 1", 3), ""))),
            "e.vtu:6: more than 3 values (DataArray of the Points)");
  EXPECT_EQ(error(vtu(piece(1, 1, data_array("Float64", "Points", "ascii", "0 nan 0", 3), ""))),
            "e.vtu:6: non-finite coordinate nan (point 0) (DataArray of the Points)");
  EXPECT_EQ(error(vtu(piece(1, 1, data_array("Float128", "Points", "ascii", "0 0 0", 3), ""))),
            "e.vtu:6: unknown data type 'Float128' (DataArray of the Points)");
  EXPECT_EQ(error(vtu(piece(1, 1, data_array("Float64", "Points", "hex", "0 0 0", 3), ""))),
            "e.vtu:6: unknown DataArray format 'hex' (expected ascii, binary or appended) (DataArray of the Points)");
  EXPECT_EQ(error(vtu(piece(8, 1, data_array("Float64", "Points", "ascii", "0 0 0", 3), ""))),
            "e.vtu:6: 24 values cannot fit in its 5 bytes of text (DataArray of the Points)");
  // Cells.
  EXPECT_EQ(error(vtu(piece(8, 1, data_array("Float64", "Points", "ascii", ascii_list(kCube), 3), ""))),
            "e.vtu:10: <Cells> has no DataArray named 'types'");
  EXPECT_EQ(error(ascii_cube("0 1 2 3 4 5 6 8")),
            "e.vtu:11: point id 8 out of range [0, 8) (cell 0) (DataArray 'connectivity')");
  EXPECT_EQ(error(ascii_cube("0 1 2 3 4 5 6 0")), "e.vtu:11: point id 0 repeated (cell 0) (DataArray 'connectivity')");
  EXPECT_EQ(error(ascii_cube("0 1 2 3 4 5 6", "7")),
            "e.vtu:11: cell 0 has type 12 (hexahedron) but 7 points, expected 8 (DataArray 'connectivity')");
  EXPECT_EQ(error(ascii_cube("0 1 2 3 4 5 6 7", "9")),
            "e.vtu:12: offset 9 of cell 0 is outside [0, 8] (DataArray 'offsets')");
  EXPECT_EQ(error(ascii_cube("0 1 2 3 4 5 6 7", "8", "12 12")), "e.vtu:13: more than 1 values (DataArray 'types')");
  EXPECT_EQ(error(ascii_cube("0 1 2 3 4 5 6 7", "8", "10")),
            "e.vtu:11: cell 0 has type 10 (tetra) but 8 points, expected 4 (DataArray 'connectivity')");
  EXPECT_EQ(error(ascii_cube("0 1 2 3 4 5 6 7", "8", "9")), "e.vtu:3: cell 0 has type 9 but 8 points");
  EXPECT_EQ(error(ascii_cube("0 1 2 3 4 5 6 7", "8", "4")), "e.vtu:3: no volume cells (1 cell of type 4)");
  EXPECT_EQ(error(ascii_cube("0 1 2 3 4 5 6 7.5")),
            "e.vtu:11: expected an integer, got '7.5' (DataArray 'connectivity' value 7)");
  // Binary and appended data.
  EXPECT_EQ(error(inline_cube([](const std::string& d) { return base64(raw_block(d, false)).substr(0, 20); }, "")),
            "e.vtu:6: data truncated: its header claims 192 bytes, at most 11 left, data at byte offset 222 "
            "(DataArray of the Points)");
  EXPECT_EQ(error(inline_cube([](const std::string& d) { return "wAAA*" + base64(d); }, "")),
            "e.vtu:6: invalid base64 character '*' at byte offset 226 in its byte count header (DataArray of the "
            "Points)");
  EXPECT_EQ(error(inline_cube([](const std::string& d) { return base64(raw_block(d + "x", false)); }, "")),
            "e.vtu:6: byte count 193 in its header, expected 192, data at byte offset 222 (DataArray of the Points)");
  EXPECT_EQ(error(vtu(piece(1, 0, appended_array("Float64", "Points", 0, 3), ""))),
            "e.vtu:6: format=\"appended\" but the file has no <AppendedData> (DataArray of the Points)");
  EXPECT_EQ(error(vtu(piece(1, 0, appended_array("Float64", "Points", 99, 3), ""), "",
                      "<AppendedData encoding=\"raw\">_abc</AppendedData>")),
            "e.vtu:6: offset 99 is past the end of the AppendedData (DataArray of the Points)");
  EXPECT_EQ(error(vtu("", "", "<AppendedData encoding=\"raw\">abc")),
            "e.vtu:5: expected '_' at the start of the AppendedData");
  EXPECT_EQ(error(vtu("", "", "<AppendedData encoding=\"hex\">_")),
            "e.vtu:5: unknown AppendedData encoding 'hex' (expected raw or base64)");
}

}  // namespace
}  // namespace hq
