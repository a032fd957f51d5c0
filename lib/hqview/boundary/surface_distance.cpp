// The one CGAL translation unit of the boundary module: repair/orientation
// (Polygon Mesh Processing) and closest points (AABB tree). Compiling it takes
// ~20 s and >1 GB: keep everything that does not need CGAL elsewhere.

#include "hqview/boundary/surface_distance.h"

#include "hqview/core/box3.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Surface_mesh.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace hq {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

// Queries per block: each block starts from the tree's own hint, so the
// answers do not depend on how blocks are spread over threads.
constexpr std::size_t kQueryBlock = 512;

Point to_point(const Vec3& p) { return {p.x, p.y, p.z}; }
Vec3 to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }

double twice_area(const TriSurface& s, const std::array<Index, 3>& t) {
  return norm(cross(s.points[t[1]] - s.points[t[0]], s.points[t[2]] - s.points[t[0]]));
}

// Orients every connected component (across shared vertices) so that its
// signed volume about its centroid is non-negative.
void orient_components_outward(TriSurface& s) {
  const std::size_t nv = s.points.size();
  std::vector<Index> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](Index v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& t : s.triangles)
    for (int k = 1; k < 3; ++k) {
      const Index a = find(t[0]), b = find(t[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<Vec3> centroid_sum(nv);
  std::vector<double> count(nv, 0.0);
  for (const auto& t : s.triangles)
    for (Index v : t) {
      const Index r = find(v);
      centroid_sum[r] = centroid_sum[r] + s.points[v];
      count[r] += 1.0;
    }
  std::vector<double> volume(nv, 0.0);
  for (const auto& t : s.triangles) {
    const Index r = find(t[0]);
    const Vec3 c = centroid_sum[r] / count[r];
    volume[r] += det(s.points[t[0]] - c, s.points[t[1]] - c, s.points[t[2]] - c);
  }
  for (auto& t : s.triangles)
    if (volume[find(t[0])] < 0.0) std::swap(t[1], t[2]);
}

std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

// Query order along a Morton curve (deterministic, ties by index).
std::vector<std::uint32_t> morton_order(std::span<const Vec3> q) {
  const Box3 box = bounding_box(q);
  const Vec3 lo = box.lo, hi = box.hi;
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-300});
  const double scale = double((1u << 21) - 1) / extent;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    auto cell = [&](double v, double l) {
      return static_cast<std::uint64_t>(std::clamp((v - l) * scale, 0.0, 2097151.0));
    };
    const Vec3& p = q[i];
    keys[i] = {spread_bits(cell(p.x, lo.x)) | spread_bits(cell(p.y, lo.y)) << 1 | spread_bits(cell(p.z, lo.z)) << 2,
               static_cast<std::uint32_t>(i)};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> order(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) order[i] = keys[i].second;
  return order;
}

}  // namespace

RepairedSurface repair_reference(const TriSurface& reference) {
  RepairedSurface out;
  std::vector<Point> points;
  points.reserve(reference.points.size());
  for (const Vec3& p : reference.points) points.push_back(to_point(p));
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(reference.triangles.size());
  for (const auto& t : reference.triangles)
    polygons.push_back(
        {static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});

  PMP::repair_polygon_soup(points, polygons);
  out.num_removed_triangles = static_cast<Index>(reference.triangles.size() - polygons.size());
  if (polygons.empty()) return out;
  PMP::orient_polygon_soup(points, polygons);

  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  const bool closed = CGAL::is_closed(mesh) && CGAL::is_triangle_mesh(mesh);
  if (closed && PMP::does_bound_a_volume(mesh)) {
    PMP::orient_to_bound_a_volume(mesh);
    out.is_closed_manifold = true;
  }
  out.surface.points.reserve(mesh.number_of_vertices());
  for (auto v : mesh.vertices()) out.surface.points.push_back(to_vec(mesh.point(v)));
  out.surface.triangles.reserve(mesh.number_of_faces());
  for (auto f : mesh.faces()) {
    std::array<Index, 3> t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k < 3) t[k] = static_cast<Index>(v.idx());
      ++k;
    }
    if (k == 3) out.surface.triangles.push_back(t);
  }
  if (!out.is_closed_manifold) orient_components_outward(out.surface);
  for (const auto& t : out.surface.triangles)
    if (twice_area(out.surface, t) == 0.0) ++out.num_zero_area_triangles;
  return out;
}

struct ClosestPointTree::Impl {
  const TriSurface* surface = nullptr;
  std::vector<Triangle> triangles;
  std::vector<Index> triangle_ids;
  Tree tree;
};

ClosestPointTree::ClosestPointTree(const TriSurface& surface) : impl_(std::make_unique<Impl>()) {
  impl_->surface = &surface;
  impl_->triangles.reserve(surface.triangles.size());
  impl_->triangle_ids.reserve(surface.triangles.size());
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& tri = surface.triangles[t];
    if (twice_area(surface, tri) == 0.0) continue;
    impl_->triangles.emplace_back(to_point(surface.points[tri[0]]), to_point(surface.points[tri[1]]),
                                  to_point(surface.points[tri[2]]));
    impl_->triangle_ids.push_back(static_cast<Index>(t));
  }
  if (impl_->triangles.empty()) return;
  impl_->tree.rebuild(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.accelerate_distance_queries();
  // Builds the search structure before the threads share it.
  (void)impl_->tree.closest_point(to_point(surface.points[surface.triangles[impl_->triangle_ids[0]][0]]));
}

ClosestPointTree::~ClosestPointTree() = default;

const TriSurface& ClosestPointTree::surface() const { return *impl_->surface; }

std::vector<ClosestPoint> ClosestPointTree::query(std::span<const Vec3> queries,
                                                  const ClosestPointOptions& options) const {
  std::vector<ClosestPoint> result(queries.size(), ClosestPoint{{}, kNoIndex, INFINITY});
  const Tree& tree = impl_->tree;
  const std::vector<Triangle>& triangles = impl_->triangles;
  const std::vector<Index>& triangle_ids = impl_->triangle_ids;
  if (triangles.empty() || queries.empty()) return result;

  std::vector<std::uint32_t> order(queries.size());
  if (options.spatial_order)
    order = morton_order(queries);
  else
    std::iota(order.begin(), order.end(), 0u);
  const std::size_t num_blocks = (queries.size() + kQueryBlock - 1) / kQueryBlock;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_blocks), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      const std::size_t end = std::min(queries.size(), (b + 1) * kQueryBlock);
      const Point first = to_point(queries[order[b * kQueryBlock]]);
      Tree::Point_and_primitive_id hint = tree.closest_point_and_primitive(first);
      for (std::size_t i = b * kQueryBlock; i < end; ++i) {
        const std::uint32_t q = order[i];
        const Point p = to_point(queries[q]);
        hint = options.spatial_order ? tree.closest_point_and_primitive(p, hint) : tree.closest_point_and_primitive(p);
        ClosestPoint& c = result[q];
        c.point = to_vec(hint.first);
        c.triangle = triangle_ids[static_cast<std::size_t>(hint.second - triangles.cbegin())];
        c.distance = norm(queries[q] - c.point);
      }
    }
  });
  return result;
}

std::vector<ClosestPoint> closest_points(const TriSurface& surface, std::span<const Vec3> queries,
                                         const ClosestPointOptions& options) {
  if (queries.empty()) return {};
  return ClosestPointTree(surface).query(queries, options);
}

}  // namespace hq
