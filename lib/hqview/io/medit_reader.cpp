#include "hqview/io/medit_reader.h"

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "hqview/core/error.h"
#include "hqview/core/types.h"
#include "hqview/io/cell_reading.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/io/read_limits.h"
#include "hqview/io/text_scanner.h"

namespace hq {
namespace {

using detail::quote;
using detail::TextScanner;

enum class SectionKind { kVersion, kDimension, kEnd, kVertices, kVolume, kTriangles, kQuadrilaterals, kSkipped };

struct SectionInfo {
  std::string_view keyword;
  SectionKind kind;
  int values_per_entry;    // numbers on each entry line
  std::string_view entry;  // what an entry line holds, for messages
  CellKind cell_kind = CellKind::hex;  // kVolume: the block its entries go to
  int num_nodes = 0;                   // kVolume: vertex ids per entry when more than the corners (P2, Q2)
};

// libMeshb's keywords that occur in hex-meshing datasets, plus "Quads"
// (non-standard, written by some tools for boundary quadrilaterals).
constexpr SectionInfo kSections[] = {
    {"MeshVersionFormatted", SectionKind::kVersion, 0, ""},
    {"Dimension", SectionKind::kDimension, 0, ""},
    {"End", SectionKind::kEnd, 0, ""},
    {"Vertices", SectionKind::kVertices, 4, "3 coordinates and a reference"},
    {"Hexahedra", SectionKind::kVolume, 9, "8 vertex ids and a reference", CellKind::hex},
    {"Hexaedra", SectionKind::kVolume, 9, "8 vertex ids and a reference", CellKind::hex},
    {"Triangles", SectionKind::kTriangles, 4, "3 vertex ids and a reference", CellKind::triangle},
    {"Quadrilaterals", SectionKind::kQuadrilaterals, 5, "4 vertex ids and a reference", CellKind::quad},
    {"Quads", SectionKind::kQuadrilaterals, 5, "4 vertex ids and a reference", CellKind::quad},
    {"Edges", SectionKind::kSkipped, 3, "2 vertex ids and a reference"},
    {"Corners", SectionKind::kSkipped, 1, "a vertex id"},
    {"RequiredVertices", SectionKind::kSkipped, 1, "a vertex id"},
    {"Ridges", SectionKind::kSkipped, 1, "an edge id"},
    {"RequiredEdges", SectionKind::kSkipped, 1, "an edge id"},
    {"RequiredTriangles", SectionKind::kSkipped, 1, "a triangle id"},
    {"RequiredQuadrilaterals", SectionKind::kSkipped, 1, "a quadrilateral id"},
    {"Tetrahedra", SectionKind::kVolume, 5, "4 vertex ids and a reference", CellKind::tet},
    {"Prisms", SectionKind::kVolume, 7, "6 vertex ids and a reference", CellKind::wedge},
    {"Pyramids", SectionKind::kVolume, 6, "5 vertex ids and a reference", CellKind::pyramid},
    // Second-order cells (libMeshb; Gmsh writes TetrahedraP2), read by their
    // corners, which come first as Gmsh and the INRIA tools write them.
    {"TetrahedraP2", SectionKind::kVolume, 11, "10 vertex ids and a reference", CellKind::tet, 10},
    {"HexahedraQ2", SectionKind::kVolume, 28, "27 vertex ids and a reference", CellKind::hex, 27},
    {"Normals", SectionKind::kSkipped, 3, "3 components"},
    {"Tangents", SectionKind::kSkipped, 3, "3 components"},
    {"NormalAtVertices", SectionKind::kSkipped, 2, "a vertex id and a normal id"},
    {"NormalAtTriangleVertices", SectionKind::kSkipped, 3, "a triangle id, a corner and a normal id"},
    {"NormalAtQuadrilateralVertices", SectionKind::kSkipped, 3, "a quadrilateral id, a corner and a normal id"},
    {"TangentAtVertices", SectionKind::kSkipped, 2, "a vertex id and a tangent id"},
    {"TangentAtEdges", SectionKind::kSkipped, 3, "an edge id, an end and a tangent id"},
};

// Gmsh (4.8) writes its 27-node (and 20-node) hexahedra in a Hexahedra
// section, 27 (20) vertex ids an entry: read so when the first entry has
// that many values.
constexpr SectionInfo kGmshHexahedra27 = {"Hexahedra", SectionKind::kVolume, 28, "27 vertex ids and a reference",
                                          CellKind::hex, 27};
constexpr SectionInfo kGmshHexahedra20 = {"Hexahedra", SectionKind::kVolume, 21, "20 vertex ids and a reference",
                                          CellKind::hex, 20};

const SectionInfo* find_section(std::string_view keyword) {
  for (const SectionInfo& info : kSections)
    if (detail::iequals(info.keyword, keyword)) return &info;
  return nullptr;
}

bool starts_like_keyword(std::string_view token) {
  const char c = token.empty() ? '\0' : token[0];
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

// Which entry a message is about: " (vertex 3 of 10)". Held as its parts
// and spelt out only when a message is made, not for every entry read.
struct EntryAt {
  std::string_view what;
  std::string_view suffix;  // after `what`: " entry" for skipped sections
  std::int64_t i, n;
  std::string label() const {
    return " (" + std::string(what) + std::string(suffix) + " " + std::to_string(i + 1) + " of " +
           std::to_string(n) + ")";
  }
};

enum class Target { kVolumes, kTriangles };

// Sections of at least this many entries are read in kEntryParts parts in
// parallel (a fixed count, so the parts do not depend on the thread count).
constexpr std::int64_t kParallelEntriesMin = std::int64_t{1} << 15;
constexpr std::int64_t kEntryParts = 8;

struct MeditContent {
  Mesh mesh;                       // points and the volume blocks
  std::int64_t vertices_line = 0;  // 0 = no Vertices section yet
  // Per volume kind: the line of its section (0: none), and whether it was
  // read before Vertices (its ids are range-checked at the end).
  std::array<std::int64_t, kNumCellKinds> volume_line{};
  std::array<bool, kNumCellKinds> volume_needs_range_check{};
  std::array<const SectionInfo*, kNumCellKinds> volume_section{};  // the section read into each block
  detail::CellNotes notes;  // higher-order sections read by their corners
  std::vector<std::array<Index, 3>> triangles;
  std::int64_t triangles_line = 0;
  // Target::kVolumes: the Quadrilaterals (Quads) and Triangles entries as
  // written (1-based ids, unchecked), for a surface mesh; a volume mesh
  // leaves them unread, as boundary faces.
  struct SurfaceEntry {
    std::array<std::int64_t, 4> ids;  // a triangle's first 3
    std::int64_t line;
  };
  std::array<std::vector<SurfaceEntry>, 2> surface_entries;  // quadrilaterals, triangles
  std::map<std::string, std::int64_t> surface_sections;      // entries by section keyword
  bool triangles_need_range_check = false;
  std::vector<std::string> warnings;
};

class MeditParser {
 public:
  MeditParser(std::string_view text, const std::string& name, Target target, const ReadLimits& limits = {})
      : s_(text, name, /*has_hash_comments=*/true), target_(target), limits_(limits), file_bytes_(text.size()) {}

  MeditContent parse() {
    read_version();
    while (s_.skip_space()) {
      const std::int64_t keyword_line = s_.line();
      const std::string_view token = s_.read_token();
      const SectionInfo* info = find_section(token);
      if (info == nullptr) {
        skip_unknown_section(token, keyword_line);
        continue;
      }
      switch (info->kind) {
        case SectionKind::kEnd:
          return finish();
        case SectionKind::kVersion:
          s_.fail_at(keyword_line, "second MeshVersionFormatted keyword");
        case SectionKind::kDimension: {
          const std::int64_t dimension = read_value("Dimension", "the dimension");
          if (dimension != 3)
            s_.fail_at(keyword_line, "unsupported Dimension " + std::to_string(dimension) + " (expected 3)");
          break;
        }
        case SectionKind::kVertices:
          read_vertices(*info, keyword_line);
          break;
        case SectionKind::kVolume:
          if (target_ == Target::kVolumes) {
            read_volume_section(info->cell_kind == CellKind::hex ? hexahedra_as_written(*info) : *info, keyword_line);
          } else {
            skip_section(*info);
          }
          break;
        case SectionKind::kQuadrilaterals:
          if (target_ == Target::kVolumes && limits_.dimension != MeshDimension::volume)
            read_surface_section(*info);
          else
            skip_section(*info);
          break;
        case SectionKind::kTriangles:
          if (target_ == Target::kVolumes && limits_.dimension != MeshDimension::volume) {
            read_surface_section(*info);
          } else if (target_ == Target::kTriangles) {
            if (content_.triangles_line != 0) duplicate(*info, keyword_line, content_.triangles_line);
            content_.triangles_line = keyword_line;
            content_.triangles_need_range_check = content_.vertices_line == 0;
            read_elements<3>(*info, "triangle", content_.triangles);
          } else {
            skip_section(*info);
          }
          break;
        case SectionKind::kSkipped:
          skip_section(*info);
          break;
      }
    }
    return finish();
  }

 private:
  void read_version() {
    if (!s_.skip_space()) s_.fail("unexpected end of file, expected MeshVersionFormatted");
    const std::int64_t line = s_.line();
    const std::string_view token = s_.read_token();
    if (!detail::iequals(token, "MeshVersionFormatted"))
      s_.fail_at(line, "expected MeshVersionFormatted, got " + quote(token));
    const std::int64_t version = read_value("MeshVersionFormatted", "the version number");
    if (version < 1 || version > 4)
      s_.fail_at(line, "unsupported MeshVersionFormatted " + std::to_string(version) + " (expected 1 to 4)");
  }

  // The integer after a keyword, on the same line or a later one; nothing
  // else may follow it on its line.
  std::int64_t read_value(std::string_view keyword, const std::string& what) {
    if (!s_.skip_space()) s_.fail("unexpected end of file, expected " + what + " after " + std::string(keyword));
    value_line_ = s_.line();
    std::int64_t value = 0;
    if (!s_.read_int(value))
      s_.fail("expected " + what + " after " + std::string(keyword) + ", got " + quote(s_.peek_token()));
    if (!s_.finish_line()) s_.fail("unexpected " + quote(s_.peek_token()) + " after " + what);
    return value;
  }

  // A section's entry count, checked before anything is allocated from it.
  std::int64_t read_count(std::string_view keyword, int values_per_entry) {
    const std::string what = "the number of " + std::string(keyword);
    const std::int64_t n = read_value(keyword, what);
    const std::int64_t line = value_line_;
    if (n < 0) s_.fail_at(line, "negative number of " + std::string(keyword) + ": " + std::to_string(n));
    if (n > kMaxIndexCount)
      s_.fail_at(line, "number of " + std::string(keyword) + " " + std::to_string(n) + " exceeds the limit of " +
                           std::to_string(kMaxIndexCount));
    // Each number takes at least one character and one separator.
    if (detail::exceeds_remaining(n, 2 * std::int64_t{values_per_entry}, s_.remaining(), true))
      s_.fail_at(line, std::to_string(n) + " " + std::string(keyword) + " cannot fit in the " +
                           std::to_string(s_.remaining()) + " bytes left in the file");
    return n;
  }

  [[noreturn]] void duplicate(const SectionInfo& info, std::int64_t line, std::int64_t first_line) {
    s_.fail_at(line, "second " + std::string(info.keyword) + " section (the first is at line " +
                         std::to_string(first_line) + ")");
  }

  // After the last value of an entry: nothing else may follow on its line.
  static void end_entry(TextScanner& s, std::string_view entry, int values, const EntryAt& at) {
    if (s.skip_blank()) {
      const std::int64_t extra = s.count_tokens_on_line();
      s.fail("expected " + std::string(entry) + ", got " + std::to_string(values + extra) + " values" + at.label());
    }
  }

  static void read_reference(TextScanner& s, const SectionInfo& info, int values_before, const EntryAt& at) {
    if (!s.skip_blank())
      s.fail("expected " + std::string(info.entry) + ", got " + std::to_string(values_before) + " values" + at.label());
    std::int64_t reference = 0;
    if (!s.read_int(reference)) s.fail("expected an integer reference, got " + quote(s.peek_token()) + at.label());
  }

  // One vertex entry: 3 finite coordinates and a reference.
  static Vec3 read_vertex(TextScanner& s, const SectionInfo& info, const EntryAt& at) {
    if (!s.skip_space()) s.fail("unexpected end of file, expected " + std::string(info.entry) + at.label());
    double xyz[3];
    for (int k = 0; k < 3; ++k) {
      if (!s.skip_blank())
        s.fail("expected " + std::string(info.entry) + ", got " + std::to_string(k) + " values" + at.label());
      if (!s.read_double(xyz[k])) s.fail("expected a coordinate, got " + quote(s.peek_token()) + at.label());
      if (!std::isfinite(xyz[k]))
        s.fail(std::string("non-finite coordinate ") +
               (std::isnan(xyz[k]) ? "nan"
                : xyz[k] > 0       ? "inf"
                                   : "-inf") +
               at.label());
    }
    read_reference(s, info, 3, at);
    end_entry(s, info.entry, 4, at);
    return {xyz[0], xyz[1], xyz[2]};
  }

  // One element entry: N 1-based vertex ids in [1, max_id] and a reference,
  // distinct (a second-order section's: its corners, listed first).
  template <int N>
  static std::array<Index, N> read_element(TextScanner& s, const SectionInfo& info, const EntryAt& at,
                                           std::int64_t max_id, bool has_vertices) {
    if (!s.skip_space()) s.fail("unexpected end of file, expected " + std::string(info.entry) + at.label());
    std::array<Index, N> element;
    for (int k = 0; k < N; ++k) {
      if (!s.skip_blank())
        s.fail("expected " + std::string(info.entry) + ", got " + std::to_string(k) + " values" + at.label());
      std::int64_t id = 0;
      if (!s.read_int(id)) s.fail("expected an integer vertex id, got " + quote(s.peek_token()) + at.label());
      if (id < 1 || id > max_id) {
        const std::string range = has_vertices ? " out of range [1, " + std::to_string(max_id) + "]"
                                               : (id < 1 ? " out of range (ids start at 1)"
                                                         : " exceeds the limit of " + std::to_string(max_id));
        s.fail("vertex id " + std::to_string(id) + range + at.label());
      }
      element[k] = static_cast<Index>(id - 1);
    }
    read_reference(s, info, N, at);
    end_entry(s, info.entry, N + 1, at);
    const int distinct = info.num_nodes > 0 ? cell_kind_num_corners(info.cell_kind) : N;  // P2, Q2: the corners
    for (int a = 1; a < distinct; ++a)
      for (int b = 0; b < a; ++b)
        if (element[a] == element[b]) {
          // A hexahedron collapsed to another kind: moved to that kind's block at the end.
          if constexpr (N == 8)
            if (info.cell_kind == CellKind::hex && info.num_nodes == 0 && detail::collapse_hex(element)) return element;
          s.fail("vertex id " + std::to_string(element[a] + 1) + " repeated" + at.label());
        }
    return element;
  }

  // Reads the n entries of a section into out[first + i] (out already that
  // long) with read(scanner, i). A large section is read in kEntryParts
  // parts on the worker threads when every entry takes one line: each part
  // by its own scanner from the line where it starts, so each value and
  // message is the one the sequential reading would give. If any part
  // fails, the section is read again from its start, sequentially, and that
  // reading's first error is the one reported (the same file always gives
  // the same message, whatever the thread count).
  template <class T, class Read>
  void read_entries(std::int64_t n, std::vector<T>& out, std::size_t first, Read read) {
    if (n >= kParallelEntriesMin) {
      std::vector<std::int64_t> every;
      for (std::int64_t k = 0; k < kEntryParts; ++k) every.push_back(n * k / kEntryParts);
      std::vector<TextScanner::Mark> starts;
      TextScanner::Mark end;
      if (s_.mark_entry_lines(n, every, starts, end)) {
        std::atomic<bool> failed{false};
        tbb::parallel_for(std::int64_t{0}, kEntryParts, [&](std::int64_t k) {
          const auto part = static_cast<std::size_t>(k);
          const std::size_t last = part + 1 < starts.size() ? starts[part + 1].offset : end.offset;
          TextScanner piece(s_, starts[part].offset, last, starts[part].line);
          const std::int64_t stop = k + 1 < kEntryParts ? every[part + 1] : n;
          try {
            for (std::int64_t i = every[part]; i < stop; ++i) out[first + static_cast<std::size_t>(i)] = read(piece, i);
          } catch (const ParseError&) {
            failed = true;
          }
        });
        if (!failed) {
          s_.move_to(end);
          return;
        }
      }
    }
    for (std::int64_t i = 0; i < n; ++i) out[first + static_cast<std::size_t>(i)] = read(s_, i);
  }

  void read_vertices(const SectionInfo& info, std::int64_t keyword_line) {
    if (content_.vertices_line != 0) duplicate(info, keyword_line, content_.vertices_line);
    content_.vertices_line = keyword_line;
    const std::int64_t n = read_count(info.keyword, info.values_per_entry);
    if (target_ == Target::kVolumes) check_mesh_memory(limits_, s_.name(), value_line_, file_bytes_, n, -1);
    content_.mesh.points.resize(static_cast<std::size_t>(n));
    read_entries(n, content_.mesh.points, 0,
                 [&](TextScanner& s, std::int64_t i) { return read_vertex(s, info, EntryAt{"vertex", "", i, n}); });
  }

  // Elements of N 1-based vertex ids and a reference.
  template <int N>
  void read_elements(const SectionInfo& info, const char* what, std::vector<std::array<Index, N>>& out) {
    const std::int64_t n = read_count(info.keyword, info.values_per_entry);
    if (target_ == Target::kVolumes)  // every volume cell counted as a hexahedron
      check_mesh_memory(limits_, s_.name(), value_line_, file_bytes_,
                        static_cast<std::int64_t>(content_.mesh.points.size()),
                        num_volume_cells(content_.mesh) + n);
    const bool has_vertices = content_.vertices_line != 0;
    const std::int64_t max_id = has_vertices ? static_cast<std::int64_t>(content_.mesh.points.size()) : kMaxIndexCount;
    const std::size_t first = out.size();
    out.resize(first + static_cast<std::size_t>(n));
    read_entries(n, out, first, [&](TextScanner& s, std::int64_t i) {
      return read_element<N>(s, info, EntryAt{what, "", i, n}, max_id, has_vertices);
    });
  }

  // Skips a known section entry by entry; returns its count. Gmsh writes
  // its second-order quadrilaterals (9 or 8 vertices) in a Quadrilaterals
  // section and 3-vertex edges in an Edges section: when the first entry has
  // that many values, every entry must.
  std::int64_t skip_section(const SectionInfo& info) {
    const std::int64_t n = read_count(info.keyword, info.values_per_entry);
    const bool is_quad = info.keyword == "Quadrilaterals" || info.keyword == "Quads";
    std::int64_t expected = info.values_per_entry;
    for (std::int64_t i = 0; i < n; ++i) {
      const EntryAt at{info.keyword, " entry", i, n};
      const std::string entry =
          expected == info.values_per_entry ? std::string(info.entry) : std::to_string(expected) + " values";
      if (!s_.skip_space()) s_.fail("unexpected end of file, expected " + entry + at.label());
      double first = 0.0;
      if (!s_.read_double(first)) s_.fail("expected " + entry + ", got " + quote(s_.peek_token()) + at.label());
      const std::int64_t values = 1 + s_.count_tokens_on_line();
      if (i == 0 && ((is_quad && (values == 9 || values == 10)) || (info.keyword == "Edges" && values == 4)))
        expected = values;
      if (values != expected) s_.fail("expected " + entry + ", got " + std::to_string(values) + " values" + at.label());
    }
    return n;
  }

  // The entries of a Quadrilaterals or Triangles section as written (their
  // ids checked once the mesh is known to be a surface: surface_cells()).
  // As skip_section, Gmsh's second-order quadrilaterals (9 or 8 vertices)
  // are read by their corners.
  void read_surface_section(const SectionInfo& info) {
    const std::int64_t n = read_count(info.keyword, info.values_per_entry);
    const bool is_quad = info.cell_kind == CellKind::quad;
    const int corners = is_quad ? 4 : 3;
    auto& entries = content_.surface_entries[is_quad ? 0 : 1];
    content_.surface_sections[std::string(info.keyword)] += n;
    std::int64_t expected = info.values_per_entry;
    for (std::int64_t i = 0; i < n; ++i) {
      const EntryAt at{info.keyword, " entry", i, n};
      if (!s_.skip_space()) s_.fail("unexpected end of file, expected " + std::string(info.entry) + at.label());
      MeditContent::SurfaceEntry entry{{0, 0, 0, 0}, s_.line()};
      for (int k = 0; k < corners; ++k)
        if (!s_.skip_blank() || !s_.read_int(entry.ids[static_cast<std::size_t>(k)]))
          s_.fail("expected " + std::string(info.entry) + ", got " + quote(s_.peek_token()) + at.label());
      const std::int64_t values = corners + s_.count_tokens_on_line();
      if (i == 0 && is_quad && (values == 9 || values == 10)) expected = values;
      if (values != expected)
        s_.fail("expected " + (expected == info.values_per_entry ? std::string(info.entry) : std::to_string(expected) + " values") +
                ", got " + std::to_string(values) + " values" + at.label());
      entries.push_back(entry);
    }
  }

  // An unknown keyword must be followed by an entry count; its entries are
  // skipped one non-blank line each.
  void skip_unknown_section(std::string_view keyword, std::int64_t keyword_line) {
    if (!starts_like_keyword(keyword)) s_.fail_at(keyword_line, "expected a keyword, got " + quote(keyword));
    std::int64_t n = 0;
    if (!s_.skip_space()) s_.fail_at(keyword_line, "unknown keyword " + quote(keyword));
    const std::int64_t count_line = s_.line();
    if (!s_.read_int(n) || !s_.finish_line()) s_.fail_at(keyword_line, "unknown keyword " + quote(keyword));
    const std::string name(keyword);
    if (n < 0) s_.fail_at(count_line, "negative number of " + name + ": " + std::to_string(n));
    if (n > kMaxIndexCount || detail::exceeds_remaining(n, 2, s_.remaining(), true))
      s_.fail_at(count_line, std::to_string(n) + " " + name + " cannot fit in the " + std::to_string(s_.remaining()) +
                                 " bytes left in the file");
    for (std::int64_t i = 0; i < n; ++i) {
      if (!s_.skip_space())
        s_.fail("unexpected end of file, expected " + std::to_string(n) + " entries of " + quote(keyword) + ", got " +
                std::to_string(i));
      s_.read_line();
    }
    content_.warnings.push_back(s_.name() + ": unknown section " + quote(keyword) + " (" + std::to_string(n) +
                                " entries) skipped");
  }

  template <class Elements>
  void check_ids_late(const Elements& elements, std::int64_t line, const char* what) {
    const auto n = static_cast<std::int64_t>(elements.size());
    const auto num_points = static_cast<Index>(content_.mesh.points.size());
    for (std::int64_t i = 0; i < n; ++i)
      for (const Index id : elements[static_cast<std::size_t>(i)])
        if (id >= num_points)
          s_.fail_at(line, "vertex id " + std::to_string(std::int64_t{id} + 1) + " out of range [1, " +
                               std::to_string(num_points) + "]" + EntryAt{what, "", i, n}.label());
  }

  MeditContent finish() {
    if (content_.vertices_line == 0) s_.fail_at(0, "no Vertices section");
    for_each_cell_kind([&](auto kind) {
      const auto k = static_cast<std::size_t>(kind());
      if (content_.volume_needs_range_check[k])
        check_ids_late(cell_block<kind()>(content_.mesh), content_.volume_line[k],
                       element_word(kind()));
    });
    if (content_.triangles_need_range_check) check_ids_late(content_.triangles, content_.triangles_line, "triangle");
    move_collapsed_hexahedra();
    if (target_ == Target::kVolumes && keep_surface()) return std::move(content_);
    if (target_ == Target::kVolumes && num_volume_cells(content_.mesh) == 0)
      s_.fail_at(0, "no volume cells (Hexahedra, Tetrahedra, Prisms or Pyramids)");
    if (target_ == Target::kTriangles && content_.triangles.empty()) s_.fail_at(0, "no triangles");
    return std::move(content_);
  }

  // When the mesh is a surface (detail::keep_dimension): its volume blocks
  // dropped, the Quadrilaterals and Triangles entries checked and read
  // (source index: the 1-based entry of its section), true.
  bool keep_surface() {
    Mesh& mesh = content_.mesh;
    std::map<std::string, std::int64_t> unused;
    std::int64_t num_volume_dropped = 0;
    if (!detail::keep_dimension(mesh, limits_.dimension, unused, content_.surface_sections, num_volume_dropped))
      return false;
    if (num_volume_dropped > 0)
      content_.warnings.push_back(detail::volume_dropped_warning(s_.name(), num_volume_dropped, "cell"));
    const auto num_points = static_cast<std::int64_t>(mesh.points.size());
    for (int block = 0; block < 2; ++block) {
      const CellKind kind = block == 0 ? CellKind::quad : CellKind::triangle;
      const auto& entries = content_.surface_entries[static_cast<std::size_t>(block)];
      const auto n = static_cast<std::int64_t>(entries.size());
      for (std::int64_t i = 0; i < n; ++i) {
        const MeditContent::SurfaceEntry& e = entries[static_cast<std::size_t>(i)];
        std::array<Index, 4> ids{};
        for (int k = 0; k < cell_kind_num_corners(kind); ++k) {
          const std::int64_t id = e.ids[static_cast<std::size_t>(k)];
          if (id < 1 || id > num_points)
            s_.fail_at(e.line, "vertex id " + std::to_string(id) + " out of range [1, " + std::to_string(num_points) +
                                   "]" + EntryAt{element_word(kind), "", i, n}.label());
          ids[static_cast<std::size_t>(k)] = static_cast<Index>(id - 1);
        }
        surface_notes_.append(mesh, kind, ids.data(), i + 1);
      }
    }
    if (detail::num_surface_cells(mesh) == 0)
      s_.fail_at(0, surface_notes_.no_cells_message());
    surface_notes_.append_warnings(s_.name(), "cell", content_.warnings);
    return true;
  }

  // The hexahedra whose repeated corners read_element() accepted as a
  // collapse pattern go to the block of the kind they collapse to, with
  // their Hexahedra entry as source index; the blocks they leave and join
  // then store their source indices (the others keep their entry numbers).
  void move_collapsed_hexahedra() {
    Mesh& mesh = content_.mesh;
    std::vector<std::pair<detail::CollapsedHex, std::int64_t>> moved;  // the cell, its Hexahedra entry
    std::vector<std::int64_t> kept;
    std::size_t out = 0;
    for (std::size_t i = 0; i < mesh.hexes.size(); ++i) {
      const Hex hex = mesh.hexes[i];
      const std::optional<detail::CollapsedHex> collapsed =
          detail::first_repeated(hex.data(), 8) >= 0 ? detail::collapse_hex(hex) : std::nullopt;
      if (collapsed) {
        moved.emplace_back(*collapsed, static_cast<std::int64_t>(i) + 1);
      } else {
        mesh.hexes[out++] = hex;
        kept.push_back(static_cast<std::int64_t>(i) + 1);
      }
    }
    if (moved.empty()) return;
    mesh.hexes.resize(out);
    mesh.source_index[static_cast<std::size_t>(CellKind::hex)] = std::move(kept);
    for (const auto& [cell, entry] : moved) {
      std::vector<std::int64_t>& sources = mesh.source_index[static_cast<std::size_t>(cell.kind)];
      if (sources.empty())
        for (std::int64_t j = 1; j <= num_cells_of(mesh, cell.kind); ++j) sources.push_back(j);
      detail::append_cell(mesh, cell.kind, cell.corners.data(), nullptr, entry);
      content_.notes.add_collapsed(cell.kind, entry);
    }
  }

  static const char* element_word(CellKind kind) {
    switch (kind) {
      case CellKind::tet:
        return "tetrahedron";
      case CellKind::wedge:
        return "prism";
      case CellKind::pyramid:
        return "pyramid";
      case CellKind::quad:
        return "quadrilateral";
      case CellKind::triangle:
        return "triangle";
      default:
        return "hexahedron";
    }
  }

  // A hexahedra section's entries as Gmsh writes its second-order ones (27
  // or 20 vertex ids and a reference on the first entry's line), else `info`;
  // the scanner does not move.
  const SectionInfo& hexahedra_as_written(const SectionInfo& info) {
    if (info.num_nodes != 0) return info;
    const TextScanner::Mark start{s_.offset(), s_.line()};
    std::int64_t values = 0;
    if (s_.skip_space() && s_.read_int(values) && s_.finish_line() && values > 0 && s_.skip_space()) {
      s_.read_token();
      values = 1 + s_.count_tokens_on_line();
    } else {
      values = 0;
    }
    s_.move_to(start);
    return values == kGmshHexahedra27.values_per_entry   ? kGmshHexahedra27
           : values == kGmshHexahedra20.values_per_entry ? kGmshHexahedra20
                                                         : info;
  }

  // A Hexahedra, Tetrahedra, Prisms or Pyramids section into its block (one
  // section per kind: each entry's source index, its 1-based position in the
  // section, is its position in the block, left implicit). MEDIT lists a
  // prism's first triangle with its normal towards the second (P. L. George's
  // convention, as Gmsh): permuted to VTK's order.
  void read_volume_section(const SectionInfo& info, std::int64_t keyword_line) {
    const auto k = static_cast<std::size_t>(info.cell_kind);
    if (content_.volume_line[k] != 0) {
      const SectionInfo& first = *content_.volume_section[k];
      if (info.num_nodes == first.num_nodes) duplicate(info, keyword_line, content_.volume_line[k]);
      s_.fail_at(keyword_line, std::string(info.keyword) + " section beside the " + std::string(first.keyword) +
                                   " section at line " + std::to_string(content_.volume_line[k]) +
                                   " (one section per cell kind)");
    }
    content_.volume_section[k] = &info;
    // Only the corners are kept: the other ids are range-checked as they are read.
    if (info.num_nodes > 0 && content_.vertices_line == 0)
      s_.fail_at(keyword_line, std::string(info.keyword) + " section before the Vertices section");
    content_.volume_line[k] = keyword_line;
    content_.volume_needs_range_check[k] = content_.vertices_line == 0;
    for_each_cell_kind([&](auto kind) {
      if constexpr (CellKindTable<kind()>::dimension == 3) {
        if (kind() != info.cell_kind) return;
        auto& block = cell_block<kind()>(content_.mesh);
        constexpr int kCorners = CellKindTable<kind()>::num_corners;
        if (info.num_nodes == 10 || info.num_nodes == 20 || info.num_nodes == 27) {
          const auto read_by_corners = [&](auto nodes) {
            std::vector<std::array<Index, decltype(nodes)::value>> entries;
            read_elements<decltype(nodes)::value>(info, element_word(kind()), entries);
            block.reserve(entries.size());
            for (const auto& entry : entries) {
              CellCorners<kind()> corners;
              std::copy(entry.begin(), entry.begin() + kCorners, corners.begin());
              block.push_back(corners);
            }
            if (!entries.empty())
              content_.notes.add_higher_order(
                  std::string(info.keyword) +
                      (info.keyword == "Hexahedra" ? " (" + std::to_string(info.num_nodes) + " vertices)" : ""),
                  static_cast<std::int64_t>(entries.size()));
          };
          if (info.num_nodes == 10) read_by_corners(std::integral_constant<int, 10>{});
          else if (info.num_nodes == 20) read_by_corners(std::integral_constant<int, 20>{});
          else read_by_corners(std::integral_constant<int, 27>{});
        } else {
          read_elements<kCorners>(info, element_word(kind()), block);
        }
        if constexpr (kind() == CellKind::wedge)
          for (std::size_t i = 0; i < block.size(); ++i) {
            const auto wedge = block[i];
            for (int j = 0; j < 6; ++j) block[i][static_cast<std::size_t>(j)] = wedge[detail::kWedgeFlippedToVtk[j]];
          }
      }
    });
  }

  TextScanner s_;
  Target target_;
  ReadLimits limits_;
  std::uint64_t file_bytes_;
  std::int64_t value_line_ = 0;  // line of the last read_value()
  MeditContent content_;
  detail::SurfaceNotes surface_notes_;
};

}  // namespace

LoadedMesh read_medit(std::string_view text, const std::string& name, const ReadLimits& limits) {
  MeditContent content = MeditParser(text, name, Target::kVolumes, limits).parse();
  LoadedMesh loaded;
  loaded.mesh = std::move(content.mesh);
  loaded.format = "medit";
  loaded.warnings = std::move(content.warnings);
  content.notes.append_warnings(name, "cell", loaded.warnings);
  return loaded;
}

TriSurface read_medit_triangles(std::string_view text, const std::string& name) {
  MeditContent content = MeditParser(text, name, Target::kTriangles).parse();
  TriSurface surface;
  surface.points = std::move(content.mesh.points);
  surface.triangles = std::move(content.triangles);
  return surface;
}

}  // namespace hq
