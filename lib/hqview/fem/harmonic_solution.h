#pragma once
// The manufactured solutions of the Poisson check: harmonic functions of the
// normalised coordinates x^_i = a_i . (x - c) / d (a_i the axes of a frame,
// c the centre and d the diagonal of a bounding box in it; principal_frame.h),
// so -Laplace u = 0 and the Dirichlet values at the boundary decide u_h (an
// orthogonal map, a reflection too, keeps a function harmonic).
//   exp_cos along axis a: u = exp(pi x^_a) cos(pi (x^_b + x^_c) / sqrt 2),
//     (a, b, c) a cyclic permutation of (x, y, z);
//   linear: u = slope . x^ (the patch test: Q1 reproduces it exactly).
// Values, physical gradients (1 / model units) and the squared Frobenius norm
// of the physical Hessian (1 / model units^4).

#include <array>
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
  // Orthonormal rows: x^_i = axes[i] . (x - center) / diagonal (the model
  // axes by default).
  std::array<Vec3, 3> axes{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  // How the frame was chosen (principal_frame.h): the volume's principal
  // variances, descending (model units^2; NaN for no positive volume), the
  // axes taken from the model axes inside a degenerate eigenspace (0, 2 or
  // 3) and the axes whose sign no third moment decided (the model axes'
  // rule then). Both 0: the frame turns with the mesh. signs_from_points:
  // the axes whose sign the used points' third moment decided (the volume's
  // was below the tolerance).
  std::array<double, 3> principal_variances{};
  int axes_from_input = 0;
  int signs_from_input = 0;
  int signs_from_points = 0;
};

// exp_x, exp_y, exp_z: the check's three solutions.
std::vector<HarmonicSolution> default_harmonic_solutions();

double solution_value(const HarmonicSolution& u, const Normalization& n, const Vec3& x);
Vec3 solution_gradient(const HarmonicSolution& u, const Normalization& n, const Vec3& x);
// Value and gradient at once (one exp, one sin and cos).
void solution_value_and_gradient(const HarmonicSolution& u, const Normalization& n, const Vec3& x, double& value,
                                 Vec3& gradient);
// x^ = axes (x - c) / d.
Vec3 normalised_point(const Normalization& n, const Vec3& x);
// solution_value_and_gradient at x^ = normalised_point(n, x) (the same bits):
// several solutions at one point share x^.
void solution_value_and_gradient_normalised(const HarmonicSolution& u, const Normalization& n, const Vec3& xn,
                                            double& value, Vec3& gradient);
double solution_hessian_norm2(const HarmonicSolution& u, const Normalization& n, const Vec3& x);

}  // namespace hq
