#pragma once
// The faces of every volume cell (any kind) matched by their vertex ids:
// stage D and the boundary of the unflagged cells on a mesh that is not
// pure hex (a pure-hex mesh reads the hex topology's faces instead). The
// topology's matching (Topology::cell_face_offsets/uses) when it has one;
// otherwise (a topology of the hexes alone) matched here, the same table.

#include <array>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/tet_geometry.h"

namespace hq::detail {

// One use of a face: cell c's local face k (CellKindTable order).
using FaceUse = CellHalfFace;

// Unique faces (a quad and a triangle never match): the triangles, then the
// quads, each in the order of their sorted vertex ids; face f is used by
// uses[offsets[f] .. offsets[f+1]) (half-face ids, Topology's numbering) in
// ascending cell order: 1 = boundary, 2 = interior, more = non-manifold.
// Not copyable or movable (it may point at its own arrays).
class CellFaceMap {
 public:
  CellFaceMap(const VolumeCells& cells, const Topology& topo);
  CellFaceMap(const CellFaceMap&) = delete;
  CellFaceMap& operator=(const CellFaceMap&) = delete;

  Index num_faces() const { return static_cast<Index>(offsets_->size()) - 1; }
  Index begin(Index f) const { return (*offsets_)[static_cast<std::size_t>(f)]; }
  Index end(Index f) const { return (*offsets_)[static_cast<std::size_t>(f) + 1]; }
  FaceUse use(Index i) const { return cell_half_face(first_, (*uses_)[static_cast<std::size_t>(i)]); }
  // True when the topology's matching is read (nothing matched here).
  bool reads_topology() const { return own_offsets_.empty(); }
  const std::vector<Index>& offsets() const { return *offsets_; }
  const std::vector<Index>& uses() const { return *uses_; }

 private:
  std::array<Index, 5> first_{};
  std::vector<Index> own_offsets_, own_uses_;
  const std::vector<Index>* offsets_ = nullptr;
  const std::vector<Index>* uses_ = nullptr;
};

// Every face of every cell matched here (a sort; TBB, deterministic):
// what CellFaceMap builds when the topology has no matching. offsets and
// uses as Topology::cell_face_offsets/uses.
void match_cell_faces(const VolumeCells& cells, std::vector<Index>& offsets, std::vector<Index>& uses);

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
