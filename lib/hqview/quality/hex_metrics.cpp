#include "hqview/quality/hex_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "hqview/core/error.h"
#include "hqview/core/hex_topology.h"
#include "hqview/quality/triangle_metrics.h"

// Operation order follows Verdict where it decides the last digits (sums of
// more than two terms, the raw-coordinate formulas); elsewhere the kernels
// share intermediate results, which changes nothing but the speed.

namespace hq {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Verdict's VERDICT_DBL_MIN and VERDICT_DBL_MAX.
constexpr double kDblMin = 1e-30;
constexpr double kDblMax = kVerdictDegenerate;
// Verdict 1.4.5 computes oddy, nodal_jacobian_ratio and relative_size_squared
// on unscaled coordinates and calls a hex degenerate there when a Jacobian
// determinant (or their sum) is tiny in absolute terms: the oracle's
// tiny_cube_1e-9 (determinants 1e-27) gives oddy 1e30, nodal_jacobian_ratio
// -1e30 and relative_size_squared 0, where Verdict <= 1.4 with 1e-30 gave 0,
// 1 and 1e-54. Any threshold in (8e-27, 0.26) reproduces every oracle case;
// machine epsilon is the natural one after Verdict's element scaling.
constexpr double kUnscaledMin = std::numeric_limits<double>::epsilon();
constexpr double kVerdictPi = 3.1415926535897932384626;

constexpr std::array<HexMetricInfo, kNumHexMetrics> kInfo = {{
    {"edge_ratio", 1.0, 1.3, false},
    {"max_edge_ratio", 1.0, 1.3, false},
    {"max_aspect_frobenius", 1.0, 3.0, false},
    {"med_aspect_frobenius", 1.0, 3.0, false},
    {"skew", 0.0, 0.5, false},
    {"taper", 0.0, 0.5, false},
    {"volume", 0.0, kInf, false},
    {"stretch", 0.25, 1.0, false},
    {"diagonal", 0.65, 1.0, false},
    {"dimension", 0.0, kInf, false},
    {"oddy", 0.0, 0.5, false},
    {"condition", 1.0, 8.0, false},
    {"jacobian", 0.0, kInf, false},
    {"scaled_jacobian", 0.5, 1.0, false},
    {"shear", 0.3, 1.0, false},
    {"shape", 0.3, 1.0, false},
    {"relative_size_squared", 0.5, 1.0, true},
    {"shape_and_size", 0.2, 1.0, true},
    {"shear_and_size", 0.2, 1.0, true},
    {"distortion", 0.5, 1.0, false},
    {"nodal_jacobian_ratio", 0.0, 1.0, false},
    {"equiangle_skew", 0.0, 0.5, false},
}};

// std::fmin / std::fmax semantics (a NaN operand loses), inlined: the
// library calls cost more than the comparisons.
inline double min_of(double a, double b) { return a < b || std::isnan(b) ? a : b; }
inline double max_of(double a, double b) { return a > b || std::isnan(b) ? a : b; }

// Verdict's final clamp of a metric into [-1e30, 1e30].
double clamp_sentinel(double v) { return v > 0 ? min_of(v, kDblMax) : max_of(v, -kDblMax); }

// Verdict's safe_ratio: 1e30 for a huge numerator or a tiny denominator.
double safe_ratio(double numerator, double denominator) {
  return std::fabs(numerator) <= kDblMax && std::fabs(denominator) >= kDblMin ? numerator / denominator : kDblMax;
}

// ---------------------------------------------------------------------------
// Shared geometry of one hex.

// The centre frame (principal axes) and the 8 corner frames with their
// squared lengths and determinants.
struct HexFrames {
  std::array<Vec3, 3> axis;
  std::array<double, 3> axis_len2;
  double axis_det;
  std::array<std::array<Vec3, 3>, 8> corner;
  std::array<std::array<double, 3>, 8> len2;
  std::array<double, 8> det;
};

// Corner positions relative to corner 0: exact for a hex at the origin,
// and no digits lost to a large offset.
HexCorners relative_to_first(const HexCorners& p) {
  HexCorners q;
  for (int i = 0; i < 8; ++i) q[i] = p[i] - p[0];
  return q;
}

// Verdict's calc_hex_efg: +4 corners -4 corners, summed in its order. The
// order matters: on the oracle's flat hex it gives an exactly zero third axis
// (Verdict's 1e30), where a sum of edge vectors leaves 1e-17.
Vec3 signed_sum(const HexCorners& q, const int (&plus)[4], const int (&minus)[4]) {
  Vec3 v = q[plus[0]];
  for (int k = 1; k < 4; ++k) v = v + q[plus[k]];
  for (int k = 0; k < 4; ++k) v = v - q[minus[k]];
  return v;
}

HexFrames make_frames(const HexCorners& p) {
  HexFrames f;
  const HexCorners q = relative_to_first(p);
  f.axis[0] = signed_sum(q, {1, 2, 5, 6}, {0, 3, 4, 7});
  f.axis[1] = signed_sum(q, {2, 3, 6, 7}, {0, 1, 4, 5});
  f.axis[2] = signed_sum(q, {4, 5, 6, 7}, {0, 1, 2, 3});
  for (int k = 0; k < 3; ++k) f.axis_len2[k] = squared_norm(f.axis[k]);
  f.axis_det = det(f.axis[0], f.axis[1], f.axis[2]);
  for (int i = 0; i < 8; ++i) {
    const auto& n = kCornerFrames[i];
    for (int k = 0; k < 3; ++k) {
      f.corner[i][k] = p[n[k]] - p[i];
      f.len2[i][k] = squared_norm(f.corner[i][k]);
    }
    f.det[i] = det(f.corner[i][0], f.corner[i][1], f.corner[i][2]);
  }
  return f;
}

double jacobian_of(const HexFrames& f) {
  // The centre frame spans twice the hex in each direction: 2^3 * 8 = 64.
  double jacobian = kDblMax;
  const double centre = f.axis_det / 64.0;
  if (centre < jacobian) jacobian = centre;
  for (double d : f.det)
    if (d < jacobian) jacobian = d;
  return clamp_sentinel(jacobian);
}

double scaled_jacobian_of(const HexFrames& f) {
  const auto scaled = [](double det, const std::array<double, 3>& l2, double& out) {
    if (l2[0] <= kDblMin || l2[1] <= kDblMin || l2[2] <= kDblMin) return false;
    out = det / std::sqrt(l2[0] * l2[1] * l2[2]);
    return true;
  };
  double min_scaled = kDblMax, s = 0;
  if (!scaled(f.axis_det, f.axis_len2, s)) return kDblMax;
  if (s < min_scaled) min_scaled = s;
  for (int i = 0; i < 8; ++i) {
    if (!scaled(f.det[i], f.len2[i], s)) return kDblMax;
    if (s < min_scaled) min_scaled = s;
  }
  return clamp_sentinel(min_scaled);
}

double shear_of(const HexFrames& f) {
  double min_shear = 1.0;
  for (int i = 0; i < 8; ++i) {
    const auto& l2 = f.len2[i];
    if (l2[0] <= kDblMin || l2[1] <= kDblMin || l2[2] <= kDblMin) return 0;
    if (f.det[i] < kDblMin) return 0;
    min_shear = min_of(f.det[i] / std::sqrt(l2[0] * l2[1] * l2[2]), min_shear);
  }
  if (min_shear <= kDblMin) min_shear = 0;
  return clamp_sentinel(min_shear);
}

double shape_of(const HexFrames& f) {
  // Verdict takes the minimum of 3 det^(2/3) / |frame|^2 over the corners.
  // (shape/3)^3 = det^2 / |frame|^6 orders the corners the same way without
  // a pow, so pow runs once, at the worst corner.
  int worst = 0;
  double worst_key = kInf;
  for (int i = 0; i < 8; ++i) {
    if (!(f.det[i] > kDblMin)) return 0;
    const double sum = f.len2[i][0] + f.len2[i][1] + f.len2[i][2];
    const double ratio = f.det[i] / sum;  // scale-free key: no overflow
    const double key = ratio * ratio / sum;
    if (key < worst_key) {
      worst_key = key;
      worst = i;
    }
  }
  const auto& l2 = f.len2[worst];
  double min_shape = 1.0;
  const double shape = 3 * std::pow(f.det[worst], 2.0 / 3.0) / (l2[0] + l2[1] + l2[2]);
  if (shape < min_shape) min_shape = shape;
  if (min_shape <= kDblMin) min_shape = 0;
  return clamp_sentinel(min_shape);
}

// Frobenius condition number of one corner frame (Knupp 2000), 1e30 when
// the frame is inverted or flat.
double corner_condition(const HexFrames& f, int i) {
  if (f.det[i] <= kDblMin) return kDblMax;
  const auto& [a, b, c] = f.corner[i];
  const double term1 = f.len2[i][0] + f.len2[i][1] + f.len2[i][2];
  const Vec3 ab = cross(a, b), bc = cross(b, c), ca = cross(c, a);
  const double term2 = dot(ab, ab) + dot(bc, bc) + dot(ca, ca);
  return std::sqrt(term1 * term2) / f.det[i];
}

struct Conditions {
  double max_aspect_frobenius, med_aspect_frobenius;
};

Conditions conditions_of(const HexFrames& f) {
  double max_condition = 0, sum = 0;
  for (int i = 0; i < 8; ++i) {
    const double c = corner_condition(f, i);
    if (i == 0 || c > max_condition) max_condition = c;
    sum += c;
  }
  Conditions out;
  out.max_aspect_frobenius = max_condition >= kDblMax    ? kDblMax
                             : max_condition <= -kDblMax ? -kDblMax
                                                         : max_condition / 3.;
  out.med_aspect_frobenius = sum >= kDblMax ? kDblMax : sum <= -kDblMax ? -kDblMax : sum / 24.;
  return out;
}

// Oddy's measure of one frame (deviation of the metric tensor from a
// multiple of the identity): numerator / det^(4/3). Returns false for a frame
// Verdict calls degenerate.
bool oddy_terms(const Vec3& a, const Vec3& b, const Vec3& c, double g11, double g22, double g33, double rt_g,
                double& numerator) {
  if (!(rt_g > kUnscaledMin)) return false;
  const double g12 = dot(a, b), g13 = dot(a, c), g23 = dot(b, c);
  const double norm_g_squared = g11 * g11 + 2.0 * g12 * g12 + 2.0 * g13 * g13 + g22 * g22 + 2.0 * g23 * g23 + g33 * g33;
  const double norm_j_squared = g11 + g22 + g33;
  numerator = norm_g_squared - (1.0 / 3.0) * norm_j_squared * norm_j_squared;
  return true;
}

double oddy_of(const HexFrames& f) {
  // Verdict: the largest of 0 and every frame's oddy (centre first), 1e30 for
  // a degenerate frame. (numerator/det)^3/det orders the frames like
  // numerator/det^(4/3) does, so pow runs once, at the worst frame.
  double worst_numerator = 0, worst_det = 0, worst_key = 0;
  bool any_positive = false;
  auto visit = [&](const std::array<Vec3, 3>& v, const std::array<double, 3>& l2, double rt_g) {
    double numerator = 0;
    if (!oddy_terms(v[0], v[1], v[2], l2[0], l2[1], l2[2], rt_g, numerator)) return false;
    if (numerator > 0) {
      const double ratio = numerator / rt_g;  // scale-free key: no overflow
      const double key = ratio * ratio * ratio / rt_g;
      if (!any_positive || key > worst_key) {
        any_positive = true;
        worst_key = key;
        worst_numerator = numerator;
        worst_det = rt_g;
      }
    }
    return true;
  };
  if (!visit(f.axis, f.axis_len2, f.axis_det)) return kDblMax;
  for (int i = 0; i < 8; ++i)
    if (!visit(f.corner[i], f.len2[i], f.det[i])) return kDblMax;
  double oddy = 0.0;
  if (any_positive) {
    const double current = worst_numerator / std::pow(worst_det, 4.0 / 3.0);
    if (current > oddy) oddy = current;
  }
  return clamp_sentinel(oddy);
}

double relative_size_squared_of(const HexFrames& f, double average_volume) {
  // The weight is the cube of side cbrt(average_volume), as Verdict builds it.
  if (average_volume == 0) return 0;
  const double scale = std::pow(average_volume / 1.0, 1.0 / 3.0);
  const double detw = scale * (scale * scale);
  if (detw < kDblMin) return 0;
  double det_sum = 0;
  for (double d : f.det) det_sum += d;
  double size = 0;
  if (det_sum > kUnscaledMin) {
    double tau = det_sum / (8 * detw);
    tau = min_of(tau, 1.0 / tau);
    size = tau * tau;
  }
  return clamp_sentinel(size);
}

// ---------------------------------------------------------------------------
// Edges, diagonals, centre vectors.

std::array<double, 12> edge_lengths_squared(const HexCorners& p) {
  std::array<double, 12> l2;
  for (int e = 0; e < 12; ++e) l2[e] = squared_norm(p[kHexEdges[e][1]] - p[kHexEdges[e][0]]);
  return l2;
}

// Verdict's diagonal order: 0-6, 2-4, 1-7, 3-5.
std::array<double, 4> diagonal_lengths(const HexCorners& p) {
  return {norm(p[6] - p[0]), norm(p[4] - p[2]), norm(p[7] - p[1]), norm(p[5] - p[3])};
}

double edge_ratio_of(const std::array<double, 12>& l2) {
  // Verdict's quirk: the shortest of all 12 edges but the longest of the
  // bottom and top rings' first two sides only (edges 0-5); box_1x1x3 gives 1.
  double m2 = l2[0], M2 = l2[0];
  for (int e = 1; e < 12; ++e) m2 = l2[e] < m2 ? l2[e] : m2;
  if (m2 < kDblMin) return kDblMax;
  for (int e = 1; e < 6; ++e) M2 = l2[e] > M2 ? l2[e] : M2;
  return clamp_sentinel(std::sqrt(M2 / m2));
}

double stretch_of(const std::array<double, 12>& length, const std::array<double, 4>& diagonals) {
  double min_edge = length[0];
  for (int e = 1; e < 12; ++e) min_edge = min_of(min_edge, length[e]);
  double max_diagonal = diagonals[0];
  for (int d = 1; d < 4; ++d) max_diagonal = max_of(max_diagonal, diagonals[d]);
  return clamp_sentinel(std::sqrt(3.0) * safe_ratio(min_edge, max_diagonal));
}

double diagonal_of(const std::array<double, 4>& diagonals) {
  double lo = diagonals[0], hi = diagonals[0];
  for (int d = 1; d < 4; ++d) {
    lo = min_of(lo, diagonals[d]);
    hi = max_of(hi, diagonals[d]);
  }
  return clamp_sentinel(safe_ratio(lo, hi));
}

double max_edge_ratio_of(const HexFrames& f) {
  const double m1 = std::sqrt(f.axis_len2[0]), m2 = std::sqrt(f.axis_len2[1]), m3 = std::sqrt(f.axis_len2[2]);
  const double a12 = safe_ratio(max_of(m1, m2), min_of(m1, m2));
  const double a13 = safe_ratio(max_of(m1, m3), min_of(m1, m3));
  const double a23 = safe_ratio(max_of(m2, m3), min_of(m2, m3));
  return clamp_sentinel(max_of(a12, max_of(a13, a23)));
}

double skew_of(const HexFrames& f) {
  std::array<Vec3, 3> unit;
  for (int k = 0; k < 3; ++k) {
    const double length = std::sqrt(f.axis_len2[k]);
    if (length <= kDblMin) return kDblMax;
    unit[k] = f.axis[k] / length;
  }
  const double skew = max_of(std::fabs(dot(unit[0], unit[1])),
                             max_of(std::fabs(dot(unit[0], unit[2])), std::fabs(dot(unit[1], unit[2]))));
  return clamp_sentinel(skew);
}

double taper_of(const HexCorners& p, const HexFrames& f) {
  // Verdict's efg12, efg13, efg23: the "twist" vectors between axis pairs.
  const HexCorners q = relative_to_first(p);
  const Vec3 t12 = signed_sum(q, {0, 2, 4, 6}, {1, 3, 5, 7});
  const Vec3 t13 = signed_sum(q, {0, 3, 5, 6}, {1, 2, 4, 7});
  const Vec3 t23 = signed_sum(q, {0, 1, 6, 7}, {2, 3, 4, 5});
  const double l1 = std::sqrt(f.axis_len2[0]), l2 = std::sqrt(f.axis_len2[1]), l3 = std::sqrt(f.axis_len2[2]);
  const double taper_1 = std::fabs(safe_ratio(norm(t12), min_of(l1, l2)));
  const double taper_2 = std::fabs(safe_ratio(norm(t13), min_of(l1, l3)));
  const double taper_3 = std::fabs(safe_ratio(norm(t23), min_of(l2, l3)));
  return clamp_sentinel(max_of(taper_1, max_of(taper_2, taper_3)));
}

// ---------------------------------------------------------------------------
// Volume and dimension: computed around corner 0 (translation only moves
// rounding errors; the 24-tetrahedron sum is Verdict's hex_volume).

double volume_of(const HexCorners& p) {
  const HexCorners q = relative_to_first(p);
  // Verdict's face list and tetrahedron order (each face: 4 tets from the
  // face centre to the cell centre).
  static constexpr int kFaces[6][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6},
                                       {3, 0, 4, 7}, {3, 2, 1, 0}, {4, 5, 6, 7}};
  const Vec3 centre = (q[0] + q[1] + q[2] + q[3] + q[4] + q[5] + q[6] + q[7]) * 0.125;
  double volume = 0.0;
  for (const auto& face : kFaces) {
    const Vec3 face_centre = (q[face[0]] + q[face[1]] + q[face[2]] + q[face[3]]) * 0.25;
    const Vec3 to_face = centre - face_centre;
    Vec3 side[4];
    for (int s = 0; s < 4; ++s) side[s] = centre - q[face[s]];
    for (int j = 0; j < 3; ++j) volume += dot(to_face, cross(side[j + 1], side[j])) / 6.0;
    volume += dot(to_face, cross(side[0], side[3])) / 6.0;
  }
  return clamp_sentinel(volume);
}

// Node permutations of the Flanagan-Belytschko gradient operator: row a
// relabels corners so that the same 6-term formula gives dV/dx_a.
constexpr int kGradPermutation[8][8] = {
    {0, 1, 2, 3, 4, 5, 6, 7}, {1, 2, 3, 0, 5, 6, 7, 4}, {2, 3, 0, 1, 6, 7, 4, 5}, {3, 0, 1, 2, 7, 4, 5, 6},
    {4, 7, 6, 5, 0, 3, 2, 1}, {5, 4, 7, 6, 1, 0, 3, 2}, {6, 5, 4, 7, 2, 1, 0, 3}, {7, 6, 5, 4, 3, 2, 1, 0},
};

// One component of the volume gradient at a corner (Pronto3D, Taylor and
// Flanagan SAND87-1912): u, w are two coordinate arrays (y,z / z,x / x,y).
double volume_gradient(const int (&perm)[8], const std::array<double, 8>& u, const std::array<double, 8>& w) {
  auto U = [&](int k) { return u[perm[k - 1]]; };
  auto W = [&](int k) { return w[perm[k - 1]]; };
  const double w24 = W(2) - W(4), w52 = W(5) - W(2), w45 = W(4) - W(5);
  return (U(2) * (W(6) - W(3) - w45) + U(3) * w24 + U(4) * (W(3) - W(8) - w52) + U(5) * (W(8) - W(6) - w24) +
          U(6) * w52 + U(8) * w45) /
         12.0;
}

double dimension_of(const HexCorners& p) {
  const HexCorners q = relative_to_first(p);
  std::array<double, 8> x, y, z;
  for (int i = 0; i < 8; ++i) {
    x[i] = q[i].x;
    y[i] = q[i].y;
    z[i] = q[i].z;
  }
  std::array<double, 8> gx, gy, gz;
  for (int a = 0; a < 8; ++a) {
    gx[a] = volume_gradient(kGradPermutation[a], y, z);
    gy[a] = volume_gradient(kGradPermutation[a], z, x);
    gz[a] = volume_gradient(kGradPermutation[a], x, y);
  }
  double volume = 0;
  for (int a = 0; a < 8; ++a) volume += x[a] * gx[a];
  double gradient_squared = 0;
  for (const auto* g : {&gx, &gy, &gz})
    for (double v : *g) gradient_squared += v * v;
  const double dimension = std::sqrt(.5 * (volume * volume) / gradient_squared);
  // All 8 corners at one point: Verdict computes 0/0; report it as degenerate.
  return std::isnan(dimension) ? kDblMax : dimension;
}

// ---------------------------------------------------------------------------
// Distortion: {min |J| over 2x2x2 Gauss points and the 8 nodes} / volume * 8
// (SDRC I-DEAS), with Verdict's Gauss point constant and summation order.

constexpr double kGaussPoint = 0.577350269189626;  // Verdict's 15-digit 1/sqrt(3)
constexpr double kNodeSign[8][3] = {{-1., -1., -1.}, {1., -1., -1.}, {1., 1., -1.}, {-1., 1., -1.},
                                    {-1., -1., 1.},  {1., -1., 1.},  {1., 1., 1.},  {-1., 1., 1.}};

struct GaussTables {
  double d1[8][8], d2[8][8], d3[8][8];  // [gauss point][node] shape-function derivatives
};

constexpr GaussTables make_gauss_tables() {
  GaussTables t{};
  const double g[2] = {-kGaussPoint, kGaussPoint};
  int point = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k, ++point)
        for (int n = 0; n < 8; ++n) {
          const double t1 = 1 + kNodeSign[n][0] * g[i], t2 = 1 + kNodeSign[n][1] * g[j],
                       t3 = 1 + kNodeSign[n][2] * g[k];
          t.d1[point][n] = 0.125 * kNodeSign[n][0] * t2 * t3;
          t.d2[point][n] = 0.125 * kNodeSign[n][1] * t1 * t3;
          t.d3[point][n] = 0.125 * kNodeSign[n][2] * t1 * t2;
        }
  return t;
}

constexpr GaussTables kGauss = make_gauss_tables();

double distortion_of(const HexCorners& p) {
  double minimum_jacobian = kDblMax, element_volume = 0.0;
  for (int point = 0; point < 8; ++point) {
    Vec3 xxi, xet, xze;
    for (int n = 0; n < 8; ++n) {
      xxi = xxi + kGauss.d1[point][n] * p[n];
      xet = xet + kGauss.d2[point][n] * p[n];
      xze = xze + kGauss.d3[point][n] * p[n];
    }
    const double jacobian = det(xxi, xet, xze);
    if (minimum_jacobian > jacobian) minimum_jacobian = jacobian;
    element_volume += 1.0 * jacobian;  // Gauss weights are 1
  }
  // At a node the derivatives are +-0.5 on the two ends of each edge through
  // it and 0 elsewhere, so Verdict's 8-term sums reduce to these exactly.
  for (int node = 0; node < 8; ++node) {
    Vec3 axis[3];
    // Neighbours along the reference axes r, s, t (VTK order).
    static constexpr int kAlong[8][3] = {{1, 3, 4}, {0, 2, 5}, {3, 1, 6}, {2, 0, 7},
                                         {5, 7, 0}, {4, 6, 1}, {7, 5, 2}, {6, 4, 3}};
    for (int d = 0; d < 3; ++d) {
      const int m = kAlong[node][d];
      // +0.5 on the end with the larger reference coordinate.
      const bool node_is_high = kNodeSign[node][d] > 0;
      const Vec3& high = node_is_high ? p[node] : p[m];
      const Vec3& low = node_is_high ? p[m] : p[node];
      axis[d] = 0.5 * high + -0.5 * low;
    }
    const double jacobian = det(axis[0], axis[1], axis[2]);
    if (minimum_jacobian > jacobian) minimum_jacobian = jacobian;
  }
  double distortion = kDblMax;
  if (std::fabs(element_volume) > 0.0) distortion = minimum_jacobian / element_volume * 8.;
  if (distortion > kDblMax) return kDblMax;
  if (distortion < -kDblMax) return -kDblMax;
  if (std::isnan(distortion)) return kDblMax;
  return distortion;
}

// ---------------------------------------------------------------------------
// Nodal Jacobian ratio: Verdict's closed form on raw coordinates, the
// determinant of the tetrahedron (a, b, c, d) at each corner.

constexpr int kNodalTet[8][4] = {{0, 1, 3, 4}, {0, 1, 2, 5}, {1, 2, 3, 6}, {0, 2, 3, 7},
                                 {0, 4, 5, 7}, {1, 4, 5, 6}, {2, 5, 6, 7}, {3, 4, 6, 7}};

double nodal_jacobian_ratio_of(const HexCorners& p) {
  // xy(u, v) = x_u y_v - x_v y_u, as Verdict's x0y1 ... x6y7.
  auto xy = [&](int u, int v) { return p[u].x * p[v].y - p[v].x * p[u].y; };
  double min_value = kDblMax, max_value = -kDblMax;
  for (const auto& t : kNodalTet) {
    const int a = t[0], b = t[1], c = t[2], d = t[3];
    const double jdet = (-xy(b, c) + xy(b, d) - xy(c, d)) * p[a].z + (xy(a, c) - xy(a, d) + xy(c, d)) * p[b].z +
                        (-xy(a, b) + xy(a, d) - xy(b, d)) * p[c].z + (xy(a, b) - xy(a, c) + xy(b, c)) * p[d].z;
    min_value = min_of(min_value, jdet);
    max_value = max_of(max_value, jdet);
  }
  // Fully inverted (or collapsed) hex: Verdict's huge negative value.
  if (max_value <= kUnscaledMin) return -kDblMax;
  return min_value / max_value;
}

// ---------------------------------------------------------------------------
// Equiangle skew: the largest deviation of a face angle from 90 degrees.

double degrees(double radians) { return radians * 180.0 / kVerdictPi; }

// Verdict's hex_equiangle_skew: over the 6 faces (V_QuadMetric's
// quad_minimum_maximum_angle each), the smallest and largest corner angles,
// then the larger of (max - 90) / 90 and (90 - min) / 90.
//
// Verdict takes acos of all 24 corner cosines. acos is decreasing, so the
// extreme angles are the acos of extreme cosines: the faces are reduced to
// cosines first and acos runs at most 3 times per hex, for the same values.
double equiangle_skew_of(const HexCorners& p, const std::array<double, 12>& edge_length) {
  // Verdict's faces, in its order, and their sides as hex edges (for lengths).
  static constexpr int kFaces[6][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6},
                                       {3, 0, 4, 7}, {4, 5, 6, 7}, {3, 2, 1, 0}};
  static constexpr int kFaceEdges[6][4] = {{0, 9, 4, 8},  {1, 10, 5, 9}, {2, 11, 6, 10},
                                           {3, 8, 7, 11}, {4, 5, 6, 7},  {2, 1, 0, 3}};
  double min_angle = 360.0, max_angle = 0.0;  // degrees, from faces folded in directly
  double smallest_angle_cosine = -kInf;       // largest cosine of any regular face
  double straight_largest_cosine = kInf;      // smallest cosine of faces without a reflex corner
  double reflex_largest_cosine = -kInf;       // same, faces with one (360 - angle)
  auto fold = [&](double lo, double hi) {
    if (lo < min_angle) min_angle = lo;
    if (hi > max_angle) max_angle = hi;
  };
  for (int f = 0; f < 6; ++f) {
    const Vec3& q0 = p[kFaces[f][0]];
    const Vec3& q1 = p[kFaces[f][1]];
    const Vec3& q2 = p[kFaces[f][2]];
    const Vec3& q3 = p[kFaces[f][3]];
    // A quad with its last two corners equal is Verdict's triangle.
    if (q3 == q2) {
      fold(triangle_minimum_angle({q0, q1, q2}), triangle_maximum_angle({q0, q1, q2}));
      continue;
    }
    const Vec3 e[4] = {q1 - q0, q2 - q1, q3 - q2, q0 - q3};
    double length[4];
    for (int k = 0; k < 4; ++k) length[k] = edge_length[static_cast<std::size_t>(kFaceEdges[f][k])];
    if (length[0] <= kDblMin || length[1] <= kDblMin || length[2] <= kDblMin || length[3] <= kDblMin)
      continue;  // (360, 0)
    // Verdict skips NaN angles (fmin/fmax): a cosine outside [-1, 1].
    double largest = -kInf, smallest = kInf;
    for (int k = 0; k < 4; ++k) {
      const int n = (k + 1) % 4;
      const double cosine = -dot(e[k], e[n]) / (length[k] * length[n]);
      if (!(cosine >= -1.0 && cosine <= 1.0)) continue;
      largest = max_of(largest, cosine);
      smallest = min_of(smallest, cosine);
    }
    // A negative signed corner area against the face's centre normal marks a
    // reflex corner: Verdict then reports 360 minus the largest angle. Only
    // the sign matters, so the centre normal is left unnormalized.
    const Vec3 centre_normal = cross(e[0] - e[2], e[1] - e[3]);
    const bool reflex = dot(centre_normal, cross(e[3], e[0])) < 0 || dot(centre_normal, cross(e[0], e[1])) < 0 ||
                        dot(centre_normal, cross(e[1], e[2])) < 0 || dot(centre_normal, cross(e[2], e[3])) < 0;
    if (largest == -kInf) {  // no valid angle: Verdict keeps its start values 360 (radians!) and 0
      fold(degrees(360.0), reflex ? 360 - degrees(0.0) : degrees(0.0));
      continue;
    }
    smallest_angle_cosine = max_of(smallest_angle_cosine, largest);
    if (reflex)
      reflex_largest_cosine = max_of(reflex_largest_cosine, smallest);
    else
      straight_largest_cosine = min_of(straight_largest_cosine, smallest);
  }
  if (smallest_angle_cosine > -kInf) fold(degrees(std::acos(smallest_angle_cosine)), 0.0);
  if (straight_largest_cosine < kInf) fold(360.0, degrees(std::acos(straight_largest_cosine)));
  if (reflex_largest_cosine > -kInf) fold(360.0, 360 - degrees(std::acos(reflex_largest_cosine)));
  const double skew_max = (max_angle - 90.0) / 90.0;
  const double skew_min = (90.0 - min_angle) / 90.0;
  return skew_max > skew_min ? skew_max : skew_min;
}

std::array<double, 12> edge_lengths(const std::array<double, 12>& squared) {
  std::array<double, 12> l;
  for (int e = 0; e < 12; ++e) l[static_cast<std::size_t>(e)] = std::sqrt(squared[static_cast<std::size_t>(e)]);
  return l;
}

}  // namespace

const HexMetricInfo& hex_metric_info(HexMetric m) { return kInfo[static_cast<std::size_t>(m)]; }

std::optional<HexMetric> hex_metric_from_name(std::string_view name) {
  for (int i = 0; i < kNumHexMetrics; ++i)
    if (kInfo[static_cast<std::size_t>(i)].name == name) return static_cast<HexMetric>(i);
  return std::nullopt;
}

HexMetricValues hex_metrics(const HexCorners& p, double average_volume, const HexMetricSet& which) {
  using M = HexMetric;
  HexMetricValues out;
  out.fill(std::numeric_limits<double>::quiet_NaN());
  auto wants = [&](M m) { return contains(which, m); };
  auto set = [&](M m, double v) { out[static_cast<std::size_t>(m)] = v; };

  const HexFrames f = make_frames(p);
  if (wants(M::jacobian)) set(M::jacobian, jacobian_of(f));
  if (wants(M::scaled_jacobian)) set(M::scaled_jacobian, scaled_jacobian_of(f));
  const bool any_shear = wants(M::shear) || wants(M::shear_and_size);
  const bool any_shape = wants(M::shape) || wants(M::shape_and_size);
  const bool any_size = wants(M::relative_size_squared) || wants(M::shape_and_size) || wants(M::shear_and_size);
  const double shear = any_shear ? shear_of(f) : 0;
  const double shape = any_shape ? shape_of(f) : 0;
  const double size = any_size ? relative_size_squared_of(f, average_volume) : 0;
  if (wants(M::shear)) set(M::shear, shear);
  if (wants(M::shape)) set(M::shape, shape);
  if (wants(M::relative_size_squared)) set(M::relative_size_squared, size);
  if (wants(M::shape_and_size)) set(M::shape_and_size, clamp_sentinel(size * shape));
  if (wants(M::shear_and_size)) set(M::shear_and_size, clamp_sentinel(shear * size));
  if (wants(M::max_aspect_frobenius) || wants(M::med_aspect_frobenius) || wants(M::condition)) {
    const Conditions c = conditions_of(f);
    if (wants(M::max_aspect_frobenius)) set(M::max_aspect_frobenius, c.max_aspect_frobenius);
    if (wants(M::condition)) set(M::condition, c.max_aspect_frobenius);
    if (wants(M::med_aspect_frobenius)) set(M::med_aspect_frobenius, c.med_aspect_frobenius);
  }
  if (wants(M::oddy)) set(M::oddy, oddy_of(f));
  if (wants(M::max_edge_ratio)) set(M::max_edge_ratio, max_edge_ratio_of(f));
  if (wants(M::skew)) set(M::skew, skew_of(f));
  if (wants(M::taper)) set(M::taper, taper_of(p, f));
  if (wants(M::edge_ratio) || wants(M::stretch) || wants(M::equiangle_skew)) {
    const auto l2 = edge_lengths_squared(p);
    if (wants(M::edge_ratio)) set(M::edge_ratio, edge_ratio_of(l2));
    if (wants(M::stretch) || wants(M::equiangle_skew)) {
      const auto length = edge_lengths(l2);
      if (wants(M::stretch)) set(M::stretch, stretch_of(length, diagonal_lengths(p)));
      if (wants(M::equiangle_skew)) set(M::equiangle_skew, equiangle_skew_of(p, length));
    }
  }
  if (wants(M::diagonal)) set(M::diagonal, diagonal_of(diagonal_lengths(p)));
  if (wants(M::volume)) set(M::volume, volume_of(p));
  if (wants(M::dimension)) set(M::dimension, dimension_of(p));
  if (wants(M::distortion)) set(M::distortion, distortion_of(p));
  if (wants(M::nodal_jacobian_ratio)) set(M::nodal_jacobian_ratio, nodal_jacobian_ratio_of(p));
  return out;
}

// Declared in corner_jacobian.h; defined here so that the cell field and the
// metric field share one arithmetic.
double hex_scaled_jacobian(const HexCorners& p) { return scaled_jacobian_of(make_frames(p)); }

double hex_edge_ratio(const HexCorners& p) { return edge_ratio_of(edge_lengths_squared(p)); }
double hex_max_edge_ratio(const HexCorners& p) { return max_edge_ratio_of(make_frames(p)); }
double hex_max_aspect_frobenius(const HexCorners& p) { return conditions_of(make_frames(p)).max_aspect_frobenius; }
double hex_med_aspect_frobenius(const HexCorners& p) { return conditions_of(make_frames(p)).med_aspect_frobenius; }
double hex_skew(const HexCorners& p) { return skew_of(make_frames(p)); }
double hex_taper(const HexCorners& p) { return taper_of(p, make_frames(p)); }
double hex_volume(const HexCorners& p) { return volume_of(p); }
double hex_stretch(const HexCorners& p) {
  return stretch_of(edge_lengths(edge_lengths_squared(p)), diagonal_lengths(p));
}
double hex_diagonal(const HexCorners& p) { return diagonal_of(diagonal_lengths(p)); }
double hex_dimension(const HexCorners& p) { return dimension_of(p); }
double hex_oddy(const HexCorners& p) { return oddy_of(make_frames(p)); }
double hex_condition(const HexCorners& p) { return hex_max_aspect_frobenius(p); }
double hex_jacobian(const HexCorners& p) { return jacobian_of(make_frames(p)); }
double hex_shear(const HexCorners& p) { return shear_of(make_frames(p)); }
double hex_shape(const HexCorners& p) { return shape_of(make_frames(p)); }
double hex_relative_size_squared(const HexCorners& p, double average_volume) {
  return relative_size_squared_of(make_frames(p), average_volume);
}
double hex_shape_and_size(const HexCorners& p, double average_volume) {
  const HexFrames f = make_frames(p);
  return clamp_sentinel(relative_size_squared_of(f, average_volume) * shape_of(f));
}
double hex_shear_and_size(const HexCorners& p, double average_volume) {
  const HexFrames f = make_frames(p);
  return clamp_sentinel(shear_of(f) * relative_size_squared_of(f, average_volume));
}
double hex_distortion(const HexCorners& p) { return distortion_of(p); }
double hex_nodal_jacobian_ratio(const HexCorners& p) { return nodal_jacobian_ratio_of(p); }
double hex_equiangle_skew(const HexCorners& p) { return equiangle_skew_of(p, edge_lengths(edge_lengths_squared(p))); }

double hex_metric(HexMetric m, const HexCorners& p, double average_volume) {
  switch (m) {
    case HexMetric::edge_ratio:
      return hex_edge_ratio(p);
    case HexMetric::max_edge_ratio:
      return hex_max_edge_ratio(p);
    case HexMetric::max_aspect_frobenius:
      return hex_max_aspect_frobenius(p);
    case HexMetric::med_aspect_frobenius:
      return hex_med_aspect_frobenius(p);
    case HexMetric::skew:
      return hex_skew(p);
    case HexMetric::taper:
      return hex_taper(p);
    case HexMetric::volume:
      return hex_volume(p);
    case HexMetric::stretch:
      return hex_stretch(p);
    case HexMetric::diagonal:
      return hex_diagonal(p);
    case HexMetric::dimension:
      return hex_dimension(p);
    case HexMetric::oddy:
      return hex_oddy(p);
    case HexMetric::condition:
      return hex_condition(p);
    case HexMetric::jacobian:
      return hex_jacobian(p);
    case HexMetric::scaled_jacobian:
      return hex_scaled_jacobian(p);
    case HexMetric::shear:
      return hex_shear(p);
    case HexMetric::shape:
      return hex_shape(p);
    case HexMetric::relative_size_squared:
      return hex_relative_size_squared(p, average_volume);
    case HexMetric::shape_and_size:
      return hex_shape_and_size(p, average_volume);
    case HexMetric::shear_and_size:
      return hex_shear_and_size(p, average_volume);
    case HexMetric::distortion:
      return hex_distortion(p);
    case HexMetric::nodal_jacobian_ratio:
      return hex_nodal_jacobian_ratio(p);
    case HexMetric::equiangle_skew:
      return hex_equiangle_skew(p);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace hq
