#include "hqview/quality/cell_corner_jacobian.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>

#include "hqview/core/cell_kinds.h"

namespace hq {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

constexpr double kSqrt2 = 1.414213562373095048801689;
constexpr double kTwoOverSqrt3 = 2.0 / 1.732050807568877293527446;

// The corner values of a volume kind K with `factor`, over its corner frames;
// `fold`: a value above 1 becomes 2 - value (Verdict's pyramid), else the
// value is clamped to 1.
template <CellKind K, std::size_t N>
auto volume_corners(const std::array<Vec3, N>& p, double factor, bool fold = false) {
  using T = CellKindTable<K>;
  constexpr std::size_t C = T::corner_frames.size();
  KindCornerJacobians<C> out;
  for (std::size_t i = 0; i < C; ++i) {
    const auto& f = T::corner_frames[i];
    const Vec3& o = p[i];  // frame i belongs to corner i (the pyramid's apex, corner 4, has none)
    const Vec3 a = p[f[0]] - o, b = p[f[1]] - o, c = p[f[2]] - o;
    const double lengths = norm(a) * norm(b) * norm(c);
    const bool degenerate = !(lengths > 0.0);
    const double value = factor * det(a, b, c) / lengths;
    out.value[i] = degenerate ? 0.0 : std::clamp(fold && value > 1.0 ? 2.0 - value : value, -1.0, 1.0);
    out.degenerate_mask |= static_cast<std::uint8_t>(static_cast<unsigned>(degenerate) << i);
  }
  return out;
}

template <CellKind K, std::size_t N>
CellValidity volume_validity(const std::array<Vec3, N>& p) {
  using T = CellKindTable<K>;
  auto point = [&](int i) { return Kernel::Point_3(p[i].x, p[i].y, p[i].z); };
  bool flat = false;
  for (std::size_t i = 0; i < T::corner_frames.size(); ++i) {
    const auto& f = T::corner_frames[i];
    // orientation(o, a, b, c) is the sign of det[a - o, b - o, c - o].
    const auto s = CGAL::orientation(point(static_cast<int>(i)), point(f[0]), point(f[1]), point(f[2]));
    if (s == CGAL::NEGATIVE) return CellValidity::inverted;
    flat = flat || s == CGAL::ZERO;
  }
  return flat ? CellValidity::flat : CellValidity::valid;
}

// Verdict's quad centre normal, unit (zero when the quad has none).
Vec3 quad_centre_normal(const std::array<Vec3, 4>& p) {
  return normalized(cross(p[1] + p[2] - p[0] - p[3], p[2] + p[3] - p[0] - p[1]));
}

// Surface corners against the unit normal n: signed (e(i-1) x e(i)) . n.
template <std::size_t N>
KindCornerJacobians<N> surface_corners(const std::array<Vec3, N>& p, const Vec3& n, double factor) {
  KindCornerJacobians<N> out;
  for (std::size_t i = 0; i < N; ++i) {
    const Vec3 to_next = p[(i + 1) % N] - p[i];
    const Vec3 to_previous = p[(i + N - 1) % N] - p[i];
    const double lengths = norm(to_next) * norm(to_previous);
    const bool degenerate = !(lengths > 0.0);
    const double area = dot(cross(to_next, to_previous), n);
    out.value[i] = degenerate ? 0.0 : std::clamp(factor * area / lengths, -1.0, 1.0);
    out.degenerate_mask |= static_cast<std::uint8_t>(static_cast<unsigned>(degenerate) << i);
  }
  return out;
}

template <std::size_t N>
CellValidity surface_validity(const std::array<Vec3, N>& p, const Vec3& n) {
  bool flat = false;
  for (std::size_t i = 0; i < N; ++i) {
    const double area = dot(cross(p[(i + 1) % N] - p[i], p[(i + N - 1) % N] - p[i]), n);
    if (area < 0) return CellValidity::inverted;
    flat = flat || !(area > 0);
  }
  return flat ? CellValidity::flat : CellValidity::valid;
}

}  // namespace

KindCornerJacobians<4> tet_corner_scaled_jacobians(const std::array<Vec3, 4>& p) {
  return volume_corners<CellKind::tet>(p, kSqrt2);
}
KindCornerJacobians<6> wedge_corner_scaled_jacobians(const std::array<Vec3, 6>& p) {
  return volume_corners<CellKind::wedge>(p, kTwoOverSqrt3);
}
KindCornerJacobians<4> pyramid_corner_scaled_jacobians(const std::array<Vec3, 5>& p) {
  return volume_corners<CellKind::pyramid>(p, kSqrt2, /*fold=*/true);
}

KindCornerJacobians<4> quad_corner_scaled_jacobians(const std::array<Vec3, 4>& p, const std::optional<Vec3>& normal) {
  return surface_corners(p, normal ? normalized(*normal) : quad_centre_normal(p), 1.0);
}

KindCornerJacobians<3> triangle_corner_scaled_jacobians(const std::array<Vec3, 3>& p,
                                                        const std::optional<Vec3>& normal) {
  return surface_corners(p, normalized(normal ? *normal : cross(p[1] - p[0], p[2] - p[0])), kTwoOverSqrt3);
}

CellValidity tet_validity(const std::array<Vec3, 4>& p) {
  // The 4 corner frames list the corners in even permutations of (0,1,2,3)
  // ((1,2,0,3), (2,0,1,3), (3,0,2,1)): their determinants' exact signs are
  // one sign, so corner 0's decides.
  const auto s = CGAL::orientation(Kernel::Point_3(p[0].x, p[0].y, p[0].z), Kernel::Point_3(p[1].x, p[1].y, p[1].z),
                                   Kernel::Point_3(p[2].x, p[2].y, p[2].z), Kernel::Point_3(p[3].x, p[3].y, p[3].z));
  return s == CGAL::NEGATIVE ? CellValidity::inverted : s == CGAL::ZERO ? CellValidity::flat : CellValidity::valid;
}
CellValidity wedge_validity(const std::array<Vec3, 6>& p) { return volume_validity<CellKind::wedge>(p); }
CellValidity pyramid_validity(const std::array<Vec3, 5>& p) { return volume_validity<CellKind::pyramid>(p); }

CellValidity quad_validity(const std::array<Vec3, 4>& p, const std::optional<Vec3>& normal) {
  return surface_validity(p, normal ? *normal : quad_centre_normal(p));
}

CellValidity triangle_validity(const std::array<Vec3, 3>& p, const std::optional<Vec3>& normal) {
  return surface_validity(p, normal ? *normal : cross(p[1] - p[0], p[2] - p[0]));
}

}  // namespace hq
