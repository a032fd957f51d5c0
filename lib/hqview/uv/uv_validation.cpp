// The one CGAL translation unit of the UV module: exact orientation
// predicates and box intersection (both light headers).

#include "hqview/uv/uv_validation.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace hq {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using Box2 = CGAL::Box_intersection_d::Box_with_info_d<double, 2, Index, CGAL::Box_intersection_d::ID_EXPLICIT>;
using Box3 = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Index, CGAL::Box_intersection_d::ID_EXPLICIT>;

Point corner(std::span<const Uv> uvs, Index t, int k) {
  const Uv& p = uvs[3 * static_cast<std::size_t>(t) + static_cast<std::size_t>(k)];
  return {p[0], p[1]};
}

// Interiors of two counter-clockwise triangles are disjoint iff the line
// through some edge of one has the other on its closed outer side. A vertex
// equal to an edge end is on the line: no predicate (shared vertices of
// neighbouring triangles would otherwise send every test to exact arithmetic).
bool separated_by_edge_of(const Point (&a)[3], const Point (&b)[3]) {
  for (int i = 0; i < 3; ++i) {
    const Point &p = a[i], &q = a[(i + 1) % 3];
    bool all_outside = true;
    for (int j = 0; j < 3 && all_outside; ++j)
      all_outside = b[j] == p || b[j] == q || CGAL::orientation(p, q, b[j]) != CGAL::LEFT_TURN;
    if (all_outside) return true;
  }
  return false;
}

// Appends (s, t), smaller first, when the interiors of UV triangles s and t meet.
void add_if_overlapping(std::span<const Uv> uvs, Index s, Index t, std::vector<std::array<Index, 2>>& found) {
  const Point a[3] = {corner(uvs, s, 0), corner(uvs, s, 1), corner(uvs, s, 2)};
  const Point b[3] = {corner(uvs, t, 0), corner(uvs, t, 1), corner(uvs, t, 2)};
  if (!separated_by_edge_of(a, b) && !separated_by_edge_of(b, a)) found.push_back({std::min(s, t), std::max(s, t)});
}

Box2 uv_box(std::span<const Uv> uvs, Index t) {
  double lo[2], hi[2];
  for (int d = 0; d < 2; ++d) {
    lo[d] = hi[d] = uvs[3 * static_cast<std::size_t>(t)][d];
    for (int k = 1; k < 3; ++k) {
      lo[d] = std::min(lo[d], uvs[3 * static_cast<std::size_t>(t) + k][d]);
      hi[d] = std::max(hi[d], uvs[3 * static_cast<std::size_t>(t) + k][d]);
    }
  }
  return Box2(lo, hi, t);
}

template <class Box, class Add>
std::vector<std::array<Index, 2>> overlapping_pairs(std::span<const Uv> uvs, std::span<const Index> subset, Index nt,
                                                    Add add) {
  std::vector<Box> boxes;
  if (subset.empty()) {
    boxes.reserve(static_cast<std::size_t>(nt));
    for (Index t = 0; t < nt; ++t) boxes.push_back(add(t));
  } else {
    boxes.reserve(subset.size());
    for (Index t : subset) boxes.push_back(add(t));
  }
  // Candidates are tested on TBB's threads; the pairs are gathered and
  // sorted, so the result does not depend on the thread count.
  tbb::enumerable_thread_specific<std::vector<std::array<Index, 2>>> found;
  CGAL::box_self_intersection_d<CGAL::Parallel_tag>(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    const Index s = x.info(), t = y.info();
    const Point a[3] = {corner(uvs, s, 0), corner(uvs, s, 1), corner(uvs, s, 2)};
    const Point b[3] = {corner(uvs, t, 0), corner(uvs, t, 1), corner(uvs, t, 2)};
    if (!separated_by_edge_of(a, b) && !separated_by_edge_of(b, a))
      found.local().push_back({std::min(s, t), std::max(s, t)});
  });
  std::vector<std::array<Index, 2>> pairs;
  for (const auto& local : found) pairs.insert(pairs.end(), local.begin(), local.end());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace

std::vector<std::array<Index, 2>> uv_overlapping_pairs_by_part(std::span<const Uv> uvs, std::span<const Index> part_of) {
  const auto nt = static_cast<Index>(uvs.size() / 3);
  Index num_parts = 0;
  for (Index t = 0; t < nt; ++t) num_parts = std::max(num_parts, part_of[t] + 1);
  std::vector<std::vector<Box2>> members(static_cast<std::size_t>(num_parts));
  for (Index t = 0; t < nt; ++t) members[part_of[t]].push_back(uv_box(uvs, t));
  // Each part's box, and the pairs of parts whose boxes meet.
  std::vector<Box2> part_boxes;
  for (Index p = 0; p < num_parts; ++p) {
    if (members[p].empty()) continue;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (const Box2& b : members[p])
      for (int d = 0; d < 2; ++d) lo[d] = std::min(lo[d], b.min_coord(d)), hi[d] = std::max(hi[d], b.max_coord(d));
    part_boxes.emplace_back(lo, hi, p);
  }
  std::vector<std::array<Index, 2>> tasks;
  for (const Box2& b : part_boxes) tasks.push_back({b.info(), b.info()});
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(
      part_boxes.begin(), part_boxes.end(),
      [&](const Box2& x, const Box2& y) { tasks.push_back({std::min(x.info(), y.info()), std::max(x.info(), y.info())}); });
  std::vector<const Box2*> box_of_part(static_cast<std::size_t>(num_parts), nullptr);
  for (const Box2& b : part_boxes) box_of_part[b.info()] = &b;
  const auto meets = [](const Box2& a, const Box2& b) {
    return a.min_coord(0) <= b.max_coord(0) && b.min_coord(0) <= a.max_coord(0) && a.min_coord(1) <= b.max_coord(1) &&
           b.min_coord(1) <= a.max_coord(1);
  };
  tbb::enumerable_thread_specific<std::vector<std::array<Index, 2>>> found;
  tbb::parallel_for(std::size_t{0}, tasks.size(), [&](std::size_t i) {
    const auto [p, q] = tasks[i];
    auto& out = found.local();
    const auto report = [&](const Box2& x, const Box2& y) { add_if_overlapping(uvs, x.info(), y.info(), out); };
    if (p == q) {
      std::vector<Box2> boxes = members[p];
      CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes.begin(), boxes.end(), report);
      return;
    }
    // Across two parts only their triangles inside the other part's box can meet.
    std::vector<Box2> a, b;
    for (const Box2& x : members[p])
      if (meets(x, *box_of_part[q])) a.push_back(x);
    for (const Box2& y : members[q])
      if (meets(y, *box_of_part[p])) b.push_back(y);
    CGAL::box_intersection_d<CGAL::Sequential_tag>(a.begin(), a.end(), b.begin(), b.end(), report);
  });
  std::vector<std::array<Index, 2>> pairs;
  for (const auto& local : found) pairs.insert(pairs.end(), local.begin(), local.end());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

std::vector<std::uint8_t> uv_flipped_triangles(std::span<const Uv> uvs) {
  const Index nt = static_cast<Index>(uvs.size() / 3);
  std::vector<std::uint8_t> flipped(static_cast<std::size_t>(nt));
  for (Index t = 0; t < nt; ++t)
    flipped[t] = CGAL::orientation(corner(uvs, t, 0), corner(uvs, t, 1), corner(uvs, t, 2)) != CGAL::LEFT_TURN;
  return flipped;
}

std::vector<std::array<Index, 2>> uv_overlapping_pairs(std::span<const Uv> uvs, std::span<const Index> group,
                                                       std::span<const Index> subset) {
  const Index nt = static_cast<Index>(uvs.size() / 3);
  auto bounds = [&](Index t, double* lo, double* hi) {
    for (int d = 0; d < 2; ++d) {
      lo[d] = hi[d] = uvs[3 * static_cast<std::size_t>(t)][d];
      for (int k = 1; k < 3; ++k) {
        lo[d] = std::min(lo[d], uvs[3 * static_cast<std::size_t>(t) + k][d]);
        hi[d] = std::max(hi[d], uvs[3 * static_cast<std::size_t>(t) + k][d]);
      }
    }
  };
  if (group.empty())
    return overlapping_pairs<Box2>(uvs, subset, nt, [&](Index t) {
      double lo[2], hi[2];
      bounds(t, lo, hi);
      return Box2(lo, hi, t);
    });
  // A third dimension keeps groups apart: closed boxes [g, g] meet only within a group.
  return overlapping_pairs<Box3>(uvs, subset, nt, [&](Index t) {
    double lo[3], hi[3];
    bounds(t, lo, hi);
    lo[2] = hi[2] = static_cast<double>(group[t]);
    return Box3(lo, hi, t);
  });
}

}  // namespace hq
