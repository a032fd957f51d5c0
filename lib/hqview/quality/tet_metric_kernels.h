#pragma once
// The Verdict 1.4.5 tet kernels of tet_metrics.cpp, each written once for a
// vector type V: hq::Vec3 (one tet, the double arithmetic of core/vec3.h)
// or LaneVec3 (one tet per SIMD lane, for tet_metric_list_many). Internal
// to the quality module: included by tet_metrics.cpp (built for the
// baseline x86-64, SSE2) and tet_metrics_avx2.cpp (built with AVX2, run
// only where the CPU has it).
//
// Verdict's early returns are selects between both branches' values, its
// ternaries selects on the same comparisons; +, -, *, / and sqrt are IEEE
// operations, exact per lane, and the libm calls (acos, pow) run lane by
// lane on the scalar function: every lane's value is the one-tet value, bit
// for bit. Neither file may contract a * b + c into a fused multiply-add
// (-ffp-contract=off, no -mfma), which would round once instead of twice.
//
// Everything here has internal linkage (an unnamed namespace), so that the
// AVX2 file's copies of these functions never stand in for the baseline
// file's at link time.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <experimental/simd>
#include <limits>
#include <span>
#include <type_traits>
#include <utility>

#include "hqview/core/vec3.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/verdict_support.h"

namespace hq::tet_kernels {
namespace {

using namespace verdict_support;
namespace stdx = std::experimental;

// Verdict's radians-to-degrees factor (180 x a 34-digit 1/pi).
constexpr double kToDegrees = 180. * .3183098861837906715377675267450287;

// ---------------------------------------------------------------------------
// Numbers of one tet (double) or of one tet per lane (Lanes: as many as the
// target's vector registers hold, 2 with SSE2, 4 with AVX2), and the few
// operations the kernels need on either.

using Lanes = stdx::native_simd<double>;
using LaneMask = Lanes::mask_type;
constexpr std::size_t kTetLanes = Lanes::size();

// Vec3's operations on lanes, in Vec3's operation order.
struct LaneVec3 {
  Lanes x, y, z;
};
inline LaneVec3 operator+(const LaneVec3& a, const LaneVec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline LaneVec3 operator-(const LaneVec3& a, const LaneVec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline LaneVec3 operator-(const LaneVec3& a) { return {-a.x, -a.y, -a.z}; }
inline LaneVec3 operator*(const Lanes& s, const LaneVec3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline LaneVec3 operator*(double s, const LaneVec3& a) { return Lanes(s) * a; }
inline LaneVec3 operator/(const LaneVec3& a, const Lanes& s) { return {a.x / s, a.y / s, a.z / s}; }
inline LaneVec3 operator/(const LaneVec3& a, double s) { return a / Lanes(s); }
inline Lanes dot(const LaneVec3& a, const LaneVec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline LaneVec3 cross(const LaneVec3& a, const LaneVec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Lanes squared_norm(const LaneVec3& a) { return dot(a, a); }
inline Lanes norm(const LaneVec3& a) { return stdx::sqrt(dot(a, a)); }

// The number type of a vector type: double for Vec3, Lanes for LaneVec3.
template <class V>
using Num = std::remove_cvref_t<decltype(std::declval<V>().x)>;

template <class V>
using Corners = std::array<V, 4>;

// c ? a : b, lane by lane.
inline double select(bool c, double a, double b) { return c ? a : b; }
inline Lanes select(const LaneMask& c, const Lanes& a, const Lanes& b) {
  Lanes r = b;
  stdx::where(c, r) = a;
  return r;
}
inline Vec3 select(bool c, const Vec3& a, const Vec3& b) { return c ? a : b; }
inline LaneVec3 select(const LaneMask& c, const LaneVec3& a, const LaneVec3& b) {
  return {select(c, a.x, b.x), select(c, a.y, b.y), select(c, a.z, b.z)};
}

inline double sqrt_of(double v) { return std::sqrt(v); }
inline Lanes sqrt_of(const Lanes& v) { return stdx::sqrt(v); }
inline double fabs_of(double v) { return std::fabs(v); }
inline Lanes fabs_of(const Lanes& v) { return stdx::fabs(v); }

// A libm function of one or two doubles, lane by lane.
template <class F>
double each(F f, double a) {
  return f(a);
}
template <class F>
Lanes each(F f, const Lanes& a) {
  return Lanes([&](auto i) { return f(a[i]); });
}
template <class F>
double each(F f, double a, double b) {
  return f(a, b);
}
template <class F>
Lanes each(F f, const Lanes& a, const Lanes& b) {
  return Lanes([&](auto i) { return f(a[i], b[i]); });
}
inline auto acos_of(const auto& v) {
  return each([](double x) { return std::acos(x); }, v);
}
inline auto pow_of(const auto& v, double e) {
  return each([e](double x) { return std::pow(x, e); }, v);
}

// Verdict's fmin(a, b) as HQView has always computed it: GCC takes fmin
// as commutative and called glibc's fmin(b, a), which returns its first
// argument when the two compare equal (so -0 or +0 is b's). Written out
// so that every lane and every build picks the same zero; NaN as glibc's.
inline double fmin_of(double a, double b) { return b <= a ? b : (b > a ? a : (std::isnan(a) ? b : a)); }
inline Lanes fmin_of(const Lanes& a, const Lanes& b) {
  return select(b <= a, b, select(b > a, a, select(stdx::isnan(a), b, a)));
}

// verdict_support's clamps (NaN handled as there), on lanes beside doubles.
using verdict_support::clamp_signed;
using verdict_support::fix_range;
inline Lanes clamp_signed(const Lanes& v) {
  return select(v > 0.0, select(v < kDblMax, v, Lanes(kDblMax)), select(v > -kDblMax, v, Lanes(-kDblMax)));
}
inline Lanes fix_range(const Lanes& v) {
  const Lanes clamped = select(v >= kDblMax, Lanes(kDblMax), select(v <= -kDblMax, Lanes(-kDblMax), v));
  return select(stdx::isnan(v), Lanes(kDblMax), clamped);
}

// verdict_support::char_size: the bounding box diagonal, 1 below kDblMin.
template <class V>
Num<V> size_of(const Corners<V>& p) {
  using T = Num<V>;
  T lo_x = kDblMax, lo_y = kDblMax, lo_z = kDblMax, hi_x = -kDblMax, hi_y = -kDblMax, hi_z = -kDblMax;
  for (const V& q : p) {
    lo_x = select(q.x < lo_x, q.x, lo_x);
    lo_y = select(q.y < lo_y, q.y, lo_y);
    hi_x = select(q.x > hi_x, q.x, hi_x);
    hi_y = select(q.y > hi_y, q.y, hi_y);
    lo_z = select(q.z < lo_z, q.z, lo_z);
    hi_z = select(q.z > hi_z, q.z, hi_z);
  }
  const T length = norm(V{hi_x - lo_x, hi_y - lo_y, hi_z - lo_z});
  return select(length < kDblMin, T(1.0), length);
}

// ---------------------------------------------------------------------------
// The kernels.

// Verdict's six sides: 0-1, 1-2, 2-0, 0-3, 1-3, 2-3 (head minus tail).
template <class V>
std::array<V, 6> sides_of(const Corners<V>& p) {
  return {p[1] - p[0], p[2] - p[1], p[0] - p[2], p[3] - p[0], p[3] - p[1], p[3] - p[2]};
}

// The sides divided by the characteristic size `size` (size_of(p), computed
// once per tet by the callers).
template <class V>
std::array<V, 6> scaled_sides(const Corners<V>& p, const Num<V>& size) {
  auto s = sides_of(p);
  for (V& v : s) v = v / size;
  return s;
}

template <class V>
Num<V> volume_of(const Corners<V>& p) {
  const V side2 = p[1] - p[0], side0 = p[2] - p[0], side3 = p[3] - p[0];
  return dot(side3, cross(side2, side0)) / 6.0;
}

template <class V>
Num<V> jacobian_of(const Corners<V>& p) {
  const V side0 = p[1] - p[0], side2 = p[0] - p[2], side3 = p[3] - p[0];
  return dot(side3, cross(side2, side0));
}

// Verdict's tri_area (triangle_area(), inlined here: the inradius of the 12
// sub-tets of normalized_inradius calls it 48 times per tet).
template <class V>
Num<V> face_area(const V& a, const V& b, const V& c) {
  return clamp_signed(0.5 * norm(cross(b - a, c - a)));
}

template <class V>
Num<V> inradius_of(const Corners<V>& p) {
  const Num<V> a1 = face_area(p[0], p[1], p[2]);
  const Num<V> a2 = face_area(p[0], p[3], p[1]);
  const Num<V> a3 = face_area(p[0], p[2], p[3]);
  const Num<V> a4 = face_area(p[1], p[3], p[2]);
  return 3 * volume_of(p) / (a1 + a2 + a3 + a4);
}

template <class V>
Num<V> edge_ratio_of(const Corners<V>& p, const Num<V>& size) {
  const auto v = scaled_sides(p, size);
  Num<V> m2 = squared_norm(v[0]), M2 = m2;
  for (int i = 1; i < 6; ++i) {
    const Num<V> l2 = squared_norm(v[i]);
    m2 = select(l2 < m2, l2, m2);
    M2 = select(l2 > M2, l2, M2);
  }
  return select(m2 < kDblMin, Num<V>(kDblMax), fix_range(sqrt_of(M2 / m2)));
}

template <class V>
Num<V> radius_ratio_of(const Corners<V>& p, const Num<V>& size) {
  const auto s = scaled_sides(p, size);
  const V numerator = squared_norm(s[3]) * cross(s[2], s[0]) + squared_norm(s[2]) * cross(s[3], s[0]) +
                      squared_norm(s[0]) * cross(s[3], s[2]);
  const Num<V> area_sum =
      (norm(cross(s[2], s[0])) + norm(cross(s[3], s[0])) + norm(cross(s[4], s[1])) + norm(cross(s[3], s[2]))) * 0.5;
  Num<V> volume = volume_of(p);
  volume /= (size * size * size);
  return select(fabs_of(volume) < kDblMin, Num<V>(kDblMax),
                fix_range(norm(numerator) * area_sum / (108 * volume * volume)));
}

template <class V>
Num<V> aspect_ratio_of(const Corners<V>& p, const Num<V>& size) {
  using T = Num<V>;
  const V ab = (p[1] - p[0]) / size, ac = (p[2] - p[0]) / size, ad = (p[3] - p[0]) / size;
  const T det_tet = dot(ab, cross(ac, ad));
  const V bc = (p[2] - p[1]) / size, bd = (p[3] - p[1]) / size, cd = (p[3] - p[2]) / size;
  const T ab2 = squared_norm(ab), bc2 = squared_norm(bc), ac2 = squared_norm(ac), ad2 = squared_norm(ad),
          bd2 = squared_norm(bd), cd2 = squared_norm(cd);
  T A = select(ab2 > bc2, ab2, bc2);
  T B = select(ac2 > ad2, ac2, ad2);
  T C = select(bd2 > cd2, bd2, cd2);
  T D = select(A > B, A, B);
  const T hm = select(D > C, sqrt_of(D), sqrt_of(C));
  A = norm(cross(ab, bc));
  B = norm(cross(ab, ad));
  C = norm(cross(ac, ad));
  D = norm(cross(bc, cd));
  return select(fabs_of(det_tet) < kDblMin, T(kDblMax),
                fix_range(kSqrt6 / 12. * hm * (A + B + C + D) / fabs_of(det_tet)));
}

template <class V>
Num<V> aspect_gamma_of(const Corners<V>& p, const Num<V>& size) {
  using T = Num<V>;
  const auto s = scaled_sides(p, size);
  T volume = fabs_of(volume_of(p));
  volume /= (size * size * size);
  const T srms = sqrt_of((squared_norm(s[0]) + squared_norm(s[1]) + squared_norm(s[2]) + squared_norm(s[3]) +
                          squared_norm(s[4]) + squared_norm(s[5])) /
                         6.0);
  return select(volume < kDblMin, T(kDblMax), (srms * srms * srms) / (8.48528137423857 * volume));
}

// Angle extremes taken on the arguments of acos (acos is decreasing), so acos
// runs once per extreme for the same values: an argument outside [-1, 1]
// (or NaN) is a NaN angle, and Verdict's ternaries `m = m < a ? m : a`
// replace a NaN on the left and keep one on the right.
template <class T>
auto in_acos_domain(const T& c) {
  return c >= -1.0 && c <= 1.0;
}

template <class T, std::size_t N>
T ternary_min_angle_argument(const std::array<T, N>& c) {
  T chosen = c[0];
  for (std::size_t i = 1; i < N; ++i)
    chosen = select(in_acos_domain(chosen) && in_acos_domain(c[i]) && chosen > c[i], chosen, c[i]);
  return chosen;
}

template <class T, std::size_t N>
T ternary_max_angle_argument(const std::array<T, N>& c) {
  T chosen = c[0];
  for (std::size_t i = 1; i < N; ++i)
    chosen = select(in_acos_domain(chosen) && in_acos_domain(c[i]) && chosen < c[i], chosen, c[i]);
  return chosen;
}

template <class V>
Num<V> minimum_angle_of(const Corners<V>& p) {
  using T = Num<V>;
  const V ab = p[1] - p[0], ad = p[3] - p[0], bc = p[2] - p[1], cd = p[3] - p[2];
  const V abc = cross(ab, bc), abd = cross(ab, ad), acd = cross(ad, cd), bcd = cross(bc, cd);
  const T nabc = norm(abc), nabd = norm(abd), nacd = norm(acd), nbcd = norm(bcd);
  // The six dihedral angles' cosines, in Verdict's order (alpha ... zeta).
  const std::array<T, 6> c = {dot(abc, abd) / (nabc * nabd), dot(abc, acd) / (nabc * nacd),
                              dot(abc, bcd) / (nabc * nbcd), dot(abd, acd) / (nabd * nacd),
                              dot(abd, bcd) / (nabd * nbcd), dot(acd, bcd) / (nacd * nbcd)};
  return fix_range(acos_of(ternary_min_angle_argument(c)) * kToDegrees);
}

template <class V>
Num<V> collapse_ratio_of(const Corners<V>& p) {
  using T = Num<V>;
  const V e01 = p[1] - p[0], e02 = p[2] - p[0], e03 = p[3] - p[0], e12 = p[2] - p[1], e13 = p[3] - p[1],
          e23 = p[3] - p[2];
  const T l[6] = {norm(e01), norm(e02), norm(e03), norm(e12), norm(e13), norm(e23)};
  T l012 = select(l[4] > l[0], l[4], l[0]);
  l012 = select(l[1] > l012, l[1], l012);
  T l031 = select(l[0] > l[2], l[0], l[2]);
  l031 = select(l[3] > l031, l[3], l031);
  T l023 = select(l[2] > l[1], l[2], l[1]);
  l023 = select(l[5] > l023, l[5], l023);
  T l132 = select(l[4] > l[3], l[4], l[3]);
  l132 = select(l[5] > l132, l[5], l132);
  // Height of the fourth corner over each face, over the face's longest edge.
  auto ratio = [](const V& n, const V& to_apex, const T& longest) { return dot(to_apex, n) / norm(n) / longest; };
  T smallest = ratio(cross(e01, e02), e03, l012);
  T r = ratio(cross(e03, e01), e02, l031);
  smallest = select(r < smallest, r, smallest);
  r = ratio(cross(e02, e03), e01, l023);
  smallest = select(r < smallest, r, smallest);
  r = ratio(cross(e12, e13), e01, l132);
  smallest = select(r < smallest, r, smallest);
  return fix_range(smallest);
}

template <class V>
Num<V> condition_of(const Corners<V>& p, const Num<V>& size) {
  using T = Num<V>;
  const V side0 = (p[1] - p[0]) / size, side2 = (p[0] - p[2]) / size, side3 = (p[3] - p[0]) / size;
  // The corner frame mapped to the regular tet.
  const V c1 = side0;
  const V c2 = (-2. * side2 - side0) / kSqrt3;
  const V c3 = (3. * side3 + side2 - side0) / kSqrt6;
  const T term1 = dot(c1, c1) + dot(c2, c2) + dot(c3, c3);
  const V c12 = cross(c1, c2), c23 = cross(c2, c3), c13 = cross(c1, c3);
  const T term2 = dot(c12, c12) + dot(c23, c23) + dot(c13, c13);
  const T det = dot(c1, cross(c2, c3));
  return select(fabs_of(det) <= kDblMin, T(kDblMax), sqrt_of(term1) * sqrt_of(term2) / (3.0 * det));
}

template <class V>
Num<V> mean_ratio_of(const Corners<V>& p, const Num<V>& size) {
  using T = Num<V>;
  const auto s = scaled_sides(p, size);
  // Verdict's calculate_tet_volume_using_sides(side0, side2, side3).
  const T volume = dot(s[3], cross(s[2], s[0])) / 6.0;
  const T sum = (squared_norm(s[0]) + squared_norm(s[1]) + squared_norm(s[2]) + squared_norm(s[3]) +
                 squared_norm(s[4]) + squared_norm(s[5])) /
                6;
  return select(fabs_of(volume) < kDblMin, T(0.0), 6 * kSqrt2 * volume / pow_of(sum, 3. / 2.));
}

// Verdict's tet4_normalized_inradius: the tet split at its edge midpoints
// and their centroid into 4 corner tets and 8 inner tets; the smallest
// inradius of each group, normalised by the circumradius so that the regular
// tet scores 1.
template <class V>
Num<V> normalized_inradius_of(const Corners<V>& p) {
  using T = Num<V>;
  std::array<V, 11> q;
  for (int i = 0; i < 4; ++i) q[i] = p[i];
  static constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (int i = 4; i < 10; ++i) {
    const V& a = p[kEdge[i - 4][0]];
    const V& b = p[kEdge[i - 4][1]];
    q[i] = {(a.x + b.x) * 0.5, (a.y + b.y) * 0.5, (a.z + b.z) * 0.5};
  }
  V centre{T(0.0), T(0.0), T(0.0)};
  for (int i = 4; i < 10; ++i) centre = centre + q[i];
  q[10] = centre / 6.0;
  static constexpr int kSubTet[12][4] = {{0, 4, 6, 7},  {1, 5, 4, 8},  {2, 6, 5, 9},  {3, 8, 7, 9},
                                         {4, 8, 5, 10}, {5, 8, 9, 10}, {9, 8, 7, 10}, {7, 8, 4, 10},
                                         {4, 5, 6, 10}, {5, 9, 6, 10}, {9, 7, 6, 10}, {7, 4, 6, 10}};
  auto smallest_inradius = [&](int begin, int end) {
    T smallest = kDblMax;
    for (int t = begin; t <= end; ++t) {
      const T r = inradius_of(Corners<V>{q[kSubTet[t][0]], q[kSubTet[t][1]], q[kSubTet[t][2]], q[kSubTet[t][3]]});
      smallest = select(r < smallest, r, smallest);
    }
    return smallest;
  };
  const T with_corner = smallest_inradius(0, 3);
  const T inner = smallest_inradius(4, 11);
  const T aC = norm(p[1] - p[0]), bC = norm(p[2] - p[0]), cC = norm(p[3] - p[0]);
  const T AC = norm(p[3] - p[2]), BC = norm(p[3] - p[1]), CC = norm(p[2] - p[1]);
  const T VP = fabs_of(dot(cross(p[1] - p[0], p[2] - p[0]), p[3] - p[0]) / 6);
  const T circumradius = sqrt_of((aC * AC + bC * BC + cC * CC) * (aC * AC + bC * BC - cC * CC) *
                                 (aC * AC - bC * BC + cC * CC) * (-aC * AC + bC * BC + cC * CC)) /
                         24 / VP;
  const T a = 6.0 * with_corner / circumradius;
  const T b = 3.0 * (1 + kSqrt3) * inner / circumradius;
  return fix_range(fmin_of(a, b));
}

template <class V>
Num<V> shape_of(const Corners<V>& p, const Num<V>& size) {
  using T = Num<V>;
  const V e0 = (p[1] - p[0]) / size, e1 = (p[0] - p[2]) / size, e2 = (p[3] - p[0]) / size;
  const T jacobian = dot(e2, cross(e1, e0));
  const T num = 3 * pow_of(kSqrt2 * jacobian, 2.0 / 3.0);
  const T den = 1.5 * (dot(e0, e0) + dot(e1, e1) + dot(e2, e2)) - (dot(e0, -e1) + dot(-e1, e2) + dot(e2, e0));
  const T shape = num / den;
  return select(jacobian < kDblMin || den < kDblMin, T(0.0), fix_range(select(shape < 0, T(0.0), shape)));
}

template <class V>
Num<V> equivolume_skew_of(const Corners<V>& p) {
  using T = Num<V>;
  const V ab = p[1] - p[0], ac = p[2] - p[0], ad = p[3] - p[0];
  const V bc = cross(ab, ac), db = cross(ad, ab), cd = cross(ac, ad);
  const V num = squared_norm(ad) * bc + squared_norm(ac) * db + squared_norm(ab) * cd;
  const T den = dot(2 * ab, cd);
  const T circumradius = norm(num) / den;
  const T volume = volume_of(p);
  const T optimal_length = circumradius / std::sqrt(3.0 / 8.0);
  const T optimal_volume = (1.0 / 12.0) * std::sqrt(2.0) * (optimal_length * optimal_length * optimal_length);
  return fix_range((optimal_volume - volume) / optimal_volume);
}

template <class V>
Num<V> squish_index_of(const Corners<V>& p) {
  using T = Num<V>;
  const V centre = (p[0] + p[1] + p[2] + p[3]) / 4.0;
  const auto s = sides_of(p);
  T largest = 0.0;
  auto visit = [&](const V& face_centre, const V& area_vector) {
    const V to_face = face_centre - centre;
    const T squish = 1 - dot(area_vector, to_face) / (norm(area_vector) * norm(to_face));
    largest = select(squish > largest, squish, largest);
  };
  visit((p[0] + p[1] + p[3]) / 3.0, 0.5 * cross(s[0], s[4]));
  visit((p[1] + p[2] + p[3]) / 3.0, 0.5 * cross(s[1], s[5]));
  visit((p[0] + p[2] + p[3]) / 3.0, 0.5 * cross(s[2], s[3]));
  visit((p[0] + p[1] + p[2]) / 3.0, 0.5 * cross(s[1], s[0]));
  return largest;
}

// VerdictVector::normalize without its length: a vector not longer than
// 2 * kDblMin becomes zero.
template <class V>
V unit(const V& v) {
  const Num<V> length = norm(v);
  const Num<V> zero = 0.0;
  return select(length > kDblMin * 2.0, v / length, V{zero, zero, zero});
}

template <class V>
Num<V> equiangle_skew_of(const Corners<V>& p) {
  using T = Num<V>;
  const V ab = unit(p[1] - p[0]), ac = unit(p[2] - p[0]), ad = unit(p[3] - p[0]), bc = unit(p[2] - p[1]),
          bd = unit(p[3] - p[1]), cd = unit(p[3] - p[2]);
  const V abc = unit(cross(bc, ab)), abd = unit(cross(ab, ad)), acd = unit(cross(cd, ad)), bcd = unit(cross(bc, cd));
  // Dihedral angles (the acos arguments, Verdict's order).
  const std::array<T, 6> dihedral = {-dot(abc, abd), -dot(abc, acd), -dot(abc, bcd),
                                     -dot(abd, acd), -dot(abd, bcd), -dot(acd, bcd)};
  T min_angle = acos_of(ternary_min_angle_argument(dihedral)) * kToDegrees;
  T max_angle = acos_of(ternary_max_angle_argument(dihedral)) * kToDegrees;
  const double theta = std::acos(1 / 3.0) * kToDegrees;
  const T dihedral_skew_max = (max_angle - theta) / (180 - theta);
  const T dihedral_skew_min = (theta - min_angle) / theta;
  // Face angles: Verdict starts from 360 and 0 (radians) and skips NaNs.
  const T face[12] = {-dot(ab, bc), dot(bc, ac), dot(ac, ab), -dot(ab, bd), dot(bd, ad),  dot(ad, ab),
                      -dot(bc, cd), dot(cd, bd), dot(bd, bc), dot(ad, cd),  -dot(cd, ac), dot(ac, ad)};
  auto any = T(0.0) != T(0.0);  // false in every lane
  T largest_cosine = 0, smallest_cosine = 0;
  for (const T& c : face) {
    const auto counted = in_acos_domain(c);
    largest_cosine = select(counted && (!any || c > largest_cosine), c, largest_cosine);
    smallest_cosine = select(counted && (!any || c < smallest_cosine), c, smallest_cosine);
    any = any || counted;
  }
  min_angle = select(any, acos_of(largest_cosine), T(360.0)) * kToDegrees;
  max_angle = select(any, acos_of(smallest_cosine), T(0.0)) * kToDegrees;
  const T skew_max = (max_angle - 60.0) / 120.0;
  const T skew_min = (60.0 - min_angle) / 60.0;
  T skew = dihedral_skew_min;
  skew = select(skew > dihedral_skew_max, skew, dihedral_skew_max);
  skew = select(skew > skew_min, skew, skew_min);
  skew = select(skew > skew_max, skew, skew_max);
  return skew;
}

template <class V>
Num<V> relative_size_squared_of(const Corners<V>& p, const TetSizeReference& reference) {
  using T = Num<V>;
  const double avg_volume = reference.regular_volume;
  if (avg_volume < kDblMin) return T(0.0);
  T size = volume_of(p) / avg_volume;
  const auto zero = size <= kDblMin;
  size = select(size > 1, 1.0 / size, size);
  return select(zero, T(0.0), size * size);
}

template <class V>
Num<V> scaled_jacobian_with_size(const Corners<V>& p, const Num<V>& size) {
  using T = Num<V>;
  const auto s = scaled_sides(p, size);
  const T jacobian = dot(s[3], cross(s[2], s[0]));
  T l2[6];
  for (int i = 0; i < 6; ++i) l2[i] = squared_norm(s[i]);
  // The edge-length products at the 4 corners; the largest normalises.
  const T product[4] = {l2[0] * l2[2] * l2[3], l2[0] * l2[1] * l2[4], l2[1] * l2[2] * l2[5], l2[3] * l2[4] * l2[5]};
  T largest = product[0];
  for (int i = 1; i < 4; ++i) largest = select(product[i] > largest, product[i], largest);
  T length_product = sqrt_of(largest);
  length_product = select(length_product < fabs_of(jacobian), fabs_of(jacobian), length_product);
  return select(length_product < kDblMin, T(kDblMax), kSqrt2 * jacobian / length_product);
}

template <class V>
Num<V> aspect_frobenius_with_size(const Corners<V>& p, const Num<V>& size) {
  using T = Num<V>;
  const V u = (p[1] - p[0]) / size, v = (p[2] - p[0]) / size, w = (p[3] - p[0]) / size;
  T denominator = dot(u, cross(v, w));
  denominator *= denominator;
  denominator *= 2.;
  denominator = 3. * pow_of(denominator, 1.0 / 3.0);
  T numerator = dot(u, u);
  numerator += dot(v, v);
  numerator += dot(w, w);
  numerator *= 1.5;
  numerator -= dot(v, u);
  numerator -= dot(w, u);
  numerator -= dot(w, v);
  return select(denominator < kDblMin, T(kDblMax), fix_range(numerator / denominator));
}

// One metric, given the tet's characteristic size (size_of(p)).
template <class V>
Num<V> metric_with_size(TetMetric m, const Corners<V>& p, const TetSizeReference& reference, const Num<V>& size) {
  using M = TetMetric;
  using T = Num<V>;
  switch (m) {
    case M::inradius:
      return inradius_of(p);
    case M::edge_ratio:
      return edge_ratio_of(p, size);
    case M::radius_ratio:
      return radius_ratio_of(p, size);
    case M::aspect_ratio:
      return aspect_ratio_of(p, size);
    case M::aspect_gamma:
      return aspect_gamma_of(p, size);
    case M::aspect_frobenius:
      return aspect_frobenius_with_size(p, size);
    case M::minimum_angle:
      return minimum_angle_of(p);
    case M::collapse_ratio:
      return collapse_ratio_of(p);
    case M::volume:
      return volume_of(p);
    case M::condition:
      return condition_of(p, size);
    case M::jacobian:
      return jacobian_of(p);
    case M::scaled_jacobian:
      return scaled_jacobian_with_size(p, size);
    case M::mean_ratio:
      return mean_ratio_of(p, size);
    case M::normalized_inradius:
      return normalized_inradius_of(p);
    case M::shape:
      return shape_of(p, size);
    case M::distortion:
      return T(1.0);  // every linear tet (Verdict's tet_distortion for 4 nodes)
    case M::equivolume_skew:
      return equivolume_skew_of(p);
    case M::squish_index:
      return squish_index_of(p);
    case M::equiangle_skew:
      return equiangle_skew_of(p);
    case M::relative_size_squared:
      return relative_size_squared_of(p, reference);
    case M::shape_and_size:
      return shape_of(p, size) * relative_size_squared_of(p, reference);
  }
  return T(std::numeric_limits<double>::quiet_NaN());
}

// ---------------------------------------------------------------------------

// tet_metric_list_many's loop: kTetLanes tets at a time.
inline void metric_list_lanes(std::span<const TetMetric> metrics, std::span<const TetCorners> tets,
                              const TetSizeReference& reference, std::span<double* const> out) {
  for (std::size_t first = 0; first < tets.size(); first += kTetLanes) {
    const std::size_t count = std::min<std::size_t>(kTetLanes, tets.size() - first);
    // The lanes past the last tet repeat it (computed, not stored).
    std::array<const TetCorners*, kTetLanes> tet;
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) tet[lane] = &tets[first + std::min(lane, count - 1)];
    Corners<LaneVec3> p;
    for (std::size_t k = 0; k < 4; ++k) {
      p[k].x = Lanes([&](auto lane) { return (*tet[lane])[k].x; });
      p[k].y = Lanes([&](auto lane) { return (*tet[lane])[k].y; });
      p[k].z = Lanes([&](auto lane) { return (*tet[lane])[k].z; });
    }
    const Lanes size = size_of(p);  // shared by every scaled metric
    for (std::size_t j = 0; j < metrics.size(); ++j) {
      const Lanes v = metric_with_size(metrics[j], p, reference, size);
      for (std::size_t lane = 0; lane < count; ++lane) out[j][first + lane] = v[lane];
    }
  }
}

}  // namespace
}  // namespace hq::tet_kernels

namespace hq::detail {
// tet_metric_list_many on 4 lanes (tet_metrics_avx2.cpp): call only where
// the CPU has AVX2.
void tet_metric_list_many_avx2(std::span<const TetMetric> metrics, std::span<const TetCorners> tets,
                               const TetSizeReference& reference, std::span<double* const> out);
}  // namespace hq::detail
