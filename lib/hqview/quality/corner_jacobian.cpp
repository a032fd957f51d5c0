#include "hqview/quality/corner_jacobian.h"

#include <algorithm>
#include <cmath>

#include "hqview/core/hex_topology.h"

namespace hq {
CornerJacobians corner_scaled_jacobians(const std::array<Vec3, 8>& p) {
  // Each edge belongs to two corner frames: its length is taken once.
  std::array<double, 12> length;
  for (int e = 0; e < 12; ++e) length[e] = std::sqrt(squared_norm(p[kHexEdges[e][1]] - p[kHexEdges[e][0]]));
  CornerJacobians out;
  for (int i = 0; i < 8; ++i) {
    const auto& f = kCornerFrames[i];
    const auto& fe = kCornerFrameEdges[i];
    const double lengths = length[fe[0]] * length[fe[1]] * length[fe[2]];
    const double j = det(p[f[0]] - p[i], p[f[1]] - p[i], p[f[2]] - p[i]);
    // Branch-free, so the loop stays straight-line code.
    const bool degenerate = !(lengths > 0.0);
    out.value[i] = degenerate ? 0.0 : std::min(1.0, std::max(-1.0, j / lengths));
    out.degenerate_mask |= static_cast<std::uint8_t>(static_cast<unsigned>(degenerate) << i);
  }
  return out;
}

// hex_scaled_jacobian() is defined in hex_metrics.cpp, with the other Verdict
// kernels it shares its frames with.

}  // namespace hq
