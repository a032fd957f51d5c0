#include "hqview/quality/corner_jacobian.h"

#include <algorithm>
#include <cmath>

#include "hqview/core/hex_topology.h"

namespace hq {
namespace {

// Verdict's VERDICT_DBL_MIN: a squared frame length at or below it makes the
// element degenerate (the oracle's flat hex has |X3|^2 ~ 4e-34, not 0).
constexpr double kVerdictMinSquared = 1e-30;

}  // namespace

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

double hex_scaled_jacobian(const std::array<Vec3, 8>& p) {
  // Centre frame first, then the corners, each normalised as Verdict does
  // (sqrt of the product of squared lengths).
  const Vec3 x1 = (p[1] - p[0]) + (p[2] - p[3]) + (p[5] - p[4]) + (p[6] - p[7]);
  const Vec3 x2 = (p[3] - p[0]) + (p[2] - p[1]) + (p[7] - p[4]) + (p[6] - p[5]);
  const Vec3 x3 = (p[4] - p[0]) + (p[5] - p[1]) + (p[6] - p[2]) + (p[7] - p[3]);
  double min_scaled = kVerdictDegenerate;
  auto visit = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const double la = squared_norm(a), lb = squared_norm(b), lc = squared_norm(c);
    if (la <= kVerdictMinSquared || lb <= kVerdictMinSquared || lc <= kVerdictMinSquared) return false;
    min_scaled = std::min(min_scaled, det(a, b, c) / std::sqrt(la * lb * lc));
    return true;
  };
  if (!visit(x1, x2, x3)) return kVerdictDegenerate;
  for (int i = 0; i < 8; ++i) {
    const auto& f = kCornerFrames[i];
    if (!visit(p[f[0]] - p[i], p[f[1]] - p[i], p[f[2]] - p[i])) return kVerdictDegenerate;
  }
  return min_scaled > 0 ? std::min(min_scaled, kVerdictDegenerate) : std::max(min_scaled, -kVerdictDegenerate);
}

}  // namespace hq
