#include "hqview/io/ovm_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/io/cell_reading.h"
#include "hqview/io/text_scanner.h"

namespace hq {
namespace {

using detail::iequals;
using detail::quote;
using detail::TextScanner;

using Quad = std::array<std::int64_t, 4>;

constexpr const char* kNotACell = "not a hexahedron, tetrahedron, wedge or pyramid";

// True when the first n entries of b are a cyclic rotation of a's (same orientation).
bool same_cycle(const Quad& a, const Quad& b, int n) {
  for (int r = 0; r < n; ++r) {
    bool same = true;
    for (int k = 0; k < n && same; ++k) same = a[k] == b[(r + k) % n];
    if (same) return true;
  }
  return false;
}

// True when b is a cyclic rotation of a (same orientation).
bool same_cycle(const Quad& a, const Quad& b) {
  for (int r = 0; r < 4; ++r)
    if (a[0] == b[r] && a[1] == b[(r + 1) % 4] && a[2] == b[(r + 2) % 4] && a[3] == b[(r + 3) % 4]) return true;
  return false;
}

class OvmParser {
 public:
  OvmParser(std::string_view bytes, const std::string& name, const ReadLimits& limits)
      : s_(bytes, name, /*has_hash_comments=*/false), limits_(limits), file_bytes_(bytes.size()) {}

  LoadedMesh parse() {
    if (!s_.skip_space()) s_.fail("empty file, expected 'OVM ASCII'");
    const std::string_view magic = s_.read_token();
    if (!iequals(magic, "OVM")) s_.fail("expected 'OVM ASCII', got " + quote(magic));
    if (!s_.skip_blank()) s_.fail("expected ASCII after OVM");
    const std::string_view kind = s_.read_token();
    if (iequals(kind, "BINARY")) s_.fail("OVM BINARY files are not supported (write OVM ASCII)");
    if (!iequals(kind, "ASCII")) s_.fail("expected 'OVM ASCII', got 'OVM " + std::string(kind) + "'");

    const std::int64_t num_vertices = section("Vertices", 6);
    check_mesh_memory(limits_, s_.name(), s_.line(), file_bytes_, num_vertices, -1);
    points_.reserve(static_cast<std::size_t>(num_vertices));
    for (std::int64_t i = 0; i < num_vertices; ++i) {
      double xyz[3];
      for (double& c : xyz) c = read_double("a coordinate", "vertex", i, num_vertices);
      for (const double c : xyz)
        if (!std::isfinite(c)) s_.fail("non-finite coordinate (vertex " + std::to_string(i) + ")");
      points_.push_back({xyz[0], xyz[1], xyz[2]});
    }

    const std::int64_t num_edges = section("Edges", 4);
    edges_.reserve(static_cast<std::size_t>(num_edges));
    for (std::int64_t e = 0; e < num_edges; ++e) {
      std::array<std::int64_t, 2> ends;
      for (std::int64_t& v : ends) {
        v = read_int("a vertex id", "edge", e, num_edges);
        if (v < 0 || v >= num_vertices)
          s_.fail("vertex id " + std::to_string(v) + " out of range [0, " + std::to_string(num_vertices) + ") (edge " +
                  std::to_string(e) + ")");
      }
      if (ends[0] == ends[1])
        s_.fail("edge " + std::to_string(e) + " joins vertex " + std::to_string(ends[0]) + " to itself");
      edges_.push_back(ends);
    }

    const std::int64_t num_faces = section("Faces", 4);
    faces_.reserve(static_cast<std::size_t>(num_faces));
    for (std::int64_t f = 0; f < num_faces; ++f) {
      const std::int64_t valence = read_int("a face valence", "face", f, num_faces);
      std::vector<std::int64_t> halfedges;
      if (valence < 3 || detail::exceeds_remaining(valence, 2, s_.remaining(), true))
        s_.fail("face valence " + std::to_string(valence) + " (face " + std::to_string(f) + ")");
      for (std::int64_t k = 0; k < valence; ++k) {
        const std::int64_t h = read_int("a half-edge id", "face", f, num_faces);
        if (h < 0 || h >= 2 * num_edges)
          s_.fail("half-edge id " + std::to_string(h) + " out of range [0, " + std::to_string(2 * num_edges) +
                  ") (face " + std::to_string(f) + ")");
        halfedges.push_back(h);
      }
      for (std::size_t k = 0; k < halfedges.size(); ++k)
        if (to_vertex(halfedges[k]) != from_vertex(halfedges[(k + 1) % halfedges.size()]))
          s_.fail("the half-edges of face " + std::to_string(f) + " do not form a cycle");
      // Triangles and quads only matter: other faces are kept as markers.
      Quad face{-1, -1, -1, -1};
      if (valence <= 4)
        for (int k = 0; k < valence; ++k) face[k] = from_vertex(halfedges[static_cast<std::size_t>(k)]);
      faces_.push_back(face);
      face_valences_.push_back(valence);
    }

    const std::int64_t num_cells = section("Polyhedra", 4);
    check_mesh_memory(limits_, s_.name(), s_.line(), file_bytes_, num_vertices, num_cells, "cell");
    for (std::int64_t c = 0; c < num_cells; ++c) {
      const std::int64_t valence = read_int("a polyhedron valence", "polyhedron", c, num_cells);
      const std::int64_t line = s_.line();
      if (valence < 4 || valence > 6)
        s_.fail("polyhedron " + std::to_string(c) + " has " + std::to_string(valence) + " half-faces: " + kNotACell);
      std::vector<Quad> faces;
      int num_triangles = 0;
      for (std::int64_t k = 0; k < valence; ++k) {
        const std::int64_t hf = read_int("a half-face id", "polyhedron", c, num_cells);
        if (hf < 0 || hf >= 2 * num_faces)
          s_.fail("half-face id " + std::to_string(hf) + " out of range [0, " + std::to_string(2 * num_faces) +
                  ") (polyhedron " + std::to_string(c) + ")");
        const auto f = static_cast<std::size_t>(hf / 2);
        const std::int64_t face_valence = face_valences_[f];
        if (face_valence > 4)
          s_.fail("polyhedron " + std::to_string(c) + " has a face with " + std::to_string(face_valence) +
                  " edges (face " + std::to_string(f) + "): " + kNotACell);
        Quad q = faces_[f];
        if (hf % 2 == 1) std::reverse(q.begin(), q.begin() + face_valence);
        num_triangles += face_valence == 3 ? 1 : 0;
        faces.push_back(q);
      }
      const auto num_quads = static_cast<int>(valence) - num_triangles;
      if (num_quads == 6) {
        std::array<Quad, 6> quads;
        std::copy(faces.begin(), faces.end(), quads.begin());
        detail::append_cell<CellKind::hex>(mesh_, rebuild_hex(quads, c, line), c);
      } else if (num_triangles == 4 && num_quads == 0) {
        detail::append_cell<CellKind::tet>(mesh_, rebuild_cell<CellKind::tet>(faces, c, line), c);
      } else if (num_triangles == 2 && num_quads == 3) {
        detail::append_cell<CellKind::wedge>(mesh_, rebuild_cell<CellKind::wedge>(faces, c, line), c);
      } else if (num_triangles == 4 && num_quads == 1) {
        detail::append_cell<CellKind::pyramid>(mesh_, rebuild_cell<CellKind::pyramid>(faces, c, line), c);
      } else {
        s_.fail_at(line, "polyhedron " + std::to_string(c) + " has " + std::to_string(num_triangles) +
                             " triangles and " + std::to_string(num_quads) + " quadrilaterals: " + kNotACell);
      }
    }
    if (num_cells == 0) s_.fail("no volume cells (no polyhedra)");
    LoadedMesh loaded;
    loaded.format = "ovm-ascii";
    mesh_.points = std::move(points_);
    loaded.mesh = std::move(mesh_);
    return loaded;
  }

 private:
  std::int64_t from_vertex(std::int64_t h) const { return edges_[static_cast<std::size_t>(h / 2)][h % 2 == 0 ? 0 : 1]; }
  std::int64_t to_vertex(std::int64_t h) const { return edges_[static_cast<std::size_t>(h / 2)][h % 2 == 0 ? 1 : 0]; }

  // "<Keyword>\n<count>"; checks the count against the rest of the file
  // (each entry takes at least min_bytes).
  std::int64_t section(std::string_view keyword, std::int64_t min_bytes) {
    if (!s_.skip_space()) s_.fail("unexpected end of file, expected " + std::string(keyword));
    const std::string_view token = s_.read_token();
    if (!iequals(token, keyword)) s_.fail("expected " + std::string(keyword) + ", got " + quote(token));
    if (!s_.skip_space()) s_.fail("unexpected end of file, expected the number of " + std::string(keyword));
    std::int64_t n = 0;
    if (!s_.read_int(n)) s_.fail("expected the number of " + std::string(keyword) + ", got " + quote(s_.peek_token()));
    if (n < 0) s_.fail("negative number of " + std::string(keyword) + ": " + std::to_string(n));
    if (n > kMaxIndexCount)
      s_.fail("number of " + std::string(keyword) + " " + std::to_string(n) + " exceeds the limit of " +
              std::to_string(kMaxIndexCount));
    if (detail::exceeds_remaining(n, min_bytes, s_.remaining(), true))
      s_.fail(std::to_string(n) + " " + std::string(keyword) + " cannot fit in the " + std::to_string(s_.remaining()) +
              " bytes left in the file");
    return n;
  }

  std::int64_t read_int(const char* what, const char* entity, std::int64_t i, std::int64_t n) {
    if (!s_.skip_space())
      s_.fail("unexpected end of file, expected " + std::string(what) + " (" + entity + " " + std::to_string(i) +
              " of " + std::to_string(n) + ")");
    std::int64_t value = 0;
    if (!s_.read_int(value)) s_.fail("expected " + std::string(what) + ", got " + quote(s_.peek_token()));
    return value;
  }
  double read_double(const char* what, const char* entity, std::int64_t i, std::int64_t n) {
    if (!s_.skip_space())
      s_.fail("unexpected end of file, expected " + std::string(what) + " (" + entity + " " + std::to_string(i) +
              " of " + std::to_string(n) + ")");
    double value = 0;
    if (!s_.read_double(value)) s_.fail("expected " + std::string(what) + ", got " + quote(s_.peek_token()));
    return value;
  }

  // A tetrahedron, wedge or pyramid in VTK order from its outward half-faces
  // (triangles have -1 as their 4th entry); throws unless they are exactly
  // the faces of that cell (CellKindTable<K>::faces), each once, outward.
  // The base is the first triangle (tet, wedge) or the quad (pyramid): a
  // tet's (0,2,1) and a wedge's (0,1,2) are outward, a pyramid's (0,3,2,1).
  template <CellKind K>
  CellCorners<K> rebuild_cell(const std::vector<Quad>& faces, std::int64_t c, std::int64_t line) const {
    using Table = CellKindTable<K>;
    const auto fail = [&](const std::string& why) {
      s_.fail_at(line, "polyhedron " + std::to_string(c) + " is not a " + std::string(Table::name) + ": " + why);
    };
    const auto size_of = [](const Quad& f) { return f[3] < 0 ? 3 : 4; };
    const auto contains = [&](const Quad& f, std::int64_t v) {
      for (int k = 0; k < size_of(f); ++k)
        if (f[static_cast<std::size_t>(k)] == v) return true;
      return false;
    };
    const int base_size = K == CellKind::pyramid ? 4 : 3;
    std::size_t b = 0;
    while (size_of(faces[b]) != base_size) ++b;
    const Quad& base = faces[b];
    std::array<std::int64_t, Table::num_corners> h{};
    if constexpr (K == CellKind::tet) {
      h = {base[0], base[2], base[1], -1};
    } else if constexpr (K == CellKind::pyramid) {
      h = {base[0], base[3], base[2], base[1], -1};
    } else {
      h = {base[0], base[1], base[2], -1, -1, -1};
    }
    if constexpr (K == CellKind::tet || K == CellKind::pyramid) {
      // The apex: the vertex of another face off the base.
      for (const Quad& f : faces)
        for (int k = 0; k < size_of(f); ++k)
          if (!contains(base, f[static_cast<std::size_t>(k)])) h.back() = f[static_cast<std::size_t>(k)];
    } else {
      // Corner i+3: the neighbour of corner i along a quad's edge, off the base.
      for (int i = 0; i < 3; ++i)
        for (const Quad& f : faces) {
          if (size_of(f) != 4) continue;
          for (int k = 0; k < 4; ++k) {
            if (f[static_cast<std::size_t>(k)] != h[static_cast<std::size_t>(i)]) continue;
            for (const std::int64_t v : {f[static_cast<std::size_t>((k + 1) % 4)], f[static_cast<std::size_t>((k + 3) % 4)]})
              if (!contains(base, v)) {
                if (h[static_cast<std::size_t>(i) + 3] != -1 && h[static_cast<std::size_t>(i) + 3] != v)
                  fail("corner " + std::to_string(h[static_cast<std::size_t>(i)]) + " has more than 3 neighbours");
                h[static_cast<std::size_t>(i) + 3] = v;
              }
          }
        }
    }
    for (std::size_t i = 0; i < h.size(); ++i) {
      if (h[i] < 0) fail("its faces do not close up as a " + std::string(Table::name) + "'s");
      for (std::size_t j = 0; j < i; ++j)
        if (h[i] == h[j]) fail("vertex " + std::to_string(h[i]) + " is two of its corners");
    }
    // The outward faces of that cell must be the half-faces, each once.
    std::array<bool, Table::faces.size()> used{};
    for (const Quad& f : faces) {
      bool found = false, is_flipped = false;
      for (std::size_t k = 0; k < Table::faces.size() && !found; ++k) {
        const CellFace& face = Table::faces[k];
        if (face.size != size_of(f)) continue;
        Quad expected{-1, -1, -1, -1}, reversed{-1, -1, -1, -1};
        for (int j = 0; j < face.size; ++j) {
          expected[static_cast<std::size_t>(j)] = h[static_cast<std::size_t>(face.v[static_cast<std::size_t>(j)])];
          reversed[static_cast<std::size_t>(face.size - 1 - j)] = expected[static_cast<std::size_t>(j)];
        }
        if (!used[k] && same_cycle(expected, f, face.size)) used[k] = found = true;
        is_flipped = is_flipped || same_cycle(reversed, f, face.size);
      }
      if (!found)
        fail(is_flipped ? "its half-faces are not consistently oriented"
                        : "its faces do not close up as a " + std::string(Table::name) + "'s");
    }
    CellCorners<K> cell;
    for (std::size_t i = 0; i < h.size(); ++i) cell[i] = static_cast<Index>(h[i]);
    return cell;
  }

  // Corners in VTK order from 6 outward-oriented quads; throws unless they
  // are exactly the faces of that hexahedron.
  Hex rebuild_hex(const std::array<Quad, 6>& quads, std::int64_t c, std::int64_t line) const {
    const auto not_hex = [&](const std::string& why) {
      s_.fail_at(line, "polyhedron " + std::to_string(c) + " is not a hexahedron: " + why);
    };
    // Bottom: the first half-face reversed (inward normal). OVM's HexahedralMesh
    // stores (o3, o2, o1, o0) there: reversed, corners 0-3 are o0-o3.
    Quad bottom = quads[0];
    std::reverse(bottom.begin(), bottom.end());
    std::array<std::int64_t, 8> h{};
    for (int i = 0; i < 4; ++i) h[static_cast<std::size_t>(i)] = bottom[static_cast<std::size_t>(i)];
    for (int i = 0; i < 4; ++i) {
      // The neighbour of corner i along an edge of some other face, off the bottom.
      std::int64_t above = -1;
      for (int k = 1; k < 6; ++k)
        for (int j = 0; j < 4; ++j) {
          const Quad& q = quads[static_cast<std::size_t>(k)];
          if (q[static_cast<std::size_t>(j)] != h[static_cast<std::size_t>(i)]) continue;
          for (const std::int64_t v :
               {q[static_cast<std::size_t>((j + 1) % 4)], q[static_cast<std::size_t>((j + 3) % 4)]})
            if (std::find(bottom.begin(), bottom.end(), v) == bottom.end()) {
              if (above != -1 && above != v)
                not_hex("corner " + std::to_string(h[static_cast<std::size_t>(i)]) + " has more than 3 neighbours");
              above = v;
            }
        }
      if (above == -1)
        not_hex("no edge leaves the bottom face at vertex " + std::to_string(h[static_cast<std::size_t>(i)]));
      h[static_cast<std::size_t>(i) + 4] = above;
    }
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < i; ++j)
        if (h[static_cast<std::size_t>(i)] == h[static_cast<std::size_t>(j)])
          not_hex("vertex " + std::to_string(h[static_cast<std::size_t>(i)]) + " is two of its corners");
    // The outward faces of that hexahedron must be the 6 half-faces, each once.
    const std::array<Quad, 6> expected = {{{h[0], h[3], h[2], h[1]},
                                           {h[4], h[5], h[6], h[7]},
                                           {h[0], h[1], h[5], h[4]},
                                           {h[1], h[2], h[6], h[5]},
                                           {h[2], h[3], h[7], h[6]},
                                           {h[3], h[0], h[4], h[7]}}};
    std::array<bool, 6> used{};
    for (const Quad& q : quads) {
      bool found = false;
      for (std::size_t k = 0; k < 6 && !found; ++k)
        if (!used[k] && same_cycle(expected[k], q)) used[k] = found = true;
      if (!found) {
        Quad reversed = q;
        std::reverse(reversed.begin(), reversed.end());
        bool is_flipped = false;
        for (const Quad& e : expected) is_flipped = is_flipped || same_cycle(e, reversed);
        not_hex(is_flipped ? "its half-faces are not consistently oriented"
                           : "its faces do not close up as a hexahedron's");
      }
    }
    Hex hex;
    for (int i = 0; i < 8; ++i) hex[i] = static_cast<Index>(h[static_cast<std::size_t>(i)]);
    return hex;
  }

  TextScanner s_;
  ReadLimits limits_;
  std::uint64_t file_bytes_;
  std::vector<Vec3> points_;
  std::vector<std::array<std::int64_t, 2>> edges_;
  std::vector<Quad> faces_;
  std::vector<std::int64_t> face_valences_;
  Mesh mesh_;  // the cell blocks (points_ are moved in at the end)
};

}  // namespace

bool looks_like_ovm(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && detail::is_space(bytes[i])) ++i;
  return detail::istarts_with(bytes.substr(i), "OVM ASCII") || detail::istarts_with(bytes.substr(i), "OVM BINARY");
}

LoadedMesh read_ovm(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  return OvmParser(bytes, name, limits).parse();
}

}  // namespace hq
