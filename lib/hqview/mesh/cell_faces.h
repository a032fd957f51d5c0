#pragma once
// A cell of any volume kind by its id over all blocks (hexes first, then
// tets, wedges, pyramids: mesh.h), its kind and its corners, and its faces
// from CellKindTable (outward): what the views that draw cells as cells read,
// so no view spells a kind's connectivity again.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "hqview/core/cell_kinds.h"
#include "hqview/core/types.h"
#include "hqview/mesh/mesh.h"

namespace hq {

// A volume cell's kind and its corner ids (the first `num_corners` of
// `corners`).
struct CellRef {
  CellKind kind = CellKind::hex;
  std::size_t index = 0;  // in its block
  int num_corners = 0;
  std::array<Index, 8> corners{};
};

// The first cell id of each volume block: hexes 0, tets H, wedges H+T,
// pyramids H+T+W, and the end.
inline std::array<Index, 5> volume_block_starts(const Mesh& mesh) {
  const auto h = static_cast<Index>(mesh.hexes.size()), t = static_cast<Index>(mesh.tets.size()),
             w = static_cast<Index>(mesh.wedges.size()), p = static_cast<Index>(mesh.pyramids.size());
  return {0, h, h + t, h + t + w, h + t + w + p};
}

// The number of volume cells (every block but the surface ones), summed in
// 64 bits: the readers add a declared count to it before checking the
// memory budget, so the sum must not overflow Index.
inline std::int64_t num_volume_cells(const Mesh& mesh) {
  return static_cast<std::int64_t>(mesh.hexes.size()) + static_cast<std::int64_t>(mesh.tets.size()) +
         static_cast<std::int64_t>(mesh.wedges.size()) + static_cast<std::int64_t>(mesh.pyramids.size());
}

namespace detail {
// The CellRef of cell `id` of `block` (of `kind`), whose first cell id is `first`.
template <class Block>
CellRef block_cell(CellKind kind, const Block& block, Index first, Index id) {
  CellRef ref;
  ref.kind = kind;
  ref.index = static_cast<std::size_t>(id - first);
  const auto& cell = block[ref.index];
  ref.num_corners = static_cast<int>(cell.size());
  for (std::size_t i = 0; i < cell.size(); ++i) ref.corners[i] = cell[i];
  return ref;
}
}  // namespace detail

// Cell `id` over the volume blocks. Precondition: 0 <= id < num_volume_cells(mesh).
inline CellRef volume_cell(const Mesh& mesh, Index id) {
  const std::array<Index, 5> start = volume_block_starts(mesh);
  CellRef ref;
  const auto fill = [&](CellKind kind, const auto& block, Index first) { ref = detail::block_cell(kind, block, first, id); };
  if (id < start[1]) fill(CellKind::hex, mesh.hexes, start[0]);
  else if (id < start[2]) fill(CellKind::tet, mesh.tets, start[1]);
  else if (id < start[3]) fill(CellKind::wedge, mesh.wedges, start[2]);
  else fill(CellKind::pyramid, mesh.pyramids, start[3]);
  return ref;
}

// Cell `id` over every block (volume blocks, then quads and triangles: a
// surface mesh's cells). Precondition: 0 <= id < num_cells(mesh).
inline CellRef any_cell(const Mesh& mesh, Index id) {
  if (id < num_volume_cells(mesh)) return volume_cell(mesh, id);
  const Index quads = num_volume_cells(mesh), triangles = quads + static_cast<Index>(mesh.quads.size());
  return id < triangles ? detail::block_cell(CellKind::quad, mesh.quads, quads, id)
                        : detail::block_cell(CellKind::triangle, mesh.triangles, triangles, id);
}

// Calls f(corner ids, size) for each face of the cell (CellKindTable order,
// outward), corner ids as an std::array<Index, 4> whose first `size` (3 or
// 4) are used.
template <class F>
void for_each_face_of(const CellRef& cell, F&& f) {
  for_each_cell_kind([&](auto kind) {
    if constexpr (CellKindTable<kind()>::dimension == 3) {
      if (kind() != cell.kind) return;
      for (const CellFace& face : CellKindTable<kind()>::faces) {
        std::array<Index, 4> v{kNoIndex, kNoIndex, kNoIndex, kNoIndex};
        for (int i = 0; i < face.size; ++i) v[static_cast<std::size_t>(i)] = cell.corners[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])];
        f(v, face.size);
      }
    }
  });
}

// Calls f(a, b) for each edge of the cell (CellKindTable edges order).
template <class F>
void for_each_edge_of(const CellRef& cell, F&& f) {
  for_each_cell_kind([&](auto kind) {
    if constexpr (CellKindTable<kind()>::dimension == 3) {
      if (kind() != cell.kind) return;
      for (const auto& e : CellKindTable<kind()>::edges)
        f(cell.corners[static_cast<std::size_t>(e[0])], cell.corners[static_cast<std::size_t>(e[1])]);
    }
  });
}

// "cells: 64 hex, 484 tet, 16 pyramid": the kinds with a count > 0, in block
// order (a legend's line); empty when every count is 0.
inline std::string cell_kinds_text(const std::array<std::int64_t, kNumCellKinds>& count) {
  std::string text;
  for (CellKind kind : kCellKinds)
    if (count[static_cast<std::size_t>(kind)] > 0)
      text += (text.empty() ? "cells: " : ", ") + std::to_string(count[static_cast<std::size_t>(kind)]) + " " +
              std::string(cell_kind_name(kind));
  return text;
}

// The mesh's kinds as cell_kinds_text; empty for a pure-hex mesh (whose
// views keep their bytes: the legend line is for meshes of several kinds).
inline std::string mesh_kinds_text(const Mesh& mesh) {
  if (mesh.tets.empty() && mesh.wedges.empty() && mesh.pyramids.empty()) return {};
  std::array<std::int64_t, kNumCellKinds> count{};
  for (CellKind kind : kCellKinds) count[static_cast<std::size_t>(kind)] = num_cells_of(mesh, kind);
  return cell_kinds_text(count);
}

}  // namespace hq
