#pragma once
// Shared pieces of the Verdict 1.4.5 kernels for tets, wedges, pyramids,
// quads and triangles (tet_metrics, wedge_metrics, pyramid_metrics,
// quad_metrics, triangle_metrics): Verdict's constants, its range clamps and
// its element scaling. Internal to the quality module (the hex kernels keep
// their own copies in hex_metrics.cpp, which predates this header).
//
// Verdict 1.4.5 rescales many metrics' edge vectors by a characteristic size
// (the diagonal of the cell's bounding box) before it compares them with its
// absolute thresholds, so those metrics decide "degenerate" the same way at
// any scale; the kernels here scale exactly where Verdict does, so that
// degenerate and tiny cells get Verdict's values too.

#include <array>
#include <cmath>
#include <cstddef>

#include "hqview/core/vec3.h"

namespace hq::verdict_support {

// verdict.h: VERDICT_DBL_MIN (10 machine epsilons), VERDICT_DBL_MAX (the
// value of a degenerate cell), VERDICT_PI.
inline constexpr double kDblMin = 2.2204460492503131e-15;
inline constexpr double kDblMax = 1e30;
inline constexpr double kPi = 3.1415926535897932384626;
inline constexpr double kSqrt2 = 1.414213562373095048801689;
inline constexpr double kSqrt3 = 1.732050807568877293527446;
inline constexpr double kSqrt6 = 2.449489742783178098197284;

// Verdict's closing clamp of most metrics: min(v, 1e30) when v > 0, else
// max(v, -1e30) (a NaN becomes -1e30, as fmax(NaN, -1e30) does).
// Written with comparisons (the same values as fmin/fmax here, v > 0 being
// no NaN) so that it inlines instead of calling libm.
inline double clamp_signed(double v) { return v > 0 ? (v < kDblMax ? v : kDblMax) : (v > -kDblMax ? v : -kDblMax); }

// Verdict's fix_range (tet metrics): NaN -> +1e30, then into [-1e30, 1e30].
inline double fix_range(double v) {
  if (std::isnan(v)) return kDblMax;
  if (v >= kDblMax) return kDblMax;
  if (v <= -kDblMax) return -kDblMax;
  return v;
}

// Verdict's elem_scaling: the bounding box diagonal (1 when it is below
// kDblMin) and the centroid (the origin then). `dimension` 2 ignores z.
struct ElemScale {
  Vec3 centre;
  double scale;
};

template <std::size_t N>
ElemScale elem_scaling(const std::array<Vec3, N>& p) {
  Vec3 lo{kDblMax, kDblMax, kDblMax}, hi{-kDblMax, -kDblMax, -kDblMax}, centre{};
  for (const Vec3& q : p) {
    if (q.x < lo.x) lo.x = q.x;
    if (q.y < lo.y) lo.y = q.y;
    if (q.x > hi.x) hi.x = q.x;
    if (q.y > hi.y) hi.y = q.y;
    if (q.z < lo.z) lo.z = q.z;
    if (q.z > hi.z) hi.z = q.z;
    centre = centre + q;
  }
  centre = centre / static_cast<double>(N);
  double length = norm(hi - lo);
  if (length < kDblMin) return {Vec3{}, 1.0};
  return {centre, length};
}

template <std::size_t N>
double char_size(const std::array<Vec3, N>& p) {
  return elem_scaling(p).scale;
}

// VerdictVector::normalize: the length, and v scaled to unit length; a vector
// not longer than 2 * kDblMin becomes zero and the length returned is 0.
inline double normalize(Vec3& v) {
  const double length = norm(v);
  if (length > kDblMin * 2.0) {
    v = {v.x / length, v.y / length, v.z / length};
    return length;
  }
  v = Vec3{};
  return 0.0;
}

// VerdictVector::interior_angle, in degrees (0 for a zero-length vector).
inline double interior_angle(const Vec3& u, const Vec3& v) {
  double cosine = 0.0, radians = 0.0;
  const double l1 = norm(u);
  const double l2 = l1 > 0 ? norm(v) : 0.0;
  if (l1 > 0 && l2 > 0) cosine = dot(u, v) / (l1 * l2);
  if (cosine > 1.0 && cosine < 1.0001)
    radians = std::acos(1.0);
  else if (cosine < -1.0 && cosine > -1.0001)
    radians = std::acos(-1.0);
  else if (cosine >= -1.0 && cosine <= 1.0)
    radians = std::acos(cosine);
  return (radians * 180.) / kPi;
}

}  // namespace hq::verdict_support
