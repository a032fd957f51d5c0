#include "hqview/structure/quad_structure.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "hqview/core/vec3.h"

namespace hq {
namespace {

using Quad = CellCorners<CellKind::quad>;

std::uint64_t edge_key(Index a, Index b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b)), hi = static_cast<std::uint32_t>(std::max(a, b));
  return std::uint64_t{lo} << 32 | hi;
}

// The place of corner (or edge) k of quad q in per-corner arrays.
std::size_t slot(Index q, int k) { return 4 * static_cast<std::size_t>(q) + static_cast<std::size_t>(k); }

// The quads' unique edges: quad_edge[4 q + k] is the edge from corner k to
// corner k + 1 of quad q; edge_quads[e] how many quads hold edge e (1
// boundary, 2 interior, more non-manifold); edge_ends[e] its vertices.
struct QuadEdges {
  std::vector<Index> quad_edge;
  std::vector<Index> edge_quads;
  std::vector<std::array<Index, 2>> edge_ends;
};

// The (edge key, slot) entries ascending, without a comparison sort: counted
// into the bucket of the edge's smaller id, placed there in slot order, and
// each bucket (a vertex's edges up: a handful) ordered by key by insertion,
// a large one (the apex of a fan) by a stable sort.
QuadEdges build_quad_edges(const std::vector<Quad>& quads, Index num_vertices) {
  using Entry = std::pair<std::uint64_t, std::uint32_t>;
  const auto key = [&](std::size_t q, int k) { return edge_key(quads[q][k], quads[q][(k + 1) % 4]); };
  std::vector<std::size_t> next(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (std::size_t q = 0; q < quads.size(); ++q)
    for (int k = 0; k < 4; ++k) ++next[(key(q, k) >> 32) + 1];
  for (std::size_t v = 1; v < next.size(); ++v) next[v] += next[v - 1];
  std::vector<Entry> entries(quads.size() * 4);
  for (std::size_t q = 0; q < quads.size(); ++q)
    for (int k = 0; k < 4; ++k) entries[next[key(q, k) >> 32]++] = {key(q, k), static_cast<std::uint32_t>(4 * q + k)};
  // next[v] is now the end of v's bucket.
  for (std::size_t v = 0, begin = 0; v + 1 < next.size(); begin = next[v++]) {
    if (next[v] - begin > 32) {
      std::sort(entries.begin() + static_cast<std::ptrdiff_t>(begin), entries.begin() + static_cast<std::ptrdiff_t>(next[v]));
      continue;
    }
    for (std::size_t i = begin + 1; i < next[v]; ++i) {
      const Entry e = entries[i];
      std::size_t j = i;
      for (; j > begin && e < entries[j - 1]; --j) entries[j] = entries[j - 1];
      entries[j] = e;
    }
  }
  QuadEdges edges;
  edges.quad_edge.assign(entries.size(), kNoIndex);
  for (std::size_t i = 0; i < entries.size();) {
    std::size_t j = i;
    const auto e = static_cast<Index>(edges.edge_ends.size());
    while (j < entries.size() && entries[j].first == entries[i].first) edges.quad_edge[entries[j++].second] = e;
    edges.edge_quads.push_back(static_cast<Index>(j - i));
    edges.edge_ends.push_back(
        {static_cast<Index>(entries[i].first >> 32), static_cast<Index>(entries[i].first & 0xffffffffu)});
    i = j;
  }
  return edges;
}

// Vertex -> (quad, corner) in CSR form, quads ascending.
struct VertexQuads {
  std::vector<std::int64_t> offsets;
  std::vector<std::pair<Index, int>> corners;
};

VertexQuads build_vertex_quads(const std::vector<Quad>& quads, Index num_vertices) {
  VertexQuads vq;
  vq.offsets.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (const Quad& quad : quads)
    for (const Index v : quad) ++vq.offsets[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < static_cast<std::size_t>(num_vertices); ++v) vq.offsets[v + 1] += vq.offsets[v];
  vq.corners.resize(quads.size() * 4);
  std::vector<std::int64_t> next(vq.offsets.begin(), vq.offsets.end() - 1);
  for (std::size_t q = 0; q < quads.size(); ++q)
    for (int k = 0; k < 4; ++k)
      vq.corners[static_cast<std::size_t>(next[static_cast<std::size_t>(quads[q][k])]++)] = {static_cast<Index>(q), k};
  return vq;
}

// The angle at p between the directions to a and b, in radians (0 for a
// zero-length side).
double corner_angle(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 u = a - p, w = b - p;
  return std::atan2(norm(cross(u, w)), dot(u, w));
}

class QuadStructureBuilder {
 public:
  QuadStructureBuilder(const Mesh& mesh, const QuadStructureOptions& options)
      : mesh_(mesh),
        options_(options),
        num_vertices_(mesh.num_vertices()),
        edges_(build_quad_edges(mesh.quads, mesh.num_vertices())),
        vq_(build_vertex_quads(mesh.quads, num_vertices_)) {}

  QuadStructure build() {
    classify_vertices();
    trace_separatrices();
    find_patches();
    return std::move(s_);
  }

 private:
  // Valences, vertex kinds, ideal valences and the irregular vertices.
  void classify_vertices() {
    const auto n = static_cast<std::size_t>(num_vertices_);
    s_.valence.assign(n, 0);
    s_.vertex_kind.assign(n, QuadVertexKind::interior);
    s_.ideal_valence.assign(n, 0);
    s_.irregular.assign(n, 0);
    std::vector<char> blocked(n, 0);
    // Vertices of the other blocks (a quad-dominant mesh's triangles).
    for_each_block(mesh_, [&](auto kind, const auto& cells) {
      if constexpr (kind() != CellKind::quad)
        for (const auto& cell : cells)
          for (const Index v : cell) blocked[static_cast<std::size_t>(v)] = 1;
    });
    std::vector<std::array<Index, 2>> holes = options_.hole_edges;
    std::sort(holes.begin(), holes.end());
    std::vector<Index> boundary_edges(n, 0);
    s_.num_edges = static_cast<Index>(edges_.edge_ends.size());
    for (std::size_t e = 0; e < edges_.edge_ends.size(); ++e) {
      const auto [a, b] = edges_.edge_ends[e];
      const Index count = edges_.edge_quads[e];
      const bool is_hole = std::binary_search(holes.begin(), holes.end(), std::array<Index, 2>{a, b});
      if (count > 2) ++s_.num_nonmanifold_edges;
      if (count == 1 && !is_hole) ++s_.num_boundary_edges;
      if (count > 2 || is_hole) {
        blocked[static_cast<std::size_t>(a)] = blocked[static_cast<std::size_t>(b)] = 1;
      } else if (count == 1) {
        ++boundary_edges[static_cast<std::size_t>(a)];
        ++boundary_edges[static_cast<std::size_t>(b)];
      }
    }
    for (std::size_t v = 0; v < n; ++v) {
      const auto valence = static_cast<Index>(vq_.offsets[v + 1] - vq_.offsets[v]);
      s_.valence[v] = valence;
      if (valence == 0 || blocked[v] || (boundary_edges[v] != 0 && boundary_edges[v] != 2)) {
        s_.vertex_kind[v] = QuadVertexKind::unclassified;
        if (valence > 0) ++s_.num_unclassified;
        continue;
      }
      if (boundary_edges[v] == 0) {
        s_.ideal_valence[v] = 4;
      } else {
        s_.vertex_kind[v] = QuadVertexKind::boundary;
        double theta = 0;
        for (std::int64_t i = vq_.offsets[v]; i < vq_.offsets[v + 1]; ++i) {
          const auto [q, k] = vq_.corners[static_cast<std::size_t>(i)];
          const Quad& quad = mesh_.quads[static_cast<std::size_t>(q)];
          theta += corner_angle(mesh_.points[v], mesh_.points[static_cast<std::size_t>(quad[(k + 1) % 4])],
                                mesh_.points[static_cast<std::size_t>(quad[(k + 3) % 4])]);
        }
        const double ideal = std::isfinite(theta) ? std::round(theta / (std::numbers::pi / 2)) : 1.0;
        s_.ideal_valence[v] = static_cast<std::int8_t>(std::clamp(ideal, 1.0, 100.0));
      }
      if (valence == s_.ideal_valence[v]) continue;
      s_.irregular[v] = 1;
      s_.irregular_vertices.push_back(static_cast<Index>(v));
      ++s_.num_irregular;
      if (s_.vertex_kind[v] == QuadVertexKind::interior) {
        ++s_.num_irregular_interior;
        ++s_.interior_by_valence[valence];
      } else {
        ++s_.num_irregular_boundary;
        ++s_.boundary_by_valence[valence];
      }
    }
  }

  Index other_end(Index e, Index v) const {
    const auto& ends = edges_.edge_ends[static_cast<std::size_t>(e)];
    return ends[0] == v ? ends[1] : ends[0];
  }

  // The edges at v, in the order of its quads (each quad's edge to its next
  // corner, then from its previous one), each once.
  std::vector<Index> edges_at(Index v) const {
    std::vector<Index> out;
    for (std::int64_t i = vq_.offsets[static_cast<std::size_t>(v)]; i < vq_.offsets[static_cast<std::size_t>(v) + 1];
         ++i) {
      const auto [q, k] = vq_.corners[static_cast<std::size_t>(i)];
      for (const int local : {k, (k + 3) % 4}) {
        const Index e = edges_.quad_edge[slot(q, local)];
        if (std::find(out.begin(), out.end(), e) == out.end()) out.push_back(e);
      }
    }
    return out;
  }

  // At a regular interior vertex b (4 quads) reached from a: the edge
  // opposite (b, a), shared by the two quads at b that do not hold a;
  // kNoIndex when there is none (b is not a disk of 4 quads).
  Index opposite_edge(Index b, Index a) const {
    std::array<std::pair<Index, Index>, 4> seen{};  // (neighbour, edge) of the quads without a
    int num_seen = 0;
    for (std::int64_t i = vq_.offsets[static_cast<std::size_t>(b)]; i < vq_.offsets[static_cast<std::size_t>(b) + 1];
         ++i) {
      const auto [q, k] = vq_.corners[static_cast<std::size_t>(i)];
      const Quad& quad = mesh_.quads[static_cast<std::size_t>(q)];
      if (std::find(quad.begin(), quad.end(), a) != quad.end()) continue;
      if (num_seen > 2) return kNoIndex;
      seen[static_cast<std::size_t>(num_seen++)] = {quad[(k + 1) % 4], edges_.quad_edge[slot(q, k)]};
      seen[static_cast<std::size_t>(num_seen++)] = {quad[(k + 3) % 4], edges_.quad_edge[slot(q, (k + 3) % 4)]};
    }
    if (num_seen != 4) return kNoIndex;
    for (int i = 0; i < 2; ++i)
      for (int j = 2; j < 4; ++j)
        if (seen[static_cast<std::size_t>(i)].first == seen[static_cast<std::size_t>(j)].first)
          return seen[static_cast<std::size_t>(i)].second;
    return kNoIndex;
  }

  bool is_cap_reached() const {
    return options_.max_traced_edges > 0 && s_.num_traced_edges >= options_.max_traced_edges;
  }

  void trace_separatrices() {
    traced_.assign(edges_.edge_ends.size(), 0);
    for (const Index v : s_.irregular_vertices) {
      for (const Index first : edges_at(v)) {
        if (edges_.edge_quads[static_cast<std::size_t>(first)] != 2 || traced_[static_cast<std::size_t>(first)])
          continue;
        if (is_cap_reached()) {
          s_.is_capped = true;
          return;
        }
        trace_one(v, first);
      }
    }
  }

  // One separatrix from irregular vertex v along edge `e`.
  void trace_one(Index v, Index e) {
    s_.separatrix_vertices.push_back(v);
    Index from = v;
    SeparatrixEnd end = SeparatrixEnd::cap;
    while (true) {
      traced_[static_cast<std::size_t>(e)] = 1;
      ++s_.num_traced_edges;
      const Index to = other_end(e, from);
      s_.separatrix_vertices.push_back(to);
      const auto t = static_cast<std::size_t>(to);
      if (s_.irregular[t]) {
        end = SeparatrixEnd::irregular_vertex;
        break;
      }
      if (s_.vertex_kind[t] != QuadVertexKind::interior) {
        end = s_.vertex_kind[t] == QuadVertexKind::boundary ? SeparatrixEnd::boundary
                                                            : SeparatrixEnd::unclassified_vertex;
        break;
      }
      const Index next = opposite_edge(to, from);
      if (next == kNoIndex) {
        end = SeparatrixEnd::unclassified_vertex;
        break;
      }
      if (traced_[static_cast<std::size_t>(next)]) {
        end = SeparatrixEnd::traced_edge;
        break;
      }
      if (is_cap_reached()) {
        s_.is_capped = true;
        break;
      }
      from = to;
      e = next;
    }
    s_.separatrix_end.push_back(end);
    s_.separatrix_offsets.push_back(static_cast<std::int64_t>(s_.separatrix_vertices.size()));
    ++s_.num_separatrices;
  }

  // Union-find over the quads across the interior manifold edges no
  // separatrix traced.
  void find_patches() {
    const std::size_t num_quads = mesh_.quads.size();
    std::vector<Index> parent(num_quads);
    for (std::size_t q = 0; q < num_quads; ++q) parent[q] = static_cast<Index>(q);
    const auto root = [&](Index q) {
      while (parent[static_cast<std::size_t>(q)] != q) {
        parent[static_cast<std::size_t>(q)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(q)])];
        q = parent[static_cast<std::size_t>(q)];
      }
      return q;
    };
    std::vector<Index> first_quad(edges_.edge_ends.size(), kNoIndex);
    for (std::size_t i = 0; i < edges_.quad_edge.size(); ++i) {
      const auto e = static_cast<std::size_t>(edges_.quad_edge[i]);
      if (edges_.edge_quads[e] != 2 || traced_[e]) continue;
      const auto q = static_cast<Index>(i / 4);
      if (first_quad[e] == kNoIndex) {
        first_quad[e] = q;
        continue;
      }
      const Index a = root(first_quad[e]), b = root(q);
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
    s_.quad_patch.assign(num_quads, kNoIndex);
    std::vector<Index> patch_of_root(num_quads, kNoIndex);
    for (std::size_t q = 0; q < num_quads; ++q) {
      const auto r = static_cast<std::size_t>(root(static_cast<Index>(q)));
      if (patch_of_root[r] == kNoIndex) patch_of_root[r] = s_.num_patches++;
      s_.quad_patch[q] = patch_of_root[r];
    }
  }

  const Mesh& mesh_;
  const QuadStructureOptions& options_;
  Index num_vertices_;
  QuadEdges edges_;
  VertexQuads vq_;
  std::vector<char> traced_;
  QuadStructure s_;
};

}  // namespace

QuadStructure compute_quad_structure(const Mesh& mesh, const QuadStructureOptions& options) {
  return QuadStructureBuilder(mesh, options).build();
}

}  // namespace hq
