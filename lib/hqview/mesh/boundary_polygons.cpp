#include "hqview/mesh/boundary_polygons.h"

#include <algorithm>

namespace hq {

std::vector<BoundaryPolygon> boundary_polygons(const Topology& t) {
  std::vector<BoundaryPolygon> out;
  out.reserve(num_boundary_faces_all_kinds(t));
  for (Index f : t.boundary_faces) {
    const auto fi = static_cast<std::size_t>(f);
    out.push_back({t.faces[fi], 4, t.face_hexes[static_cast<std::size_t>(t.face_hex_offsets[fi])]});
  }
  for (std::size_t i = 0; i < t.boundary_quads_non_hex.size(); ++i)
    out.push_back({t.boundary_quads_non_hex[i], 4, t.boundary_quad_non_hex_cells[i]});
  for (std::size_t i = 0; i < t.boundary_triangles.size(); ++i) {
    const Tri& tri = t.boundary_triangles[i];
    out.push_back({{tri[0], tri[1], tri[2], kNoIndex}, 3, t.boundary_triangle_cells[i]});
  }
  return out;
}

namespace {

template <class Faces>
void add_cycle_edges(const Faces& faces, std::vector<Edge>& edges) {
  for (const auto& face : faces) {
    const auto n = static_cast<int>(face.size());
    for (int i = 0; i < n; ++i) {
      const Index a = face[static_cast<std::size_t>(i)], b = face[static_cast<std::size_t>((i + 1) % n)];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
}

void sort_unique(std::vector<Edge>& edges) {
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
}

}  // namespace

std::vector<Edge> boundary_edges_all_kinds(const Topology& t) {
  // A pure-hex mesh: its hex boundary (no other faces); a surface mesh's
  // faces are the non-hex ones (surface_boundary.h).
  if (!t.across_kinds && t.boundary_quads_non_hex.empty() && t.boundary_triangles.empty()) return boundary_edges(t);
  std::vector<Edge> edges = boundary_edges(t);
  add_cycle_edges(t.boundary_quads_non_hex, edges);
  add_cycle_edges(t.boundary_triangles, edges);
  sort_unique(edges);
  return edges;
}

std::vector<Edge> non_conforming_edges(const Topology& t) {
  std::vector<Edge> edges;
  for (const NonConformingFace& nc : t.non_conforming_faces) add_cycle_edges(std::array<Quad, 1>{nc.quad}, edges);
  sort_unique(edges);
  return edges;
}

}  // namespace hq
