#include "hqview/mesh/mesh_summary.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "hqview/core/box3.h"

namespace hq {

Box3 referenced_bounding_box(const HexMesh& mesh, const Topology& topo) {
  // Every vertex but the unreferenced ones (ascending), which a hybrid
  // mesh's non-hex cells may use.
  Box3 box;
  auto skip = topo.unreferenced_vertices.begin();
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (skip != topo.unreferenced_vertices.end() && static_cast<std::size_t>(*skip) == v) {
      ++skip;
      continue;
    }
    box.add(mesh.points[v]);
  }
  return box;
}

MeshSummary summarize_mesh(const HexMesh& mesh, const Topology& topo) {
  MeshSummary s;
  // A vertex is a corner of a cell: nodes no cell uses (a second-order
  // cell's mid-edge and face nodes, read by its corners; stray nodes) are
  // counted apart.
  s.num_unreferenced_vertices = static_cast<Index>(topo.unreferenced_vertices.size());
  s.num_vertices = mesh.num_vertices() - s.num_unreferenced_vertices;
  s.num_hexes = mesh.num_hexes();
  s.num_boundary_faces = static_cast<Index>(num_boundary_faces_all_kinds(topo));
  s.num_boundary_vertices = static_cast<Index>(topo.boundary_vertices.size());
  s.num_non_manifold_faces = static_cast<Index>(topo.non_manifold_faces.size()) + topo.num_non_manifold_faces_non_hex;
  s.num_non_conforming_faces = static_cast<Index>(topo.non_conforming_faces.size());
  s.is_surface = is_surface_mesh(mesh);
  s.num_boundary_edges = topo.surface.num_boundary_edges;
  s.num_non_manifold_edges = topo.surface.num_non_manifold_edges;
  s.num_reversed_faces = topo.surface.num_reversed;
  const Box3 box = referenced_bounding_box(mesh, topo);
  if (!box.is_empty()) {
    s.bbox_min = box.lo;
    s.bbox_max = box.hi;
  }
  s.bbox_diagonal = norm(s.bbox_max - s.bbox_min);
  // Over every edge: the hex part's (topo.edges) and, on a hybrid mesh,
  // every kind's (topo.all_edges, the same ascending order).
  const std::vector<Edge>& edges = topo.across_kinds ? topo.all_edges : topo.edges;
  if (!edges.empty()) {
    double sum = 0.0;
    s.edge_length_min = INFINITY;
    for (const Edge& e : edges) {
      const double l = norm(mesh.points[e[1]] - mesh.points[e[0]]);
      s.edge_length_min = std::min(s.edge_length_min, l);
      s.edge_length_max = std::max(s.edge_length_max, l);
      sum += l;
    }
    s.edge_length_mean = sum / static_cast<double>(edges.size());
  }
  return s;
}

}  // namespace hq
