#pragma once
// The connectivity of a surface mesh (quadrilaterals and triangles, no
// volume cell; mesh.h): its unique edges and how many faces use each, the
// boundary and non-manifold edges, and the faces whose orientation disagrees
// with their neighbours' (docs/analysis.md, "Surface meshes").
//
// Orientation: two faces sharing a manifold edge (one used by exactly two
// faces) agree when they run along it in opposite directions. Each
// edge-connected component (through manifold edges) is oriented from its
// lowest face id by a breadth-first walk; the faces that disagree with that
// face, or, when they are fewer, the faces that agree with it, are the
// component's reversed faces (the minority; on a tie, the ones that disagree
// with the lowest face). On a non-orientable component (a Moebius strip) the
// walk's first assignment stands.

#include <cstdint>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/mesh/mesh.h"

namespace hq {

struct SurfaceTopology {
  // Unique edges of every quad and triangle, (a, b) with a < b, ascending,
  // and per edge the number of faces using it.
  std::vector<std::array<Index, 2>> edges;
  std::vector<Index> edge_num_faces;
  Index num_boundary_edges = 0;      // used by one face
  Index num_non_manifold_edges = 0;  // used by more than two faces
  // Per face (cell id over the surface blocks: quads, then triangles): 1
  // when it is one of its component's reversed faces.
  std::vector<char> is_reversed;
  Index num_reversed = 0;
  Index num_components = 0;  // edge-connected through manifold edges
};

// Linear in the faces and vertices (counting sorts). Faces with a
// repeated corner (a zero-length edge) take part through their other edges.
SurfaceTopology build_surface_topology(const Mesh& mesh);

// Calls f(corner ids, size) for each surface cell in cell-id order (quads,
// then triangles), corner ids an std::array<Index, 4> whose first `size` (4
// or 3) are used.
template <class F>
void for_each_surface_cell(const Mesh& mesh, F&& f) {
  for (const auto& q : mesh.quads) f(q, 4);
  for (const auto& t : mesh.triangles) f(std::array<Index, 4>{t[0], t[1], t[2], kNoIndex}, 3);
}

}  // namespace hq
