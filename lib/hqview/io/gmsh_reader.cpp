#include "hqview/io/gmsh_reader.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/io/cell_reading.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/io/text_scanner.h"

namespace hq {
namespace {

using detail::quote;
using detail::TextScanner;

// The element types read (GmshDefines.h; the manual's "MSH file
// format"), the kind each is read as and its node count: the linear ones
// (MSH_TET_4, MSH_HEX_8, MSH_PRI_6, MSH_PYR_5), and the complete
// higher-order ones by their corner nodes, which Gmsh lists first in the
// linear element's order (vertices, then edge, face and volume nodes):
// tetrahedra of order 2 to 10 (MSH_TET_10 ... MSH_TET_286), hexahedra of
// order 2 to 9 and the 20-node serendipity one (MSH_HEX_27, MSH_HEX_20,
// MSH_HEX_64 ... MSH_HEX_1000), prisms (MSH_PRI_18, MSH_PRI_15, MSH_PRI_40
// ... MSH_PRI_550) and pyramids (MSH_PYR_14, MSH_PYR_13, MSH_PYR_30 ...
// MSH_PYR_385). The incomplete (serendipity) types of order 3 and more are
// not read: their node counts changed between Gmsh versions.
struct GmshCellType {
  int type;
  CellKind kind;
  int num_nodes;
};
// clang-format off
constexpr GmshCellType kGmshCellTypes[] = {
    {4, CellKind::tet, 4}, {5, CellKind::hex, 8}, {6, CellKind::wedge, 6}, {7, CellKind::pyramid, 5},
    {11, CellKind::tet, 10}, {29, CellKind::tet, 20}, {30, CellKind::tet, 35}, {31, CellKind::tet, 56},
    {71, CellKind::tet, 84}, {72, CellKind::tet, 120}, {73, CellKind::tet, 165}, {74, CellKind::tet, 220},
    {75, CellKind::tet, 286},
    {12, CellKind::hex, 27}, {17, CellKind::hex, 20}, {92, CellKind::hex, 64}, {93, CellKind::hex, 125},
    {94, CellKind::hex, 216}, {95, CellKind::hex, 343}, {96, CellKind::hex, 512}, {97, CellKind::hex, 729},
    {98, CellKind::hex, 1000},
    {13, CellKind::wedge, 18}, {18, CellKind::wedge, 15}, {90, CellKind::wedge, 40}, {91, CellKind::wedge, 75},
    {106, CellKind::wedge, 126}, {107, CellKind::wedge, 196}, {108, CellKind::wedge, 288},
    {109, CellKind::wedge, 405}, {110, CellKind::wedge, 550},
    {14, CellKind::pyramid, 14}, {19, CellKind::pyramid, 13}, {118, CellKind::pyramid, 30},
    {119, CellKind::pyramid, 55}, {120, CellKind::pyramid, 91}, {121, CellKind::pyramid, 140},
    {122, CellKind::pyramid, 204}, {123, CellKind::pyramid, 285}, {124, CellKind::pyramid, 385},
    // Surface elements (a file without volume elements is a surface mesh):
    // triangles 2 (MSH_TRI_3), 9 (6 nodes), 20 (9), 21 (10); quadrangles 3
    // (MSH_QUA_4), 10 (9 nodes), 16 (8), by their corners, listed first.
    {2, CellKind::triangle, 3}, {9, CellKind::triangle, 6}, {20, CellKind::triangle, 9}, {21, CellKind::triangle, 10},
    {3, CellKind::quad, 4}, {10, CellKind::quad, 9}, {16, CellKind::quad, 8},
};
// clang-format on

// The dimension of Gmsh's element types of dimension 0-2, -1 for the others:
// points (15), lines (1, 8, 26-28), triangles (2, 9, 20-25) and quads (3,
// 10, 16, 36-41). Gmsh writes them for the geometric entities (the points
// and curves of a surface mesh, the surfaces of a volume mesh) beside the
// cells: below the mesh's dimension they are skipped as a note.
int gmsh_type_dimension(std::int64_t type) {
  switch (type) {
    case 15:
      return 0;
    case 1: case 8: case 26: case 27: case 28:
      return 1;
    case 2: case 3: case 9: case 10: case 16: case 20: case 21: case 22: case 23: case 24: case 25:
    case 36: case 37: case 38: case 39: case 40: case 41:
      return 2;
    default:
      return -1;
  }
}

const GmshCellType* gmsh_cell_type(std::int64_t type) {
  for (const GmshCellType& entry : kGmshCellTypes)
    if (entry.type == type) return &entry;
  return nullptr;
}

// Nodes per Gmsh element type (gmsh's GmshDefines.h / the manual's list);
// needed to step over binary elements. 0: unknown.
// clang-format off
int gmsh_node_count(std::int64_t type) {
  if (const GmshCellType* volume = gmsh_cell_type(type)) return volume->num_nodes;
  switch (type) {
    case 1: return 2;    case 2: return 3;    case 3: return 4;    case 8: return 3;
    case 9: return 6;    case 10: return 9;   case 15: return 1;   case 16: return 8;
    case 20: return 9;   case 21: return 10;  case 22: return 12;  case 23: return 15;
    case 24: return 15;  case 25: return 21;  case 26: return 4;   case 27: return 5;
    case 28: return 6;
    default: return 0;
  }
}
// clang-format on

std::string non_finite_text(double value) { return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf"); }

class GmshParser {
 public:
  GmshParser(std::string_view bytes, const std::string& name, const ReadLimits& limits)
      : s_(bytes, name, /*has_hash_comments=*/false), limits_(limits), file_bytes_(bytes.size()) {}

  LoadedMesh parse() {
    read_format();
    while (nodes_line_ == 0 || elements_line_ == 0) {
      if (!s_.skip_space())
        s_.fail(std::string("unexpected end of file: no ") + (nodes_line_ == 0 ? "$Nodes" : "$Elements") + " section");
      const std::int64_t line = s_.line();
      const std::string_view keyword = s_.read_token();
      if (keyword == "$Nodes") {
        if (nodes_line_ != 0)
          s_.fail_at(line, "second $Nodes section (first at line " + std::to_string(nodes_line_) + ")");
        nodes_line_ = line;
        end_keyword_line();
        is_v4_ ? read_nodes_v4() : read_nodes_v2();
        expect_end("$EndNodes");
      } else if (keyword == "$Elements") {
        if (nodes_line_ == 0) s_.fail_at(line, "$Elements before $Nodes");
        elements_line_ = line;
        end_keyword_line();
        is_v4_ ? read_elements_v4() : read_elements_v2();
        expect_end("$EndElements");
      } else if (keyword.size() > 1 && keyword[0] == '$') {
        skip_section(keyword, line);
      } else {
        s_.fail_at(line, "expected a section such as $Nodes, got " + quote(keyword));
      }
    }
    return build();
  }

 private:
  // "$MeshFormat\n<version> <file-type> <data-size>\n[binary int 1\n]$EndMeshFormat"
  void read_format() {
    if (!s_.skip_space()) s_.fail("empty file, expected $MeshFormat");
    const std::string_view magic = s_.read_token();
    if (magic != "$MeshFormat") s_.fail("expected $MeshFormat, got " + quote(magic));
    if (!s_.skip_space()) s_.fail("unexpected end of file, expected the MSH version");
    const std::string_view version = s_.read_token();
    if (version == "2" || version == "2.0" || version == "2.1" || version == "2.2") {
      is_v4_ = false;
    } else if (version == "4.1") {
      is_v4_ = true;
    } else {
      s_.fail("unsupported MSH version " + quote(version) + " (expected 2.2 or 4.1)");
    }
    version_ = version == "4.1" ? "4.1" : "2.2";
    const std::int64_t file_type = read_int("the file type");
    if (file_type != 0 && file_type != 1)
      s_.fail("file type " + std::to_string(file_type) + ", expected 0 (ASCII) or 1 (binary)");
    binary_ = file_type == 1;
    const std::int64_t data_size = read_int("the data size");
    if (data_size != 8 && data_size != 4) s_.fail("data size " + std::to_string(data_size) + ", expected 8 (or 4)");
    size_t_size_ = static_cast<int>(data_size);
    if (binary_) {
      if (!s_.finish_line()) s_.fail("unexpected " + quote(s_.peek_token()) + " after the MSH format line");
      if (s_.remaining() < 4) s_.fail("unexpected end of file in the binary format check");
      const std::string_view one = s_.read_bytes(4);
      std::uint32_t value;
      std::memcpy(&value, one.data(), 4);
      if (value == 1) {
        swap_ = false;
      } else if (value == 0x01000000u) {
        swap_ = true;
      } else {
        s_.fail("binary format check: expected the integer 1, got bytes " + quote(one));
      }
    }
    expect_end("$EndMeshFormat");
  }

  std::int64_t read_int(const std::string& what) {
    if (!s_.skip_space()) s_.fail("unexpected end of file, expected " + what);
    std::int64_t value = 0;
    if (!s_.read_int(value)) s_.fail("expected " + what + ", got " + quote(s_.peek_token()));
    return value;
  }
  double read_double(const std::string& what) {
    if (!s_.skip_space()) s_.fail("unexpected end of file, expected " + what);
    double value = 0;
    if (!s_.read_double(value)) s_.fail("expected " + what + ", got " + quote(s_.peek_token()));
    return value;
  }
  void end_keyword_line() {
    if (!s_.finish_line()) s_.fail("unexpected " + quote(s_.peek_token()) + " after the section keyword");
  }
  void expect_end(std::string_view end) {
    if (!s_.skip_space()) s_.fail("unexpected end of file, expected " + std::string(end));
    const std::string_view token = s_.read_token();
    if (token != end) s_.fail("expected " + std::string(end) + ", got " + quote(token));
  }
  void skip_section(std::string_view keyword, std::int64_t line) {
    const std::string end = "$End" + std::string(keyword.substr(1));
    while (true) {
      if (s_.at_end()) s_.fail_at(line, "unexpected end of file: " + std::string(keyword) + " without " + end);
      const std::string_view text = s_.read_line();
      std::size_t i = 0;
      while (i < text.size() && detail::is_blank(text[i])) ++i;
      if (text.substr(i).starts_with(end)) return;
    }
  }

  void check_count(std::int64_t n, const std::string& what, std::int64_t limit = kMaxIndexCount) {
    if (n < 0) s_.fail("negative " + what + " " + std::to_string(n));
    if (n > limit) s_.fail(what + " " + std::to_string(n) + " exceeds the limit of " + std::to_string(limit));
  }
  // Before allocating: n entries of min_bytes each must fit in the rest.
  void check_room(std::int64_t n, std::int64_t min_bytes, const std::string& what) {
    if (detail::exceeds_remaining(n, min_bytes, s_.remaining(), !binary_))
      s_.fail(std::to_string(n) + " " + what + " cannot fit in the " + std::to_string(s_.remaining()) +
              " bytes left in the file");
  }

  // --- binary values -------------------------------------------------------
  std::uint64_t load(const char* p, int size) const {
    std::uint64_t v = 0;
    for (int i = 0; i < size; ++i) {
      const auto byte = static_cast<std::uint64_t>(static_cast<unsigned char>(p[swap_ ? i : size - 1 - i]));
      v = (v << 8) | byte;
    }
    return v;
  }
  [[noreturn]] void fail_binary(std::int64_t section_line, const std::string& message, std::size_t offset) const {
    s_.fail_at(section_line, message + " (byte offset " + std::to_string(offset) + ")");
  }
  std::string_view take(std::size_t n, std::int64_t section_line) {
    if (s_.remaining() < n) fail_binary(section_line, "unexpected end of file in binary data", s_.offset());
    return s_.read_bytes(n);
  }
  std::int64_t binary_int(std::int64_t section_line) {  // a C int (4 bytes)
    const std::uint64_t bits = load(take(4, section_line).data(), 4);
    return static_cast<std::int32_t>(static_cast<std::uint32_t>(bits));
  }
  std::int64_t binary_size(std::int64_t section_line) {  // a size_t (data size)
    const std::size_t at = s_.offset();
    const std::uint64_t bits = load(take(static_cast<std::size_t>(size_t_size_), section_line).data(), size_t_size_);
    if (bits > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      fail_binary(section_line, "value " + std::to_string(bits) + " out of range", at);
    return static_cast<std::int64_t>(bits);
  }
  double binary_double(std::int64_t section_line) {
    return std::bit_cast<double>(load(take(8, section_line).data(), 8));
  }

  // --- nodes ---------------------------------------------------------------
  void add_node(std::int64_t tag, const double xyz[3], std::int64_t line, std::size_t offset) {
    const auto fail = [&](const std::string& message) {
      if (binary_) fail_binary(nodes_line_, message, offset);
      s_.fail_at(line, message);
    };
    if (tag < 0) fail("negative node tag " + std::to_string(tag));
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(xyz[k]))
        fail("non-finite coordinate " + non_finite_text(xyz[k]) + " (node " + std::to_string(tag) + ")");
    const auto [it, inserted] = index_of_tag_.emplace(tag, static_cast<Index>(points_.size()));
    if (!inserted) fail("node tag " + std::to_string(tag) + " defined twice");
    points_.push_back({xyz[0], xyz[1], xyz[2]});
  }

  void read_nodes_v2() {
    const std::int64_t n = read_int("the number of nodes");
    check_count(n, "number of nodes");
    check_room(n, binary_ ? 28 : 8, "nodes");
    check_mesh_memory(limits_, s_.name(), s_.line(), file_bytes_, n, -1);
    if (!s_.finish_line()) s_.fail("unexpected " + quote(s_.peek_token()) + " after the number of nodes");
    points_.reserve(static_cast<std::size_t>(n));
    index_of_tag_.reserve(static_cast<std::size_t>(n));
    for (std::int64_t i = 0; i < n; ++i) {
      double xyz[3];
      if (binary_) {
        const std::size_t offset = s_.offset();
        const std::int64_t tag = binary_int(nodes_line_);
        for (double& c : xyz) c = binary_double(nodes_line_);
        add_node(tag, xyz, 0, offset);
      } else {
        const std::int64_t tag = read_int("a node tag");
        const std::int64_t line = s_.line();
        for (double& c : xyz) c = read_double("a coordinate");
        add_node(tag, xyz, line, 0);
      }
    }
  }

  void read_nodes_v4() {
    std::int64_t header[4];
    for (std::int64_t& h : header) h = binary_ ? binary_size(nodes_line_) : read_int("a $Nodes header count");
    const std::int64_t num_blocks = header[0];
    const std::int64_t n = header[1];
    check_count(num_blocks, "number of node blocks");
    check_count(n, "number of nodes");
    check_room(n, binary_ ? 8 + 24 : 8, "nodes");
    check_mesh_memory(limits_, s_.name(), nodes_line_, file_bytes_, n, -1);
    check_room(num_blocks, binary_ ? 12 + size_t_size_ : 8, "node blocks");
    points_.reserve(static_cast<std::size_t>(n));
    index_of_tag_.reserve(static_cast<std::size_t>(n));
    std::int64_t total = 0;
    std::vector<std::int64_t> tags;
    std::vector<std::size_t> tag_offsets;
    std::vector<std::int64_t> tag_lines;
    for (std::int64_t b = 0; b < num_blocks; ++b) {
      std::int64_t dim, parametric, count;
      if (binary_) {
        dim = binary_int(nodes_line_);
        binary_int(nodes_line_);  // entity tag
        parametric = binary_int(nodes_line_);
        count = binary_size(nodes_line_);
      } else {
        dim = read_int("an entity dimension");
        read_int("an entity tag");
        parametric = read_int("the parametric flag");
        count = read_int("the number of nodes in the block");
      }
      if (dim < 0 || dim > 3)
        s_.fail("entity dimension " + std::to_string(dim) + " (node block " + std::to_string(b) + ")");
      if (parametric != 0 && parametric != 1)
        s_.fail("parametric flag " + std::to_string(parametric) + ", expected 0 or 1");
      if (count < 0 || count > n - total)
        s_.fail("node block " + std::to_string(b) + " claims " + std::to_string(count) + " nodes, " +
                std::to_string(n - total) + " are left of the " + std::to_string(n) + " in the header");
      total += count;
      const int num_values = 3 + (parametric == 1 ? static_cast<int>(dim) : 0);
      tags.assign(static_cast<std::size_t>(count), 0);
      tag_offsets.assign(static_cast<std::size_t>(count), 0);
      tag_lines.assign(static_cast<std::size_t>(count), 0);
      for (std::int64_t i = 0; i < count; ++i) {
        tag_offsets[static_cast<std::size_t>(i)] = s_.offset();
        tags[static_cast<std::size_t>(i)] = binary_ ? binary_size(nodes_line_) : read_int("a node tag");
        tag_lines[static_cast<std::size_t>(i)] = s_.line();
      }
      for (std::int64_t i = 0; i < count; ++i) {
        double values[6];
        const std::int64_t line = s_.line() + 1;
        for (int k = 0; k < num_values; ++k)
          values[k] = binary_ ? binary_double(nodes_line_) : read_double("a coordinate");
        add_node(tags[static_cast<std::size_t>(i)], values, binary_ ? 0 : std::max(line, s_.line()),
                 tag_offsets[static_cast<std::size_t>(i)]);
      }
    }
    if (total != n)
      s_.fail("the node blocks hold " + std::to_string(total) + " nodes, the header says " + std::to_string(n));
  }

  // --- elements ------------------------------------------------------------
  // One volume element given its node tags in Gmsh's order (n of them, the
  // type's count); where = line (ASCII) or byte offset (binary). Every tag
  // must be defined; the corners, listed first, are kept. Gmsh's prism
  // lists its first triangle with the normal towards the second: permuted
  // to VTK's order.
  void add_cell(const GmshCellType& volume, std::int64_t element_tag, const std::int64_t* tags,
                std::int64_t where) {
    const auto fail = [&](const std::string& message) {
      if (binary_) fail_binary(elements_line_, message, static_cast<std::size_t>(where));
      s_.fail_at(where, message);
    };
    const CellKind kind = volume.kind;
    if (cell_kind_dimension(kind) == 2) return add_surface_cell(volume, element_tag, tags, where);
    const int n = cell_kind_num_corners(kind);
    std::array<Index, 8> corners{};
    for (int j = 0; j < volume.num_nodes; ++j) {
      const auto it = index_of_tag_.find(tags[j]);
      if (it == index_of_tag_.end())
        fail("node tag " + std::to_string(tags[j]) + " is not defined (element " + std::to_string(element_tag) + ")");
      if (j < n) corners[static_cast<std::size_t>(j)] = it->second;
    }
    if (volume.num_nodes > n) notes_.add_higher_order(std::to_string(volume.type));
    const int* to_vtk = kind == CellKind::wedge ? detail::kWedgeFlippedToVtk.data() : nullptr;
    if (const int j = detail::first_repeated(corners.data(), n); j >= 0) {
      if (kind == CellKind::hex && detail::append_collapsed_hex(mesh_, corners.data(), nullptr, element_tag, notes_))
        return;
      fail("node tag " + std::to_string(tags[j]) + " repeated (element " + std::to_string(element_tag) + ")");
    }
    detail::append_cell(mesh_, kind, corners.data(), to_vtk, element_tag);
  }

  // A surface element into the surface blocks beside the volume ones
  // (detail::SurfaceCells: where = its line or byte offset).
  void add_surface_cell(const GmshCellType& surface, std::int64_t element_tag, const std::int64_t* tags,
                        std::int64_t where) {
    ++surface_.types[surface.type];
    const int n = cell_kind_num_corners(surface.kind);
    std::array<Index, 4> corners{};
    for (int j = 0; j < surface.num_nodes; ++j) {
      const auto it = index_of_tag_.find(tags[j]);
      if (it == index_of_tag_.end()) {
        surface_.set_bad(where, 0, "node tag " + std::to_string(tags[j]) + " is not defined (element " +
                                       std::to_string(element_tag) + ")");
        return;
      }
      if (j < n) corners[static_cast<std::size_t>(j)] = it->second;
    }
    if (surface.num_nodes > n) surface_.higher_order.add_higher_order(std::to_string(surface.type));
    surface_.notes.append(mesh_, surface.kind, corners.data(), element_tag);
  }

  void read_elements_v2() {
    const std::int64_t m = read_int("the number of elements");
    check_count(m, "number of elements", std::numeric_limits<std::int64_t>::max());
    check_room(m, binary_ ? 12 : 8, "elements");
    check_mesh_memory(limits_, s_.name(), s_.line(), file_bytes_, static_cast<std::int64_t>(points_.size()), m,
                      "element");
    if (!s_.finish_line()) s_.fail("unexpected " + quote(s_.peek_token()) + " after the number of elements");
    if (binary_) {
      std::int64_t done = 0;
      while (done < m) {
        const std::size_t header_offset = s_.offset();
        const std::int64_t type = binary_int(elements_line_);
        const std::int64_t follow = binary_int(elements_line_);
        const std::int64_t num_tags = binary_int(elements_line_);
        const int num_nodes = gmsh_node_count(type);
        if (num_nodes == 0) fail_binary(elements_line_, "unknown element type " + std::to_string(type), header_offset);
        if (follow <= 0 || follow > m - done)
          fail_binary(
              elements_line_,
              "element block claims " + std::to_string(follow) + " elements, " + std::to_string(m - done) + " are left",
              header_offset);
        if (num_tags < 0 || num_tags > 1000)
          fail_binary(elements_line_, "element block claims " + std::to_string(num_tags) + " tags", header_offset);
        const std::int64_t ints = 1 + num_tags + num_nodes;
        if (detail::exceeds_remaining(follow, 4 * ints, s_.remaining(), false))
          fail_binary(elements_line_, "element block of " + std::to_string(follow) + " elements truncated",
                      header_offset);
        for (std::int64_t e = 0; e < follow; ++e) {
          const std::size_t offset = s_.offset();
          const std::int64_t tag = binary_int(elements_line_);
          for (std::int64_t t = 0; t < num_tags; ++t) binary_int(elements_line_);
          if (const GmshCellType* volume = gmsh_cell_type(type)) {
            nodes_.resize(static_cast<std::size_t>(num_nodes));
            for (int j = 0; j < num_nodes; ++j) nodes_[static_cast<std::size_t>(j)] = binary_int(elements_line_);
            add_cell(*volume, tag, nodes_.data(), static_cast<std::int64_t>(offset));
          } else {
            s_.read_bytes(static_cast<std::size_t>(4 * num_nodes));
            ++skipped_by_type_[type];
          }
        }
        done += follow;
      }
      return;
    }
    for (std::int64_t e = 0; e < m; ++e) {
      const std::int64_t tag = read_int("an element tag");
      const std::int64_t line = s_.line();
      if (!s_.skip_blank()) s_.fail("expected an element type after element " + std::to_string(tag));
      std::int64_t type = 0;
      if (!s_.read_int(type)) s_.fail("expected an element type, got " + quote(s_.peek_token()));
      std::int64_t num_tags = 0;
      if (!s_.skip_blank() || !s_.read_int(num_tags) || num_tags < 0)
        s_.fail("expected the number of tags of element " + std::to_string(tag));
      const GmshCellType* volume = gmsh_cell_type(type);
      if (volume == nullptr) {
        ++skipped_by_type_[type];
        s_.read_line();
        continue;
      }
      for (std::int64_t t = 0; t < num_tags; ++t) {
        std::int64_t ignored = 0;
        if (!s_.skip_blank() || !s_.read_int(ignored))
          s_.fail("expected " + std::to_string(num_tags) + " tags for element " + std::to_string(tag));
      }
      read_ascii_cell(*volume, tag, line);
    }
  }

  // The node tags of a volume element on the current line, then the end of the line.
  void read_ascii_cell(const GmshCellType& volume, std::int64_t tag, std::int64_t line) {
    const int n = volume.num_nodes;
    const bool is_linear = n == cell_kind_num_corners(volume.kind);
    const std::string what = std::to_string(n) + " node tags for " + detail::cell_kind_noun(volume.kind, 1) + " " +
                             std::to_string(tag) + (is_linear ? "" : " (type " + std::to_string(volume.type) + ")") +
                             ", got ";
    nodes_.resize(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) {
      if (!s_.skip_blank()) s_.fail("expected " + what + std::to_string(j));
      if (!s_.read_int(nodes_[static_cast<std::size_t>(j)]))
        s_.fail("expected a node tag, got " + quote(s_.peek_token()));
    }
    if (s_.skip_blank()) s_.fail("expected " + what + std::to_string(n + s_.count_tokens_on_line()));
    add_cell(volume, tag, nodes_.data(), line);
  }

  void read_elements_v4() {
    std::int64_t header[4];
    for (std::int64_t& h : header) h = binary_ ? binary_size(elements_line_) : read_int("an $Elements header count");
    const std::int64_t num_blocks = header[0];
    const std::int64_t m = header[1];
    check_count(num_blocks, "number of element blocks", std::numeric_limits<std::int64_t>::max());
    check_count(m, "number of elements", std::numeric_limits<std::int64_t>::max());
    check_room(m, binary_ ? 2 * size_t_size_ : 4, "elements");
    check_mesh_memory(limits_, s_.name(), elements_line_, file_bytes_, static_cast<std::int64_t>(points_.size()), m,
                      "element");
    std::int64_t total = 0;
    for (std::int64_t b = 0; b < num_blocks; ++b) {
      const std::size_t header_offset = s_.offset();
      std::int64_t type, count;
      if (binary_) {
        binary_int(elements_line_);  // entity dim
        binary_int(elements_line_);  // entity tag
        type = binary_int(elements_line_);
        count = binary_size(elements_line_);
      } else {
        read_int("an entity dimension");
        read_int("an entity tag");
        type = read_int("an element type");
        count = read_int("the number of elements in the block");
      }
      if (count < 0 || count > m - total) {
        const std::string message = "element block " + std::to_string(b) + " claims " + std::to_string(count) +
                                    " elements, " + std::to_string(m - total) + " are left";
        if (binary_) fail_binary(elements_line_, message, header_offset);
        s_.fail(message);
      }
      total += count;
      const int num_nodes = gmsh_node_count(type);
      if (binary_) {
        if (num_nodes == 0) fail_binary(elements_line_, "unknown element type " + std::to_string(type), header_offset);
        const std::int64_t entry = static_cast<std::int64_t>(size_t_size_) * (1 + num_nodes);
        if (detail::exceeds_remaining(count, entry, s_.remaining(), false))
          fail_binary(elements_line_, "element block of " + std::to_string(count) + " elements truncated",
                      header_offset);
        for (std::int64_t e = 0; e < count; ++e) {
          const std::size_t offset = s_.offset();
          const std::int64_t tag = binary_size(elements_line_);
          if (const GmshCellType* volume = gmsh_cell_type(type)) {
            nodes_.resize(static_cast<std::size_t>(num_nodes));
            for (int j = 0; j < num_nodes; ++j) nodes_[static_cast<std::size_t>(j)] = binary_size(elements_line_);
            add_cell(*volume, tag, nodes_.data(), static_cast<std::int64_t>(offset));
          } else {
            s_.read_bytes(static_cast<std::size_t>(entry - size_t_size_));
          }
        }
        if (gmsh_cell_type(type) == nullptr && count > 0) skipped_by_type_[type] += count;
        continue;
      }
      if (!s_.finish_line()) s_.fail("unexpected " + quote(s_.peek_token()) + " after the element block header");
      for (std::int64_t e = 0; e < count; ++e) {
        const std::int64_t tag = read_int("an element tag");
        const std::int64_t line = s_.line();
        if (const GmshCellType* volume = gmsh_cell_type(type)) {
          read_ascii_cell(*volume, tag, line);
        } else {
          s_.read_line();
          ++skipped_by_type_[type];
        }
      }
    }
    if (total != m)
      s_.fail("the element blocks hold " + std::to_string(total) + " elements, the header says " + std::to_string(m));
  }

  LoadedMesh build() {
    std::int64_t num_volume_dropped = 0;
    const bool is_surface =
        detail::keep_dimension(mesh_, limits_.dimension, skipped_by_type_, surface_.types, num_volume_dropped);
    if (is_surface && surface_.has_bad()) {
      if (binary_) fail_binary(elements_line_, surface_.bad_message, static_cast<std::size_t>(surface_.bad_where));
      s_.fail_at(surface_.bad_where, surface_.bad_message);
    }
    const SkippedCells skipped(skipped_by_type_);
    if (is_surface && detail::num_surface_cells(mesh_) == 0)
      s_.fail_at(elements_line_, surface_.notes.no_cells_message() +
                                     (skipped.count > 0 ? " among " + skipped.counted("element") : std::string()));
    if (!is_surface && num_volume_cells(mesh_) == 0)
      s_.fail_at(elements_line_, "no volume elements (types 4, 5, 6, 7)" +
                                     (skipped.count > 0 ? " among " + skipped.counted("element") : std::string()));
    LoadedMesh loaded;
    loaded.format = "gmsh-" + version_ + (binary_ ? "-binary" : "-ascii");
    if (num_volume_dropped > 0)
      loaded.warnings.push_back(detail::volume_dropped_warning(s_.name(), num_volume_dropped, "element"));
    SkippedCells::report(skipped_by_type_, gmsh_type_dimension, is_surface ? 2 : 3, s_.name(), "element", loaded.notes,
                         loaded.warnings);
    if (is_surface)
      surface_.append_warnings(s_.name(), "element", loaded.warnings);
    else
      notes_.append_warnings(s_.name(), "element", loaded.warnings);
    mesh_.points = std::move(points_);
    loaded.mesh = std::move(mesh_);
    return loaded;
  }

  TextScanner s_;
  ReadLimits limits_;
  std::uint64_t file_bytes_;
  bool is_v4_ = false;
  bool binary_ = false;
  bool swap_ = false;
  int size_t_size_ = 8;
  std::string version_;
  std::int64_t nodes_line_ = 0;
  std::int64_t elements_line_ = 0;
  std::vector<Vec3> points_;
  // Lookups only, never iterated: output order does not depend on hashing.
  std::unordered_map<std::int64_t, Index> index_of_tag_;
  Mesh mesh_;  // the volume blocks (points_ are moved in at the end)
  std::map<std::int64_t, std::int64_t> skipped_by_type_;
  detail::SurfaceCells<std::int64_t> surface_;
  detail::CellNotes notes_;
  std::vector<std::int64_t> nodes_;  // the node tags of the element being read
};

}  // namespace

bool looks_like_gmsh(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && detail::is_space(bytes[i])) ++i;
  return bytes.substr(i).starts_with("$MeshFormat");
}

LoadedMesh read_gmsh(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  return GmshParser(bytes, name, limits).parse();
}

}  // namespace hq
