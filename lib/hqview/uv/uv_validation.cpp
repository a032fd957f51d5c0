// The one CGAL translation unit of the UV module: exact orientation and
// segment predicates and box intersection (light headers).

#include "hqview/uv/uv_validation.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Intersections_2/Segment_2_Segment_2.h>
#include <CGAL/box_intersection_d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>

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

bool less_uv(const Uv& a, const Uv& b) { return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]); }

// The border of the sum of the triangles: each edge with the number of
// times it is run forwards less the times it is run backwards, kept where
// that is +1 or -1 (as a directed segment). False where it is more: two
// triangles run that edge the same way, so both lie on its left.
bool border_segments(std::span<const Uv> uvs, std::vector<std::array<Uv, 2>>& border) {
  struct Edge {
    Uv lo, hi;
    int sign;
  };
  const std::size_t nt = uvs.size() / 3;
  std::vector<Edge> edges;
  edges.reserve(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Uv &p = uvs[3 * t + k], &q = uvs[3 * t + (k + 1) % 3];
      if (less_uv(p, q)) edges.push_back({p, q, 1});
      else edges.push_back({q, p, -1});
    }
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
    return less_uv(a.lo, b.lo) || (a.lo == b.lo && less_uv(a.hi, b.hi));
  });
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int net = 0;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) net += edges[j++].sign;
    if (net > 1 || net < -1) return false;
    if (net == 1) border.push_back({edges[i].lo, edges[i].hi});
    if (net == -1) border.push_back({edges[i].hi, edges[i].lo});
    i = j;
  }
  return true;
}

enum class Verdict { one_to_one, overlapping, unknown };

// What the border of counter-clockwise triangles proves (see
// uv_border_certifies_one_to_one). Each border segment has a triangle on
// its left that runs it, so two border segments that cross (each through
// the other's interior) prove that two triangles overlap, as does an edge
// two triangles run the same way.
Verdict border_verdict(std::span<const Uv> uvs) {
  const std::size_t nt = uvs.size() / 3;
  for (const Uv& p : uvs)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1])) return Verdict::unknown;
  for (std::size_t t = 0; t < nt; ++t)
    if (CGAL::orientation(corner(uvs, Index(t), 0), corner(uvs, Index(t), 1), corner(uvs, Index(t), 2)) !=
        CGAL::LEFT_TURN)
      return Verdict::unknown;
  std::vector<std::array<Uv, 2>> border;
  if (!border_segments(uvs, border)) return Verdict::overlapping;
  if (border.size() < 3) return nt == 0 ? Verdict::one_to_one : Verdict::unknown;
  // One closed polygon: every border point starts exactly one segment, and
  // following the segments from the first runs through all of them.
  const std::size_t n = border.size(), none = n;
  bool one_loop = true;
  std::vector<std::size_t> by_start(n);
  std::iota(by_start.begin(), by_start.end(), std::size_t{0});
  std::sort(by_start.begin(), by_start.end(),
            [&](std::size_t a, std::size_t b) { return less_uv(border[a][0], border[b][0]); });
  for (std::size_t i = 1; i < n; ++i)
    if (border[by_start[i]][0] == border[by_start[i - 1]][0]) one_loop = false;
  std::vector<std::size_t> next(n, none);
  for (std::size_t s = 0; s < n; ++s) {
    const auto it = std::lower_bound(by_start.begin(), by_start.end(), border[s][1],
                                     [&](std::size_t a, const Uv& p) { return less_uv(border[a][0], p); });
    if (it != by_start.end() && border[*it][0] == border[s][1]) next[s] = *it;
    else one_loop = false;
  }
  if (one_loop) {
    std::vector<std::uint8_t> visited(n, 0);
    std::size_t s = 0, steps = 0;
    for (; s != none && !visited[s]; s = next[s], ++steps) visited[s] = 1;
    one_loop = s == 0 && steps == n;
  }
  // Simple: two segments meet only at the point one ends and the next
  // starts, and there without running back along each other.
  std::vector<Box2> boxes;
  boxes.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    double lo[2] = {std::min(border[i][0][0], border[i][1][0]), std::min(border[i][0][1], border[i][1][1])};
    double hi[2] = {std::max(border[i][0][0], border[i][1][0]), std::max(border[i][0][1], border[i][1][1])};
    boxes.emplace_back(lo, hi, static_cast<Index>(i));
  }
  const auto point = [](const Uv& p) { return Point(p[0], p[1]); };
  // Segment a ends where segment b starts: they may only share that point.
  const auto only_joined = [&](std::size_t a, std::size_t b) {
    const Point p = point(border[a][0]), q = point(border[a][1]), r = point(border[b][1]);
    return CGAL::orientation(p, q, r) != CGAL::COLLINEAR || CGAL::angle(p, q, r) == CGAL::OBTUSE;
  };
  bool simple = true, crossing = false;
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes.begin(), boxes.end(), [&](const Box2& x, const Box2& y) {
    if (crossing) return;
    const auto a = static_cast<std::size_t>(x.info()), b = static_cast<std::size_t>(y.info());
    const Point p = point(border[a][0]), q = point(border[a][1]), r = point(border[b][0]), t = point(border[b][1]);
    const CGAL::Orientation pqr = CGAL::orientation(p, q, r), pqt = CGAL::orientation(p, q, t);
    if (pqr != CGAL::COLLINEAR && pqr == CGAL::opposite(pqt)) {
      const CGAL::Orientation rtp = CGAL::orientation(r, t, p), rtq = CGAL::orientation(r, t, q);
      if (rtp != CGAL::COLLINEAR && rtp == CGAL::opposite(rtq)) {
        crossing = true;
        return;
      }
    }
    if (!simple) return;
    if (next[a] == b || next[b] == a)
      simple = (next[a] != b || only_joined(a, b)) && (next[b] != a || only_joined(b, a));
    else
      simple = !CGAL::do_intersect(Kernel::Segment_2(p, q), Kernel::Segment_2(r, t));
  });
  if (crossing) return Verdict::overlapping;
  return one_loop && simple ? Verdict::one_to_one : Verdict::unknown;
}

struct FoundOverlap {};

// Whether any two interiors meet: the search of uv_overlapping_pairs,
// stopped at the first pair.
bool any_overlap(std::span<const Uv> uvs) {
  std::vector<Box2> boxes;
  boxes.reserve(uvs.size() / 3);
  for (Index t = 0; t < static_cast<Index>(uvs.size() / 3); ++t) boxes.push_back(uv_box(uvs, t));
  std::vector<std::array<Index, 2>> found;
  try {
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes.begin(), boxes.end(), [&](const Box2& x, const Box2& y) {
      add_if_overlapping(uvs, x.info(), y.info(), found);
      if (!found.empty()) throw FoundOverlap{};
    });
  } catch (const FoundOverlap&) {
    return true;
  }
  return false;
}

}  // namespace

bool uv_border_certifies_one_to_one(std::span<const Uv> uvs) { return border_verdict(uvs) == Verdict::one_to_one; }

bool uv_one_to_one(std::span<const Uv> uvs) {
  switch (border_verdict(uvs)) {
    case Verdict::one_to_one: return true;
    case Verdict::overlapping: return false;
    case Verdict::unknown: break;
  }
  return !any_overlap(uvs);
}

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
      std::vector<Uv> corners;
      corners.reserve(3 * members[p].size());
      for (const Box2& x : members[p])
        for (int k = 0; k < 3; ++k) corners.push_back(uvs[3 * static_cast<std::size_t>(x.info()) + k]);
      if (uv_border_certifies_one_to_one(corners)) return;
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
