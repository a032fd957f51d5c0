#pragma once
// Internals of the overlap stages: the volume cells of every kind as one id
// range, and the points and tets of their solids (overlap.h documents the
// formulas), as plain data.

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "hqview/core/box3.h"
#include "hqview/core/cell_kinds.h"
#include "hqview/core/hex_topology.h"
#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/mesh.h"
#include "hqview/mesh/topology.h"

namespace hq::detail {

inline constexpr int kNumVolumeKinds = 4;  // hex, tet, wedge, pyramid: the first kinds of CellKind

// The corner ids of one volume cell (any kind), in VTK order: v[0, n).
struct CellCornerIds {
  std::array<Index, 8> v{};
  int n = 0;
  CellKind kind = CellKind::hex;
  Index local = 0;  // its index in its block
  const Index* begin() const { return v.data(); }
  const Index* end() const { return v.data() + n; }
};

// The volume cells of a mesh: ids over the blocks in CellKind order (hexes
// [0, H), then tets, wedges, pyramids), as Mesh numbers them.
struct VolumeCells {
  const Mesh* mesh = nullptr;
  std::array<Index, kNumVolumeKinds + 1> first{};  // first id of each kind; first[4] = the number of cells

  explicit VolumeCells(const Mesh& m) : mesh(&m) {
    first[1] = static_cast<Index>(m.hexes.size());
    first[2] = first[1] + static_cast<Index>(m.tets.size());
    first[3] = first[2] + static_cast<Index>(m.wedges.size());
    first[4] = first[3] + static_cast<Index>(m.pyramids.size());
  }
  Index size() const { return first[kNumVolumeKinds]; }
  bool is_pure_hex() const { return first[kNumVolumeKinds] == first[1]; }
  CellKind kind_of(Index c) const {
    int k = 0;
    while (c >= first[static_cast<std::size_t>(k) + 1]) ++k;
    return static_cast<CellKind>(k);
  }
  CellCornerIds corners(Index c) const {
    CellCornerIds out;
    out.kind = kind_of(c);
    out.local = c - first[static_cast<std::size_t>(out.kind)];
    // Element by element, of the kind's fixed count (std::copy of the four
    // kinds' arrays became one libc memcpy of a variable length: 1.4 % of a
    // tet run's samples).
    const auto copy = [&]<std::size_t N>(const std::array<Index, N>& cell) {
      out.n = static_cast<int>(N);
      for (std::size_t i = 0; i < N; ++i) out.v[i] = cell[i];
    };
    const auto l = static_cast<std::size_t>(out.local);
    switch (out.kind) {
      case CellKind::hex: copy(mesh->hexes[l]); break;
      case CellKind::tet: copy(mesh->tets[l]); break;
      case CellKind::wedge: copy(mesh->wedges[l]); break;
      default: copy(mesh->pyramids[l]); break;
    }
    return out;
  }
};

// vertex -> volume cells (CSR, ascending cell ids): the hex topology's own
// arrays on a pure-hex mesh, arrays over every kind otherwise.
struct VertexCells {
  std::vector<Index> own_offsets, own_cells;  // filled on a mixed mesh only
  const Index* offsets = nullptr;             // num_vertices + 1
  const Index* cells = nullptr;
  Index begin(Index v) const { return offsets[static_cast<std::size_t>(v)]; }
  Index end(Index v) const { return offsets[static_cast<std::size_t>(v) + 1]; }
  Index cell(Index i) const { return cells[static_cast<std::size_t>(i)]; }
};
VertexCells build_vertex_cells(const VolumeCells& cells, const Topology& topo);

// One point array for every tet corner: mesh vertices [0, face_base), hex
// face centres [face_base, cell_base) by topology face id, cell centres from
// cell_base by cell id (every kind), then the centres of the quad faces of
// wedges (3 per wedge) and pyramids (their base) from quad_face_base.
struct TetPoints {
  std::vector<Vec3> points;
  Index face_base = 0;
  Index cell_base = 0;
  Index quad_face_base = 0;
};

using Tet = std::array<Index, 4>;       // ids into TetPoints::points
using Triangle = std::array<Index, 3>;  // ids into TetPoints::points

// Builds the face and cell centres (TBB). Deterministic.
TetPoints build_tet_points(const VolumeCells& cells, const Topology& topo);

inline Vec3 face_centre(const Mesh& mesh, const Quad& face) {
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

// The mean of a cell's corners, summed in corner order (pairwise for a hex).
inline Vec3 cell_centre(const Mesh& mesh, const CellCornerIds& c) {
  const auto& p = mesh.points;
  if (c.n == 8) {
    const auto q = [&](int i) { return p[static_cast<std::size_t>(c.v[static_cast<std::size_t>(i)])]; };
    return (((q(0) + q(1)) + (q(2) + q(3))) + ((q(4) + q(5)) + (q(6) + q(7)))) * 0.125;
  }
  Vec3 sum{};
  for (Index v : c) sum = sum + p[static_cast<std::size_t>(v)];
  return sum / static_cast<double>(c.n);
}

// The tets of a cell's solid, at most 24 (a hex): for each face (CellKind
// Table order, outward) a quad gives, for each edge i -> j, the tet (p_j,
// p_i, c_f, c_h), a triangle (p0, p1, p2) the tet (p1, p0, p2, c_h). Each is
// positively oriented in a valid cell, and (t[1], t[0], t[2]) is a triangle
// of the solid's boundary. A quad's centre c_f: a hex face's by its
// topology id, a wedge's three and a pyramid's base after the cell centres.
struct SolidTets {
  std::array<Tet, 24> tets;
  int n = 0;
};

// Cell `local` of the block of kind K, whose id over the blocks is `cell`.
template <CellKind K>
[[gnu::always_inline]] inline SolidTets kind_solid_tets(const CellCorners<K>& c, Index local, Index cell, const Topology& topo, const TetPoints& tp,
                          Index num_wedges) {
  using Table = CellKindTable<K>;
  SolidTets out;
  const Index centre = tp.cell_base + cell;
  int next_quad = 0;  // the kind's quad faces in table order
  for (std::size_t k = 0; k < Table::faces.size(); ++k) {
    const CellFace& f = Table::faces[k];
    const auto at = [&](int e) { return c[static_cast<std::size_t>(f.v[static_cast<std::size_t>(e % f.size)])]; };
    if (f.size == 3) {
      out.tets[static_cast<std::size_t>(out.n++)] = {at(1), at(0), at(2), centre};
      continue;
    }
    Index face = 0;
    if constexpr (K == CellKind::hex)
      face = tp.face_base + topo.hex_faces[6 * static_cast<std::size_t>(local) + k];
    else if constexpr (K == CellKind::wedge)
      face = tp.quad_face_base + 3 * local + next_quad;
    else
      face = tp.quad_face_base + 3 * num_wedges + local;  // a pyramid's base
    ++next_quad;
    for (int e = 0; e < 4; ++e) out.tets[static_cast<std::size_t>(out.n++)] = {at(e + 1), at(e), face, centre};
  }
  return out;
}

// The same for a cell given by its id over the blocks.
inline SolidTets cell_solid_tets(const VolumeCells& cells, const Topology& topo, const TetPoints& tp, Index cell) {
  const CellKind kind = cells.kind_of(cell);
  const Index local = cell - cells.first[static_cast<std::size_t>(kind)];
  const auto l = static_cast<std::size_t>(local);
  const auto nw = static_cast<Index>(cells.mesh->wedges.size());
  switch (kind) {
    case CellKind::hex: return kind_solid_tets<CellKind::hex>(cells.mesh->hexes[l], local, cell, topo, tp, nw);
    case CellKind::tet: return kind_solid_tets<CellKind::tet>(cells.mesh->tets[l], local, cell, topo, tp, nw);
    case CellKind::wedge: return kind_solid_tets<CellKind::wedge>(cells.mesh->wedges[l], local, cell, topo, tp, nw);
    default: return kind_solid_tets<CellKind::pyramid>(cells.mesh->pyramids[l], local, cell, topo, tp, nw);
  }
}

// The point id of the centre of quad face k (CellKindTable order) of a cell.
inline Index quad_centre_id(const Topology& topo, const TetPoints& tp, const VolumeCells& cells,
                            const CellCornerIds& c, int k) {
  switch (c.kind) {
    case CellKind::hex:
      return tp.face_base + topo.hex_faces[6 * static_cast<std::size_t>(c.local) + static_cast<std::size_t>(k)];
    case CellKind::wedge: return tp.quad_face_base + 3 * c.local + (k - 2);
    default:
      return tp.quad_face_base + 3 * static_cast<Index>(cells.mesh->wedges.size()) + c.local;  // pyramid base
  }
}

// The faces of a cell's kind (CellKindTable<K>::faces) at run time.
struct KindFaces {
  const CellFace* faces = nullptr;
  int n = 0;
};
inline KindFaces kind_faces(CellKind kind) {
  KindFaces out;
  for_each_cell_kind([&](auto k) {
    if (k() == kind) {
      out.faces = CellKindTable<k()>::faces.data();
      out.n = static_cast<int>(CellKindTable<k()>::faces.size());
    }
  });
  return out;
}

// A boundary face of a set of cells, as seen from outside its one cell in
// the set: a quad's fan triangles are (q_e, q_e+1, c_f), a triangle is
// itself; outward.
struct BoundaryFace {
  Index face = 0;              // face id (the topology's on a pure-hex mesh; the face map's otherwise)
  Index cell = 0;              // the cell of the set that owns it
  std::array<Index, 4> corners{};  // the cell's local order (CellKindTable faces), outward; [3] unused for a triangle
  Index centre = kNoIndex;     // a quad's face centre (TetPoints id); kNoIndex for a triangle
  int size() const { return centre == kNoIndex ? 3 : 4; }
  int num_fan_triangles() const { return centre == kNoIndex ? 1 : 4; }
};

inline Triangle fan_triangle(const BoundaryFace& q, int e) {
  if (q.centre == kNoIndex) return {q.corners[0], q.corners[1], q.corners[2]};
  return {q.corners[static_cast<std::size_t>(e)], q.corners[static_cast<std::size_t>((e + 1) % 4)], q.centre};
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
