#pragma once
// Derived connectivity of a HexMesh, built once by build_topology() and then
// read by every later stage. Flat CSR arrays, 0-based Index ids, all orders
// deterministic (sorted by vertex ids, never by hash order).

#include <array>
#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/untouched_vector.h"
#include "hqview/mesh/hex_mesh.h"

namespace hq {

using Quad = std::array<Index, 4>;
using Edge = std::array<Index, 2>;

struct Topology {
  // vertex -> incident hexes: hexes of vertex v are
  // vertex_hexes[vertex_hex_offsets[v] .. vertex_hex_offsets[v+1]), ascending.
  std::vector<Index> vertex_hex_offsets;  // num_vertices + 1
  std::vector<Index> vertex_hexes;

  // Unique faces (4 vertex ids as seen from outside their first hex, i.e. the
  // lowest-numbered hex using the face), ordered by their sorted vertex ids.
  UntouchedVector<Quad> faces;
  // face -> incident hexes (CSR, ascending hex ids); 1 = boundary face,
  // 2 = interior face, more = non-manifold.
  UntouchedVector<Index> face_hex_offsets;  // faces.size() + 1
  UntouchedVector<Index> face_hexes;
  // For hex h and local face f (kHexFaces order), its face id: hex_faces[6*h+f].
  UntouchedVector<Index> hex_faces;

  std::vector<Index> boundary_faces;         // face ids used by exactly one hex, ascending
  std::vector<Index> non_manifold_faces;     // face ids used by more than two hexes
  std::vector<Index> boundary_vertices;      // ascending vertex ids on a boundary face
  std::vector<char> is_boundary_vertex;      // num_vertices, 0/1
  std::vector<Edge> edges;                   // unique edges (a < b), ascending
  std::vector<Index> unreferenced_vertices;  // vertices used by no hex, ascending

  // The hexes using vertex v, ascending.
  std::span<const Index> hexes_of(Index v) const {
    return {vertex_hexes.data() + vertex_hex_offsets[static_cast<std::size_t>(v)],
            vertex_hexes.data() + vertex_hex_offsets[static_cast<std::size_t>(v) + 1]};
  }

  Index num_face_hexes(Index face) const {
    return face_hex_offsets[static_cast<std::size_t>(face) + 1] - face_hex_offsets[static_cast<std::size_t>(face)];
  }
};

// The unique edges of the boundary faces (a < b), ascending.
std::vector<Edge> boundary_edges(const Topology& topology);

// Builds every table above in O(#hexes) expected time.
// Precondition: every id in mesh.hexes is in [0, mesh.num_vertices()) (the
// readers guarantee it). Throws nothing.
Topology build_topology(const HexMesh& mesh);

}  // namespace hq
