#pragma once
// Reference cleanup and exact closest-point queries on a triangle surface,
// behind a plain interface: CGAL (Polygon Mesh Processing, AABB tree) stays
// inside surface_distance.cpp (ALGORITHMS.md §5, §7).

#include <memory>
#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/mesh/hex_mesh.h"

namespace hq {

// A reference surface after repair and orientation.
struct RepairedSurface {
  TriSurface surface;                 // merged points, no degenerate or duplicate triangles, consistently oriented
  bool is_closed_manifold = false;    // closed, manifold, and bounds a volume (outward oriented)
  Index num_removed_triangles = 0;    // input triangles dropped by the repair (degenerate, duplicate)
  Index num_zero_area_triangles = 0;  // zero-area triangles kept out of the distance structure
};

// PMP::repair_polygon_soup, orient_polygon_soup, polygon_soup_to_polygon_mesh;
// when the result is closed and PMP::does_bound_a_volume holds, it is
// oriented outward (orient_to_bound_a_volume). Otherwise each connected
// component is oriented so that its signed volume about its centroid is
// positive (outward for an open but mostly closed surface). Throws nothing;
// an empty input gives an empty surface.
RepairedSurface repair_reference(const TriSurface& reference);

struct ClosestPoint {
  Vec3 point;                 // closest point on the surface
  Index triangle = kNoIndex;  // the triangle it lies on (index into surface.triangles)
  double distance = 0;        // Euclidean distance from the query, model units
};

// The closest point of `surface` to every query (exact up to floating-point
// rounding: CGAL AABB tree with accelerated distance queries). Queries are
// visited in Morton order in fixed-size blocks (each block seeded by the
// previous answer as hint), in parallel with TBB; results do not depend on the
// thread count. Zero-area triangles are left out. Precondition: surface has
// at least one triangle of positive area (else every answer has triangle ==
// kNoIndex and an infinite distance).
struct ClosestPointOptions {
  // Morton order with the previous answer as hint (false: input order, each
  // query from the tree's own hint; for the benchmark baseline).
  bool spatial_order = true;
};
std::vector<ClosestPoint> closest_points(const TriSurface& surface, std::span<const Vec3> queries,
                                         const ClosestPointOptions& options = {});

// closest_points() with the search tree built once and queried many times
// (the adaptive sampling asks one surface level after level). Same answers as
// closest_points() for the same queries. The surface must outlive the tree.
class ClosestPointTree {
 public:
  explicit ClosestPointTree(const TriSurface& surface);
  ~ClosestPointTree();
  ClosestPointTree(const ClosestPointTree&) = delete;
  ClosestPointTree& operator=(const ClosestPointTree&) = delete;
  std::vector<ClosestPoint> query(std::span<const Vec3> queries, const ClosestPointOptions& options = {}) const;
  const TriSurface& surface() const;  // the surface it was built on

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hq
