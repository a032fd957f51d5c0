#include "hqview/mesh/surface_boundary.h"

namespace hq {

void add_surface_faces_as_boundary(const Mesh& mesh, Topology& topology) {
  if (!is_surface_mesh(mesh)) return;
  const auto num_quads = static_cast<Index>(mesh.quads.size());
  topology.boundary_quads_non_hex.clear();
  topology.boundary_quad_non_hex_cells.clear();
  topology.boundary_triangles.clear();
  topology.boundary_triangle_cells.clear();
  topology.boundary_quads_non_hex.reserve(mesh.quads.size());
  topology.boundary_quad_non_hex_cells.reserve(mesh.quads.size());
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
    const auto& c = mesh.quads[q];
    topology.boundary_quads_non_hex.push_back({c[0], c[1], c[2], c[3]});
    topology.boundary_quad_non_hex_cells.push_back(static_cast<Index>(q));
  }
  topology.boundary_triangles.reserve(mesh.triangles.size());
  topology.boundary_triangle_cells.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& c = mesh.triangles[t];
    topology.boundary_triangles.push_back({c[0], c[1], c[2]});
    topology.boundary_triangle_cells.push_back(num_quads + static_cast<Index>(t));
  }
}

}  // namespace hq
