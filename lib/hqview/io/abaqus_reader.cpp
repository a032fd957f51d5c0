#include "hqview/io/abaqus_reader.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "hqview/core/text.h"
#include "hqview/core/types.h"
#include "hqview/io/cell_reading.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/io/text_scanner.h"

namespace hq {
namespace {

using detail::iequals;
using detail::quote;

// The volume element types read, by kind (Abaqus Analysis User's Guide,
// "Three-dimensional solid element library": stress/displacement, hybrid
// (H), incompatible modes (I), modified (M), improved surface stress (S),
// coupled temperature-displacement (T), heat transfer and mass diffusion
// (DC), acoustic (AC), piezoelectric (E) and pore pressure (P) variants,
// first and second order). Abaqus numbers the corner nodes first, then the
// midside ones ("Triangular, tetrahedral, and wedge elements", "Solid
// (continuum) elements"): a second-order element is read by its corners,
// with min_nodes to max_nodes nodes in all (the variable-node C3D15V and
// C3D27 may leave out their face and centre nodes). Abaqus has no
// second-order pyramid: C3D5 and C3D5H are its only pyramids.
struct ElementType {
  std::string_view name;
  CellKind kind;
  int min_nodes;
  int max_nodes;
};
// clang-format off
constexpr ElementType kVolumeTypes[] = {
    {"C3D8", CellKind::hex, 8, 8},     {"C3D8R", CellKind::hex, 8, 8},    {"C3D8I", CellKind::hex, 8, 8},
    {"C3D8H", CellKind::hex, 8, 8},    {"C3D8RH", CellKind::hex, 8, 8},   {"C3D8IH", CellKind::hex, 8, 8},
    {"C3D8S", CellKind::hex, 8, 8},    {"C3D8HS", CellKind::hex, 8, 8},   {"C3D8T", CellKind::hex, 8, 8},
    {"C3D8HT", CellKind::hex, 8, 8},   {"C3D8RT", CellKind::hex, 8, 8},   {"C3D8RHT", CellKind::hex, 8, 8},
    {"C3D8E", CellKind::hex, 8, 8},    {"C3D8P", CellKind::hex, 8, 8},    {"C3D8PH", CellKind::hex, 8, 8},
    {"C3D8RP", CellKind::hex, 8, 8},   {"C3D8RPH", CellKind::hex, 8, 8},  {"DC3D8", CellKind::hex, 8, 8},
    {"DC3D8E", CellKind::hex, 8, 8},   {"AC3D8", CellKind::hex, 8, 8},
    {"C3D4", CellKind::tet, 4, 4},     {"C3D4H", CellKind::tet, 4, 4},    {"C3D4T", CellKind::tet, 4, 4},
    {"C3D4E", CellKind::tet, 4, 4},    {"C3D4P", CellKind::tet, 4, 4},    {"DC3D4", CellKind::tet, 4, 4},
    {"DC3D4E", CellKind::tet, 4, 4},   {"AC3D4", CellKind::tet, 4, 4},
    {"C3D6", CellKind::wedge, 6, 6},   {"C3D6H", CellKind::wedge, 6, 6},  {"C3D6T", CellKind::wedge, 6, 6},
    {"C3D6HT", CellKind::wedge, 6, 6}, {"C3D6E", CellKind::wedge, 6, 6},  {"C3D6P", CellKind::wedge, 6, 6},
    {"DC3D6", CellKind::wedge, 6, 6},  {"DC3D6E", CellKind::wedge, 6, 6}, {"AC3D6", CellKind::wedge, 6, 6},
    {"C3D5", CellKind::pyramid, 5, 5}, {"C3D5H", CellKind::pyramid, 5, 5},
    // Second order.
    {"C3D20", CellKind::hex, 20, 20},   {"C3D20R", CellKind::hex, 20, 20},  {"C3D20H", CellKind::hex, 20, 20},
    {"C3D20RH", CellKind::hex, 20, 20}, {"C3D20T", CellKind::hex, 20, 20},  {"C3D20HT", CellKind::hex, 20, 20},
    {"C3D20RT", CellKind::hex, 20, 20}, {"C3D20RHT", CellKind::hex, 20, 20}, {"C3D20E", CellKind::hex, 20, 20},
    {"C3D20RE", CellKind::hex, 20, 20}, {"C3D20P", CellKind::hex, 20, 20},  {"C3D20PH", CellKind::hex, 20, 20},
    {"C3D20RP", CellKind::hex, 20, 20}, {"C3D20RPH", CellKind::hex, 20, 20}, {"DC3D20", CellKind::hex, 20, 20},
    {"DC3D20E", CellKind::hex, 20, 20}, {"AC3D20", CellKind::hex, 20, 20},
    {"C3D27", CellKind::hex, 21, 27},   {"C3D27H", CellKind::hex, 21, 27},  {"C3D27R", CellKind::hex, 21, 27},
    {"C3D27RH", CellKind::hex, 21, 27},
    {"C3D10", CellKind::tet, 10, 10},    {"C3D10H", CellKind::tet, 10, 10},   {"C3D10HS", CellKind::tet, 10, 10},
    {"C3D10I", CellKind::tet, 10, 10},   {"C3D10M", CellKind::tet, 10, 10},   {"C3D10MH", CellKind::tet, 10, 10},
    {"C3D10MT", CellKind::tet, 10, 10},  {"C3D10MHT", CellKind::tet, 10, 10}, {"C3D10E", CellKind::tet, 10, 10},
    {"C3D10MP", CellKind::tet, 10, 10},  {"C3D10MPH", CellKind::tet, 10, 10}, {"DC3D10", CellKind::tet, 10, 10},
    {"DC3D10E", CellKind::tet, 10, 10},  {"AC3D10", CellKind::tet, 10, 10},
    {"C3D15", CellKind::wedge, 15, 15},  {"C3D15H", CellKind::wedge, 15, 15}, {"C3D15E", CellKind::wedge, 15, 15},
    {"C3D15V", CellKind::wedge, 15, 18}, {"C3D15VH", CellKind::wedge, 15, 18}, {"DC3D15", CellKind::wedge, 15, 15},
    {"DC3D15E", CellKind::wedge, 15, 15}, {"AC3D15", CellKind::wedge, 15, 15},
};

// The surface element types read (a file without volume elements is a
// surface mesh), from the Abaqus Analysis User's Guide's "Plane stress",
// "Plane strain", "Conventional shell", "Membrane", "Surface" and "Rigid"
// element libraries and their heat-transfer (DC2D, DS) and coupled
// temperature-displacement (T) variants: 4-node quadrilaterals (S4, S4R,
// CPS4, CPE4, ...), 3-node triangles (S3, S3R, CPS3, CPE3, ...), and the
// second-order ones by their corners (listed first): 8-node quadrilaterals
// (S8R, CPS8, CPE8, ...), 9-node S9R5, 6-node triangles (STRI65, CPS6,
// CPE6, ...). Axisymmetric elements (CAX) are left out: their plane is a
// section of a body of revolution, not the mesh.
constexpr ElementType kSurfaceTypes[] = {
    {"S4", CellKind::quad, 4, 4},      {"S4R", CellKind::quad, 4, 4},     {"S4R5", CellKind::quad, 4, 4},
    {"S4RS", CellKind::quad, 4, 4},    {"S4RSW", CellKind::quad, 4, 4},   {"S4T", CellKind::quad, 4, 4},
    {"S4RT", CellKind::quad, 4, 4},    {"M3D4", CellKind::quad, 4, 4},    {"M3D4R", CellKind::quad, 4, 4},
    {"R3D4", CellKind::quad, 4, 4},    {"SFM3D4", CellKind::quad, 4, 4},  {"SFM3D4R", CellKind::quad, 4, 4},
    {"DS4", CellKind::quad, 4, 4},     {"CPS4", CellKind::quad, 4, 4},    {"CPS4R", CellKind::quad, 4, 4},
    {"CPS4I", CellKind::quad, 4, 4},   {"CPS4T", CellKind::quad, 4, 4},   {"CPS4RT", CellKind::quad, 4, 4},
    {"CPE4", CellKind::quad, 4, 4},    {"CPE4R", CellKind::quad, 4, 4},   {"CPE4I", CellKind::quad, 4, 4},
    {"CPE4H", CellKind::quad, 4, 4},   {"CPE4RH", CellKind::quad, 4, 4},  {"CPE4IH", CellKind::quad, 4, 4},
    {"CPE4T", CellKind::quad, 4, 4},   {"CPE4RT", CellKind::quad, 4, 4},  {"CPEG4", CellKind::quad, 4, 4},
    {"CPEG4R", CellKind::quad, 4, 4},  {"DC2D4", CellKind::quad, 4, 4},
    {"S3", CellKind::triangle, 3, 3},  {"S3R", CellKind::triangle, 3, 3}, {"S3RS", CellKind::triangle, 3, 3},
    {"S3T", CellKind::triangle, 3, 3}, {"S3RT", CellKind::triangle, 3, 3}, {"STRI3", CellKind::triangle, 3, 3},
    {"M3D3", CellKind::triangle, 3, 3}, {"R3D3", CellKind::triangle, 3, 3}, {"SFM3D3", CellKind::triangle, 3, 3},
    {"DS3", CellKind::triangle, 3, 3}, {"CPS3", CellKind::triangle, 3, 3}, {"CPS3T", CellKind::triangle, 3, 3},
    {"CPE3", CellKind::triangle, 3, 3}, {"CPE3H", CellKind::triangle, 3, 3}, {"CPE3T", CellKind::triangle, 3, 3},
    {"CPEG3", CellKind::triangle, 3, 3}, {"DC2D3", CellKind::triangle, 3, 3},
    {"S8R", CellKind::quad, 8, 8},     {"S8R5", CellKind::quad, 8, 8},    {"S8RT", CellKind::quad, 8, 8},
    {"M3D8", CellKind::quad, 8, 8},    {"M3D8R", CellKind::quad, 8, 8},   {"CPS8", CellKind::quad, 8, 8},
    {"CPS8R", CellKind::quad, 8, 8},   {"CPE8", CellKind::quad, 8, 8},    {"CPE8R", CellKind::quad, 8, 8},
    {"CPE8H", CellKind::quad, 8, 8},   {"CPE8RH", CellKind::quad, 8, 8},  {"DC2D8", CellKind::quad, 8, 8},
    {"S9R5", CellKind::quad, 9, 9},    {"M3D9", CellKind::quad, 9, 9},    {"M3D9R", CellKind::quad, 9, 9},
    {"STRI65", CellKind::triangle, 6, 6}, {"M3D6", CellKind::triangle, 6, 6}, {"CPS6", CellKind::triangle, 6, 6},
    {"CPS6M", CellKind::triangle, 6, 6}, {"CPE6", CellKind::triangle, 6, 6}, {"CPE6M", CellKind::triangle, 6, 6},
    {"CPE6H", CellKind::triangle, 6, 6}, {"DC2D6", CellKind::triangle, 6, 6},
};
// clang-format on

// The type of that name, volume or surface; nullptr for every other type.
const ElementType* find_element_type(std::string_view name) {
  for (const ElementType& type : kVolumeTypes)
    if (type.name == name) return &type;
  for (const ElementType& type : kSurfaceTypes)
    if (type.name == name) return &type;
  return nullptr;
}

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
    enum class Block { kNone, kNodes, kVolumeElements, kOtherElements, kSkipped };
    Block block = Block::kNone;
    std::string element_type;
    const ElementType* volume = nullptr;
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
          volume = find_element_type(element_type);
          block = volume != nullptr ? Block::kVolumeElements : Block::kOtherElements;
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
        case Block::kVolumeElements:
          read_cell(*volume, line);
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

  // One element of a volume type. Abaqus lists a C3D6 wedge's first
  // triangle with its normal towards the second (face 1 = 1-2-3 faces
  // inward, as a C3D8's face 1 = 1-2-3-4): permuted to VTK's order. Every
  // node must be defined; the corners, listed first, are kept.
  void read_cell(const ElementType& type, std::string_view line) {
    const CellKind kind = type.kind;
    const int n = cell_kind_num_corners(kind);
    const std::int64_t first_line = line_number_;
    std::vector<std::string_view> fields = split(line);
    // A record continues while its line ends with a comma; the strings stay
    // views into bytes_.
    while (trim(fields.back()).empty() && fields.size() < static_cast<std::size_t>(type.max_nodes) + 2) {
      fields.pop_back();
      if (!next_line()) fail(first_line, "unexpected end of file in an element continued on the next line");
      const std::vector<std::string_view> more = split(trim(line_));
      fields.insert(fields.end(), more.begin(), more.end());
    }
    if (!fields.empty() && trim(fields.back()).empty()) fields.pop_back();
    if (fields.size() < static_cast<std::size_t>(type.min_nodes) + 1 ||
        fields.size() > static_cast<std::size_t>(type.max_nodes) + 1)
      fail(line_number_, "expected an element id and " + std::to_string(type.min_nodes) +
                             (type.max_nodes > type.min_nodes ? " to " + std::to_string(type.max_nodes) : "") +
                             " node ids, got " + std::to_string(fields.size()) + " fields" +
                             (type.min_nodes > n ? " (" + std::string(type.name) + ")" : ""));
    const auto id = parse_number<std::int64_t>(fields[0], "an element id");
    if (cell_kind_dimension(kind) == 2) return read_surface_cell(type, id, fields);
    std::array<Index, 8> corners{};
    std::array<std::int64_t, 8> nodes{};
    for (std::size_t j = 0; j + 1 < fields.size(); ++j) {
      const auto node = parse_number<std::int64_t>(fields[j + 1], "a node id");
      const auto it = index_of_id_.find(node);
      if (it == index_of_id_.end())
        fail(line_number_, "node " + std::to_string(node) + " is not defined (element " + std::to_string(id) + ")");
      if (j < static_cast<std::size_t>(n)) {
        corners[j] = it->second;
        nodes[j] = node;
      }
    }
    if (type.min_nodes > n) notes_.add_higher_order(std::string(type.name));
    const int* to_vtk = kind == CellKind::wedge ? detail::kWedgeFlippedToVtk.data() : nullptr;
    if (const int j = detail::first_repeated(corners.data(), n); j >= 0) {
      if (kind == CellKind::hex && detail::append_collapsed_hex(mesh_, corners.data(), nullptr, id, notes_)) return;
      fail(line_number_, "node " + std::to_string(nodes[static_cast<std::size_t>(j)]) + " repeated (element " +
                             std::to_string(id) + ")");
    }
    detail::append_cell(mesh_, kind, corners.data(), to_vtk, id);
  }

  // A surface element (kSurfaceTypes) into the surface blocks beside the
  // volume ones (detail::SurfaceCells: where = its line).
  void read_surface_cell(const ElementType& type, std::int64_t id, const std::vector<std::string_view>& fields) {
    ++surface_.types[std::string(type.name)];
    const int n = cell_kind_num_corners(type.kind);
    std::array<Index, 4> corners{};
    for (std::size_t j = 0; j + 1 < fields.size(); ++j) {
      const auto node = parse_number<std::int64_t>(fields[j + 1], "a node id");
      const auto it = index_of_id_.find(node);
      if (it == index_of_id_.end()) {
        surface_.set_bad(line_number_, 0,
                         "node " + std::to_string(node) + " is not defined (element " + std::to_string(id) + ")");
        return;
      }
      if (j < static_cast<std::size_t>(n)) corners[j] = it->second;
    }
    if (type.min_nodes > n) surface_.higher_order.add_higher_order(std::string(type.name));
    surface_.notes.append(mesh_, type.kind, corners.data(), id);
  }

  LoadedMesh build() {
    std::int64_t num_volume_dropped = 0;
    const bool is_surface =
        detail::keep_dimension(mesh_, limits_.dimension, skipped_by_type_, surface_.types, num_volume_dropped);
    if (is_surface && surface_.has_bad()) fail(surface_.bad_where, surface_.bad_message);
    const SkippedCells skipped(skipped_by_type_);
    if (is_surface && detail::num_surface_cells(mesh_) == 0)
      fail(0, surface_.notes.no_cells_message() +
                  (skipped.count > 0 ? ": " + skipped.counted("element") : std::string()));
    if (!is_surface && num_volume_cells(mesh_) == 0)
      fail(0, "no volume elements (*ELEMENT, TYPE=C3D8, C3D8R, C3D4, C3D6, C3D5 ...)" +
                  (skipped.count > 0 ? ": " + skipped.counted("element") : std::string()));
    // Abaqus declares no counts: the budget is checked once the file is read
    // (what reading allocates is bounded by the file's size), before the analysis.
    check_mesh_memory(limits_, name_, 0, bytes_.size(), static_cast<std::int64_t>(points_.size()),
                      is_surface ? detail::num_surface_cells(mesh_) : num_volume_cells(mesh_));
    LoadedMesh loaded;
    loaded.format = "abaqus";
    if (num_volume_dropped > 0)
      loaded.warnings.push_back(detail::volume_dropped_warning(name_, num_volume_dropped, "element"));
    if (skipped.count > 0) loaded.warnings.push_back(skipped.warning(name_, "element"));
    if (is_surface)
      surface_.append_warnings(name_, "element", loaded.warnings);
    else
      notes_.append_warnings(name_, "element", loaded.warnings);
    mesh_.points = std::move(points_);
    loaded.mesh = std::move(mesh_);
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
  Mesh mesh_;  // the cell blocks (points_ are moved in at the end)
  detail::SurfaceCells<std::string> surface_;
  std::map<std::string, std::int64_t> skipped_by_type_;
  detail::CellNotes notes_;
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
