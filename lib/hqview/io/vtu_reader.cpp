#include "hqview/io/vtu_reader.h"

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

#ifdef HQ_HAVE_ZLIB
#include <zlib.h>
#endif

#include "hqview/core/types.h"
#include "hqview/io/cell_reading.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/io/text_scanner.h"
#include "hqview/io/vtk_cells.h"
#include "hqview/io/xml_parser.h"

namespace hq {
namespace {

using detail::quote;
using detail::XmlDocument;
using detail::XmlElement;

using vtk::kVoxelToHex;
using vtk::sign_extend;

// zlib's largest expansion of deflated data is 1032:1 (zlib FAQ); a block
// that claims more cannot be genuine, so nothing is allocated for it.
constexpr std::uint64_t kMaxZlibRatio = 1032;

enum class ValueKind { kSigned, kUnsigned, kFloat };

struct XmlType {
  std::string_view name;
  int size;
  ValueKind kind;
};

constexpr XmlType kXmlTypes[] = {
    {"Int8", 1, ValueKind::kSigned},     {"UInt8", 1, ValueKind::kUnsigned},  {"Int16", 2, ValueKind::kSigned},
    {"UInt16", 2, ValueKind::kUnsigned}, {"Int32", 4, ValueKind::kSigned},    {"UInt32", 4, ValueKind::kUnsigned},
    {"Int64", 8, ValueKind::kSigned},    {"UInt64", 8, ValueKind::kUnsigned}, {"Float32", 4, ValueKind::kFloat},
    {"Float64", 8, ValueKind::kFloat},
};

const XmlType* find_type(std::string_view name) {
  for (const XmlType& type : kXmlTypes)
    if (type.name == name) return &type;
  return nullptr;
}

std::uint64_t load_bits(const char* p, int size, bool big_endian) {
  std::uint64_t v = 0;
  for (int i = 0; i < size; ++i) {
    const auto byte = static_cast<std::uint64_t>(static_cast<unsigned char>(p[big_endian ? i : size - 1 - i]));
    v = (v << 8) | byte;
  }
  return v;
}

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// Binary bytes of a DataArray: raw (appended raw) or decoded from base64
// (inline binary, appended base64). Base64 is decoded quad by quad, and a
// padded quad may be followed by more quads: VTK and meshio encode a
// compression header and the blocks as separate base64 strings.
class ByteSource {
 public:
  ByteSource(std::string_view data, std::size_t file_offset, bool is_base64)
      : data_(data), file_offset_(file_offset), is_base64_(is_base64) {}

  // An upper bound of the bytes that can still be read.
  std::uint64_t max_available() const {
    const std::uint64_t left = data_.size() - pos_;
    return is_base64_ ? pending_.size() + left / 4 * 3 : left;
  }
  // The file offset of the next byte (raw) or base64 character.
  std::size_t file_offset() const { return file_offset_ + pos_; }

  // Appends the next n bytes to out; on failure returns an error message.
  std::optional<std::string> read(std::size_t n, std::string& out) {
    if (!is_base64_) {
      if (n > data_.size() - pos_)
        return "data ends after " + std::to_string(data_.size() - pos_) + " of " + std::to_string(n) + " bytes";
      out.append(data_.substr(pos_, n));
      pos_ += n;
      return std::nullopt;
    }
    while (n > 0) {
      if (pending_.empty())
        if (auto error = decode_quad()) return error;
      const std::size_t take = std::min(n, pending_.size());
      out.append(pending_, 0, take);
      pending_.erase(0, take);
      n -= take;
    }
    return std::nullopt;
  }

 private:
  std::optional<std::string> decode_quad() {
    int values[4];
    int count = 0;
    int padding = 0;
    while (count < 4) {
      while (pos_ < data_.size() && detail::is_space(data_[pos_])) ++pos_;
      if (pos_ == data_.size()) return std::string("base64 data ends early");
      const char c = data_[pos_];
      if (c == '=' && count >= 2) {
        ++padding;
        values[count++] = 0;
      } else {
        const int v = base64_value(c);
        if (v < 0 || padding > 0)
          return "invalid base64 character " + quote(std::string_view(&data_[pos_], 1)) + " at byte offset " +
                 std::to_string(file_offset());
        values[count++] = v;
      }
      ++pos_;
    }
    const std::uint32_t bits = (static_cast<std::uint32_t>(values[0]) << 18) |
                               (static_cast<std::uint32_t>(values[1]) << 12) |
                               (static_cast<std::uint32_t>(values[2]) << 6) | static_cast<std::uint32_t>(values[3]);
    const char bytes[3] = {static_cast<char>(bits >> 16), static_cast<char>(bits >> 8), static_cast<char>(bits)};
    pending_.assign(bytes, static_cast<std::size_t>(3 - padding));
    return std::nullopt;
  }

  std::string_view data_;
  std::size_t file_offset_;
  bool is_base64_;
  std::size_t pos_ = 0;
  std::string pending_;  // decoded, not yet handed out
};

// One DataArray and how to read it.
struct ArrayRef {
  const XmlElement* element = nullptr;
  std::string label;  // "DataArray 'connectivity'" for messages
  XmlType type{};
  std::int64_t components = 1;
  std::string format;  // ascii, binary, appended
};

class VtuParser {
 public:
  VtuParser(std::string_view bytes, const std::string& name, const ReadLimits& limits)
      : bytes_(bytes), name_(name), limits_(limits) {}

  LoadedMesh parse() {
    doc_ = detail::parse_xml(bytes_, name_, "AppendedData");
    const XmlElement& root = doc_.elements.front();
    if (root.name != "VTKFile") fail(root, "expected a <VTKFile> root element, got <" + std::string(root.name) + ">");
    const std::string* type = root.attribute("type");
    if (type == nullptr) fail(root, "<VTKFile> has no type attribute");
    if (*type != "UnstructuredGrid")
      fail(root, "unsupported VTK XML type " + quote(*type) + " (expected UnstructuredGrid)");
    if (const std::string* order = root.attribute("byte_order")) {
      if (*order == "BigEndian") {
        big_endian_ = true;
      } else if (*order != "LittleEndian") {
        fail(root, "unknown byte_order " + quote(*order) + " (expected LittleEndian or BigEndian)");
      }
    }
    if (const std::string* header = root.attribute("header_type")) {
      if (*header == "UInt64") {
        header_size_ = 8;
      } else if (*header != "UInt32") {
        fail(root, "unsupported header_type " + quote(*header) + " (expected UInt32 or UInt64)");
      }
    }
    if (const std::string* compressor = root.attribute("compressor")) {
      if (*compressor == "vtkZLibDataCompressor") {
#ifdef HQ_HAVE_ZLIB
        compressed_ = true;
#else
        fail(root, "compressor vtkZLibDataCompressor: this HQView was built without zlib");
#endif
      } else if (!compressor->empty()) {
        fail(root, "unsupported compressor " + quote(*compressor) + " (expected vtkZLibDataCompressor)");
      }
    }
    if (doc_.stop_element != static_cast<std::size_t>(-1)) find_appended_data();

    const XmlElement* grid = child(root, "UnstructuredGrid");
    if (grid == nullptr) fail(root, "<VTKFile> has no <UnstructuredGrid> element");
    bool has_piece = false;
    for (const std::size_t index : grid->children) {
      const XmlElement& piece = doc_.elements[index];
      if (piece.name != "Piece") continue;
      has_piece = true;
      read_piece(piece);
    }
    if (!has_piece) fail(*grid, "<UnstructuredGrid> has no <Piece>");
    return build(*grid);
  }

 private:
  const XmlElement* child(const XmlElement& parent, std::string_view name) const {
    for (const std::size_t index : parent.children)
      if (doc_.elements[index].name == name) return &doc_.elements[index];
    return nullptr;
  }

  [[noreturn]] void fail(const XmlElement& element, const std::string& message) const {
    throw ParseError(name_, element.line, message);
  }
  [[noreturn]] void fail(const ArrayRef& array, const std::string& message) const {
    throw ParseError(name_, array.element->line, message + " (" + array.label + ")");
  }

  std::int64_t count_attribute(const XmlElement& element, std::string_view key, std::int64_t limit) const {
    const std::string* text = element.attribute(key);
    if (text == nullptr) fail(element, "<" + std::string(element.name) + "> has no " + std::string(key) + " attribute");
    std::int64_t value = 0;
    const auto [ptr, ec] = std::from_chars(text->data(), text->data() + text->size(), value);
    if (ec != std::errc{} || ptr != text->data() + text->size())
      fail(element, "expected an integer " + std::string(key) + ", got " + quote(*text));
    if (value < 0) fail(element, "negative " + std::string(key) + " " + *text);
    if (value > limit) fail(element, std::string(key) + " " + *text + " exceeds the limit of " + std::to_string(limit));
    return value;
  }

  void find_appended_data() {
    const XmlElement& appended = doc_.elements[doc_.stop_element];
    const std::string* encoding = appended.attribute("encoding");
    if (encoding == nullptr) fail(appended, "<AppendedData> has no encoding attribute");
    if (*encoding == "base64") {
      appended_base64_ = true;
    } else if (*encoding != "raw") {
      fail(appended, "unknown AppendedData encoding " + quote(*encoding) + " (expected raw or base64)");
    }
    std::size_t pos = doc_.stop_offset;
    while (pos < bytes_.size() && detail::is_space(bytes_[pos])) ++pos;
    if (pos == bytes_.size() || bytes_[pos] != '_') fail(appended, "expected '_' at the start of the AppendedData");
    appended_offset_ = pos + 1;
  }

  ArrayRef array_ref(const XmlElement& element, const std::string& label) const {
    ArrayRef array;
    array.element = &element;
    array.label = label;
    const std::string* type = element.attribute("type");
    if (type == nullptr) fail(array, "<DataArray> has no type attribute");
    const XmlType* found = find_type(*type);
    if (found == nullptr) fail(array, "unknown data type " + quote(*type));
    array.type = *found;
    if (element.attribute("NumberOfComponents") != nullptr)
      array.components = count_attribute(element, "NumberOfComponents", 1 << 20);
    const std::string* format = element.attribute("format");
    array.format = format == nullptr ? "ascii" : *format;
    if (array.format != "ascii" && array.format != "binary" && array.format != "appended")
      fail(array, "unknown DataArray format " + quote(array.format) + " (expected ascii, binary or appended)");
    return array;
  }

  const XmlElement& named_array(const XmlElement& cells, std::string_view array_name) const {
    for (const std::size_t index : cells.children) {
      const XmlElement& element = doc_.elements[index];
      const std::string* name = element.attribute("Name");
      if (element.name == "DataArray" && name != nullptr && *name == array_name) return element;
    }
    fail(cells, "<Cells> has no DataArray named " + quote(array_name));
  }

  // --- reading values ------------------------------------------------------

  // ASCII values as integers (is_integer) or doubles; expected < 0: any count.
  template <class T>
  std::vector<T> read_ascii(const ArrayRef& array, std::int64_t expected) const {
    const std::string_view text = array.element->text;
    std::vector<T> values;
    if (expected >= 0) {
      if (detail::exceeds_remaining(expected, 2, text.size(), true))
        fail(array,
             std::to_string(expected) + " values cannot fit in its " + std::to_string(text.size()) + " bytes of text");
      values.reserve(static_cast<std::size_t>(expected));
    }
    std::int64_t line = array.element->text_line;
    std::size_t pos = 0;
    while (true) {
      while (pos < text.size() && detail::is_space(text[pos])) {
        if (text[pos] == '\n') ++line;
        ++pos;
      }
      if (pos == text.size()) break;
      std::size_t end = pos;
      while (end < text.size() && !detail::is_space(text[end])) ++end;
      const std::string_view token = text.substr(pos, end - pos);
      T value{};
      const char* first = token.data() + (token.size() > 1 && token[0] == '+' ? 1 : 0);
      const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), value);
      if (ec != std::errc{} || ptr != token.data() + token.size())
        throw ParseError(name_, line,
                         std::string("expected ") + (std::is_integral_v<T> ? "an integer" : "a number") + ", got " +
                             quote(token) + " (" + array.label + " value " + std::to_string(values.size()) + ")");
      if (expected >= 0 && static_cast<std::int64_t>(values.size()) == expected)
        throw ParseError(name_, line, "more than " + std::to_string(expected) + " values (" + array.label + ")");
      values.push_back(value);
      pos = end;
    }
    if (expected >= 0 && static_cast<std::int64_t>(values.size()) != expected)
      fail(array, std::to_string(values.size()) + " values, expected " + std::to_string(expected));
    return values;
  }

  std::uint64_t read_header_value(ByteSource& source, const ArrayRef& array, const char* what) const {
    std::string bytes;
    if (auto error = source.read(static_cast<std::size_t>(header_size_), bytes))
      fail(array, *error + " in its " + what);
    return load_bits(bytes.data(), header_size_, big_endian_);
  }

  // The decoded data bytes of a binary or appended array. expected_bytes <
  // 0: any size (a multiple of the value size).
  std::string read_binary(const ArrayRef& array, std::int64_t expected_bytes) const {
    std::optional<ByteSource> source;
    if (array.format == "binary") {
      source.emplace(array.element->text, array.element->text_offset, true);
    } else {
      if (appended_offset_ == 0) fail(array, "format=\"appended\" but the file has no <AppendedData>");
      const std::int64_t offset = count_attribute(*array.element, "offset", std::numeric_limits<std::int64_t>::max());
      if (static_cast<std::uint64_t>(offset) > bytes_.size() - appended_offset_)
        fail(array, "offset " + std::to_string(offset) + " is past the end of the AppendedData");
      const std::size_t start = appended_offset_ + static_cast<std::size_t>(offset);
      source.emplace(bytes_.substr(start), start, appended_base64_);
    }
    const std::size_t data_offset = source->file_offset();
    const std::string where = ", data at byte offset " + std::to_string(data_offset);
    std::string data;
    if (!compressed_) {
      const std::uint64_t num_bytes = read_header_value(*source, array, "byte count header");
      if (expected_bytes >= 0 && num_bytes != static_cast<std::uint64_t>(expected_bytes))
        fail(array, "byte count " + std::to_string(num_bytes) + " in its header, expected " +
                        std::to_string(expected_bytes) + where);
      if (num_bytes > source->max_available())
        fail(array, "data truncated: its header claims " + std::to_string(num_bytes) + " bytes, at most " +
                        std::to_string(source->max_available()) + " left" + where);
      data.reserve(static_cast<std::size_t>(num_bytes));
      if (auto error = source->read(static_cast<std::size_t>(num_bytes), data)) fail(array, *error + where);
    } else {
      data = read_compressed(*source, array, expected_bytes, where);
    }
    if (data.size() % static_cast<std::size_t>(array.type.size) != 0)
      fail(array, std::to_string(data.size()) + " bytes of data is not a whole number of " +
                      std::string(array.type.name) + " values" + where);
    return data;
  }

  std::string read_compressed(ByteSource& source, const ArrayRef& array, std::int64_t expected_bytes,
                              const std::string& where) const {
#ifdef HQ_HAVE_ZLIB
    const std::uint64_t num_blocks = read_header_value(source, array, "compression header");
    const std::uint64_t block_size = read_header_value(source, array, "compression header");
    const std::uint64_t last_size = read_header_value(source, array, "compression header");
    if (num_blocks > source.max_available() / static_cast<std::uint64_t>(header_size_))
      fail(array,
           "compression header claims " + std::to_string(num_blocks) + " blocks, more than the data holds" + where);
    if (last_size > block_size)
      fail(array, "last block size " + std::to_string(last_size) + " exceeds the block size " +
                      std::to_string(block_size) + where);
    std::vector<std::uint64_t> sizes(static_cast<std::size_t>(num_blocks));
    std::uint64_t total_compressed = 0;
    for (std::uint64_t& size : sizes) {
      size = read_header_value(source, array, "compression header");
      if (size > source.max_available())
        fail(array, "compressed block of " + std::to_string(size) + " bytes, more than the data holds" + where);
      total_compressed += size;
    }
    if (total_compressed > source.max_available())
      fail(array, "compressed blocks of " + std::to_string(total_compressed) + " bytes, at most " +
                      std::to_string(source.max_available()) + " left" + where);
    std::uint64_t total = 0;
    if (num_blocks > 0) {
      if (block_size > (std::numeric_limits<std::uint64_t>::max() >> 12) / num_blocks)
        fail(array, "compression header claims more data than can exist" + where);
      total = (num_blocks - 1) * block_size + (last_size == 0 ? block_size : last_size);
    }
    if (expected_bytes >= 0 && total != static_cast<std::uint64_t>(expected_bytes))
      fail(array, "compression header claims " + std::to_string(total) + " bytes, expected " +
                      std::to_string(expected_bytes) + where);
    if (total > total_compressed * kMaxZlibRatio + 64 * num_blocks)
      fail(array, "compression header claims " + std::to_string(total) + " bytes from " +
                      std::to_string(total_compressed) + " compressed bytes, more than zlib can expand" + where);
    std::string data(static_cast<std::size_t>(total), '\0');
    std::size_t out = 0;
    std::string block;
    for (std::size_t b = 0; b < sizes.size(); ++b) {
      block.clear();
      if (auto error = source.read(static_cast<std::size_t>(sizes[b]), block)) fail(array, *error + where);
      const std::uint64_t size = b + 1 == sizes.size() && last_size != 0 ? last_size : block_size;
      uLongf length = static_cast<uLongf>(size);
      const int result = uncompress(reinterpret_cast<Bytef*>(data.data() + out), &length,
                                    reinterpret_cast<const Bytef*>(block.data()), static_cast<uLong>(block.size()));
      if (result != Z_OK || length != size)
        fail(array, "zlib block " + std::to_string(b) + " does not decompress to " + std::to_string(size) + " bytes (" +
                        (result == Z_OK ? std::to_string(length) + " bytes" : std::string(zError(result))) + ")" +
                        where);
      out += static_cast<std::size_t>(size);
    }
    return data;
#else
    (void)source;
    (void)expected_bytes;
    fail(array, "compressed data: this HQView was built without zlib" + where);
#endif
  }

  std::vector<std::int64_t> read_ints(const ArrayRef& array, std::int64_t expected) const {
    if (array.type.kind == ValueKind::kFloat)
      fail(array, "expected an integer data type, got " + std::string(array.type.name));
    if (array.format == "ascii") return read_ascii<std::int64_t>(array, expected);
    const std::string data = read_binary(array, expected < 0 ? -1 : expected * array.type.size);
    const std::size_t n = data.size() / static_cast<std::size_t>(array.type.size);
    std::vector<std::int64_t> values(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t bits =
          load_bits(data.data() + i * static_cast<std::size_t>(array.type.size), array.type.size, big_endian_);
      if (array.type.kind == ValueKind::kSigned) {
        values[i] = sign_extend(bits, array.type.size);
      } else {
        if (bits > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
          fail(array, "value " + std::to_string(bits) + " out of range (value " + std::to_string(i) + ")");
        values[i] = static_cast<std::int64_t>(bits);
      }
    }
    return values;
  }

  std::vector<double> read_doubles(const ArrayRef& array, std::int64_t expected) const {
    if (array.format == "ascii") return read_ascii<double>(array, expected);
    const std::string data = read_binary(array, expected * array.type.size);
    const std::size_t n = data.size() / static_cast<std::size_t>(array.type.size);
    std::vector<double> values(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t bits =
          load_bits(data.data() + i * static_cast<std::size_t>(array.type.size), array.type.size, big_endian_);
      switch (array.type.kind) {
        case ValueKind::kFloat:
          values[i] = array.type.size == 4 ? double{std::bit_cast<float>(static_cast<std::uint32_t>(bits))}
                                           : std::bit_cast<double>(bits);
          break;
        case ValueKind::kSigned:
          values[i] = static_cast<double>(sign_extend(bits, array.type.size));
          break;
        case ValueKind::kUnsigned:
          values[i] = static_cast<double>(bits);
          break;
      }
    }
    return values;
  }

  // --- pieces --------------------------------------------------------------

  void read_piece(const XmlElement& piece) {
    const std::int64_t num_points = count_attribute(piece, "NumberOfPoints", kMaxIndexCount);
    const std::int64_t num_cells = count_attribute(piece, "NumberOfCells", kMaxIndexCount);
    const std::int64_t base = static_cast<std::int64_t>(points_.size());
    if (base + num_points > kMaxIndexCount)
      fail(piece, "more than " + std::to_string(kMaxIndexCount) + " points in all pieces");
    check_mesh_memory(limits_, name_, piece.line, bytes_.size(), base + num_points,
                      num_volume_cells(mesh_) + num_cells, "cell");

    const XmlElement* points = child(piece, "Points");
    if (points == nullptr) {
      if (num_points > 0) fail(piece, "<Piece> has no <Points>");
    } else {
      const XmlElement* element = child(*points, "DataArray");
      if (element == nullptr) fail(*points, "<Points> has no <DataArray>");
      const ArrayRef array = array_ref(*element, "DataArray of the Points");
      if (format_.empty()) format_ = array.format;
      if (array.components != 3)
        fail(array, "points have " + std::to_string(array.components) + " components, expected 3");
      const std::vector<double> xyz = read_doubles(array, 3 * num_points);
      if (static_cast<std::int64_t>(xyz.size()) != 3 * num_points)
        fail(array, std::to_string(xyz.size()) + " values, expected " + std::to_string(3 * num_points));
      for (std::int64_t i = 0; i < num_points; ++i) {
        const double* p = &xyz[static_cast<std::size_t>(3 * i)];
        for (int k = 0; k < 3; ++k)
          if (!std::isfinite(p[k]))
            fail(array, "non-finite coordinate " + std::string(std::isnan(p[k]) ? "nan" : (p[k] > 0 ? "inf" : "-inf")) +
                            " (point " + std::to_string(i) + ")");
        points_.push_back({p[0], p[1], p[2]});
      }
    }

    const XmlElement* cells = child(piece, "Cells");
    if (cells == nullptr) {
      if (num_cells > 0) fail(piece, "<Piece> has no <Cells>");
      return;
    }
    const ArrayRef types_array = array_ref(named_array(*cells, "types"), "DataArray 'types'");
    const ArrayRef offsets_array = array_ref(named_array(*cells, "offsets"), "DataArray 'offsets'");
    const ArrayRef ids_array = array_ref(named_array(*cells, "connectivity"), "DataArray 'connectivity'");
    const std::vector<std::int64_t> types = read_ints(types_array, num_cells);
    const std::vector<std::int64_t> offsets = read_ints(offsets_array, num_cells);
    const std::vector<std::int64_t> ids = read_ints(ids_array, -1);
    std::int64_t begin = 0;
    for (std::int64_t c = 0; c < num_cells; ++c) {
      const std::int64_t end = offsets[static_cast<std::size_t>(c)];
      if (end < begin || end > static_cast<std::int64_t>(ids.size()))
        fail(offsets_array, "offset " + std::to_string(end) + " of cell " + std::to_string(c) + " is outside [" +
                                std::to_string(begin) + ", " + std::to_string(ids.size()) + "]");
      const std::int64_t type = types[static_cast<std::size_t>(c)];
      const std::int64_t cell = num_cells_ + c;
      const vtk::VolumeType* volume = vtk::find_volume_type(type);
      if (volume == nullptr && vtk::is_surface_type(type)) {
        read_surface_cell(type, cell, ids, begin, end, base, num_points);
        begin = end;
        continue;
      }
      if (volume == nullptr) {
        ++skipped_by_type_[type];
        begin = end;
        continue;
      }
      if (!vtk::point_count_ok(*volume, end - begin))
        fail(ids_array, "cell " + std::to_string(cell) + " has type " + std::to_string(type) + " (" + volume->name +
                            ") but " + std::to_string(end - begin) + " points, expected " +
                            vtk::expected_point_counts(*volume));
      if (end - begin > cell_kind_num_corners(volume->kind))
        notes_.add_higher_order(vtk::higher_order_name(type, end - begin));
      // Every point id is checked; the corners, listed first, are kept.
      const int num_corners = cell_kind_num_corners(volume->kind);
      std::array<Index, 8> corners{};
      for (std::int64_t j = 0; j < end - begin; ++j) {
        const std::int64_t id = ids[static_cast<std::size_t>(begin + j)];
        if (id < 0 || id >= num_points)
          fail(ids_array, "point id " + std::to_string(id) + " out of range [0, " + std::to_string(num_points) +
                              ") (cell " + std::to_string(cell) + ")");
        if (j < num_corners) corners[static_cast<std::size_t>(j)] = static_cast<Index>(base + id);
      }
      const int* to_vtk = type == vtk::kVoxel ? kVoxelToHex.data() : nullptr;
      if (const int j = detail::first_repeated(corners.data(), num_corners); j >= 0) {
        if (volume->kind != CellKind::hex || !detail::append_collapsed_hex(mesh_, corners.data(), to_vtk, cell, notes_))
          fail(ids_array, "point id " + std::to_string(corners[static_cast<std::size_t>(j)] - base) +
                              " repeated (cell " + std::to_string(cell) + ")");
      } else {
        detail::append_cell(mesh_, volume->kind, corners.data(), to_vtk, cell);
      }
      begin = end;
    }
    num_cells_ += num_cells;
  }

  // A surface cell (vtk::kSurfaceTypes) into the surface blocks beside the
  // volume cells (detail::SurfaceCells: where = its cell id).
  void read_surface_cell(std::int64_t type, std::int64_t cell, const std::vector<std::int64_t>& ids, std::int64_t begin,
                         std::int64_t end, std::int64_t base, std::int64_t num_points) {
    bool is_count_wrong = false;
    const std::optional<CellKind> kind = vtk::surface_kind(type, end - begin, is_count_wrong);
    if (!kind && !is_count_wrong) {  // a polygon of more than 4 points
      ++skipped_by_type_[type];
      return;
    }
    ++surface_.types[type];
    if (!kind) {
      surface_.set_bad(cell, 0, "cell " + std::to_string(cell) + " has type " + std::to_string(type) + " but " +
                                    std::to_string(end - begin) + " points");
      return;
    }
    const int m = cell_kind_num_corners(*kind);
    std::array<Index, 4> corners{};
    for (std::int64_t j = 0; j < end - begin; ++j) {
      const std::int64_t id = ids[static_cast<std::size_t>(begin + j)];
      if (id < 0 || id >= num_points) {
        surface_.set_bad(cell, j, "point id " + std::to_string(id) + " out of range [0, " + std::to_string(num_points) +
                                      ") (cell " + std::to_string(cell) + ")");
        return;
      }
      if (j < m) corners[static_cast<std::size_t>(j)] = static_cast<Index>(base + id);
    }
    if (type == vtk::kPixel) corners = {corners[0], corners[1], corners[3], corners[2]};
    if (end - begin > m) surface_.higher_order.add_higher_order(std::to_string(type));
    surface_.notes.append(mesh_, *kind, corners.data(), cell);
  }

  LoadedMesh build(const XmlElement& grid) {
    std::int64_t num_volume_dropped = 0;
    const bool is_surface =
        detail::keep_dimension(mesh_, limits_.dimension, skipped_by_type_, surface_.types, num_volume_dropped);
    if (is_surface && surface_.has_bad()) fail(grid, surface_.bad_message);
    const SkippedCells skipped(skipped_by_type_);
    if (is_surface && detail::num_surface_cells(mesh_) == 0)
      fail(grid, surface_.notes.no_cells_message() +
                     (skipped.count > 0 ? " (" + skipped.counted("cell") + ")" : std::string()));
    if (!is_surface && num_volume_cells(mesh_) == 0)
      fail(grid, "no volume cells" + (skipped.count > 0 ? " (" + skipped.counted("cell") + ")" : std::string()));
    LoadedMesh loaded;
    loaded.format = "vtu-" + format_;
    if (num_volume_dropped > 0) loaded.warnings.push_back(detail::volume_dropped_warning(name_, num_volume_dropped, "cell"));
    SkippedCells::report(skipped_by_type_, vtk::type_dimension, is_surface ? 2 : 3, name_, "cell", loaded.notes, loaded.warnings);
    if (is_surface)
      surface_.append_warnings(name_, "cell", loaded.warnings);
    else
      notes_.append_warnings(name_, "cell", loaded.warnings);
    mesh_.points = std::move(points_);
    loaded.mesh = std::move(mesh_);
    return loaded;
  }

  std::string_view bytes_;
  const std::string& name_;
  ReadLimits limits_;
  XmlDocument doc_;
  bool big_endian_ = false;
  int header_size_ = 4;
  bool compressed_ = false;
  bool appended_base64_ = false;
  std::size_t appended_offset_ = 0;  // 0: no AppendedData
  std::string format_;
  std::vector<Vec3> points_;
  Mesh mesh_;  // the volume blocks (points_ are moved in at the end)
  std::int64_t num_cells_ = 0;
  std::map<std::int64_t, std::int64_t> skipped_by_type_;
  detail::CellNotes notes_;
  detail::SurfaceCells<std::int64_t> surface_;
};

}  // namespace

bool looks_like_vtu(std::string_view bytes) {
  std::size_t pos = 0;
  if (bytes.starts_with("\xEF\xBB\xBF")) pos = 3;
  while (pos < bytes.size()) {
    while (pos < bytes.size() && detail::is_space(bytes[pos])) ++pos;
    const std::string_view rest = bytes.substr(pos);
    if (rest.starts_with("<?") || rest.starts_with("<!")) {
      const std::string_view terminator = rest.starts_with("<!--") ? "-->" : ">";
      const std::size_t end = rest.find(terminator);
      if (end == std::string_view::npos) return false;
      pos += end + terminator.size();
    } else {
      return rest.starts_with("<VTKFile");
    }
  }
  return false;
}

LoadedMesh read_vtu(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  return VtuParser(bytes, name, limits).parse();
}

}  // namespace hq
