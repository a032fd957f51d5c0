#include "hqview/quality/quality_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hqview/quality/corner_jacobian.h"

namespace hq {

void compute_corner_scaled_jacobians(const HexMesh& mesh, std::span<double> out, std::span<std::uint8_t> mask) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.hexes.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t h = r.begin(); h != r.end(); ++h) {
      const CornerJacobians cj = corner_scaled_jacobians(hex_corners(mesh, static_cast<Index>(h)));
      std::copy(cj.value.begin(), cj.value.end(), out.begin() + static_cast<std::ptrdiff_t>(8 * h));
      mask[h] = cj.degenerate_mask;
    }
  });
}

QualityField compute_quality(const HexMesh& mesh, const Topology& topo) {
  const std::size_t nh = mesh.hexes.size();
  const std::size_t nv = mesh.points.size();
  QualityField q;
  q.corner_scaled_jacobian.resize(8 * nh);
  q.corner_degenerate_mask.resize(nh);
  q.cell_scaled_jacobian.resize(nh);
  compute_corner_scaled_jacobians(mesh, q.corner_scaled_jacobian, q.corner_degenerate_mask);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nh, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t h = r.begin(); h != r.end(); ++h) q.cell_scaled_jacobian[h] = hex_scaled_jacobian(hex_corners(mesh, static_cast<Index>(h)));
  });

  q.vertex_quality.assign(nv, std::numeric_limits<double>::quiet_NaN());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      double quality = std::numeric_limits<double>::infinity();
      for (Index k = topo.vertex_hex_offsets[v]; k < topo.vertex_hex_offsets[v + 1]; ++k) {
        const std::size_t h = static_cast<std::size_t>(topo.vertex_hexes[static_cast<std::size_t>(k)]);
        const Hex& hex = mesh.hexes[h];
        for (int i = 0; i < 8; ++i)
          if (hex[i] == static_cast<Index>(v)) quality = std::min(quality, q.corner_scaled_jacobian[8 * h + i]);
      }
      if (std::isfinite(quality)) q.vertex_quality[v] = quality;
    }
  });
  return q;
}

}  // namespace hq
