#include "hqview/quality/quad_metrics.h"

#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "hqview/quality/triangle_metrics.h"
#include "hqview/quality/verdict_support.h"

// Follows V_QuadMetric.cpp of Verdict 1.4.5 (linear quads), including where
// it scales edges or points by the cell's size before its thresholds.

namespace hq {
namespace {

using namespace verdict_support;

constexpr std::array<CellMetricInfo, kNumQuadMetrics> kInfo = {{
    {"edge_ratio", false},
    {"max_edge_ratio", false},
    {"aspect_ratio", false},
    {"radius_ratio", false},
    {"med_aspect_frobenius", false},
    {"max_aspect_frobenius", false},
    {"skew", false},
    {"taper", false},
    {"warpage", false},
    {"area", false},
    {"stretch", false},
    {"minimum_angle", false},
    {"maximum_angle", false},
    {"oddy", false},
    {"condition", false},
    {"jacobian", false},
    {"scaled_jacobian", false},
    {"shear", false},
    {"shape", false},
    {"distortion", false},
    {"equiangle_skew", false},
    {"relative_size_squared", true},
    {"shape_and_size", true},
    {"shear_and_size", true},
}};

bool is_collapsed(const QuadCorners& p) { return p[3] == p[2]; }
TriangleCorners first_three(const QuadCorners& p) { return {p[0], p[1], p[2]}; }

std::array<Vec3, 4> edges_of(const QuadCorners& p) { return {p[1] - p[0], p[2] - p[1], p[3] - p[2], p[0] - p[3]}; }

// The pieces Verdict's quad metrics share, each computed on first use and
// kept: one quad's metrics read its edges, size, corner areas and angles
// once (quad_metric_list), not once per metric. Each piece is the very
// expression the metric computed for itself, so every value is the same
// bit for bit.
class QuadPieces;
double scaled_jacobian_of(QuadPieces& s);
double shape_of(QuadPieces& s);
double area_of(QuadPieces& s);

class QuadPieces {
 public:
  explicit QuadPieces(const QuadCorners& corners) : p_(corners) {}
  const QuadCorners& corners() const { return p_; }

  // The edges P(i+1) - P(i).
  const std::array<Vec3, 4>& edges() {
    if (!edges_) edges_ = edges_of(p_);
    return *edges_;
  }
  // Verdict's elem_scaling: its scale is the size the metrics divide by.
  const ElemScale& scaling() {
    if (!scaling_) scaling_ = elem_scaling(p_);
    return *scaling_;
  }
  double size() { return scaling().scale; }
  // The edges divided by the size.
  const std::array<Vec3, 4>& scaled_edges() {
    if (!scaled_edges_) {
      auto e = edges();
      for (Vec3& v : e) v = v / size();
      scaled_edges_ = e;
    }
    return *scaled_edges_;
  }
  // The corners moved to the centroid and divided by the size.
  const std::array<Vec3, 4>& scaled_points() {
    if (!scaled_points_) {
      const ElemScale& s = scaling();
      std::array<Vec3, 4> q;
      for (int i = 0; i < 4; ++i) q[i] = (p_[i] - s.centre) / s.scale;
      scaled_points_ = q;
    }
    return *scaled_points_;
  }
  const std::array<double, 4>& areas() {
    if (!areas_) areas_ = quad_signed_corner_areas(p_);
    return *areas_;
  }
  // The corner areas divided by the size squared.
  const std::array<double, 4>& scaled_areas() {
    if (!scaled_areas_) {
      auto a = areas();
      for (double& v : a) v /= (size() * size());
      scaled_areas_ = a;
    }
    return *scaled_areas_;
  }
  bool has_reflex_corner() {
    const auto& a = areas();
    return a[0] < 0 || a[1] < 0 || a[2] < 0 || a[3] < 0;
  }
  // The four corner angles in radians, Verdict's order; null when an edge
  // is not longer than kDblMin.
  const std::array<double, 4>* corner_angles() {
    if (!angles_) {
      const auto& e = edges();
      double length[4];
      for (int i = 0; i < 4; ++i) length[i] = norm(e[i]);
      std::array<double, 4> angle{};
      const bool ok = !(length[0] <= kDblMin || length[1] <= kDblMin || length[2] <= kDblMin || length[3] <= kDblMin);
      if (ok) {
        for (int i = 0; i < 4; ++i) {
          const int n = (i + 1) % 4;
          angle[i] = std::acos(-dot(e[i], e[n]) / (length[i] * length[n]));
        }
      }
      angles_ = std::pair{ok, angle};
    }
    return angles_->first ? &angles_->second : nullptr;
  }
  // Metrics that others are made of (shear, the size products), kept once
  // computed.
  double scaled_jacobian() { return cached(scaled_jacobian_, scaled_jacobian_of); }
  double shape() { return cached(shape_, shape_of); }
  double area() { return cached(area_, area_of); }

 private:
  double cached(std::optional<double>& slot, double (*metric)(QuadPieces&)) {
    if (!slot) slot = metric(*this);
    return *slot;
  }

  const QuadCorners& p_;
  std::optional<std::array<Vec3, 4>> edges_, scaled_edges_, scaled_points_;
  std::optional<ElemScale> scaling_;
  std::optional<std::array<double, 4>> areas_, scaled_areas_;
  std::optional<std::pair<bool, std::array<double, 4>>> angles_;
  std::optional<double> scaled_jacobian_, shape_, area_;
};

double edge_ratio_of(QuadPieces& s) {
  const auto& e = s.scaled_edges();
  const double a2 = squared_norm(e[0]), b2 = squared_norm(e[1]), c2 = squared_norm(e[2]), d2 = squared_norm(e[3]);
  const double m2 = std::fmin(std::fmin(a2, b2), std::fmin(c2, d2));
  const double M2 = std::fmax(std::fmax(a2, b2), std::fmax(c2, d2));
  if (m2 < kDblMin) return kDblMax;
  return clamp_signed(std::sqrt(M2 / m2));
}

double max_edge_ratio_of(QuadPieces& s) {
  const auto& q = s.scaled_points();
  const double len1 = norm(q[1] + q[2] - q[0] - q[3]);
  const double len2 = norm(q[2] + q[3] - q[0] - q[1]);
  if (len1 < kDblMin || len2 < kDblMin) return kDblMax;
  return clamp_signed(std::fmax(len1 / len2, len2 / len1));
}

double aspect_ratio_of(QuadPieces& s) {
  const auto& e = s.scaled_edges();
  const double a1 = norm(e[0]), b1 = norm(e[1]), c1 = norm(e[2]), d1 = norm(e[3]);
  const double ma = a1 > b1 ? a1 : b1, mb = c1 > d1 ? c1 : d1;
  const double hm = ma > mb ? ma : mb;
  const auto& areas = s.scaled_areas();
  return clamp_signed(hm * (a1 + b1 + c1 + d1) / (areas[0] + areas[1] + areas[2] + areas[3]));
}

double radius_ratio_of(QuadPieces& s) {
  const QuadCorners& p = s.corners();
  const double size = s.size();
  const auto& e = s.scaled_edges();
  const double a2 = squared_norm(e[0]), b2 = squared_norm(e[1]), c2 = squared_norm(e[2]), d2 = squared_norm(e[3]);
  const double m2 = squared_norm((p[2] - p[0]) / size), n2 = squared_norm((p[3] - p[1]) / size);
  const double t0 = a2 > b2 ? a2 : b2, t1 = c2 > d2 ? c2 : d2, t2 = m2 > n2 ? m2 : n2;
  double h2 = t0 > t1 ? t0 : t1;
  h2 = h2 > t2 ? h2 : t2;
  const double da = norm(cross(e[3], e[0])), ab = norm(cross(e[0], e[1])), bc = norm(cross(e[1], e[2])),
               cd = norm(cross(e[2], e[3]));
  const double smallest = std::fmin(std::fmin(da, ab), std::fmin(bc, cd));
  if (smallest < kDblMin) return kDblMax;
  return clamp_signed(1. / (2. * kSqrt2) * std::sqrt((a2 + b2 + c2 + d2) * h2) / smallest);
}

// The four corner terms (|e(i)|^2 + |e(i+1)|^2) / |e(i) x e(i+1)|, or false
// when a corner is degenerate.
bool frobenius_terms(QuadPieces& s, std::array<double, 4>& q) {
  const auto& e = s.scaled_edges();
  double l2[4];
  for (int i = 0; i < 4; ++i) l2[i] = squared_norm(e[i]);
  double c[4];
  for (int i = 0; i < 4; ++i) c[i] = norm(cross(e[i], e[(i + 1) % 4]));
  if (c[0] < kDblMin || c[1] < kDblMin || c[2] < kDblMin || c[3] < kDblMin) return false;
  for (int i = 0; i < 4; ++i) q[i] = (l2[i] + l2[(i + 1) % 4]) / c[i];
  return true;
}

double med_aspect_frobenius_of(QuadPieces& s) {
  std::array<double, 4> q;
  if (!frobenius_terms(s, q)) return kDblMax;
  double sum = q[0];
  sum += q[1];
  sum += q[2];
  sum += q[3];
  return clamp_signed(.125 * sum);
}

double max_aspect_frobenius_of(QuadPieces& s) {
  std::array<double, 4> q;
  if (!frobenius_terms(s, q)) return kDblMax;
  double qmax = q[0];
  for (int i = 1; i < 4; ++i) qmax = qmax > q[i] ? qmax : q[i];
  return clamp_signed(.5 * qmax);
}

double skew_of(QuadPieces& s) {
  const auto& q = s.scaled_points();
  Vec3 a0 = q[1] + q[2] - q[3] - q[0];
  Vec3 a1 = q[2] + q[3] - q[0] - q[1];
  if (normalize(a0) < kDblMin) return 0.0;
  if (normalize(a1) < kDblMin) return 0.0;
  return std::fmin(std::fabs(dot(a0, a1)), kDblMax);
}

double taper_of(QuadPieces& s) {
  const auto& q = s.scaled_points();
  const Vec3 a0 = q[1] + q[2] - q[3] - q[0];
  const Vec3 a1 = q[2] + q[3] - q[0] - q[1];
  const Vec3 cross_derivative = q[0] + q[2] - q[1] - q[3];
  const double shortest = std::fmin(norm(a0), norm(a1));
  if (shortest < kDblMin) return kDblMax;
  return std::fmin(norm(cross_derivative) / shortest, kDblMax);
}

double warpage_of(QuadPieces& s) {
  const auto& e = s.scaled_edges();
  Vec3 n[4] = {cross(e[3], e[0]), cross(e[0], e[1]), cross(e[1], e[2]), cross(e[2], e[3])};
  if (normalize(n[0]) < kDblMin || normalize(n[1]) < kDblMin || normalize(n[2]) < kDblMin || normalize(n[3]) < kDblMin)
    return kDblMin;
  double warpage = std::fmin(dot(n[0], n[2]), dot(n[1], n[3]));
  warpage = warpage * warpage * warpage;
  return clamp_signed(warpage);
}

double area_of(QuadPieces& s) {
  const auto& a = s.areas();
  return clamp_signed(0.25 * (a[0] + a[1] + a[2] + a[3]));
}

double maximum_angle_of(QuadPieces& s) {
  if (is_collapsed(s.corners())) return triangle_maximum_angle(first_three(s.corners()));
  const auto* angle = s.corner_angles();
  if (angle == nullptr) return 0.0;
  double max_angle = 0.0;
  for (double a : *angle) max_angle = std::fmax(a, max_angle);
  max_angle = max_angle * 180.0 / kPi;
  if (s.has_reflex_corner()) max_angle = 360 - max_angle;
  return clamp_signed(max_angle);
}

double minimum_angle_of(QuadPieces& s) {
  if (is_collapsed(s.corners())) return triangle_minimum_angle(first_three(s.corners()));
  const auto* angle = s.corner_angles();
  if (angle == nullptr) return 360.0;
  double min_angle = 360.0;
  for (double a : *angle) min_angle = std::fmin(a, min_angle);
  min_angle = min_angle * 180.0 / kPi;
  return clamp_signed(min_angle);
}

double oddy_of(QuadPieces& s) {
  const auto& q = s.scaled_points();
  double max_oddy = 0.;
  for (int i = 0; i < 4; ++i) {
    const Vec3 first = q[i] - q[(i + 1) % 4];
    const Vec3 second = q[i] - q[(i + 3) % 4];
    const double g11 = dot(first, first), g12 = dot(first, second), g22 = dot(second, second);
    const double g = g11 * g22 - g12 * g12;
    const double current = g < kDblMin ? kDblMax : ((g11 - g22) * (g11 - g22) + 4. * g12 * g12) / 2. / g;
    max_oddy = std::fmax(max_oddy, current);
  }
  return clamp_signed(max_oddy);
}

double condition_of(QuadPieces& s) {
  const QuadCorners& p = s.corners();
  if (is_collapsed(p)) return triangle_condition(first_three(p));
  const double size = s.size();
  const auto& areas = s.scaled_areas();
  double max_condition = 0.;
  for (int i = 0; i < 4; ++i) {
    const Vec3 xxi = (p[i] - p[(i + 1) % 4]) / size;
    const Vec3 xet = (p[i] - p[(i + 3) % 4]) / size;
    const double condition = areas[i] < kDblMin ? kDblMax : (dot(xxi, xxi) + dot(xet, xet)) / areas[i];
    max_condition = std::fmax(max_condition, condition);
  }
  if (max_condition >= kDblMax) return kDblMax;
  if (max_condition <= -kDblMax) return -kDblMax;
  return max_condition / 2.;
}

double jacobian_of(QuadPieces& s) {
  if (is_collapsed(s.corners())) return triangle_area(first_three(s.corners())) * 2.0;
  const auto& a = s.areas();
  return clamp_signed(std::fmin(std::fmin(a[0], a[1]), std::fmin(a[2], a[3])));
}

double scaled_jacobian_of(QuadPieces& s) {
  if (is_collapsed(s.corners())) return triangle_scaled_jacobian(first_three(s.corners()));
  const auto& areas = s.scaled_areas();
  const auto& e = s.scaled_edges();
  double length[4];
  for (int i = 0; i < 4; ++i) length[i] = norm(e[i]);
  if (length[0] < kDblMin || length[1] < kDblMin || length[2] < kDblMin || length[3] < kDblMin) return 0.0;
  double smallest = kDblMax;
  for (int i = 0; i < 4; ++i) smallest = std::fmin(areas[i] / (length[i] * length[(i + 3) % 4]), smallest);
  return clamp_signed(smallest);
}

double shear_of(double scaled_jacobian) {
  if (scaled_jacobian <= kDblMin) return 0.0;
  return std::fmin(scaled_jacobian, kDblMax);
}

double relative_size_squared_of(double area, double average_area) {
  // The weight is the square of area average_area.
  const double scale = std::sqrt(average_area / 1.0);
  const double avg_area = scale * scale;
  double relative = 0;
  if (avg_area > kDblMin) {
    const double ratio = area / avg_area;
    if (ratio > kDblMin) {
      relative = std::fmin(ratio, 1 / ratio);
      relative *= relative;
    }
  }
  return clamp_signed(relative);
}

double stretch_of(QuadPieces& s) {
  const QuadCorners& p = s.corners();
  const double size = s.size();
  const auto& e = s.scaled_edges();
  double l2[4];
  for (int i = 0; i < 4; ++i) l2[i] = squared_norm(e[i]);
  const double diag02 = squared_norm((p[2] - p[0]) / size);
  const double diag13 = squared_norm((p[3] - p[1]) / size);
  const double longest = std::fmax(diag02, diag13);
  if (longest < kDblMin) return kDblMax;
  const double stretch = kSqrt2 * std::sqrt(std::fmin(std::fmin(l2[0], l2[1]), std::fmin(l2[2], l2[3])) / longest);
  return std::fmin(stretch, kDblMax);
}

double shape_of(QuadPieces& s) {
  const auto& areas = s.scaled_areas();
  const auto& e = s.scaled_edges();
  double l2[4];
  for (int i = 0; i < 4; ++i) l2[i] = squared_norm(e[i]);
  if (l2[0] <= kDblMin || l2[1] <= kDblMin || l2[2] <= kDblMin || l2[3] <= kDblMin) return 0.0;
  double min_shape = kDblMax;
  for (int i = 0; i < 4; ++i) min_shape = std::fmin(areas[i] / (l2[i] + l2[(i + 3) % 4]), min_shape);
  min_shape *= 2;
  if (min_shape < kDblMin) min_shape = 0;
  return clamp_signed(min_shape);
}

// Verdict's quad_normal: the mean of two corner normals that agree.
Vec3 quad_normal(const QuadCorners& p) {
  Vec3 n0 = cross(p[1] - p[0], p[3] - p[0]);
  normalize(n0);
  Vec3 n2 = cross(p[3] - p[2], p[1] - p[2]);
  normalize(n2);
  if (dot(n0, n2) > 0.0) return (n0 + n2) * 0.5;
  Vec3 n1 = cross(p[2] - p[1], p[0] - p[1]);
  normalize(n1);
  if (dot(n0, n1) > 0.0) return (n0 + n1) * 0.5;
  return (n2 + n1) * 0.5;
}

// Verdict's quad_distortion for 4 nodes: a thin shell of thickness
// 0.001 sqrt(area) sampled at the 2x2 Gauss points and the nodes.
double distortion_of(const QuadCorners& p) {
  const Vec3 face_normal = quad_normal(p);
  double distortion = kDblMax;
  if (is_collapsed(p)) {
    Vec3 first, second;
    for (int i = 0; i < 3; ++i) {
      first = p[i] - p[(i + 1) % 3];
      second = p[i] - p[(i + 2) % 3];
      const double sign = dot(face_normal, cross(first, second)) > 0 ? 1. : -1.;
      distortion = std::fmin(distortion, sign * norm(cross(first, second)));
    }
    const double element_area = norm(cross(first, second)) / 2.0;
    return distortion / element_area;
  }
  constexpr double g = 0.577350269189626;  // Verdict's Gauss point
  const double gauss[2] = {-g, g};
  double shape[4][4], d1[4][4], d2[4][4];
  int ife = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j, ++ife) {
      const double y1 = gauss[i], y2 = gauss[j];
      shape[ife][0] = 0.25 * (1 - y1) * (1 - y2);
      shape[ife][1] = 0.25 * (1 + y1) * (1 - y2);
      shape[ife][2] = 0.25 * (1 + y1) * (1 + y2);
      shape[ife][3] = 0.25 * (1 - y1) * (1 + y2);
      d1[ife][0] = -0.25 * (1 - y2);
      d1[ife][1] = 0.25 * (1 - y2);
      d1[ife][2] = 0.25 * (1 + y2);
      d1[ife][3] = -0.25 * (1 + y2);
      d2[ife][0] = -0.25 * (1 - y1);
      d2[ife][1] = -0.25 * (1 + y1);
      d2[ife][2] = 0.25 * (1 + y1);
      d2[ife][3] = 0.25 * (1 - y1);
    }
  double element_area = 0.0;
  for (int k = 0; k < 4; ++k) {
    Vec3 aa{}, bb{};
    for (int n = 0; n < 4; ++n) {
      aa = aa + d1[k][n] * p[n];
      bb = bb + d2[k][n] * p[n];
    }
    element_area += 1.0 * norm(cross(aa, bb));
  }
  // Derivatives at the nodes (-1,-1), (1,-1), (1,1), (-1,1).
  constexpr double kNode[4][2] = {{-1., -1.}, {1., -1.}, {1., 1.}, {-1., 1.}};
  double n1[4][4], n2[4][4];
  for (int i = 0; i < 4; ++i) {
    const double y1 = kNode[i][0], y2 = kNode[i][1];
    n1[i][0] = -0.25 * (1 - y2);
    n1[i][1] = 0.25 * (1 - y2);
    n1[i][2] = 0.25 * (1 + y2);
    n1[i][3] = -0.25 * (1 + y2);
    n2[i][0] = -0.25 * (1 - y1);
    n2[i][1] = -0.25 * (1 + y1);
    n2[i][2] = 0.25 * (1 + y1);
    n2[i][3] = 0.25 * (1 - y1);
  }
  Vec3 normal_at_node[4];
  for (int a = 0; a < 4; ++a) {
    Vec3 aa{}, bb{};
    for (int n = 0; n < 4; ++n) {
      aa = aa + n1[a][n] * p[n];
      bb = bb + n2[a][n] * p[n];
    }
    normal_at_node[a] = cross(aa, bb);
    normalize(normal_at_node[a]);
  }
  bool flat = true;
  for (int a = 0; a < 4; ++a)
    if (std::fabs(dot(normal_at_node[0], normal_at_node[a])) < 0.99) {
      flat = false;
      break;
    }
  const double thickness = 0.001 * std::sqrt(element_area);
  double zl = flat ? 0.0 : 0.5773502691896;
  const int layers = flat ? 1 : 2;
  for (int k = 0; k < 4; ++k)
    for (int layer = 0; layer < layers; ++layer) {
      zl = -zl;
      const double thickness_z = zl * thickness / 2.0;
      Vec3 aa{}, bb{}, cc{};
      for (int n = 0; n < 4; ++n) {
        const Vec3 x = p[n] + thickness_z * normal_at_node[n];
        aa = aa + d1[k][n] * x;
        bb = bb + d2[k][n] * x;
        cc = cc + (shape[k][n] * thickness / 2.0) * normal_at_node[n];
      }
      const double value = dot(cc, cross(aa, bb));
      if (value < distortion) distortion = value;
    }
  for (int a = 0; a < 4; ++a) {
    Vec3 aa{}, bb{}, cc{};
    for (int layer = 0; layer < layers; ++layer) {
      zl = -zl;
      const double thickness_z = zl * thickness / 2.0;
      aa = Vec3{};
      bb = Vec3{};
      cc = Vec3{};
      for (int n = 0; n < 4; ++n) {
        const Vec3 x = p[n] + thickness_z * normal_at_node[a];
        aa = aa + n1[a][n] * x;
        bb = bb + n2[a][n] * x;
        cc = cc + (n == a ? thickness / 2.0 : 0.) * normal_at_node[n];
      }
    }
    const Vec3 normal_at_point = cross(aa, bb);
    const double sign = dot(face_normal, normal_at_point) > 0 ? 1. : -1.;
    const double value = sign * dot(cc, normal_at_point);
    if (value < distortion) distortion = value;
  }
  if (element_area * thickness != 0)
    distortion *= 8. / (element_area * thickness);
  else
    distortion *= 8.;
  return distortion;
}

double equiangle_skew_of(QuadPieces& s) {
  const QuadCorners& p = s.corners();
  double min_angle, max_angle;
  if (is_collapsed(p)) {
    min_angle = triangle_minimum_angle(first_three(p));
    max_angle = triangle_maximum_angle(first_three(p));
  } else {
    const auto* angle = s.corner_angles();
    if (angle == nullptr) {
      min_angle = 360.0;
      max_angle = 0.0;
    } else {
      double lo = 360.0, hi = 0.0;  // Verdict's start values, in radians' place
      for (double a : *angle) {
        lo = std::fmin(a, lo);
        hi = std::fmax(a, hi);
      }
      max_angle = hi * 180.0 / kPi;
      min_angle = std::fmax(lo * 180.0 / kPi, -kDblMax);
      if (s.has_reflex_corner()) max_angle = 360 - max_angle;
      max_angle = std::fmax(max_angle, -kDblMax);
    }
  }
  const double skew_max = (max_angle - 90.0) / 90.0;
  const double skew_min = (90.0 - min_angle) / 90.0;
  return skew_max > skew_min ? skew_max : skew_min;
}

// One metric of the quad whose pieces `s` holds (and keeps for the next).
double metric_of(QuadMetric m, QuadPieces& s, double average_area) {
  using M = QuadMetric;
  switch (m) {
    case M::edge_ratio:
      return edge_ratio_of(s);
    case M::max_edge_ratio:
      return max_edge_ratio_of(s);
    case M::aspect_ratio:
      return aspect_ratio_of(s);
    case M::radius_ratio:
      return radius_ratio_of(s);
    case M::med_aspect_frobenius:
      return med_aspect_frobenius_of(s);
    case M::max_aspect_frobenius:
      return max_aspect_frobenius_of(s);
    case M::skew:
      return skew_of(s);
    case M::taper:
      return taper_of(s);
    case M::warpage:
      return warpage_of(s);
    case M::area:
      return s.area();
    case M::stretch:
      return stretch_of(s);
    case M::minimum_angle:
      return minimum_angle_of(s);
    case M::maximum_angle:
      return maximum_angle_of(s);
    case M::oddy:
      return oddy_of(s);
    case M::condition:
      return condition_of(s);
    case M::jacobian:
      return jacobian_of(s);
    case M::scaled_jacobian:
      return s.scaled_jacobian();
    case M::shear:
      return shear_of(s.scaled_jacobian());
    case M::shape:
      return s.shape();
    case M::distortion:
      return distortion_of(s.corners());
    case M::equiangle_skew:
      return equiangle_skew_of(s);
    case M::relative_size_squared:
      return relative_size_squared_of(s.area(), average_area);
    case M::shape_and_size:
      return clamp_signed(s.shape() * relative_size_squared_of(s.area(), average_area));
    case M::shear_and_size:
      return clamp_signed(shear_of(s.scaled_jacobian()) * relative_size_squared_of(s.area(), average_area));
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

const CellMetricInfo& quad_metric_info(QuadMetric m) { return kInfo[static_cast<std::size_t>(m)]; }

std::optional<QuadMetric> quad_metric_from_name(std::string_view name) {
  for (int i = 0; i < kNumQuadMetrics; ++i)
    if (kInfo[static_cast<std::size_t>(i)].name == name) return static_cast<QuadMetric>(i);
  return std::nullopt;
}

std::array<double, 4> quad_signed_corner_areas(const QuadCorners& p) {
  const auto e = edges_of(p);
  const Vec3 corner_normal[4] = {cross(e[3], e[0]), cross(e[0], e[1]), cross(e[1], e[2]), cross(e[2], e[3])};
  Vec3 centre_normal = cross(e[0] - e[2], e[1] - e[3]);
  normalize(centre_normal);
  return {dot(centre_normal, corner_normal[0]), dot(centre_normal, corner_normal[1]),
          dot(centre_normal, corner_normal[2]), dot(centre_normal, corner_normal[3])};
}

double quad_stretch(const QuadCorners& p) {
  QuadPieces s(p);
  return stretch_of(s);
}

double quad_shape(const QuadCorners& p) {
  QuadPieces s(p);
  return shape_of(s);
}

double quad_equiangle_skew(const QuadCorners& p) {
  QuadPieces s(p);
  return equiangle_skew_of(s);
}

double quad_metric(QuadMetric m, const QuadCorners& p, double average_area) {
  QuadPieces s(p);
  return metric_of(m, s, average_area);
}

void quad_metric_list(std::span<const QuadMetric> metrics, const QuadCorners& p, double average_area,
                      std::span<double> out) {
  QuadPieces s(p);
  for (std::size_t j = 0; j < metrics.size(); ++j) out[j] = metric_of(metrics[j], s, average_area);
}

QuadMetricValues quad_metrics(const QuadCorners& p, double average_area) {
  QuadMetricValues out;
  QuadPieces s(p);
  for (int m = 0; m < kNumQuadMetrics; ++m)
    out[static_cast<std::size_t>(m)] = metric_of(static_cast<QuadMetric>(m), s, average_area);
  return out;
}

}  // namespace hq
