#pragma once
// The plain data the whole pipeline works on (ARCHITECTURE.md, "Cell kinds"):
// points plus one contiguous block of cells per kind, each cell as its
// corner point ids in VTK order (core/cell_kinds.h), plus where each cell
// came from in its file (source_index).

#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "hqview/core/cell_kinds.h"
#include "hqview/core/types.h"
#include "hqview/core/vec3.h"

namespace hq {

// The corner point ids of one cell of kind K, in VTK order.
template <CellKind K>
using CellCorners = std::array<Index, CellKindTable<K>::num_corners>;

using Hex = CellCorners<CellKind::hex>;

// A mesh: points in model units and one block per cell kind, 0-based point
// ids in VTK corner order. Points not used by any cell are allowed
// (reported). Cell ids run over the blocks in CellKind order (hexes first,
// then tets, wedges, pyramids, quads, triangles), so a pure-hex mesh keeps
// every hex id.
//
// source_index[kind][i] is where cell i of that block comes from in its file,
// in the numbering a user finds it under in their own tools (docs/formats.md):
// MEDIT the 1-based entry of its section, VTK/VTU the 0-based cell id, Gmsh
// the element tag, Abaqus the element label, Exodus the 1-based element id
// over the blocks, OVM the 0-based polyhedron id. A block's source_index is
// either empty, meaning each cell's 1-based position in its block (MEDIT,
// whose one section per kind gives exactly that, and meshes built in code:
// nothing is stored), or has one entry per cell. Read it through
// cell_source_index().
struct Mesh {
  std::vector<Vec3> points;
  std::vector<Hex> hexes;  // volume cells
  std::vector<CellCorners<CellKind::tet>> tets;
  std::vector<CellCorners<CellKind::wedge>> wedges;
  std::vector<CellCorners<CellKind::pyramid>> pyramids;
  std::vector<CellCorners<CellKind::quad>> quads;  // surface cells (the quad-mesh issue)
  std::vector<CellCorners<CellKind::triangle>> triangles;
  std::array<std::vector<std::int64_t>, kNumCellKinds> source_index;

  Index num_vertices() const { return static_cast<Index>(points.size()); }
  Index num_hexes() const { return static_cast<Index>(hexes.size()); }
};

// The block of kind K.
template <CellKind K>
constexpr auto& cell_block(Mesh& mesh) {
  if constexpr (K == CellKind::hex) return mesh.hexes;
  else if constexpr (K == CellKind::tet) return mesh.tets;
  else if constexpr (K == CellKind::wedge) return mesh.wedges;
  else if constexpr (K == CellKind::pyramid) return mesh.pyramids;
  else if constexpr (K == CellKind::quad) return mesh.quads;
  else return mesh.triangles;
}
template <CellKind K>
constexpr const auto& cell_block(const Mesh& mesh) {
  return cell_block<K>(const_cast<Mesh&>(mesh));
}

// Calls f(kind, cells) for each block in CellKind order, kind a
// std::integral_constant<CellKind, K> and cells the block's vector, so each
// block's loop is compiled for its kind:
//   for_each_block(mesh, [&](auto kind, const auto& cells) {
//     using Table = CellKindTable<kind()>; ... });
template <class F>
void for_each_block(const Mesh& mesh, F&& f) {
  for_each_cell_kind([&](auto kind) { f(kind, cell_block<kind()>(mesh)); });
}

// The source index of cell i of the block of `kind` (see Mesh::source_index).
inline std::int64_t cell_source_index(const Mesh& mesh, CellKind kind, std::size_t i) {
  const std::vector<std::int64_t>& stored = mesh.source_index[static_cast<std::size_t>(kind)];
  return stored.empty() ? static_cast<std::int64_t>(i) + 1 : stored[i];
}

// The number of cells of one kind, and of all kinds.
std::int64_t num_cells_of(const Mesh& mesh, CellKind kind);
std::int64_t num_cells(const Mesh& mesh);

// A surface mesh: quads or triangles and no volume cell (a reader keeps one
// or the other: io/cell_reading.h keep_dimension).
inline bool is_surface_mesh(const Mesh& mesh) {
  return mesh.hexes.empty() && mesh.tets.empty() && mesh.wedges.empty() && mesh.pyramids.empty() &&
         (!mesh.quads.empty() || !mesh.triangles.empty());
}

// The 8 corner positions of hex h.
inline std::array<Vec3, 8> hex_corners(const Mesh& mesh, Index h) {
  std::array<Vec3, 8> p;
  const Hex& hex = mesh.hexes[static_cast<std::size_t>(h)];
  for (int i = 0; i < 8; ++i) p[i] = mesh.points[static_cast<std::size_t>(hex[i])];
  return p;
}

}  // namespace hq
