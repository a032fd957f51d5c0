#include "hqview/fem/harmonic_solution.h"

#include <cmath>
#include <numbers>

namespace hq {
namespace {

constexpr double kPi = std::numbers::pi;
const double kRootHalf = std::sqrt(0.5);

struct ExpCosTerms {
  double e, c, s;  // exp(pi x^_a), cos(theta), sin(theta), theta = pi (x^_b + x^_c) / sqrt 2
  int a, b, cc;
};

ExpCosTerms exp_cos_terms_normalised(const HarmonicSolution& u, const Vec3& xn) {
  ExpCosTerms t;
  t.a = u.axis;
  t.b = (u.axis + 1) % 3;
  t.cc = (u.axis + 2) % 3;
  const double theta = kPi * kRootHalf * (xn[t.b] + xn[t.cc]);
  t.e = std::exp(kPi * xn[t.a]);
  t.c = std::cos(theta);
  t.s = std::sin(theta);
  return t;
}

// A gradient in normalised coordinates to model coordinates: sum_i g_i a_i / d.
Vec3 model_gradient(const Normalization& n, const Vec3& g) {
  return (g[0] * n.axes[0] + g[1] * n.axes[1] + g[2] * n.axes[2]) / n.diagonal;
}

ExpCosTerms exp_cos_terms(const HarmonicSolution& u, const Normalization& n, const Vec3& x) {
  return exp_cos_terms_normalised(u, normalised_point(n, x));
}

}  // namespace

Vec3 normalised_point(const Normalization& n, const Vec3& x) {
  const Vec3 y = (x - n.center) / n.diagonal;
  return {dot(n.axes[0], y), dot(n.axes[1], y), dot(n.axes[2], y)};
}

std::vector<HarmonicSolution> default_harmonic_solutions() {
  return {{"exp_x", HarmonicSolution::Kind::exp_cos, 0, {}},
          {"exp_y", HarmonicSolution::Kind::exp_cos, 1, {}},
          {"exp_z", HarmonicSolution::Kind::exp_cos, 2, {}}};
}

double solution_value(const HarmonicSolution& u, const Normalization& n, const Vec3& x) {
  if (u.kind == HarmonicSolution::Kind::linear) return dot(u.slope, normalised_point(n, x));
  const ExpCosTerms t = exp_cos_terms(u, n, x);
  return t.e * t.c;
}

Vec3 solution_gradient(const HarmonicSolution& u, const Normalization& n, const Vec3& x) {
  double value;
  Vec3 gradient;
  solution_value_and_gradient(u, n, x, value, gradient);
  return gradient;
}

void solution_value_and_gradient(const HarmonicSolution& u, const Normalization& n, const Vec3& x, double& value,
                                 Vec3& gradient) {
  solution_value_and_gradient_normalised(u, n, normalised_point(n, x), value, gradient);
}

void solution_value_and_gradient_normalised(const HarmonicSolution& u, const Normalization& n, const Vec3& xn,
                                            double& value, Vec3& gradient) {
  if (u.kind == HarmonicSolution::Kind::linear) {
    value = dot(u.slope, xn);
    gradient = model_gradient(n, u.slope);
    return;
  }
  const ExpCosTerms t = exp_cos_terms_normalised(u, xn);
  value = t.e * t.c;
  Vec3 g;
  g[t.a] = kPi * t.e * t.c;
  g[t.b] = g[t.cc] = -kPi * kRootHalf * t.e * t.s;
  gradient = model_gradient(n, g);
}

double solution_hessian_norm2(const HarmonicSolution& u, const Normalization& n, const Vec3& x) {
  if (u.kind == HarmonicSolution::Kind::linear) return 0;
  // u_aa = pi^2 e c, u_ab = u_ac = -pi^2 e s / sqrt 2, u_bb = u_cc = u_bc = -pi^2 e c / 2:
  // the nine entries squared sum to 2 pi^4 e^2 (c^2 + s^2).
  // Only exp(pi x^_a) enters (c^2 + s^2 = 1): no sine or cosine.
  const double e = std::exp(kPi * normalised_point(n, x)[u.axis]);
  const double d2 = n.diagonal * n.diagonal;
  return 2 * std::pow(kPi, 4) * e * e / (d2 * d2);
}

}  // namespace hq
