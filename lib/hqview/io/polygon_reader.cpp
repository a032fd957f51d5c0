#include "hqview/io/polygon_reader.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/io/cell_reading.h"
#include "hqview/io/text_scanner.h"

namespace hq {
namespace {

using detail::iequals;
using detail::quote;
using detail::TextScanner;

// How many faces or edges a warning lists by name.
constexpr std::size_t kListed = 5;

std::string listed(const std::vector<std::int64_t>& values, std::int64_t count) {
  std::string text;
  for (const std::int64_t v : values) text += (text.empty() ? "" : ", ") + std::to_string(v);
  if (count > static_cast<std::int64_t>(values.size())) text += ", ...";
  return text;
}

// Collects a polygon file's faces into the triangle and quad blocks, and
// what it tells the user once per file: polygons of more than 4 vertices
// (skipped, their edges holes), faces with a repeated vertex (skipped), and
// non-manifold edges (kept). `first_id` is the file's numbering of vertices
// (1 for OBJ), for the warning's vertex ids.
class PolygonCollector {
 public:
  PolygonCollector(LoadedMesh& loaded, std::string name, int first_id)
      : loaded_(loaded), name_(std::move(name)), first_id_(first_id) {}

  // ids: 0-based, in range.
  void add_face(const Index* ids, std::size_t n, std::int64_t source_index) {
    // (A polygon of more than 4 vertices is skipped whatever its ids.)
    if (n <= 4 && detail::first_repeated(ids, static_cast<int>(n)) >= 0) {
      note(repeated_, num_repeated_, source_index);
      return;
    }
    if (n == 3) {
      detail::append_cell<CellKind::triangle>(loaded_.mesh, {ids[0], ids[1], ids[2]}, source_index);
    } else if (n == 4) {
      detail::append_cell<CellKind::quad>(loaded_.mesh, {ids[0], ids[1], ids[2], ids[3]}, source_index);
    } else {
      note(polygons_, num_polygons_, source_index);
      for (std::size_t i = 0; i < n; ++i) {
        const Index a = ids[i], b = ids[(i + 1) % n];
        loaded_.hole_edges.push_back({std::min(a, b), std::max(a, b)});
      }
    }
  }

  void finish() {
    std::vector<std::array<Index, 2>>& holes = loaded_.hole_edges;
    std::sort(holes.begin(), holes.end());
    holes.erase(std::unique(holes.begin(), holes.end()), holes.end());
    if (num_polygons_ > 0)
      loaded_.warnings.push_back(name_ + ": " + std::to_string(num_polygons_) + " polygon" +
                                 (num_polygons_ > 1 ? "s" : "") + " of more than 4 vertices skipped (face" +
                                 (num_polygons_ > 1 ? "s " : " ") + listed(polygons_, num_polygons_) +
                                 "): their edges are holes in the surface, not its boundary");
    if (num_repeated_ > 0)
      loaded_.warnings.push_back(name_ + ": " + std::to_string(num_repeated_) + " face" +
                                 (num_repeated_ > 1 ? "s" : "") + " with a repeated vertex skipped (face" +
                                 (num_repeated_ > 1 ? "s " : " ") + listed(repeated_, num_repeated_) + ")");
    warn_nonmanifold_edges();
  }

 private:
  static void note(std::vector<std::int64_t>& list, std::int64_t& count, std::int64_t source_index) {
    if (list.size() < kListed) list.push_back(source_index);
    ++count;
  }

  // Edges of the kept faces on more than two faces, by a sort of their keys.
  void warn_nonmanifold_edges() const {
    const Mesh& mesh = loaded_.mesh;
    std::vector<std::uint64_t> keys;
    keys.reserve(mesh.quads.size() * 4 + mesh.triangles.size() * 3);
    const auto add = [&](const auto& cell) {
      for (std::size_t i = 0; i < cell.size(); ++i) {
        const auto a = static_cast<std::uint32_t>(cell[i]), b = static_cast<std::uint32_t>(cell[(i + 1) % cell.size()]);
        keys.push_back(std::uint64_t{std::min(a, b)} << 32 | std::max(a, b));
      }
    };
    for (const auto& quad : mesh.quads) add(quad);
    for (const auto& triangle : mesh.triangles) add(triangle);
    std::sort(keys.begin(), keys.end());
    std::int64_t count = 0;
    std::string examples;
    for (std::size_t i = 0; i < keys.size();) {
      std::size_t j = i;
      while (j < keys.size() && keys[j] == keys[i]) ++j;
      if (j - i > 2) {
        if (count < static_cast<std::int64_t>(kListed))
          examples += (examples.empty() ? "" : ", ") + std::to_string((keys[i] >> 32) + first_id_) + "-" +
                      std::to_string((keys[i] & 0xffffffffu) + first_id_) + " (" + std::to_string(j - i) + " faces)";
        ++count;
      }
      i = j;
    }
    if (count == 0) return;
    loaded_.warnings.push_back(name_ + ": " + std::to_string(count) + " non-manifold edge" + (count > 1 ? "s" : "") +
                               " (on more than two faces; the faces are kept): vertices " + examples +
                               (count > static_cast<std::int64_t>(kListed) ? ", ..." : ""));
  }

  LoadedMesh& loaded_;
  std::string name_;
  int first_id_;
  std::vector<std::int64_t> polygons_, repeated_;
  std::int64_t num_polygons_ = 0, num_repeated_ = 0;
};

// ----------------------------------------------------------------------------
// OBJ

// One OBJ face corner token: "v", "v/vt", "v//vn" or "v/vt/vn"; returns the
// vertex id as written (non-zero), false when the token is malformed.
bool parse_obj_corner(std::string_view token, std::int64_t& id) {
  const std::size_t slash = token.find('/');
  const std::string_view vertex = token.substr(0, slash);
  const auto [ptr, ec] = std::from_chars(vertex.data(), vertex.data() + vertex.size(), id);
  if (ec != std::errc{} || ptr != vertex.data() + vertex.size() || id == 0) return false;
  if (slash == std::string_view::npos) return true;
  // vt and vn: integers (vt may be empty, "v//vn"), not checked against their counts.
  std::string_view rest = token.substr(slash + 1);
  for (int part = 0; part < 2 && !rest.empty(); ++part) {
    const std::size_t next = rest.find('/');
    const std::string_view value = rest.substr(0, next);
    if (!value.empty()) {
      std::int64_t v = 0;
      const auto [p, e] = std::from_chars(value.data(), value.data() + value.size(), v);
      if (e != std::errc{} || p != value.data() + value.size() || v == 0) return false;
    } else if (part == 1 || next == std::string_view::npos) {
      return false;  // "v/" or "v/vt/"
    }
    if (next == std::string_view::npos) return true;
    rest = rest.substr(next + 1);
    if (part == 1) return false;  // a fourth part
    if (rest.empty()) return false;
  }
  return true;
}

LoadedMesh parse_obj(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  TextScanner s(bytes, name, /*has_hash_comments=*/true);
  LoadedMesh loaded;
  loaded.format = "obj";
  std::vector<Vec3>& points = loaded.mesh.points;
  // Faces as read (ids as written, resolved once every vertex is known).
  std::vector<std::int64_t> face_ids;
  std::vector<std::int64_t> face_offsets{0};
  std::vector<std::int64_t> face_lines;
  while (s.skip_space()) {
    const std::string_view keyword = s.read_token();
    if (keyword == "v") {
      double xyz[3];
      for (double& c : xyz) {
        if (!s.skip_blank()) s.fail("expected 3 coordinates after 'v'");
        if (!s.read_double(c)) s.fail("expected a coordinate, got " + quote(s.peek_token()));
      }
      for (const double c : xyz)
        if (!std::isfinite(c)) s.fail("non-finite coordinate (vertex " + std::to_string(points.size() + 1) + ")");
      if (static_cast<std::int64_t>(points.size()) >= kMaxIndexCount)
        s.fail("more than " + std::to_string(kMaxIndexCount) + " vertices");
      points.push_back({xyz[0], xyz[1], xyz[2]});
      s.read_line();  // w, or a colour: ignored
    } else if (keyword == "f") {
      const std::int64_t line = s.line();
      std::int64_t n = 0;
      while (true) {
        if (!s.skip_blank()) {
          break;
        }
        const std::string_view token = s.read_token();
        if (token == "\\") {  // continued on the next line
          if (!s.finish_line()) s.fail("expected a line break after '\\'");
          continue;
        }
        std::int64_t id = 0;
        if (!parse_obj_corner(token, id))
          s.fail("expected a vertex id (v, v/vt, v//vn or v/vt/vn, non-zero), got " + quote(token));
        if (id < 0) {
          // Relative to the vertices read so far: -1 is the last one.
          if (-id > static_cast<std::int64_t>(points.size()))
            s.fail("vertex id " + std::to_string(id) + " out of range (only " + std::to_string(points.size()) +
                   (points.size() == 1 ? " vertex" : " vertices") + " before this face)");
          id = static_cast<std::int64_t>(points.size()) + id + 1;
        }
        face_ids.push_back(id);
        ++n;
      }
      if (n < 3) s.fail("a face needs at least 3 vertices, got " + std::to_string(n));
      face_offsets.push_back(static_cast<std::int64_t>(face_ids.size()));
      face_lines.push_back(line);
    } else {
      s.read_line();  // vt, vn, vp, l, p, o, g, s, usemtl, mtllib, ...: not read
    }
  }
  const auto num_faces = static_cast<std::int64_t>(face_lines.size());
  if (num_faces > kMaxIndexCount) s.fail("more than " + std::to_string(kMaxIndexCount) + " faces");
  check_mesh_memory(limits, name, 0, bytes.size(), static_cast<std::int64_t>(points.size()), num_faces, "face");

  PolygonCollector faces(loaded, name, 1);
  std::vector<Index> ids;
  const auto num_points = static_cast<std::int64_t>(points.size());
  for (std::int64_t f = 0; f < num_faces; ++f) {
    ids.clear();
    for (std::int64_t k = face_offsets[f]; k < face_offsets[f + 1]; ++k) {
      const std::int64_t id = face_ids[static_cast<std::size_t>(k)];
      if (id > num_points)
        s.fail_at(face_lines[f], "vertex id " + std::to_string(id) + " out of range [1, " + std::to_string(num_points) +
                                     "] (face " + std::to_string(f + 1) + ")");
      ids.push_back(static_cast<Index>(id - 1));
    }
    faces.add_face(ids.data(), ids.size(), f + 1);
  }
  faces.finish();
  return loaded;
}

// ----------------------------------------------------------------------------
// OFF

// The OFF keyword's prefixes, in their order: ST, C, N, 4, n.
struct OffKeyword {
  bool is_off = false;
  bool is_4d = false, is_ndim = false;
};

OffKeyword off_keyword(std::string_view token) {
  OffKeyword k;
  if (!token.ends_with("OFF")) return k;
  std::string_view prefix = token.substr(0, token.size() - 3);
  for (const std::string_view p : {"ST", "C", "N", "4", "n"})
    if (prefix.starts_with(p)) {
      if (p == "4") k.is_4d = true;
      if (p == "n") k.is_ndim = true;
      prefix.remove_prefix(p.size());
    }
  k.is_off = prefix.empty();
  return k;
}

LoadedMesh parse_off(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  TextScanner s(bytes, name, /*has_hash_comments=*/true);
  if (!s.skip_space()) s.fail("empty file, expected 'OFF'");
  const std::string_view keyword = s.read_token();
  const OffKeyword k = off_keyword(keyword);
  if (!k.is_off) s.fail("expected 'OFF', got " + quote(keyword));
  if (k.is_4d || k.is_ndim) s.fail(quote(keyword) + " files (4D or n-dimensional vertices) are not read");
  if (s.skip_blank() && iequals(s.peek_token(), "BINARY")) s.fail("binary OFF files are not read (write ASCII OFF)");

  const auto read_count = [&](const char* what) {
    if (!s.skip_space()) s.fail(std::string("unexpected end of file, expected the number of ") + what);
    std::int64_t n = 0;
    if (!s.read_int(n)) s.fail(std::string("expected the number of ") + what + ", got " + quote(s.peek_token()));
    if (n < 0) s.fail(std::string("negative number of ") + what + " (" + std::to_string(n) + ")");
    if (n > kMaxIndexCount)
      s.fail(std::to_string(n) + " " + what + " exceed the limit of " + std::to_string(kMaxIndexCount));
    return n;
  };
  const std::int64_t num_vertices = read_count("vertices");
  const std::int64_t num_faces = read_count("faces");
  const std::int64_t count_line = s.line();
  if (s.skip_blank()) {
    std::int64_t num_edges = 0;
    if (!s.read_int(num_edges)) s.fail("expected the number of edges, got " + quote(s.peek_token()));
  }
  // A vertex takes at least "0 0 0\n", a face "3 0 1 2\n".
  if (detail::exceeds_remaining(num_vertices, 6, s.remaining(), true))
    s.fail_at(count_line, std::to_string(num_vertices) + " vertices cannot fit in the " +
                              std::to_string(s.remaining()) + " bytes left in the file");
  check_mesh_memory(limits, name, count_line, bytes.size(), num_vertices, -1, "face");

  LoadedMesh loaded;
  loaded.format = "off";
  std::vector<Vec3>& points = loaded.mesh.points;
  points.reserve(static_cast<std::size_t>(num_vertices));
  for (std::int64_t v = 0; v < num_vertices; ++v) {
    if (!s.skip_space())
      s.fail("unexpected end of file, expected vertex " + std::to_string(v) + " of " + std::to_string(num_vertices));
    double xyz[3];
    for (int c = 0; c < 3; ++c) {
      if (c > 0 && !s.skip_blank()) s.fail("expected 3 coordinates (vertex " + std::to_string(v) + ")");
      if (!s.read_double(xyz[c]))
        s.fail("expected a coordinate, got " + quote(s.peek_token()) + " (vertex " + std::to_string(v) + ")");
    }
    for (const double c : xyz)
      if (!std::isfinite(c)) s.fail("non-finite coordinate (vertex " + std::to_string(v) + ")");
    points.push_back({xyz[0], xyz[1], xyz[2]});
    s.read_line();  // normals, colours, texture coordinates: ignored
  }
  if (detail::exceeds_remaining(num_faces, 8, s.remaining(), true))
    s.fail_at(count_line, std::to_string(num_faces) + " faces cannot fit in the " + std::to_string(s.remaining()) +
                              " bytes left after the vertices");
  check_mesh_memory(limits, name, count_line, bytes.size(), num_vertices, num_faces, "face");

  PolygonCollector faces(loaded, name, 0);
  std::vector<Index> ids;
  for (std::int64_t f = 0; f < num_faces; ++f) {
    if (!s.skip_space())
      s.fail("unexpected end of file, expected face " + std::to_string(f) + " of " + std::to_string(num_faces));
    std::int64_t n = 0;
    if (!s.read_int(n))
      s.fail("expected the number of vertices of face " + std::to_string(f) + ", got " + quote(s.peek_token()));
    if (n < 3) s.fail("face " + std::to_string(f) + " has " + std::to_string(n) + " vertices (at least 3)");
    ids.clear();
    for (std::int64_t i = 0; i < n; ++i) {
      std::int64_t id = 0;
      if (!s.skip_blank())
        s.fail("expected " + std::to_string(n) + " vertex ids, got " + std::to_string(i) + " (face " +
               std::to_string(f) + ")");
      if (!s.read_int(id))
        s.fail("expected a vertex id, got " + quote(s.peek_token()) + " (face " + std::to_string(f) + ")");
      if (id < 0 || id >= num_vertices)
        s.fail("vertex id " + std::to_string(id) + " out of range [0, " + std::to_string(num_vertices) + ") (face " +
               std::to_string(f) + ")");
      ids.push_back(static_cast<Index>(id));
    }
    const std::int64_t line = s.line();
    const std::int64_t colours = s.count_tokens_on_line();  // moves to the line's end
    if (colours > 4)
      s.fail_at(line, std::to_string(n + 1 + colours) + " values for face " + std::to_string(f) + " of " +
                          std::to_string(n) + " vertices (expected at most 4 colour values after its ids)");
    faces.add_face(ids.data(), ids.size(), f);
  }
  faces.finish();
  return loaded;
}

// ----------------------------------------------------------------------------
// PLY

enum class PlyType : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool ply_type(std::string_view word, PlyType& type) {
  static constexpr std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::int8},      {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},    {"short", PlyType::int16},     {"int16", PlyType::int16},
      {"ushort", PlyType::uint16},  {"uint16", PlyType::uint16},   {"int", PlyType::int32},
      {"int32", PlyType::int32},    {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
      {"float", PlyType::float32},  {"float32", PlyType::float32}, {"double", PlyType::float64},
      {"float64", PlyType::float64}};
  for (const auto& [n, t] : kNames)
    if (n == word) {
      type = t;
      return true;
    }
  return false;
}

int ply_size(PlyType type) {
  switch (type) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32:
      return 4;
    default:
      return 8;
  }
}

bool is_integer(PlyType type) { return type != PlyType::float32 && type != PlyType::float64; }

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType type = PlyType::float32;  // the value's, or a list's items'
  PlyType count_type = PlyType::uint8;
};

struct PlyElement {
  std::string name;
  std::int64_t count = 0;
  std::int64_t line = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat : std::uint8_t { ascii, little_endian, big_endian };

class PlyParser {
 public:
  PlyParser(std::string_view bytes, const std::string& name, const ReadLimits& limits)
      : bytes_(bytes), s_(bytes, name, /*has_hash_comments=*/false), limits_(limits) {}

  LoadedMesh parse() {
    read_header();
    loaded_.format = format_ == PlyFormat::ascii           ? "ply-ascii"
                     : format_ == PlyFormat::little_endian ? "ply-binary-little-endian"
                                                           : "ply-binary-big-endian";
    check_counts();
    PolygonCollector faces(loaded_, s_.name(), 0);
    for (const PlyElement& element : elements_) {
      const bool is_vertex = element.name == "vertex", is_face = element.name == "face";
      for (std::int64_t i = 0; i < element.count; ++i) read_instance(element, i, is_vertex, is_face, faces);
    }
    faces.finish();
    return std::move(loaded_);
  }

 private:
  void read_header() {
    const std::string_view magic = s_.read_line();
    if (magic != "ply") s_.fail_at(1, "expected 'ply', got " + quote(magic));
    bool has_format = false;
    while (true) {
      if (s_.at_end()) s_.fail("unexpected end of file in the header, expected 'end_header'");
      const std::int64_t line = s_.line();
      const std::string_view text = s_.read_line();
      std::vector<std::string_view> words;
      for (std::size_t i = 0; i < text.size();) {
        while (i < text.size() && detail::is_space(text[i])) ++i;
        std::size_t j = i;
        while (j < text.size() && !detail::is_space(text[j])) ++j;
        if (j > i) words.push_back(text.substr(i, j - i));
        i = j;
      }
      if (words.empty()) continue;
      const std::string_view key = words[0];
      if (key == "end_header") break;
      if (key == "comment" || key == "obj_info") continue;
      if (key == "format") {
        if (words.size() != 3 || words[2] != "1.0")
          s_.fail_at(line, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0', got " + quote(text));
        if (words[1] == "ascii")
          format_ = PlyFormat::ascii;
        else if (words[1] == "binary_little_endian")
          format_ = PlyFormat::little_endian;
        else if (words[1] == "binary_big_endian")
          format_ = PlyFormat::big_endian;
        else
          s_.fail_at(line, "unknown PLY format " + quote(words[1]));
        has_format = true;
      } else if (key == "element") {
        std::int64_t count = -1;
        if (words.size() != 3) s_.fail_at(line, "expected 'element NAME COUNT', got " + quote(text));
        const auto [ptr, ec] = std::from_chars(words[2].data(), words[2].data() + words[2].size(), count);
        if (ec != std::errc{} || ptr != words[2].data() + words[2].size() || count < 0)
          s_.fail_at(line, "expected a count of elements " + quote(words[1]) + ", got " + quote(words[2]));
        for (const PlyElement& e : elements_)
          if (e.name == words[1]) s_.fail_at(line, "element " + quote(words[1]) + " declared twice");
        elements_.push_back({std::string(words[1]), count, line, {}});
      } else if (key == "property") {
        if (elements_.empty()) s_.fail_at(line, "a property before any element");
        PlyProperty p;
        if (words.size() == 5 && words[1] == "list") {
          p.is_list = true;
          if (!ply_type(words[2], p.count_type) || !is_integer(p.count_type))
            s_.fail_at(line, "expected an integer type for the list's count, got " + quote(words[2]));
          if (!ply_type(words[3], p.type)) s_.fail_at(line, "unknown property type " + quote(words[3]));
          p.name = words[4];
        } else if (words.size() == 3 && words[1] != "list") {
          if (!ply_type(words[1], p.type)) s_.fail_at(line, "unknown property type " + quote(words[1]));
          p.name = words[2];
        } else {
          s_.fail_at(line, "expected 'property TYPE NAME' or 'property list TYPE TYPE NAME', got " + quote(text));
        }
        elements_.back().properties.push_back(std::move(p));
      } else {
        s_.fail_at(line, "unknown PLY header line " + quote(text));
      }
    }
    if (!has_format) s_.fail("no 'format' line in the PLY header");
    body_ = s_.offset();
  }

  // Finds the vertex and face elements' properties and checks every count
  // against the bytes left and the budget before anything is allocated.
  void check_counts() {
    std::int64_t num_vertices = 0, num_faces = 0;
    std::uint64_t min_bytes_total = 0;
    for (const PlyElement& e : elements_) {
      std::int64_t min_bytes = 0;
      for (const PlyProperty& p : e.properties)
        min_bytes += format_ == PlyFormat::ascii ? 2 : ply_size(p.is_list ? p.count_type : p.type);
      min_bytes = std::max<std::int64_t>(min_bytes, 1);
      const std::size_t left = bytes_.size() - body_ - std::min<std::size_t>(bytes_.size() - body_, min_bytes_total);
      if (detail::exceeds_remaining(e.count, min_bytes, left, format_ == PlyFormat::ascii))
        s_.fail_at(e.line, std::to_string(e.count) + " elements " + quote(e.name) + " cannot fit in the " +
                               std::to_string(left) + " bytes left in the file");
      min_bytes_total += static_cast<std::uint64_t>(e.count) * static_cast<std::uint64_t>(min_bytes);
      if (e.name == "vertex") {
        num_vertices = e.count;
        for (std::size_t i = 0; i < e.properties.size(); ++i)
          for (int c = 0; c < 3; ++c)
            if (!e.properties[i].is_list && e.properties[i].name == std::string(1, static_cast<char>('x' + c)))
              xyz_[c] = static_cast<int>(i);
        if (e.count > 0 && (xyz_[0] < 0 || xyz_[1] < 0 || xyz_[2] < 0))
          s_.fail_at(e.line, "element 'vertex' has no x, y and z properties");
      } else if (e.name == "face") {
        num_faces = e.count;
        for (std::size_t i = 0; i < e.properties.size(); ++i)
          if (e.properties[i].is_list &&
              (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
            face_list_ = static_cast<int>(i);
        if (e.count > 0 && face_list_ < 0)
          s_.fail_at(e.line, "element 'face' has no list property 'vertex_indices' (or 'vertex_index')");
        if (face_list_ >= 0 && !is_integer(e.properties[static_cast<std::size_t>(face_list_)].type))
          s_.fail_at(e.line, "the face's vertex ids are not of an integer type");
      }
    }
    if (num_vertices > kMaxIndexCount || num_faces > kMaxIndexCount)
      s_.fail("more than " + std::to_string(kMaxIndexCount) + " vertices or faces");
    num_vertices_ = num_vertices;
    check_mesh_memory(limits_, s_.name(), 0, bytes_.size(), num_vertices, num_faces, "face");
    loaded_.mesh.points.reserve(static_cast<std::size_t>(num_vertices));
    pos_ = body_;
  }

  // Binary data has no lines: the message names the byte offset of the value.
  [[noreturn]] void fail_binary(const std::string& message) const {
    throw ParseError(s_.name(), 0, message + " at byte " + std::to_string(value_pos_));
  }

  // One value: ASCII from the scanner, binary from pos_.
  double read_value(PlyType type, const PlyElement& e, std::int64_t i) {
    if (format_ == PlyFormat::ascii) {
      if (!s_.skip_space())
        s_.fail("unexpected end of file in element " + quote(e.name) + " " + std::to_string(i) + " of " +
                std::to_string(e.count));
      double v = 0;
      if (is_integer(type)) {
        std::int64_t n = 0;
        if (!s_.read_int(n))
          s_.fail("expected an integer, got " + quote(s_.peek_token()) + " (element " + quote(e.name) + " " +
                  std::to_string(i) + ")");
        v = static_cast<double>(n);
      } else if (!s_.read_double(v)) {
        s_.fail("expected a number, got " + quote(s_.peek_token()) + " (element " + quote(e.name) + " " +
                std::to_string(i) + ")");
      }
      return v;
    }
    const int size = ply_size(type);
    value_pos_ = pos_;
    if (bytes_.size() - pos_ < static_cast<std::size_t>(size))
      fail_binary("truncated binary data in element " + quote(e.name) + " " + std::to_string(i) + " of " +
                  std::to_string(e.count));
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + pos_, static_cast<std::size_t>(size));
    pos_ += static_cast<std::size_t>(size);
    if ((format_ == PlyFormat::big_endian) == (std::endian::native == std::endian::little)) std::reverse(b, b + size);
    switch (type) {
      case PlyType::int8:
        return static_cast<std::int8_t>(b[0]);
      case PlyType::uint8:
        return b[0];
      case PlyType::int16: {
        std::int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case PlyType::uint16: {
        std::uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case PlyType::int32: {
        std::int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case PlyType::uint32: {
        std::uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case PlyType::float32: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      default: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
    }
  }

  void read_instance(const PlyElement& e, std::int64_t i, bool is_vertex, bool is_face, PolygonCollector& faces) {
    double xyz[3] = {0, 0, 0};
    ids_.clear();
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const PlyProperty& p = e.properties[k];
      if (!p.is_list) {
        const double v = read_value(p.type, e, i);
        if (is_vertex)
          for (int c = 0; c < 3; ++c)
            if (xyz_[c] == static_cast<int>(k)) xyz[c] = v;
        continue;
      }
      const double n = read_value(p.count_type, e, i);
      const bool is_ids = is_face && static_cast<int>(k) == face_list_;
      if (n < 0)
        fail_here("negative list length " + std::to_string(static_cast<std::int64_t>(n)) + " (element " +
                  quote(e.name) + " " + std::to_string(i) + ")");
      if (is_ids && n < 3)
        fail_here("face " + std::to_string(i) + " has " + std::to_string(static_cast<std::int64_t>(n)) +
                  " vertices (at least 3)");
      for (std::int64_t j = 0; j < static_cast<std::int64_t>(n); ++j) {
        const double id = read_value(p.type, e, i);
        if (!is_ids) continue;
        if (id < 0 || id >= static_cast<double>(num_vertices_))
          fail_here("vertex id " + std::to_string(static_cast<std::int64_t>(id)) + " out of range [0, " +
                    std::to_string(num_vertices_) + ") (face " + std::to_string(i) + ")");
        ids_.push_back(static_cast<Index>(id));
      }
    }
    if (is_vertex) {
      for (const double c : xyz)
        if (!std::isfinite(c)) fail_here("non-finite coordinate (vertex " + std::to_string(i) + ")");
      loaded_.mesh.points.push_back({xyz[0], xyz[1], xyz[2]});
    }
    if (is_face) faces.add_face(ids_.data(), ids_.size(), i);
  }

  [[noreturn]] void fail_here(const std::string& message) const {
    if (format_ == PlyFormat::ascii) s_.fail(message);
    fail_binary(message);
  }

  std::string_view bytes_;
  TextScanner s_;
  const ReadLimits& limits_;
  PlyFormat format_ = PlyFormat::ascii;
  std::vector<PlyElement> elements_;
  std::size_t body_ = 0;
  std::size_t pos_ = 0;        // binary: the next byte
  std::size_t value_pos_ = 0;  // binary: where the last value read starts
  int xyz_[3] = {-1, -1, -1};
  int face_list_ = -1;
  std::int64_t num_vertices_ = 0;
  std::vector<Index> ids_;
  LoadedMesh loaded_;
};

}  // namespace

bool looks_like_off(std::string_view bytes) {
  const std::string_view text = detail::after_blanks_and_comments(bytes);
  std::size_t end = 0;
  while (end < text.size() && !detail::is_space(text[end])) ++end;
  return off_keyword(text.substr(0, end)).is_off;
}

bool looks_like_ply(std::string_view bytes) { return bytes.starts_with("ply\n") || bytes.starts_with("ply\r\n"); }

LoadedMesh read_obj(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  return parse_obj(bytes, name, limits);
}

LoadedMesh read_off(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  return parse_off(bytes, name, limits);
}

LoadedMesh read_ply(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  return PlyParser(bytes, name, limits).parse();
}

}  // namespace hq
