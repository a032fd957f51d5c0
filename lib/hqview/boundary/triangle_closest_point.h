#pragma once
// The closest point of a triangle to a point (Ericson, Real-Time Collision
// Detection 5.1.5: by the Voronoi regions of the corners, edges and face).
// Plain code, no CGAL: the sampled distance's per-patch bound, and tests'
// brute-force distances.

#include "hqview/core/vec3.h"

namespace hq {

// The point of triangle (a, b, c) nearest to p (a degenerate triangle gives
// a point of its segment or its corner).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace hq
