#include "hqview/io/vtk_legacy_reader.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/io/cell_reading.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/io/read_limits.h"
#include "hqview/io/text_scanner.h"
#include "hqview/io/vtk_cells.h"

namespace hq {
namespace {

using detail::iequals;
using detail::quote;
using detail::TextScanner;

using vtk::kVoxelToHex;
using vtk::sign_extend;

// The linear and quadratic VTK cell types with a fixed point count
// (vtkCellType.h). Variable-size types (poly vertex, polyline, triangle
// strip, polygon, polyhedron, Lagrange/Bezier cells) and unknown types are
// not listed: a cell of theirs with 8 points is not a mislabelled hexahedron.
struct FixedSizeCellType {
  int type;
  int num_points;
};
constexpr FixedSizeCellType kFixedSizeCellTypes[] = {
    {0, 0},    // empty cell
    {1, 1},    // vertex
    {3, 2},    // line
    {5, 3},    // triangle
    {8, 4},    // pixel
    {9, 4},    // quad
    {10, 4},   // tetra
    {11, 8},   // voxel
    {12, 8},   // hexahedron
    {13, 6},   // wedge
    {14, 5},   // pyramid
    {15, 10},  // pentagonal prism
    {16, 12},  // hexagonal prism
    {21, 3},   // quadratic edge
    {22, 6},   // quadratic triangle
    {23, 8},   // quadratic quad
    {24, 10},  // quadratic tetra
    {25, 20},  // quadratic hexahedron
    {26, 15},  // quadratic wedge
    {27, 13},  // quadratic pyramid
    {28, 9},   // biquadratic quad
    {29, 27},  // triquadratic hexahedron
    {30, 6},   // quadratic linear quad
    {31, 12},  // quadratic linear wedge
    {32, 18},  // biquadratic quadratic wedge
    {33, 24},  // biquadratic quadratic hexahedron
    {34, 7},   // biquadratic triangle
    {35, 4},   // cubic line
    {37, 19},  // triquadratic pyramid
};

// The point count of a fixed-size type, -1 for the others.
int fixed_point_count(int type) {
  for (const FixedSizeCellType& entry : kFixedSizeCellTypes)
    if (entry.type == type) return entry.num_points;
  return -1;
}

enum class ValueKind { kSigned, kUnsigned, kFloat };

struct VtkType {
  std::string_view name;
  int size;  // bytes in binary files
  ValueKind kind;
};

// Legacy type names. "vtkIdType" is written as 4-byte int by VTK's legacy
// writer; "long" is 8 bytes (LP64, the platform of every writer we know).
constexpr VtkType kTypes[] = {
    {"unsigned_char", 1, ValueKind::kUnsigned},
    {"char", 1, ValueKind::kSigned},
    {"unsigned_short", 2, ValueKind::kUnsigned},
    {"short", 2, ValueKind::kSigned},
    {"unsigned_int", 4, ValueKind::kUnsigned},
    {"int", 4, ValueKind::kSigned},
    {"unsigned_long", 8, ValueKind::kUnsigned},
    {"long", 8, ValueKind::kSigned},
    {"float", 4, ValueKind::kFloat},
    {"double", 8, ValueKind::kFloat},
    {"vtkIdType", 4, ValueKind::kSigned},
    {"vtktypeint8", 1, ValueKind::kSigned},
    {"vtktypeuint8", 1, ValueKind::kUnsigned},
    {"vtktypeint16", 2, ValueKind::kSigned},
    {"vtktypeuint16", 2, ValueKind::kUnsigned},
    {"vtktypeint32", 4, ValueKind::kSigned},
    {"vtktypeuint32", 4, ValueKind::kUnsigned},
    {"vtktypeint64", 8, ValueKind::kSigned},
    {"vtktypeuint64", 8, ValueKind::kUnsigned},
    {"vtktypefloat32", 4, ValueKind::kFloat},
    {"vtktypefloat64", 8, ValueKind::kFloat},
};
constexpr VtkType kInt32Type = {"int", 4, ValueKind::kSigned};

const VtkType* find_type(std::string_view name) {
  for (const VtkType& type : kTypes)
    if (iequals(type.name, name)) return &type;
  return nullptr;
}

std::uint64_t load_big_endian(const char* p, int size) {
  switch (size) {
    case 1:
      return static_cast<unsigned char>(*p);
    case 2: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return __builtin_bswap16(v);
    }
    case 4: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return __builtin_bswap32(v);
    }
    default: {
      std::uint64_t v;
      std::memcpy(&v, p, 8);
      return __builtin_bswap64(v);
    }
  }
}

std::string non_finite_text(double value) { return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf"); }

// The values of one data array, as ASCII tokens or big-endian binary, read
// in order. Knows where the last value came from, for error messages: its
// line (ASCII) or the section keyword's line and its byte offset (binary).
class ArrayCursor {
 public:
  ArrayCursor(TextScanner& s, bool binary, const VtkType& type, std::int64_t count, std::string section,
              std::int64_t keyword_line)
      : s_(s), binary_(binary), type_(type), count_(count), section_(std::move(section)), keyword_line_(keyword_line) {
    if (binary_) {
      data_offset_ = s_.offset();
      data_ = s_.read_bytes(static_cast<std::size_t>(count) * static_cast<std::size_t>(type.size));
    }
  }

  std::int64_t next_int() {
    if (binary_) {
      const std::uint64_t bits = advance();
      if (type_.kind == ValueKind::kSigned) return sign_extend(bits, type_.size);
      if (bits > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        fail_last("value " + std::to_string(bits) + " out of range");
      return static_cast<std::int64_t>(bits);
    }
    next_token();
    std::int64_t value = 0;
    if (!s_.read_int(value))
      s_.fail("expected an integer, got " + quote(s_.peek_token()) + " (" + section_ + " value " +
              std::to_string(index_) + " of " + std::to_string(count_) + ")");
    return value;
  }

  double next_double() {
    if (binary_) {
      const std::uint64_t bits = advance();
      switch (type_.kind) {
        case ValueKind::kFloat:
          return type_.size == 4 ? double{std::bit_cast<float>(static_cast<std::uint32_t>(bits))}
                                 : std::bit_cast<double>(bits);
        case ValueKind::kSigned:
          return static_cast<double>(sign_extend(bits, type_.size));
        case ValueKind::kUnsigned:
          return static_cast<double>(bits);
      }
    }
    next_token();
    double value = 0.0;
    if (!s_.read_double(value))
      s_.fail("expected a number, got " + quote(s_.peek_token()) + " (" + section_ + " value " +
              std::to_string(index_) + " of " + std::to_string(count_) + ")");
    return value;
  }

  // Where the last value is: its line (ASCII) or its byte offset (binary).
  std::int64_t location() const {
    return binary_ ? static_cast<std::int64_t>(data_offset_) + (index_ - 1) * type_.size : line_;
  }

  [[noreturn]] void fail_last(const std::string& message) const { fail_at(location(), 0, message); }

  // An error about a value recorded earlier by location(), j values after it.
  [[noreturn]] void fail_at(std::int64_t location, std::int64_t j, const std::string& message) const {
    if (binary_)
      s_.fail_at(keyword_line_,
                 message + " (" + section_ + " data at byte offset " + std::to_string(location + j * type_.size) + ")");
    s_.fail_at(location, message);
  }

 private:
  std::uint64_t advance() {
    const char* p = data_.data() + static_cast<std::size_t>(index_) * static_cast<std::size_t>(type_.size);
    ++index_;
    return load_big_endian(p, type_.size);
  }
  void next_token() {
    if (!s_.skip_space())
      s_.fail("unexpected end of file, expected " + std::to_string(count_) + " values in " + section_ + ", got " +
              std::to_string(index_));
    line_ = s_.line();
    ++index_;
  }

  TextScanner& s_;
  bool binary_;
  VtkType type_;
  std::int64_t count_;
  std::string section_;
  std::int64_t keyword_line_;
  std::size_t data_offset_ = 0;
  std::string_view data_;
  std::int64_t index_ = 0;  // values read so far
  std::int64_t line_ = 0;   // ASCII: line of the last value
};

struct CellArrays {
  std::int64_t line = 0;                // CELLS keyword line; 0 = not read yet
  std::vector<std::int64_t> offsets;    // count + 1, into connectivity
  std::vector<Index> connectivity;      // point ids (face streams for polyhedra)
  std::vector<std::int64_t> locations;  // per cell: where its first id is (ArrayCursor::location)
  std::int64_t connectivity_line = 0;   // keyword line of the connectivity data
  std::string connectivity_section;     // "CELLS" or "CONNECTIVITY"
  VtkType connectivity_type = kInt32Type;

  std::int64_t count() const { return offsets.empty() ? 0 : static_cast<std::int64_t>(offsets.size()) - 1; }
};

class VtkParser {
 public:
  VtkParser(std::string_view bytes, const std::string& name, const ReadLimits& limits)
      : s_(bytes, name, /*has_hash_comments=*/false), limits_(limits), file_bytes_(bytes.size()) {}

  LoadedMesh parse() {
    read_header();
    while (points_line_ == 0 || cells_.line == 0 || types_line_ == 0) {
      if (!s_.skip_space()) s_.fail("unexpected end of file: no " + first_missing_section() + " section");
      const std::int64_t line = s_.line();
      const std::string_view keyword = s_.read_token();
      if (iequals(keyword, "POINTS")) {
        read_points(line);
      } else if (iequals(keyword, "CELLS")) {
        read_cells(line);
      } else if (iequals(keyword, "CELL_TYPES")) {
        read_cell_types(line);
      } else if (iequals(keyword, "FIELD")) {
        skip_field(line);
      } else if (iequals(keyword, "METADATA")) {
        skip_metadata();
      } else if (iequals(keyword, "CELL_DATA") || iequals(keyword, "POINT_DATA")) {
        s_.fail_at(line, std::string(keyword) + " before the " + first_missing_section() + " section");
      } else {
        s_.fail_at(line, "unknown keyword " + quote(keyword) + " in an UNSTRUCTURED_GRID");
      }
    }
    return build();
  }

 private:
  void read_header() {
    if (s_.at_end()) s_.fail("empty file, expected '# vtk DataFile Version X.Y'");
    const std::string_view header = s_.read_line();
    constexpr std::string_view kMagic = "# vtk DataFile Version";
    if (!detail::istarts_with(header, kMagic))
      s_.fail_at(1, "expected '# vtk DataFile Version X.Y', got " + quote(header));
    std::string_view version = header.substr(kMagic.size());
    while (!version.empty() && detail::is_blank(version.front())) version.remove_prefix(1);
    int major = 0, minor = 0;
    const char* end = version.data() + version.size();
    std::from_chars_result result = std::from_chars(version.data(), end, major);
    if (result.ec == std::errc{} && result.ptr != end && *result.ptr == '.')
      result = std::from_chars(result.ptr + 1, end, minor);
    if (result.ec != std::errc{}) s_.fail_at(1, "expected '# vtk DataFile Version X.Y', got " + quote(header));
    if (major > 5)
      s_.fail_at(1, "unsupported file version " + std::to_string(major) + "." + std::to_string(minor) +
                        " (expected at most 5.1)");
    is_version5_ = major == 5;

    if (s_.at_end()) s_.fail("unexpected end of file, expected the title line");
    s_.read_line();  // the title: free text

    if (!s_.skip_space()) s_.fail("unexpected end of file, expected ASCII or BINARY");
    const std::string_view format = s_.read_token();
    if (iequals(format, "BINARY")) {
      binary_ = true;
    } else if (!iequals(format, "ASCII")) {
      s_.fail("expected ASCII or BINARY, got " + quote(format));
    }

    if (!s_.skip_space()) s_.fail("unexpected end of file, expected DATASET");
    const std::string_view dataset = s_.read_token();
    if (!iequals(dataset, "DATASET")) s_.fail("expected DATASET, got " + quote(dataset));
    const std::string_view type = read_word_argument("DATASET", "a dataset type");
    if (!iequals(type, "UNSTRUCTURED_GRID"))
      s_.fail("unsupported dataset type " + quote(type) + " (expected UNSTRUCTURED_GRID)");
  }

  std::string first_missing_section() const {
    if (points_line_ == 0) return "POINTS";
    if (cells_.line == 0) return "CELLS";
    return "CELL_TYPES";
  }

  // Arguments of a section keyword, on its line.
  std::int64_t read_int_argument(std::string_view keyword, const std::string& what) {
    if (!s_.skip_blank()) s_.fail("expected " + what + " after " + std::string(keyword));
    std::int64_t value = 0;
    if (!s_.read_int(value))
      s_.fail("expected " + what + " after " + std::string(keyword) + ", got " + quote(s_.peek_token()));
    return value;
  }
  std::string_view read_word_argument(std::string_view keyword, const std::string& what) {
    if (!s_.skip_blank()) s_.fail("expected " + what + " after " + std::string(keyword));
    return s_.read_token();
  }
  const VtkType& read_type_argument(std::string_view keyword, bool integer_only) {
    const std::string_view name = read_word_argument(keyword, "a data type");
    const VtkType* type = find_type(name);
    if (type == nullptr) s_.fail("unknown data type " + quote(name) + " for " + std::string(keyword));
    if (integer_only && type->kind == ValueKind::kFloat)
      s_.fail("expected an integer data type for " + std::string(keyword) + ", got " + quote(name));
    return *type;
  }
  // The end of a section header line; binary data starts right after it.
  void end_header(std::string_view keyword) {
    if (!s_.finish_line())
      s_.fail("unexpected " + quote(s_.peek_token()) + " after the " + std::string(keyword) + " header");
  }

  void check_count(std::int64_t n, std::string_view keyword, const std::string& what, std::int64_t line,
                   std::int64_t limit = kMaxIndexCount) {
    if (n < 0) s_.fail_at(line, "negative " + what + " in " + std::string(keyword) + ": " + std::to_string(n));
    if (n > limit)
      s_.fail_at(line, what + " in " + std::string(keyword) + " " + std::to_string(n) + " exceeds the limit of " +
                           std::to_string(limit));
  }

  // Before allocating from a count: the rest of the file must hold the
  // values (binary: exactly count * size bytes; ASCII: 2 bytes each at least).
  void check_room(std::int64_t values, const VtkType& type, std::string_view keyword, std::int64_t line) {
    if (binary_) {
      if (detail::exceeds_remaining(values, type.size, s_.remaining(), false))
        s_.fail_at(line, "binary " + std::string(keyword) + " data truncated: " + std::to_string(values) + " " +
                             std::string(type.name) + " values need " + std::to_string(values * type.size) +
                             " bytes, " + std::to_string(s_.remaining()) + " left");
    } else if (detail::exceeds_remaining(values, 2, s_.remaining(), true)) {
      s_.fail_at(line, std::to_string(values) + " " + std::string(keyword) + " values cannot fit in the " +
                           std::to_string(s_.remaining()) + " bytes left in the file");
    }
  }

  void check_not_seen(std::int64_t first_line, std::string_view keyword, std::int64_t line) {
    if (first_line != 0)
      s_.fail_at(line, "second " + std::string(keyword) + " section (the first is at line " +
                           std::to_string(first_line) + ")");
  }

  void read_points(std::int64_t line) {
    check_not_seen(points_line_, "POINTS", line);
    points_line_ = line;
    const std::int64_t n = read_int_argument("POINTS", "the number of points");
    check_count(n, "POINTS", "number of points", line);
    const VtkType& type = read_type_argument("POINTS", false);
    end_header("POINTS");
    check_room(3 * n, type, "POINTS", line);
    check_mesh_memory(limits_, s_.name(), line, file_bytes_, n, -1);
    ArrayCursor cursor(s_, binary_, type, 3 * n, "POINTS", line);
    points_.resize(static_cast<std::size_t>(n));
    for (std::int64_t i = 0; i < n; ++i) {
      double xyz[3];
      for (double& c : xyz) {
        c = cursor.next_double();
        if (!std::isfinite(c))
          cursor.fail_last("non-finite coordinate " + non_finite_text(c) + " (point " + std::to_string(i) + ")");
      }
      points_[static_cast<std::size_t>(i)] = {xyz[0], xyz[1], xyz[2]};
    }
  }

  // A connectivity value: a point id, or a face-stream entry of a polyhedron.
  Index checked_id(std::int64_t value, ArrayCursor& cursor, std::int64_t cell) {
    if (value < 0 || value >= kMaxIndexCount)
      cursor.fail_last("point id " + std::to_string(value) + " out of range (cell " + std::to_string(cell) + ")");
    return static_cast<Index>(value);
  }

  void read_cells(std::int64_t line) {
    check_not_seen(cells_.line, "CELLS", line);
    cells_.line = line;
    if (is_version5_) {
      read_cells_v5(line);
    } else {
      read_cells_legacy(line);
    }
    if (types_line_ != 0) check_type_count();
  }

  // <= 4.2: "CELLS n size" then, per cell, its point count and ids.
  void read_cells_legacy(std::int64_t line) {
    const std::int64_t n = read_int_argument("CELLS", "the number of cells");
    const std::int64_t size = read_int_argument("CELLS", "the size of the cell list");
    check_count(n, "CELLS", "number of cells", line);
    check_count(size, "CELLS", "cell list size", line, std::numeric_limits<std::int64_t>::max());
    end_header("CELLS");
    if (size < n)
      s_.fail_at(line, "cell list size " + std::to_string(size) + " cannot hold " + std::to_string(n) + " cells");
    check_room(size, kInt32Type, "CELLS", line);
    check_mesh_memory(limits_, s_.name(), line, file_bytes_, static_cast<std::int64_t>(points_.size()), n, "cell");
    ArrayCursor cursor(s_, binary_, kInt32Type, size, "CELLS", line);
    cells_.connectivity_line = line;
    cells_.connectivity_section = "CELLS";
    cells_.offsets.resize(static_cast<std::size_t>(n) + 1);
    cells_.locations.resize(static_cast<std::size_t>(n));
    cells_.connectivity.reserve(static_cast<std::size_t>(size - n));
    std::int64_t consumed = 0;
    for (std::int64_t c = 0; c < n; ++c) {
      if (consumed == size)
        cursor.fail_last("cell list size " + std::to_string(size) + " ends after " + std::to_string(c) + " of " +
                         std::to_string(n) + " cells");
      const std::int64_t k = cursor.next_int();
      ++consumed;
      if (k < 0 || k > size - consumed)
        cursor.fail_last("cell " + std::to_string(c) + " claims " + std::to_string(k) + " points, but " +
                         std::to_string(size - consumed) + " values are left in the cell list");
      cells_.offsets[static_cast<std::size_t>(c)] = static_cast<std::int64_t>(cells_.connectivity.size());
      cells_.locations[static_cast<std::size_t>(c)] = cursor.location() + (binary_ ? kInt32Type.size : 0);
      for (std::int64_t j = 0; j < k; ++j) cells_.connectivity.push_back(checked_id(cursor.next_int(), cursor, c));
      consumed += k;
    }
    cells_.offsets[static_cast<std::size_t>(n)] = static_cast<std::int64_t>(cells_.connectivity.size());
    if (consumed != size)
      s_.fail_at(line, "cell list size " + std::to_string(size) + " does not match the " + std::to_string(consumed) +
                           " values of its " + std::to_string(n) + " cells");
  }

  // 5.x: "CELLS nOffsets nConnectivity", then OFFSETS and CONNECTIVITY arrays.
  void read_cells_v5(std::int64_t line) {
    const std::int64_t num_offsets = read_int_argument("CELLS", "the number of offsets");
    const std::int64_t num_ids = read_int_argument("CELLS", "the connectivity size");
    check_count(num_offsets, "CELLS", "number of offsets", line, kMaxIndexCount + 1);
    check_count(num_ids, "CELLS", "connectivity size", line, std::numeric_limits<std::int64_t>::max());
    end_header("CELLS");
    const std::int64_t n = std::max<std::int64_t>(num_offsets - 1, 0);

    const std::int64_t offsets_line = expect_array_keyword("OFFSETS");
    const VtkType& offsets_type = read_type_argument("OFFSETS", true);
    end_header("OFFSETS");
    check_room(num_offsets, offsets_type, "OFFSETS", offsets_line);
    check_mesh_memory(limits_, s_.name(), line, file_bytes_, static_cast<std::int64_t>(points_.size()), n, "cell");
    ArrayCursor offsets(s_, binary_, offsets_type, num_offsets, "OFFSETS", offsets_line);
    cells_.offsets.resize(static_cast<std::size_t>(n) + 1, 0);
    for (std::int64_t i = 0; i < num_offsets; ++i) {
      const std::int64_t offset = offsets.next_int();
      if (i == 0 && offset != 0) offsets.fail_last("first offset is " + std::to_string(offset) + ", expected 0");
      if (i > 0 && offset < cells_.offsets[static_cast<std::size_t>(i - 1)])
        offsets.fail_last("offsets decrease: offset " + std::to_string(i) + " is " + std::to_string(offset) +
                          ", offset " + std::to_string(i - 1) + " is " +
                          std::to_string(cells_.offsets[static_cast<std::size_t>(i - 1)]));
      if (offset > num_ids)
        offsets.fail_last("offset " + std::to_string(offset) + " exceeds the connectivity size " +
                          std::to_string(num_ids));
      cells_.offsets[static_cast<std::size_t>(i)] = offset;
    }
    if (num_offsets > 0 && cells_.offsets.back() != num_ids)
      offsets.fail_last("last offset " + std::to_string(cells_.offsets.back()) +
                        " does not match the connectivity size " + std::to_string(num_ids));
    if (num_offsets == 0 && num_ids != 0)
      s_.fail_at(line, "connectivity size " + std::to_string(num_ids) + " without any offsets");

    const std::int64_t ids_line = expect_array_keyword("CONNECTIVITY");
    const VtkType& ids_type = read_type_argument("CONNECTIVITY", true);
    end_header("CONNECTIVITY");
    check_room(num_ids, ids_type, "CONNECTIVITY", ids_line);
    ArrayCursor ids(s_, binary_, ids_type, num_ids, "CONNECTIVITY", ids_line);
    cells_.connectivity_line = ids_line;
    cells_.connectivity_section = "CONNECTIVITY";
    cells_.connectivity_type = ids_type;
    cells_.locations.assign(static_cast<std::size_t>(n), 0);
    cells_.connectivity.resize(static_cast<std::size_t>(num_ids));
    std::int64_t cell = 0;
    for (std::int64_t m = 0; m < num_ids; ++m) {
      while (cells_.offsets[static_cast<std::size_t>(cell) + 1] <= m) ++cell;
      const Index id = checked_id(ids.next_int(), ids, cell);
      if (m == cells_.offsets[static_cast<std::size_t>(cell)])
        cells_.locations[static_cast<std::size_t>(cell)] = ids.location();
      cells_.connectivity[static_cast<std::size_t>(m)] = id;
    }
  }

  // The next keyword inside a 5.x CELLS section, METADATA blocks skipped.
  std::int64_t expect_array_keyword(std::string_view expected) {
    while (true) {
      if (!s_.skip_space()) s_.fail("unexpected end of file, expected " + std::string(expected));
      const std::int64_t line = s_.line();
      const std::string_view keyword = s_.read_token();
      if (iequals(keyword, expected)) return line;
      if (!iequals(keyword, "METADATA"))
        s_.fail_at(line, "expected " + std::string(expected) + ", got " + quote(keyword));
      skip_metadata();
    }
  }

  void read_cell_types(std::int64_t line) {
    check_not_seen(types_line_, "CELL_TYPES", line);
    types_line_ = line;
    const std::int64_t n = read_int_argument("CELL_TYPES", "the number of cells");
    check_count(n, "CELL_TYPES", "number of cells", line);
    end_header("CELL_TYPES");
    check_room(n, kInt32Type, "CELL_TYPES", line);
    ArrayCursor cursor(s_, binary_, kInt32Type, n, "CELL_TYPES", line);
    types_.resize(static_cast<std::size_t>(n));
    for (std::int64_t c = 0; c < n; ++c) {
      const std::int64_t type = cursor.next_int();
      if (type < 0 || type > 255)
        cursor.fail_last("invalid cell type " + std::to_string(type) + " (cell " + std::to_string(c) + ")");
      types_[static_cast<std::size_t>(c)] = static_cast<int>(type);
    }
    if (cells_.line != 0) check_type_count();
  }

  void check_type_count() {
    if (static_cast<std::int64_t>(types_.size()) != cells_.count())
      s_.fail_at(types_line_, "CELL_TYPES has " + std::to_string(types_.size()) + " entries but CELLS (line " +
                                  std::to_string(cells_.line) + ") has " + std::to_string(cells_.count()) + " cells");
  }

  // "FIELD name numArrays", then per array "name numComponents numTuples
  // type" and its values (or NULL_ARRAY).
  void skip_field(std::int64_t line) {
    read_word_argument("FIELD", "a field name");
    const std::int64_t num_arrays = read_int_argument("FIELD", "the number of arrays");
    check_count(num_arrays, "FIELD", "number of arrays", line);
    end_header("FIELD");
    for (std::int64_t a = 0; a < num_arrays; ++a) {
      if (!s_.skip_space()) s_.fail("unexpected end of file, expected a FIELD array");
      const std::int64_t array_line = s_.line();
      const std::string_view array_name = s_.read_token();
      if (iequals(array_name, "NULL_ARRAY")) continue;
      if (iequals(array_name, "METADATA")) {  // belongs to the previous array
        skip_metadata();
        --a;
        continue;
      }
      const std::string keyword = "FIELD array " + quote(array_name);
      const std::int64_t components = read_int_argument(keyword, "the number of components");
      const std::int64_t tuples = read_int_argument(keyword, "the number of tuples");
      check_count(components, keyword, "number of components", array_line);
      check_count(tuples, keyword, "number of tuples", array_line);
      const VtkType& type = read_type_argument(keyword, false);
      end_header(keyword);
      const std::int64_t values = components * tuples;
      check_room(values, type, keyword, array_line);
      if (binary_) {
        s_.read_bytes(static_cast<std::size_t>(values * type.size));
      } else {
        ArrayCursor cursor(s_, false, type, values, keyword, array_line);
        for (std::int64_t i = 0; i < values; ++i) cursor.next_double();
      }
    }
  }

  // METADATA blocks (5.x) run to the next blank line.
  void skip_metadata() {
    s_.read_line();
    while (!s_.at_end()) {
      const std::string_view line = s_.read_line();
      if (std::all_of(line.begin(), line.end(), [](char c) { return detail::is_blank(c); })) break;
    }
  }

  [[noreturn]] void fail_cell(std::int64_t c, std::int64_t j, const std::string& message) const {
    const std::int64_t location = cells_.locations[static_cast<std::size_t>(c)];
    if (binary_)
      s_.fail_at(cells_.connectivity_line, message + " (" + cells_.connectivity_section + " data at byte offset " +
                                               std::to_string(location + j * cells_.connectivity_type.size) + ")");
    s_.fail_at(location, message);
  }

  // A surface cell read into the mesh's surface blocks beside the volume
  // cells (detail::SurfaceCells): where = its cell id, detail = the point.
  using SurfaceCells = detail::SurfaceCells<int>;

  void read_surface_cell(Mesh& mesh, std::int64_t c, int type, std::int64_t begin, std::int64_t k,
                         std::map<int, std::int64_t>& skipped_by_type, SurfaceCells& surface) const {
    bool is_count_wrong = false;
    const std::optional<CellKind> kind = vtk::surface_kind(type, k, is_count_wrong);
    if (!kind && !is_count_wrong) {  // a polygon of more than 4 points
      ++skipped_by_type[type];
      return;
    }
    ++surface.types[type];
    const auto bad = [&](std::int64_t j, std::string message) { surface.set_bad(c, j, std::move(message)); };
    if (!kind) {
      bad(0, "cell " + std::to_string(c) + " has type " + std::to_string(type) + " but " + std::to_string(k) + " points");
      return;
    }
    const int m = cell_kind_num_corners(*kind);
    std::array<Index, 4> ids{};
    for (std::int64_t j = 0; j < k; ++j) {
      const Index id = cells_.connectivity[static_cast<std::size_t>(begin + j)];
      if (id >= static_cast<Index>(points_.size())) {
        bad(j, "point id " + std::to_string(id) + " out of range [0, " + std::to_string(points_.size()) + ") (cell " +
                   std::to_string(c) + ")");
        return;
      }
      if (j < m) ids[static_cast<std::size_t>(j)] = id;
    }
    if (type == vtk::kPixel) ids = {ids[0], ids[1], ids[3], ids[2]};
    if (k > m) surface.higher_order.add_higher_order(std::to_string(type));
    surface.notes.append(mesh, *kind, ids.data(), c);
  }

  LoadedMesh build() {
    LoadedMesh loaded;
    loaded.format = binary_ ? "vtk-legacy-binary" : "vtk-legacy-ascii";
    const std::int64_t n = cells_.count();
    const auto num_points = static_cast<std::int64_t>(points_.size());
    std::map<int, std::int64_t> skipped_by_type;
    SurfaceCells surface;
    std::map<int, std::int64_t> mislabelled_by_type;
    std::vector<std::int64_t> mislabelled_cells;
    detail::CellNotes notes;
    for (std::int64_t c = 0; c < n; ++c) {
      const int type = types_[static_cast<std::size_t>(c)];
      const std::int64_t begin = cells_.offsets[static_cast<std::size_t>(c)];
      const std::int64_t k = cells_.offsets[static_cast<std::size_t>(c) + 1] - begin;
      const vtk::VolumeType* volume = vtk::find_volume_type(type);
      std::optional<CellKind> kind = vtk::volume_kind(type);
      // An 8-point cell whose fixed-size type cannot have 8 points (HexaLab
      // loads these as hexahedra; meshes in the wild rely on it).
      const int type_points = k != 8 ? -1 : fixed_point_count(type);
      const bool is_mislabelled = type_points >= 0 && type_points != 8;
      if (volume != nullptr && !is_mislabelled && !vtk::point_count_ok(*volume, k))
        fail_cell(c, 0,
                  "cell " + std::to_string(c) + " has type " + std::to_string(type) + " (" + volume->name + ") but " +
                      std::to_string(k) + " points, expected " + vtk::expected_point_counts(*volume));
      if (!kind && !is_mislabelled && vtk::is_surface_type(type)) {
        read_surface_cell(loaded.mesh, c, type, begin, k, skipped_by_type, surface);
        continue;
      }
      if (!kind && !is_mislabelled) {
        ++skipped_by_type[type];
        continue;
      }
      if (is_mislabelled) {
        kind = CellKind::hex;
        ++mislabelled_by_type[type];
        mislabelled_cells.push_back(c);
      } else if (k > cell_kind_num_corners(*kind)) {
        notes.add_higher_order(vtk::higher_order_name(type, k));
      }
      // Every point id is checked; the corners, listed first, are kept.
      const int m = cell_kind_num_corners(*kind);
      std::array<Index, 8> ids{};
      for (std::int64_t j = 0; j < k; ++j) {
        const Index id = cells_.connectivity[static_cast<std::size_t>(begin + j)];
        if (id >= num_points)
          fail_cell(c, j,
                    "point id " + std::to_string(id) + " out of range [0, " + std::to_string(num_points) + ") (cell " +
                        std::to_string(c) + ")");
        if (j < m) ids[static_cast<std::size_t>(j)] = id;
      }
      const int* to_vtk = type == vtk::kVoxel ? kVoxelToHex.data() : nullptr;
      if (const int j = detail::first_repeated(ids.data(), m); j >= 0) {
        if (*kind == CellKind::hex && detail::append_collapsed_hex(loaded.mesh, ids.data(), to_vtk, c, notes)) continue;
        fail_cell(c, j,
                  "point id " + std::to_string(ids[static_cast<std::size_t>(j)]) + " repeated (cell " +
                      std::to_string(c) + ")");
      }
      detail::append_cell(loaded.mesh, *kind, ids.data(), to_vtk, c);
    }

    std::int64_t num_volume_dropped = 0;
    const bool is_surface = detail::keep_dimension(loaded.mesh, limits_.dimension, skipped_by_type, surface.types,
                                                   num_volume_dropped);
    if (is_surface && surface.has_bad()) fail_cell(surface.bad_where, surface.bad_detail, surface.bad_message);
    const SkippedCells skipped(skipped_by_type);
    if (is_surface && detail::num_surface_cells(loaded.mesh) == 0)
      s_.fail_at(0, surface.notes.no_cells_message() +
                        (skipped.count > 0 ? " (" + skipped.counted("cell") + ")" : std::string()));
    if (!is_surface && num_volume_cells(loaded.mesh) == 0)
      s_.fail_at(0, "no volume cells" + (skipped.count > 0 ? " (" + skipped.counted("cell") + ")" : std::string()));
    if (num_volume_dropped > 0) loaded.warnings.push_back(detail::volume_dropped_warning(s_.name(), num_volume_dropped, "cell"));
    SkippedCells::report(skipped_by_type, vtk::type_dimension, is_surface ? 2 : 3, s_.name(), "cell", loaded.notes, loaded.warnings);
    if (is_surface) {
      surface.append_warnings(s_.name(), "cell", loaded.warnings);
    } else {
      notes.append_warnings(s_.name(), "cell", loaded.warnings);
    }
    if (!mislabelled_cells.empty()) {
      constexpr std::size_t kShown = 5;
      std::string cells;
      for (std::size_t i = 0; i < mislabelled_cells.size() && i < kShown; ++i)
        cells += (i ? ", " : "") + std::to_string(mislabelled_cells[i]);
      if (mislabelled_cells.size() > kShown)
        cells += " and " + std::to_string(mislabelled_cells.size() - kShown) + " more";
      loaded.warnings.push_back(s_.name() + ": " + std::to_string(mislabelled_cells.size()) + " cell" +
                                (mislabelled_cells.size() > 1 ? "s" : "") +
                                " with 8 points but a non-hexahedral type (" + SkippedCells(mislabelled_by_type).types +
                                ") loaded as hexahedra: cell" + (mislabelled_cells.size() > 1 ? "s " : " ") + cells);
    }
    loaded.mesh.points = std::move(points_);
    return loaded;
  }

  TextScanner s_;
  ReadLimits limits_;
  std::uint64_t file_bytes_;
  bool binary_ = false;
  bool is_version5_ = false;
  std::vector<Vec3> points_;
  std::int64_t points_line_ = 0;
  CellArrays cells_;
  std::vector<int> types_;
  std::int64_t types_line_ = 0;
};

}  // namespace

LoadedMesh read_vtk_legacy(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  return VtkParser(bytes, name, limits).parse();
}

}  // namespace hq
