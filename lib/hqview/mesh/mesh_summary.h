#pragma once
// report.json `mesh`: counts, bounding box and edge lengths of a hex mesh.

#include <optional>

#include "hqview/core/box3.h"
#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/planarity.h"
#include "hqview/mesh/topology.h"

namespace hq {

struct MeshSummary {
  Index num_vertices = 0;               // points some cell uses as a corner
  Index num_hexes = 0;
  Index num_unreferenced_vertices = 0;  // points no cell uses (mid-edge nodes of second-order cells, strays)
  Index num_boundary_faces = 0;
  Index num_boundary_vertices = 0;
  Index num_non_manifold_faces = 0;     // faces used by more than two cells (of any kinds)
  Index num_non_conforming_faces = 0;   // quads against two triangles (Topology::non_conforming_faces)
  Vec3 bbox_min, bbox_max;  // of the vertices cells use (stray points do not frame views)
  double bbox_diagonal = 0;
  double edge_length_min = 0, edge_length_mean = 0, edge_length_max = 0;  // over every unique edge of every cell; 0 without edges
  // A surface mesh (quads and triangles; mesh.h is_surface_mesh): its
  // boundary and non-manifold edges, its faces reversed against their
  // neighbours (SurfaceTopology) and, filled by the pipeline, its plane.
  bool is_surface = false;
  Index num_boundary_edges = 0, num_non_manifold_edges = 0, num_reversed_faces = 0;
  std::optional<Planarity> planarity;
};

MeshSummary summarize_mesh(const HexMesh& mesh, const Topology& topo);

// A surface mesh not in one plane: no plane's normal signs its cells, so its
// inverted cells are its reversed faces (their corners signed against the
// orientation their neighbours agree on), and the pages say so.
inline bool is_curved_surface(const MeshSummary& m) { return m.is_surface && !(m.planarity && m.planarity->is_planar); }

// The box of the vertices cells use (empty when none is).
Box3 referenced_bounding_box(const HexMesh& mesh, const Topology& topo);

}  // namespace hq
