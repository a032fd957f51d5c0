#pragma once
// The conditioning of every hex as a Q1 Laplace element (q1_element.h):
// kappa_e = lambda_max / lambda_2 of K_e, lambda_max(K_e), the min and max
// of det J over the 2 x 2 x 2 Gauss points, and the count of hexes that are
// not valid trilinear elements (a Gauss-point det J <= 0) or not invertible
// (a corner det J <= 0). Parallel over
// hexes; each value is written by one task, so the field and its statistics
// are the same for any thread count.

#include <vector>

#include "hqview/mesh/hex_mesh.h"
#include "hqview/quality/statistics.h"

namespace hq {

struct FemElementField {
  // Per hex (#hexes each). kappa and lambda_max are NaN for an invalid hex.
  std::vector<double> kappa;       // unitless, >= 1
  std::vector<double> lambda_max;  // model units (K_e scales with the length)
  std::vector<double> det_j_min;   // model units^3 (det of dx/dxi on [-1, 1]^3: volume / 8 for a parallelepiped)
  std::vector<double> det_j_max;
  Index num_invalid = 0;      // hexes with a Gauss-point det J <= 0 (or non-finite)
  // Hexes whose trilinear map is not invertible: a corner det J <= 0 (or an
  // invalid hex). Includes num_invalid; the rest are solved (their K_e, by
  // 2 x 2 x 2 Gauss, stay symmetric positive semi-definite with the constants
  // as null space) but the map folds over near that corner.
  Index num_not_invertible = 0;
  double max_lambda_max = 0;  // over the valid hexes (0 when none): Fried's bound's factor
  // Statistics of the valid hexes' values (kappa, lambda_max) and of every
  // hex's (det J).
  Statistics kappa_stats, lambda_max_stats, det_j_min_stats, det_j_max_stats;
};

FemElementField compute_fem_elements(const HexMesh& mesh);

}  // namespace hq
