#include "hqview/overlap/tet_geometry.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace hq::detail {

TetPoints build_tet_points(const HexMesh& mesh, const Topology& topo) {
  TetPoints tp;
  const std::size_t nv = mesh.points.size(), nf = topo.faces.size(), nh = mesh.hexes.size();
  tp.face_base = static_cast<Index>(nv);
  tp.cell_base = static_cast<Index>(nv + nf);
  tp.points.resize(nv + nf + nh);
  std::copy(mesh.points.begin(), mesh.points.end(), tp.points.begin());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nf, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t f = r.begin(); f != r.end(); ++f) tp.points[nv + f] = face_centre(mesh, topo.faces[f]);
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nh, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t h = r.begin(); h != r.end(); ++h)
      tp.points[nv + nf + h] = cell_centre(mesh, static_cast<Index>(h));
  });
  return tp;
}

}  // namespace hq::detail
