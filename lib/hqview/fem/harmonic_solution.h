#pragma once
// The manufactured solutions of the Poisson check: harmonic functions of the
// normalised coordinates x^ = (x - c) / d (c the centre, d the diagonal of a
// bounding box), so -Laplace u = 0 and the Dirichlet values at the boundary
// decide u_h.
//   exp_cos along axis a: u = exp(pi x^_a) cos(pi (x^_b + x^_c) / sqrt 2),
//     (a, b, c) a cyclic permutation of (x, y, z);
//   linear: u = slope . x^ (the patch test: Q1 reproduces it exactly).
// Values, physical gradients (1 / model units) and the squared Frobenius norm
// of the physical Hessian (1 / model units^4).

#include <string>
#include <vector>

#include "hqview/core/vec3.h"

namespace hq {

struct HarmonicSolution {
  enum class Kind { exp_cos, linear };
  std::string name;  // report key: exp_x, exp_y, exp_z, linear
  Kind kind = Kind::exp_cos;
  int axis = 0;  // exp_cos: the axis of the exponential
  Vec3 slope;    // linear: the gradient in normalised coordinates
};

struct Normalization {
  Vec3 center;
  double diagonal = 1;
};

// exp_x, exp_y, exp_z: the check's three solutions.
std::vector<HarmonicSolution> default_harmonic_solutions();

double solution_value(const HarmonicSolution& u, const Normalization& n, const Vec3& x);
Vec3 solution_gradient(const HarmonicSolution& u, const Normalization& n, const Vec3& x);
// Value and gradient at once (one exp, one sin and cos).
void solution_value_and_gradient(const HarmonicSolution& u, const Normalization& n, const Vec3& x, double& value,
                                 Vec3& gradient);
// x^ = (x - c) / d.
Vec3 normalised_point(const Normalization& n, const Vec3& x);
// solution_value_and_gradient at x^ = normalised_point(n, x) (the same bits):
// several solutions at one point share x^.
void solution_value_and_gradient_normalised(const HarmonicSolution& u, const Normalization& n, const Vec3& xn,
                                            double& value, Vec3& gradient);
double solution_hessian_norm2(const HarmonicSolution& u, const Normalization& n, const Vec3& x);

}  // namespace hq
