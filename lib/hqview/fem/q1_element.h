#pragma once
// The trilinear (Q1) hexahedron for the Laplace operator: shape functions on
// the reference cube [-1, 1]^3 with corners in VTK_HEXAHEDRON order
// (core/hex_topology.h; corner i at (xi_i, eta_i, zeta_i) = kQ1CornerSigns[i]),
// N_i = (1 + xi xi_i)(1 + eta eta_i)(1 + zeta zeta_i) / 8, the map
// x(xi) = sum_i N_i(xi) P_i, its Jacobian J = dx/dxi (so a parallelepiped of
// volume V has det J = V / 8 everywhere) and the element stiffness
// K_ij = int_hex grad N_i . grad N_j dx by tensor Gauss-Legendre quadrature
// (Hughes, "The Finite Element Method", 3.8; Zienkiewicz-Taylor 9.3).
// Pure functions of the 8 corners; they never throw and never allocate.

#include <array>

#include "hqview/core/vec3.h"

namespace hq {

using Q1Corners = std::array<Vec3, 8>;
// Row-major 8 x 8, entry (i, j) at [8 * i + j]; symmetric.
using Q1Matrix = std::array<double, 64>;

inline constexpr std::array<std::array<double, 3>, 8> kQ1CornerSigns = {{
    {-1, -1, -1},
    {1, -1, -1},
    {1, 1, -1},
    {-1, 1, -1},  //
    {-1, -1, 1},
    {1, -1, 1},
    {1, 1, 1},
    {-1, 1, 1},
}};

// One point of the reference cube with everything the element needs there.
struct Q1PointData {
  double det_j = 0;             // det dx/dxi (model units^3 / 8 for a parallelepiped)
  std::array<Vec3, 8> grad;     // physical gradients grad N_i (1 / model units); zero when det_j == 0
  std::array<double, 8> shape;  // N_i
  Vec3 position;                // x(xi)
};

// The shape functions and their reference gradients at one reference point.
struct Q1Reference {
  std::array<double, 8> shape;
  std::array<Vec3, 8> grad;  // dN_i / dxi
};
Q1Reference q1_reference(const Vec3& xi);

// The map at reference point xi (each coordinate in [-1, 1]), or at a point
// whose reference data is already known.
Q1PointData q1_point(const Q1Corners& p, const Vec3& xi);
Q1PointData q1_point(const Q1Corners& p, const Q1Reference& ref);

// det J at the 2 x 2 x 2 Gauss points (+-1/sqrt 3), in kQ1CornerSigns order.
std::array<double, 8> q1_gauss_det_j(const Q1Corners& p);

// The smallest det J at the 8 corners (xi = +-1): the determinant of each
// corner's three edge vectors / 8 (model units^3).
double q1_corner_det_j_min(const Q1Corners& p);

// K_e by 2 x 2 x 2 Gauss-Legendre (weights 1), det J taken with its sign
// (an inverted element gives a negative definite part; callers check
// q1_gauss_det_j first).
Q1Matrix q1_laplace_stiffness(const Q1Corners& p);

// The conditioning of one element (docs/analysis.md "Finite-element check").
struct Q1Conditioning {
  double det_j_min = 0, det_j_max = 0;  // over the 8 Gauss points
  bool is_valid = false;                // every Gauss-point det J > 0
  // det J at the 8 corners (xi = +-1): the determinant of the corner's three
  // edge vectors / 8. The trilinear map is invertible on the closed cube only
  // if all are > 0 (a necessary condition); a hex valid at its Gauss points
  // can still have a corner <= 0.
  double corner_det_j_min = 0;
  bool is_invertible = false;  // every corner det J > 0
  // Eigenvalues of K_e, ascending (the first is the constants' 0 up to
  // rounding); NaN when not valid.
  std::array<double, 8> eigenvalues{};
  double lambda_max = 0;  // eigenvalues[7] (model units); NaN when not valid
  double lambda_2 = 0;    // eigenvalues[1]: the smallest off the constants
  double kappa = 0;       // lambda_max / lambda_2 (unitless, >= 1); NaN when not valid
};

// det J at the Gauss points and, for a valid element, the eigenvalues of K_e
// (Eigen's self-adjoint solver on the 8 x 8 matrix).
Q1Conditioning q1_conditioning(const Q1Corners& p);

}  // namespace hq
