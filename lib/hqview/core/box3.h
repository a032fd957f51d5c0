#pragma once
// Box3: an axis-aligned bounding box of points. Empty (lo > hi) until a
// point is added; the coordinates are those of the points, so exact.

#include <algorithm>
#include <cmath>
#include <span>

#include "hqview/core/vec3.h"

namespace hq {

struct Box3 {
  Vec3 lo{INFINITY, INFINITY, INFINITY};
  Vec3 hi{-INFINITY, -INFINITY, -INFINITY};

  void add(const Vec3& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  // No point added (or a NaN one).
  bool is_empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  // Length of the diagonal; 0 when empty.
  double diagonal() const { return is_empty() ? 0.0 : norm(hi - lo); }
  // The closed boxes share a point.
  bool overlaps(const Box3& o) const {
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z && o.lo.z <= hi.z;
  }
};

inline Box3 bounding_box(std::span<const Vec3> points) {
  Box3 box;
  for (const Vec3& p : points) box.add(p);
  return box;
}

}  // namespace hq
