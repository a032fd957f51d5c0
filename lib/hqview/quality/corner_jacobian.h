#pragma once
// Scaled Jacobians of one hexahedron (ALGORITHMS.md §2).
//
// corner_scaled_jacobians(): HQView's per-corner quantity, det[a,b,c] /
// (|a||b||c|) in each of the 8 corner frames of core/hex_topology.h; the
// input of vertex quality and glyphs (Si and Chen 2023, after Knupp 2000).
//
// hex_scaled_jacobian(): Verdict 1.4.5's cell metric: the minimum over the
// centre frame (principal axes X1, X2, X3) and the 8 corner frames, +1e30
// (kVerdictDegenerate) when any frame vector has zero length.

#include <array>
#include <cstdint>

#include "hqview/core/vec3.h"

namespace hq {

// Verdict's VERDICT_DBL_MAX: the value it returns for a degenerate element.
inline constexpr double kVerdictDegenerate = 1e30;

struct CornerJacobians {
  std::array<double, 8> value{};  // in [-1, 1]; 0 at a degenerate corner
  std::uint8_t degenerate_mask = 0;  // bit i: corner i has a zero-length frame edge
};

CornerJacobians corner_scaled_jacobians(const std::array<Vec3, 8>& p);

// Verdict hex_scaled_jacobian, to 1e-12 relative of Verdict 1.4.5.
double hex_scaled_jacobian(const std::array<Vec3, 8>& p);

}  // namespace hq
