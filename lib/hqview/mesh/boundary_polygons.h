#pragma once
// The whole boundary of a mesh over every cell kind, as the views and the
// viewer draw it: the hex boundary quads (Topology::boundary_faces, in that
// order), then the non-hex quads (boundary_quads_non_hex), then the
// triangles (boundary_triangles), each outward, with the cell it belongs to.
// On a pure-hex mesh this is exactly boundary_faces, in its order, so every
// hex view keeps its bytes. Non-conforming faces (Topology::
// non_conforming_faces) are interior and never part of it.

#include <array>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/mesh/topology.h"

namespace hq {

struct BoundaryPolygon {
  std::array<Index, 4> v{kNoIndex, kNoIndex, kNoIndex, kNoIndex};  // corners, outward; v[3] = kNoIndex for a triangle
  int size = 4;                                                   // 3 or 4
  Index cell = kNoIndex;                                          // cell id over all blocks (hexes first)
};

// Every boundary face over all kinds, in the order above.
std::vector<BoundaryPolygon> boundary_polygons(const Topology& topology);

// The unique edges (a < b, ascending) of boundary_polygons(topology): on a
// pure-hex mesh boundary_edges(topology).
std::vector<Edge> boundary_edges_all_kinds(const Topology& topology);

// The unique edges (a < b, ascending) of the non-conforming faces' quads.
std::vector<Edge> non_conforming_edges(const Topology& topology);

}  // namespace hq
