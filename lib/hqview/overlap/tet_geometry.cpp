#include "hqview/overlap/tet_geometry.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace hq::detail {

VertexCells build_vertex_cells(const VolumeCells& cells, const Topology& topo) {
  VertexCells vc;
  if (cells.is_pure_hex()) {
    vc.offsets = topo.vertex_hex_offsets.data();
    vc.cells = topo.vertex_hexes.data();
    return vc;
  }
  const std::size_t nv = cells.mesh->points.size();
  vc.own_offsets.assign(nv + 1, 0);
  for (Index c = 0; c < cells.size(); ++c)
    for (Index v : cells.corners(c)) ++vc.own_offsets[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < nv; ++v) vc.own_offsets[v + 1] += vc.own_offsets[v];
  vc.own_cells.resize(static_cast<std::size_t>(vc.own_offsets[nv]));
  std::vector<Index> next(vc.own_offsets.begin(), vc.own_offsets.end() - 1);
  for (Index c = 0; c < cells.size(); ++c)  // ascending cells, so each vertex's list is ascending
    for (Index v : cells.corners(c)) vc.own_cells[static_cast<std::size_t>(next[static_cast<std::size_t>(v)]++)] = c;
  vc.offsets = vc.own_offsets.data();
  vc.cells = vc.own_cells.data();
  return vc;
}

TetPoints build_tet_points(const VolumeCells& cells, const Topology& topo) {
  const Mesh& mesh = *cells.mesh;
  TetPoints tp;
  const std::size_t nv = mesh.points.size(), nf = topo.faces.size(), nc = static_cast<std::size_t>(cells.size());
  const std::size_t nw = mesh.wedges.size(), np = mesh.pyramids.size();
  tp.face_base = static_cast<Index>(nv);
  tp.cell_base = static_cast<Index>(nv + nf);
  tp.quad_face_base = static_cast<Index>(nv + nf + nc);
  tp.points.resize(nv + nf + nc + 3 * nw + np);
  std::copy(mesh.points.begin(), mesh.points.end(), tp.points.begin());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nf, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t f = r.begin(); f != r.end(); ++f) tp.points[nv + f] = face_centre(mesh, topo.faces[f]);
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nc, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      if (c < mesh.hexes.size()) {  // hexes first: no kind lookup
        CellCornerIds hex;
        hex.n = 8;
        std::copy(mesh.hexes[c].begin(), mesh.hexes[c].end(), hex.v.begin());
        tp.points[nv + nf + c] = cell_centre(mesh, hex);
      } else {
        tp.points[nv + nf + c] = cell_centre(mesh, cells.corners(static_cast<Index>(c)));
      }
    }
  });
  const std::size_t quads = nv + nf + nc;
  for (std::size_t w = 0; w < nw; ++w) {
    const auto& c = mesh.wedges[w];
    for (int k = 2; k < 5; ++k) {
      const auto& f = CellKindTable<CellKind::wedge>::faces[static_cast<std::size_t>(k)].v;
      tp.points[quads + 3 * w + static_cast<std::size_t>(k - 2)] = face_centre(mesh, Quad{c[f[0]], c[f[1]], c[f[2]], c[f[3]]});
    }
  }
  for (std::size_t i = 0; i < np; ++i) {
    const auto& c = mesh.pyramids[i];
    tp.points[quads + 3 * nw + i] = face_centre(mesh, Quad{c[0], c[1], c[2], c[3]});
  }
  return tp;
}

}  // namespace hq::detail
