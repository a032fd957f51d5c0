#include "hqview/fem/q1_element.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace hq {
namespace {

const double kGauss2 = 1.0 / std::sqrt(3.0);

Vec3 gauss2_point(int g) {
  return {kQ1CornerSigns[g][0] * kGauss2, kQ1CornerSigns[g][1] * kGauss2, kQ1CornerSigns[g][2] * kGauss2};
}

}  // namespace

Q1Reference q1_reference(const Vec3& xi) {
  Q1Reference r;
  for (int i = 0; i < 8; ++i) {
    const auto& s = kQ1CornerSigns[i];
    const double fx = 1 + xi.x * s[0], fy = 1 + xi.y * s[1], fz = 1 + xi.z * s[2];
    r.shape[i] = 0.125 * fx * fy * fz;
    r.grad[i] = {0.125 * s[0] * fy * fz, 0.125 * s[1] * fx * fz, 0.125 * s[2] * fx * fy};
  }
  return r;
}

Q1PointData q1_point(const Q1Corners& p, const Q1Reference& ref) {
  Q1PointData d;
  d.shape = ref.shape;
  Vec3 a, b, c;  // the columns of J
  for (int i = 0; i < 8; ++i) {
    a = a + ref.grad[i].x * p[i];
    b = b + ref.grad[i].y * p[i];
    c = c + ref.grad[i].z * p[i];
    d.position = d.position + ref.shape[i] * p[i];
  }
  d.det_j = det(a, b, c);
  if (d.det_j != 0) {
    // J^-T g = (g0 (b x c) + g1 (c x a) + g2 (a x b)) / det J.
    const Vec3 bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
    const double inv = 1.0 / d.det_j;
    for (int i = 0; i < 8; ++i) d.grad[i] = inv * (ref.grad[i].x * bc + ref.grad[i].y * ca + ref.grad[i].z * ab);
  }
  return d;
}

Q1PointData q1_point(const Q1Corners& p, const Vec3& xi) { return q1_point(p, q1_reference(xi)); }

std::array<double, 8> q1_gauss_det_j(const Q1Corners& p) {
  // The columns of J as q1_point sums them (the same bits), without the
  // shape gradients it also computes.
  static const std::array<std::array<Vec3, 8>, 8> ref_grad = [] {
    std::array<std::array<Vec3, 8>, 8> t;
    for (int g = 0; g < 8; ++g) t[g] = q1_reference(gauss2_point(g)).grad;
    return t;
  }();
  std::array<double, 8> out;
  for (int g = 0; g < 8; ++g) {
    Vec3 a, b, c;
    for (int i = 0; i < 8; ++i) {
      a = a + ref_grad[g][i].x * p[i];
      b = b + ref_grad[g][i].y * p[i];
      c = c + ref_grad[g][i].z * p[i];
    }
    out[g] = det(a, b, c);
  }
  return out;
}

double q1_corner_det_j_min(const Q1Corners& p) {
  // At corner i, dN_j/dxi is +-1/2 for i and its neighbour along xi and 0
  // for the others, so J's first column is (P_{i+x} - P_{i-x}) / 2 along that
  // edge (the same bits as q1_point's sums, whose other terms are zeros).
  double out = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 8; ++i) {
    std::array<Vec3, 3> column;
    for (int axis = 0; axis < 3; ++axis) {
      int low = i, high = i;
      for (int j = 0; j < 8; ++j) {
        bool same = true;
        for (int t = 0; t < 3; ++t)
          if (t != axis && kQ1CornerSigns[j][t] != kQ1CornerSigns[i][t]) same = false;
        if (!same || j == i) continue;
        (kQ1CornerSigns[j][axis] > 0 ? high : low) = j;
      }
      column[axis] = 0.5 * p[high] + -0.5 * p[low];
    }
    out = std::min(out, det(column[0], column[1], column[2]));
  }
  return out;
}

namespace {

// K_e, and det J at the 8 Gauss points (the same bits as q1_gauss_det_j:
// the same sums) from the Jacobians K_e is built from.
Q1Matrix stiffness_and_det_j(const Q1Corners& p, std::array<double, 8>& det_js) {
  // dN_i/dxi at the 8 Gauss points, computed once.
  static const std::array<std::array<Vec3, 8>, 8> ref_grad = [] {
    std::array<std::array<Vec3, 8>, 8> t;
    for (int g = 0; g < 8; ++g) t[g] = q1_reference(gauss2_point(g)).grad;
    return t;
  }();
  Q1Matrix k{};
  for (int g = 0; g < 8; ++g) {
    Vec3 a, b, c;  // the columns of J
    for (int i = 0; i < 8; ++i) {
      a = a + ref_grad[g][i].x * p[i];
      b = b + ref_grad[g][i].y * p[i];
      c = c + ref_grad[g][i].z * p[i];
    }
    const double det_j = det(a, b, c);
    det_js[g] = det_j;
    if (det_j == 0) continue;
    // grad N_i = J^-T g_i = (g0 (b x c) + g1 (c x a) + g2 (a x b)) / det J; the
    // weight det J (Gauss weights 1) leaves one 1/det J.
    const Vec3 bc = cross(b, c), ca = cross(c, a), ab = cross(a, b);
    std::array<Vec3, 8> grad;
    for (int i = 0; i < 8; ++i) {
      const Vec3& r = ref_grad[g][i];
      grad[i] = r.x * bc + r.y * ca + r.z * ab;
    }
    const double w = 1.0 / det_j;
    for (int i = 0; i < 8; ++i)
      for (int j = i; j < 8; ++j) k[8 * i + j] += w * dot(grad[i], grad[j]);
  }
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < i; ++j) k[8 * i + j] = k[8 * j + i];
  return k;
}

}  // namespace

Q1Matrix q1_laplace_stiffness(const Q1Corners& p) {
  std::array<double, 8> det_j;
  return stiffness_and_det_j(p, det_j);
}

Q1Conditioning q1_conditioning(const Q1Corners& p) {
  Q1Conditioning c;
  // K_e of an invalid element is computed too (and not used): one pass over
  // the Gauss points' Jacobians serves det J and K_e.
  std::array<double, 8> det_j;
  const Q1Matrix k = stiffness_and_det_j(p, det_j);
  c.det_j_min = c.det_j_max = det_j[0];
  for (double d : det_j) {
    c.det_j_min = std::min(c.det_j_min, d);
    c.det_j_max = std::max(c.det_j_max, d);
  }
  // NaN coordinates make every comparison false: not valid.
  c.is_valid = c.det_j_min > 0 && std::isfinite(c.det_j_max);
  c.corner_det_j_min = q1_corner_det_j_min(p);
  c.is_invertible = c.corner_det_j_min > 0 && c.is_valid;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!c.is_valid) {
    c.eigenvalues.fill(nan);
    c.lambda_max = c.lambda_2 = c.kappa = nan;
    return c;
  }
  const Eigen::Map<const Eigen::Matrix<double, 8, 8, Eigen::RowMajor>> matrix(k.data());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 8, 8>> solver(matrix, Eigen::EigenvaluesOnly);
  for (int i = 0; i < 8; ++i) c.eigenvalues[i] = solver.eigenvalues()[i];
  c.lambda_max = c.eigenvalues[7];
  c.lambda_2 = c.eigenvalues[1];
  c.kappa = c.lambda_max / c.lambda_2;
  return c;
}

}  // namespace hq
