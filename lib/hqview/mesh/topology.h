#pragma once
// Derived connectivity of a HexMesh, built once by build_topology() and then
// read by every later stage. Flat CSR arrays, 0-based Index ids, all orders
// deterministic (sorted by vertex ids, never by hash order).
//
// A hybrid mesh (tets, wedges, pyramids beside the hexes) keeps every hex
// table below as the hex part's, with one change: a hex face matched by a
// non-hex cell (a pyramid's base, a wedge's quad face, or two triangles of a
// non-conforming interface) is no longer in boundary_faces. The rest of the
// boundary, and the faces matched across kinds, are the additions under
// "Across kinds"; on a pure-hex mesh they are empty and every other table is
// what the hex-only build gives.

#include <array>
#include <span>
#include <vector>

#include "hqview/core/cell_kinds.h"
#include "hqview/core/types.h"
#include "hqview/core/untouched_vector.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/surface_topology.h"

namespace hq {

using Quad = std::array<Index, 4>;
using Tri = std::array<Index, 3>;
using Edge = std::array<Index, 2>;

// A topologically non-conforming interface: the quad face of one cell
// against two triangle faces of other cells over the same four vertices
// (split along one of its diagonals). Ids are cell ids over all blocks.
struct NonConformingFace {
  Quad quad;                         // outward from quad_cell, in its corner order
  Index quad_cell = kNoIndex;
  CellKind quad_kind = CellKind::hex;
  std::array<Index, 2> triangle_cells{kNoIndex, kNoIndex};  // ascending
  std::array<CellKind, 2> triangle_kinds{CellKind::tet, CellKind::tet};
  std::array<Tri, 2> triangles{};    // outward from their cells
};

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
  std::vector<Index> unreferenced_vertices;  // vertices used by no cell (of any kind), ascending

  // ---- Across kinds (all empty for a pure-hex mesh) ----
  // Set when the mesh has tets, wedges or pyramids.
  bool across_kinds = false;
  // The boundary faces of non-hex cells (used once over all kinds), outward,
  // in their cell's corner order, ordered by sorted vertex ids; with the cell
  // id each comes from. The whole boundary is boundary_faces (hex quads) +
  // boundary_quads_non_hex + boundary_triangles.
  std::vector<Quad> boundary_quads_non_hex;
  std::vector<Index> boundary_quad_non_hex_cells;
  std::vector<Tri> boundary_triangles;
  std::vector<Index> boundary_triangle_cells;
  // Quad-against-two-triangles interfaces (none of their faces is boundary),
  // ordered by the quad's sorted vertex ids.
  std::vector<NonConformingFace> non_conforming_faces;
  // Faces (quad or triangle) used by more than two cells, at least one of
  // them not a hex (the hex-only ones are non_manifold_faces).
  Index num_non_manifold_faces_non_hex = 0;
  // Per entry of `edges` (the hex part's edges): 1 when the edge is also an
  // edge of a tet, wedge or pyramid. Empty for a pure-hex mesh.
  std::vector<char> edge_touches_non_hex;
  // The unique edges (a < b) of every volume cell of any kind, ascending
  // (`edges` and the other cells' edges): what the edge lengths and the
  // overlap's zero-length edges read on such a mesh. Empty for a pure-hex
  // mesh (`edges` is that mesh's every edge).
  std::vector<Edge> all_edges;
  // Every face of every volume cell (hexes too), matched by its vertex ids:
  // the unique triangles, then the unique quads, each in the order of their
  // sorted vertex ids. Face f is used by the half-faces
  // cell_face_uses[cell_face_offsets[f] .. cell_face_offsets[f+1]),
  // ascending (1 = boundary, 2 = interior, more = non-manifold); half-face
  // ids as cell_half_face() reads them. What the overlap's stages D-F read
  // on such a mesh (the matching done once). Empty for a pure-hex mesh, and
  // when a mesh has 2^31 half-faces or more.
  std::vector<Index> cell_face_offsets;  // num faces + 1
  std::vector<Index> cell_face_uses;


  // ---- A surface mesh (quads and triangles, no volume cell) ----
  // Its edges, boundary and non-manifold edges and reversed faces; empty for
  // a volume mesh. A surface mesh's `edges` are its edges, its
  // boundary_vertices those on an edge used by one face, its
  // unreferenced_vertices those no quad or triangle uses; every hex table
  // above is empty.
  SurfaceTopology surface;

  // The hexes using vertex v, ascending.
  std::span<const Index> hexes_of(Index v) const {
    return {vertex_hexes.data() + vertex_hex_offsets[static_cast<std::size_t>(v)],
            vertex_hexes.data() + vertex_hex_offsets[static_cast<std::size_t>(v) + 1]};
  }

  Index num_face_hexes(Index face) const {
    return face_hex_offsets[static_cast<std::size_t>(face) + 1] - face_hex_offsets[static_cast<std::size_t>(face)];
  }
};

// Half-face ids: the local faces (CellKindTable order) of every volume cell,
// block by block in CellKind order (hexes, tets, wedges, pyramids), cell by
// cell, so that ids ascend with (cell id, local face). first[k] is the first
// cell id of kind k (first[4] = the number of volume cells).
struct CellHalfFace {
  Index cell = 0;  // over all blocks
  int local = 0;   // the cell's local face
};
inline constexpr std::array<int, 4> kFacesPerVolumeKind = {
    static_cast<int>(CellKindTable<CellKind::hex>::faces.size()), static_cast<int>(CellKindTable<CellKind::tet>::faces.size()),
    static_cast<int>(CellKindTable<CellKind::wedge>::faces.size()),
    static_cast<int>(CellKindTable<CellKind::pyramid>::faces.size())};
inline Index half_face_id(const std::array<Index, 5>& first, CellKind kind, Index local_cell, int local_face) {
  Index h = 0;
  const auto k = static_cast<std::size_t>(kind);
  for (std::size_t i = 0; i < k; ++i) h += (first[i + 1] - first[i]) * kFacesPerVolumeKind[i];
  return h + local_cell * kFacesPerVolumeKind[k] + local_face;
}
inline CellHalfFace cell_half_face(const std::array<Index, 5>& first, Index h) {
  for (std::size_t k = 0; k < 3; ++k) {
    const Index n = (first[k + 1] - first[k]) * kFacesPerVolumeKind[k];
    if (h < n) return {first[k] + h / kFacesPerVolumeKind[k], static_cast<int>(h % kFacesPerVolumeKind[k])};
    h -= n;
  }
  return {first[3] + h / kFacesPerVolumeKind[3], static_cast<int>(h % kFacesPerVolumeKind[3])};
}

// The unique edges of the boundary faces (a < b), ascending: of the hex
// boundary quads only (what the hex views draw).
std::vector<Edge> boundary_edges(const Topology& topology);

// The number of boundary faces over all kinds: hex quads, non-hex quads and
// triangles.
inline std::size_t num_boundary_faces_all_kinds(const Topology& t) {
  return t.boundary_faces.size() + t.boundary_quads_non_hex.size() + t.boundary_triangles.size();
}

// Builds every table above from the mesh's volume blocks: the hex tables in
// O(#hexes) expected time; then, when the mesh has tets, wedges or pyramids,
// the faces of every kind matched (CellKindTable faces, by their sorted
// vertex ids, bucketed by the smallest as the hex faces: linear in the
// non-hex faces, plus a binary search among the hex faces per non-hex quad
// and 4 among the triangles per hex boundary quad). A mesh with hexes only
// takes the hex path alone: the same tables, byte for byte, at its speed.
// Quads and triangles (surface blocks) are read only when the mesh has no
// volume cell (a surface mesh: the `surface` part above).
// Precondition: every id in every block is in [0, mesh.num_vertices()) (the
// readers guarantee it). Throws nothing.
Topology build_topology(const Mesh& mesh);

}  // namespace hq
