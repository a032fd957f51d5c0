#pragma once
// Mesh-wide quality fields over every cell (hexes, tets, wedges, pyramids;
// or a surface mesh's quads and triangles): per-corner and per-cell scaled Jacobians and the per-vertex
// quality Jm (the paper's one-ring rule: min corner scaled Jacobian over the
// corners of the incident cells at that vertex, of any kind).

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "hqview/core/cell_kinds.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/cell_corner_jacobian.h"
#include "hqview/quality/corner_jacobian.h"

namespace hq {

// The corner values each volume kind has: 8 per hex, 4 per tet, 6 per
// wedge, 4 per pyramid (its base corners; the apex has none).
template <CellKind K>
inline constexpr int kCornerValuesPerCell = static_cast<int>(CellKindTable<K>::corner_frames.size());

struct QualityField {
  // Corner values: hex h's corner i at 8*h + i (kCornerFrames order), then
  // each non-hex block's corners in CellKind order, cell c of kind k's
  // corner i at corner_begin[k] + kCornerValuesPerCell<k> * c + i
  // (corner_frames order of core/cell_kinds.h). In [-1, 1].
  std::vector<double> corner_scaled_jacobian;
  std::array<std::size_t, kNumCellKinds + 1> corner_begin{};
  // Per cell, over every volume cell in cell-id order (hexes first, then
  // tets, wedges, pyramids): bit i set when corner i has a zero-length frame
  // edge (its value is then 0).
  std::vector<std::uint8_t> corner_degenerate_mask;
  // Per cell, over every volume cell: Verdict's scaled Jacobian of its kind,
  // kVerdictDegenerate (1e30) or -1e30 where Verdict gives its sentinel.
  std::vector<double> cell_scaled_jacobian;
  // Per non-hex cell (index cell id - num_hexes): its validity by its kind's
  // rule (cell_corner_jacobian.h). Empty for a pure-hex mesh.
  std::vector<CellValidity> non_hex_validity;
  std::size_t num_hexes = 0;
  // Per vertex: min over the vertex's incident corners (of every kind); a
  // pyramid apex that is no other cell's corner takes its pyramids' lowest
  // base corner. NaN for a vertex no volume cell uses.
  std::vector<double> vertex_quality;
};

// The corner scaled Jacobians of every hex: out[8*h + i] and mask[h]
// (sizes 8*#hexes and #hexes). Parallel over hexes.
void compute_corner_scaled_jacobians(const HexMesh& mesh, std::span<double> out, std::span<std::uint8_t> mask);

// Computes every field above; parallel over cells and vertices, identical
// results for any thread count (each entry is written by one task; the
// non-hex corners reach vertex quality by a min, which is order-free). A
// pure-hex mesh gets exactly the hex-only fields.
//
// A surface mesh (quads and triangles; docs/analysis.md, "Surface meshes")
// has its cells after the (empty) volume blocks, quads then triangles: each
// corner signed against `surface.plane_normal` when the mesh is planar (a
// cell reversed or folded against the plane is negative and inverted), else
// against the orientation its neighbours agree on: the cell's own normal
// (Verdict's), turned over for a cell that `surface.is_reversed` says
// disagrees with its neighbours' (every corner negated: such a cell is
// inverted and negative, as on a plane). A surface cell's cell_scaled_jacobian is its lowest corner:
// Verdict's scaled Jacobian for every cell measured against its own normal
// or one that agrees with the plane's (except Verdict's P3 == P2 quad), and
// negative for a reversed one.
struct SurfaceOrientation {
  std::optional<Vec3> plane_normal;  // unit; a planar surface's (planarity.h)
  std::vector<char> is_reversed;     // per surface cell (SurfaceTopology); empty: none
};
QualityField compute_quality(const Mesh& mesh, const Topology& topo, const SurfaceOrientation& surface = {});

// Whether cell c (a cell id over all volume kinds) is degenerate (Verdict's
// 1e30 scaled Jacobian, or a corner with a zero-length edge) and inverted:
// a hex by its scaled Jacobian (<= 0, not degenerate), any other kind by its
// kind's rule (a corner determinant < 0).
inline bool cell_is_degenerate(const QualityField& q, std::size_t c) {
  return q.cell_scaled_jacobian[c] >= kVerdictDegenerate || q.corner_degenerate_mask[c] != 0;
}
inline bool cell_is_inverted(const QualityField& q, std::size_t c) {
  if (c >= q.num_hexes && c - q.num_hexes < q.non_hex_validity.size())
    return q.non_hex_validity[c - q.num_hexes] == CellValidity::inverted;
  return !cell_is_degenerate(q, c) && q.cell_scaled_jacobian[c] <= 0.0;
}

}  // namespace hq
