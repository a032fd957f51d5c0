#pragma once
// The faces of every volume cell (any kind) matched by their vertex ids:
// stage D and the boundary of the unflagged cells on a mesh that is not
// pure hex (a pure-hex mesh reads the hex topology's faces instead).

#include <array>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/overlap/tet_geometry.h"

namespace hq::detail {

// One use of a face: cell c's local face k (CellKindTable order).
struct FaceUse {
  Index cell = 0;
  int local = 0;
};

// Unique faces (a quad and a triangle never match), numbered in the order
// of their sorted vertex ids; face f is used by uses[offsets[f] ..
// offsets[f+1]) in ascending cell order: 1 = boundary, 2 = interior, more =
// non-manifold.
struct CellFaceMap {
  std::vector<Index> offsets;  // num_faces + 1
  std::vector<FaceUse> uses;
  Index num_faces() const { return static_cast<Index>(offsets.size()) - 1; }
};

// Every face of every cell, matched (a sort; TBB, deterministic).
CellFaceMap build_cell_face_map(const VolumeCells& cells);

// The corners of local face k of a cell, outward (its table order); [3] is
// kNoIndex for a triangle.
inline std::array<Index, 4> local_face_corners(const CellCornerIds& c, int k) {
  const CellFace& f = kind_faces(c.kind).faces[k];
  std::array<Index, 4> out{kNoIndex, kNoIndex, kNoIndex, kNoIndex};
  for (int e = 0; e < f.size; ++e)
    out[static_cast<std::size_t>(e)] = c.v[static_cast<std::size_t>(f.v[static_cast<std::size_t>(e)])];
  return out;
}

}  // namespace hq::detail
