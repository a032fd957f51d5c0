#pragma once
// Internals of the overlap stages: the points and tets of the 24-tet
// decomposition (overlap.h documents the formulas), as plain data.

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "hqview/core/box3.h"
#include "hqview/core/hex_topology.h"
#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"

namespace hq::detail {

// One point array for every tet corner: mesh vertices [0, face_base), face
// centres [face_base, cell_base) by face id, cell centres from cell_base.
struct TetPoints {
  std::vector<Vec3> points;
  Index face_base = 0;
  Index cell_base = 0;
};

using Tet = std::array<Index, 4>;       // ids into TetPoints::points
using Triangle = std::array<Index, 3>;  // ids into TetPoints::points

// Builds the face and cell centres (TBB). Deterministic.
TetPoints build_tet_points(const HexMesh& mesh, const Topology& topo);

inline Vec3 face_centre(const HexMesh& mesh, const Quad& face) {
  Quad s = face;
  // Sorted ids: both cells of the face add the same points in the same order.
  if (s[0] > s[1]) std::swap(s[0], s[1]);
  if (s[2] > s[3]) std::swap(s[2], s[3]);
  if (s[0] > s[2]) std::swap(s[0], s[2]);
  if (s[1] > s[3]) std::swap(s[1], s[3]);
  if (s[1] > s[2]) std::swap(s[1], s[2]);
  const auto& p = mesh.points;
  return ((p[s[0]] + p[s[1]]) + (p[s[2]] + p[s[3]])) * 0.25;
}

inline Vec3 cell_centre(const HexMesh& mesh, Index h) {
  const auto q = hex_corners(mesh, h);
  return (((q[0] + q[1]) + (q[2] + q[3])) + ((q[4] + q[5]) + (q[6] + q[7]))) * 0.125;
}

// The 24 tets of hex h: tet 4k+e is (p_j, p_i, c_f, c_h) for local face k
// and its edge e from corner i = kHexFaces[k][e] to j = kHexFaces[k][e+1].
inline std::array<Tet, 24> hex_tets(const HexMesh& mesh, const Topology& topo, const TetPoints& tp, Index h) {
  std::array<Tet, 24> tets;
  const Hex& hex = mesh.hexes[static_cast<std::size_t>(h)];
  const Index centre = tp.cell_base + h;
  for (int k = 0; k < 6; ++k) {
    const Index face = tp.face_base + topo.hex_faces[6 * static_cast<std::size_t>(h) + static_cast<std::size_t>(k)];
    for (int e = 0; e < 4; ++e) {
      const Index i = hex[kHexFaces[k][e]], j = hex[kHexFaces[k][(e + 1) % 4]];
      tets[static_cast<std::size_t>(4 * k + e)] = {j, i, face, centre};
    }
  }
  return tets;
}

// A boundary quad of a set of cells, as seen from outside its one cell in
// the set: its fan triangles are (q_e, q_e+1, c_f), outward.
struct BoundaryQuad {
  Index face = 0;  // topology face id
  Index cell = 0;  // the cell of the set that owns it
  Quad corners{};  // the cell's local order (kHexFaces), outward
};

inline Triangle fan_triangle(const TetPoints& tp, const BoundaryQuad& q, int e) {
  return {q.corners[static_cast<std::size_t>(e)], q.corners[static_cast<std::size_t>((e + 1) % 4)],
          tp.face_base + q.face};
}

// The box of n points given by their ids; doubles of input or centre
// points, so exact.
inline Box3 box_of(const std::vector<Vec3>& points, const Index* ids, int n) {
  Box3 b;
  for (int i = 0; i < n; ++i) b.add(points[static_cast<std::size_t>(ids[i])]);
  return b;
}

inline bool boxes_overlap_closed(const Box3& a, const Box3& b) { return a.overlaps(b); }

}  // namespace hq::detail
