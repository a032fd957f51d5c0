#include "hqview/quality/triangle_metrics.h"

#include <cmath>
#include <limits>

#include "hqview/quality/verdict_support.h"

// Follows V_TriMetric.cpp of Verdict 1.4.5 (linear triangles), including
// where it scales the edges by the cell's size before its thresholds.

namespace hq {
namespace {

using namespace verdict_support;

constexpr std::array<CellMetricInfo, kNumTriangleMetrics> kInfo = {{
    {"edge_ratio", false},
    {"aspect_ratio", false},
    {"radius_ratio", false},
    {"aspect_frobenius", false},
    {"area", false},
    {"minimum_angle", false},
    {"maximum_angle", false},
    {"condition", false},
    {"scaled_jacobian", false},
    {"shape", false},
    {"distortion", false},
    {"equiangle_skew", false},
    {"normalized_inradius", false},
    {"relative_size_squared", true},
    {"shape_and_size", true},
}};

// The sides P0->P1, P1->P2, P2->P0 divided by the characteristic size.
std::array<Vec3, 3> scaled_sides(const TriangleCorners& p) {
  const double s = char_size(p);
  return {(p[1] - p[0]) / s, (p[2] - p[1]) / s, (p[0] - p[2]) / s};
}

double edge_ratio_of(const TriangleCorners& p) {
  const auto v = scaled_sides(p);
  const double a2 = squared_norm(v[0]), b2 = squared_norm(v[1]), c2 = squared_norm(v[2]);
  const double m2 = std::fmin(a2, std::fmin(b2, c2));
  const double M2 = std::fmax(a2, std::fmax(b2, c2));
  if (m2 < kDblMin) return kDblMax;
  return clamp_signed(std::sqrt(M2 / m2));
}

double aspect_ratio_of(const TriangleCorners& p) {
  const auto v = scaled_sides(p);
  const double a1 = norm(v[0]), b1 = norm(v[1]), c1 = norm(v[2]);
  double hm = a1 > b1 ? a1 : b1;
  hm = hm > c1 ? hm : c1;
  const double denominator = norm(cross(v[0], v[1]));
  if (denominator < kDblMin) return kDblMax;
  return clamp_signed(kSqrt3 / 6. * hm * (a1 + b1 + c1) / denominator);
}

double radius_ratio_of(const TriangleCorners& p) {
  const auto v = scaled_sides(p);
  const double a1 = norm(v[0]), b1 = norm(v[1]), c1 = norm(v[2]);
  const double denominator = squared_norm(cross(v[0], v[1]));
  if (denominator < kDblMin) return kDblMax;
  return clamp_signed(.25 * a1 * b1 * c1 * (a1 + b1 + c1) / denominator);
}

double aspect_frobenius_of(const TriangleCorners& p) {
  const auto v = scaled_sides(p);
  const double srms = squared_norm(v[0]) + squared_norm(v[1]) + squared_norm(v[2]);
  const double area_x2 = norm(cross(v[0], -v[2]));
  if (area_x2 == 0.0) return kDblMax;
  return clamp_signed(srms / (2 * kSqrt3 * area_x2));
}

// Verdict's tri_minimum_angle / tri_maximum_angle: the angle opposite the
// shortest (longest) side, the first such side on ties; 0 for a zero side.
double extreme_angle(const TriangleCorners& p, bool largest) {
  const Vec3 s0 = p[1] - p[0], s1 = p[2] - p[1], s2 = p[2] - p[0], s3 = -s1;
  const double l[3] = {squared_norm(s0), squared_norm(s1), squared_norm(s2)};
  if (l[0] == 0.0 || l[1] == 0.0 || l[2] == 0.0) return 0.0;
  int side = 0;
  if (largest ? l[1] > l[0] : l[1] < l[0]) side = 1;
  if (largest ? l[2] > l[side] : l[2] < l[side]) side = 2;
  const double angle = side == 0 ? interior_angle(s2, s1) : side == 1 ? interior_angle(s0, s2) : interior_angle(s0, s3);
  return clamp_signed(angle);
}

// The inradius of a triangle (Verdict's tri_inradius, unscaled).
double inradius(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 s0 = b - a, s1 = c - b, s2 = a - c;
  const double sp = (norm(s0) + norm(s1) + norm(s2)) / 2.0;
  const double area = norm(cross(s1, s0)) / 2.0;
  return area / sp;
}

// Verdict's tri3_normalized_inradius: the triangle split at its edge
// midpoints into 4; 4 x the smallest of their inradii over the circumradius.
double normalized_inradius_of(const TriangleCorners& p) {
  const Vec3 m01 = (p[0] + p[1]) * 0.5, m12 = (p[1] + p[2]) * 0.5, m20 = (p[2] + p[0]) * 0.5;
  double min_inradius = kDblMax;
  for (const double r :
       {inradius(p[0], m01, m20), inradius(m01, p[1], m12), inradius(m20, m12, p[2]), inradius(m01, m12, m20)})
    if (r < min_inradius) min_inradius = r;
  const Vec3 s0 = p[1] - p[0], s1 = p[2] - p[1], s2 = p[0] - p[2];
  const double l0 = norm(s0), l1 = norm(s1), l2 = norm(s2);
  const double sp = (l0 + l1 + l2) / 2.0;
  const double area = norm(cross(s1, s0)) / 2.0;
  const double ir = area / sp;
  const double circumradius = (l0 * l1 * l2) / (4.0 * ir * sp);
  return fix_range(4.0 * min_inradius / circumradius);
}

double relative_size_squared_of(const TriangleCorners& p, double average_area) {
  // The weight is the equilateral triangle of area average_area.
  double w11 = 1, w21 = 0, w12 = 0.5, w22 = 0.5 * kSqrt3;
  const double scale = std::sqrt(2.0 * average_area / (w11 * w22 - w21 * w12));
  w11 *= scale;
  w21 *= scale;
  w12 *= scale;
  w22 *= scale;
  const double detw = w11 * w22 - w21 * w12;
  if (detw == 0.0) return 0.0;
  const double deta = norm(cross(p[0] - p[1], p[0] - p[2]));
  if (deta == 0.0) return 0.0;
  double size = deta / detw;
  size = size * size;
  return clamp_signed(std::fmin(size, 1.0 / size));
}

double shape_of(const TriangleCorners& p) {
  const double condition = triangle_condition(p);
  const double shape = condition <= kDblMin ? kDblMax : 1 / condition;
  return clamp_signed(shape);
}

}  // namespace

const CellMetricInfo& triangle_metric_info(TriangleMetric m) { return kInfo[static_cast<std::size_t>(m)]; }

std::optional<TriangleMetric> triangle_metric_from_name(std::string_view name) {
  for (int i = 0; i < kNumTriangleMetrics; ++i)
    if (kInfo[static_cast<std::size_t>(i)].name == name) return static_cast<TriangleMetric>(i);
  return std::nullopt;
}

double triangle_area(const TriangleCorners& p) { return clamp_signed(0.5 * norm(cross(p[1] - p[0], p[2] - p[0]))); }
double triangle_minimum_angle(const TriangleCorners& p) { return extreme_angle(p, false); }
double triangle_maximum_angle(const TriangleCorners& p) { return extreme_angle(p, true); }

double triangle_equiangle_skew(const TriangleCorners& p) {
  const double skew_max = (triangle_maximum_angle(p) - 60.0) / 120.0;
  const double skew_min = (60.0 - triangle_minimum_angle(p)) / 60.0;
  return skew_max > skew_min ? skew_max : skew_min;
}

double triangle_condition(const TriangleCorners& p) {
  const double s = char_size(p);
  const Vec3 v1 = (p[1] - p[0]) / s, v2 = (p[2] - p[0]) / s;
  const double area_x2 = norm(cross(v1, v2));
  if (area_x2 == 0.0) return kDblMax;
  return std::fmin((dot(v1, v1) + dot(v2, v2) - dot(v1, v2)) / (area_x2 * kSqrt3), kDblMax);
}

double triangle_scaled_jacobian(const TriangleCorners& p) {
  const double s = char_size(p);
  const Vec3 e0 = (p[1] - p[0]) / s, e1 = (p[2] - p[0]) / s, e2 = (p[2] - p[1]) / s;
  double jacobian = norm(cross(e1 - e0, e2 - e0));
  const double l0 = norm(e0), l1 = norm(e1), l2 = norm(e2);
  const double max_product = std::fmax(l0 * l1, std::fmax(l1 * l2, l0 * l2));
  if (max_product < kDblMin) return 0.0;
  jacobian *= 2. / kSqrt3;
  jacobian /= max_product;
  return clamp_signed(jacobian);
}

double triangle_metric(TriangleMetric m, const TriangleCorners& p, double average_area) {
  using M = TriangleMetric;
  switch (m) {
    case M::edge_ratio:
      return edge_ratio_of(p);
    case M::aspect_ratio:
      return aspect_ratio_of(p);
    case M::radius_ratio:
      return radius_ratio_of(p);
    case M::aspect_frobenius:
      return aspect_frobenius_of(p);
    case M::area:
      return triangle_area(p);
    case M::minimum_angle:
      return triangle_minimum_angle(p);
    case M::maximum_angle:
      return triangle_maximum_angle(p);
    case M::condition:
      return triangle_condition(p);
    case M::scaled_jacobian:
      return triangle_scaled_jacobian(p);
    case M::shape:
      return shape_of(p);
    case M::distortion:
      return 1.0;  // every linear triangle (Verdict's tri_distortion for 3 nodes)
    case M::equiangle_skew:
      return triangle_equiangle_skew(p);
    case M::normalized_inradius:
      return normalized_inradius_of(p);
    case M::relative_size_squared:
      return relative_size_squared_of(p, average_area);
    case M::shape_and_size:
      return clamp_signed(relative_size_squared_of(p, average_area) * shape_of(p));
  }
  return std::numeric_limits<double>::quiet_NaN();
}

TriangleMetricValues triangle_metrics(const TriangleCorners& p, double average_area) {
  TriangleMetricValues out;
  for (int m = 0; m < kNumTriangleMetrics; ++m)
    out[static_cast<std::size_t>(m)] = triangle_metric(static_cast<TriangleMetric>(m), p, average_area);
  return out;
}

}  // namespace hq
