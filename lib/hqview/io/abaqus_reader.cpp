#include "hqview/io/abaqus_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "hqview/core/text.h"
#include "hqview/core/types.h"
#include "hqview/io/text_scanner.h"

namespace hq {
namespace {

using detail::iequals;
using detail::quote;

constexpr std::string_view kHexTypes[] = {"C3D8", "C3D8R", "C3D8I", "C3D8H", "C3D8RH", "C3D8IH"};

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return out;
}

class AbaqusParser {
 public:
  AbaqusParser(std::string_view bytes, const std::string& name, const ReadLimits& limits)
      : bytes_(bytes), name_(name), limits_(limits) {}

  LoadedMesh parse() {
    enum class Block { kNone, kNodes, kHexes, kOtherElements, kSkipped };
    Block block = Block::kNone;
    std::string element_type;
    while (next_line()) {
      const std::string_view line = trim(line_);
      if (line.empty() || line.starts_with("**")) continue;
      if (line.front() == '*') {
        std::string keyword_line(line);
        while (!keyword_line.empty() && keyword_line.back() == ',' && next_line()) keyword_line += trim(line_);
        const std::vector<std::string_view> parts = split(keyword_line);
        const std::string keyword = upper(trim(parts[0]));
        if (keyword == "*NODE") {
          block = Block::kNodes;
        } else if (keyword == "*ELEMENT") {
          element_type.clear();
          for (std::size_t i = 1; i < parts.size(); ++i) {
            const std::string_view part = trim(parts[i]);
            const std::size_t eq = part.find('=');
            if (eq != std::string_view::npos && iequals(trim(part.substr(0, eq)), "TYPE"))
              element_type = upper(trim(part.substr(eq + 1)));
          }
          if (element_type.empty()) fail(line_number_, "*ELEMENT without TYPE=");
          const bool is_hex =
              std::find(std::begin(kHexTypes), std::end(kHexTypes), element_type) != std::end(kHexTypes);
          block = is_hex ? Block::kHexes : Block::kOtherElements;
        } else if (keyword == "*INCLUDE") {
          fail(line_number_, "*INCLUDE is not supported: merge the included file into this one");
        } else {
          block = Block::kSkipped;
        }
        continue;
      }
      switch (block) {
        case Block::kNone:
          fail(line_number_, "data line before any keyword: " + quote(line));
        case Block::kNodes:
          read_node(line);
          break;
        case Block::kHexes:
          read_hex(line);
          break;
        case Block::kOtherElements: {
          // One element per record; a record continues while its lines end with ','.
          std::string_view record = line;
          while (!record.empty() && record.back() == ',' && next_line()) record = trim(line_);
          ++skipped_by_type_[element_type];
          break;
        }
        case Block::kSkipped:
          break;
      }
    }
    return build();
  }

 private:
  bool next_line() {
    if (pos_ >= bytes_.size()) return false;
    const std::size_t end = std::min(bytes_.find('\n', pos_), bytes_.size());
    line_ = bytes_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_number_;
    return true;
  }

  static std::vector<std::string_view> split(std::string_view text) { return hq::split(text, ','); }

  [[noreturn]] void fail(std::int64_t line, const std::string& message) const {
    throw ParseError(name_, line, message);
  }

  template <class T>
  T parse_number(std::string_view field, const char* what) const {
    field = trim(field);
    T value{};
    const char* first = field.data() + (field.size() > 1 && field[0] == '+' ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(first, field.data() + field.size(), value);
    if (field.empty() || ec != std::errc{} || ptr != field.data() + field.size())
      fail(line_number_, std::string("expected ") + what + ", got " + quote(field));
    return value;
  }

  void read_node(std::string_view line) {
    std::vector<std::string_view> fields = split(line);
    if (!fields.empty() && trim(fields.back()).empty()) fields.pop_back();  // trailing comma
    if (fields.size() < 2 || fields.size() > 4)
      fail(line_number_, "expected a node id and 1 to 3 coordinates, got " + std::to_string(fields.size()) + " fields");
    const auto id = parse_number<std::int64_t>(fields[0], "a node id");
    if (id <= 0) fail(line_number_, "node id " + std::to_string(id) + " is not positive");
    double xyz[3] = {0, 0, 0};
    for (std::size_t k = 1; k < fields.size(); ++k) {
      xyz[k - 1] = parse_number<double>(fields[k], "a coordinate");
      if (!std::isfinite(xyz[k - 1])) fail(line_number_, "non-finite coordinate (node " + std::to_string(id) + ")");
    }
    if (static_cast<std::int64_t>(points_.size()) >= kMaxIndexCount)
      fail(line_number_, "more than " + std::to_string(kMaxIndexCount) + " nodes");
    const auto [it, inserted] = index_of_id_.emplace(id, static_cast<Index>(points_.size()));
    if (!inserted) fail(line_number_, "node id " + std::to_string(id) + " defined twice");
    points_.push_back({xyz[0], xyz[1], xyz[2]});
  }

  void read_hex(std::string_view line) {
    const std::int64_t first_line = line_number_;
    std::vector<std::string_view> fields = split(line);
    // A record continues while its line ends with a comma; the strings stay
    // views into bytes_.
    while (trim(fields.back()).empty() && fields.size() < 10) {
      fields.pop_back();
      if (!next_line()) fail(first_line, "unexpected end of file in an element continued on the next line");
      const std::vector<std::string_view> more = split(trim(line_));
      fields.insert(fields.end(), more.begin(), more.end());
    }
    if (!fields.empty() && trim(fields.back()).empty()) fields.pop_back();
    if (fields.size() != 9)
      fail(line_number_, "expected an element id and 8 node ids, got " + std::to_string(fields.size()) + " fields");
    const auto id = parse_number<std::int64_t>(fields[0], "an element id");
    Hex hex;
    for (int j = 0; j < 8; ++j) {
      const auto node = parse_number<std::int64_t>(fields[static_cast<std::size_t>(j) + 1], "a node id");
      const auto it = index_of_id_.find(node);
      if (it == index_of_id_.end())
        fail(line_number_, "node " + std::to_string(node) + " is not defined (element " + std::to_string(id) + ")");
      for (int i = 0; i < j; ++i)
        if (hex[i] == it->second)
          fail(line_number_, "node " + std::to_string(node) + " repeated (element " + std::to_string(id) + ")");
      hex[j] = it->second;
    }
    hexes_.push_back(hex);
  }

  LoadedMesh build() {
    const SkippedCells skipped(skipped_by_type_);
    if (hexes_.empty())
      fail(0, "no hexahedra (*ELEMENT, TYPE=C3D8, C3D8R or C3D8I)" +
                  (skipped.count > 0 ? ": " + skipped.counted("element") : std::string()));
    // Abaqus declares no counts: the budget is checked once the file is read
    // (what reading allocates is bounded by the file's size), before the analysis.
    check_mesh_memory(limits_, name_, 0, bytes_.size(), static_cast<std::int64_t>(points_.size()),
                      static_cast<std::int64_t>(hexes_.size()));
    LoadedMesh loaded;
    loaded.format = "abaqus";
    if (skipped.count > 0) loaded.warnings.push_back(skipped.warning(name_, "element"));
    loaded.mesh.points = std::move(points_);
    loaded.mesh.hexes = std::move(hexes_);
    return loaded;
  }

  std::string_view bytes_;
  const std::string& name_;
  ReadLimits limits_;
  std::size_t pos_ = 0;
  std::string_view line_;
  std::int64_t line_number_ = 0;
  std::vector<Vec3> points_;
  std::unordered_map<std::int64_t, Index> index_of_id_;  // lookups only, never iterated
  std::vector<Hex> hexes_;
  std::map<std::string, std::int64_t> skipped_by_type_;
};

}  // namespace

bool looks_like_abaqus(std::string_view bytes) {
  std::size_t pos = 0;
  while (pos < bytes.size()) {
    const std::size_t end = std::min(bytes.find('\n', pos), bytes.size());
    const std::string_view line = trim(bytes.substr(pos, end - pos));
    pos = end + 1;
    if (line.empty() || line.starts_with("**")) continue;
    return line.size() > 1 && line[0] == '*' &&
           ((line[1] >= 'A' && line[1] <= 'Z') || (line[1] >= 'a' && line[1] <= 'z'));
  }
  return false;
}

LoadedMesh read_abaqus(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  return AbaqusParser(bytes, name, limits).parse();
}

}  // namespace hq
