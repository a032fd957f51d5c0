#pragma once
// Broad phase of the overlap stages: pairs of intersecting axis-aligned boxes
// (CGAL::box_intersection_d behind a plain interface).

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/overlap/tet_geometry.h"

namespace hq::detail {

// closed: boxes that touch count; open: only boxes whose interiors overlap.
enum class BoxContact { closed, open };

// The pairs found, unless there are more than the caller's budget: then
// `pairs` is empty, is_complete false, and num_found counts the pairs met
// before the search stopped (it stops at kBudgetCountFactor x the budget, so
// num_found is a lower bound when is_count_exact is false).
struct BoxPairs {
  std::vector<std::array<Index, 2>> pairs;
  bool is_complete = true;
  std::int64_t num_found = 0;
  bool is_count_exact = true;
};
inline constexpr std::int64_t kBudgetCountFactor = 8;

// Every pair {i, j}, i < j, of boxes that intersect, at most max_pairs of
// them (see BoxPairs). Sorted, no repeats.
BoxPairs box_self_pairs(const std::vector<Box3>& boxes, BoxContact contact, std::int64_t max_pairs);

// Every pair {i, j}, i < j, with i or j in `subset` (ascending indices into
// boxes), whose boxes intersect, at most max_pairs of them. Sorted, no
// repeats. In open contact the other side holds only the boxes that touch a
// coarse grid's cells marked by the subset's boxes (the same pairs, a
// fraction of the copies when the subset is small).
BoxPairs box_subset_pairs(const std::vector<Box3>& boxes, const std::vector<Index>& subset, BoxContact contact,
                          std::int64_t max_pairs);
// The same, box i given by box_at(i) (called from several threads at once)
// for i < num_boxes: no array of every box (2,181,120 tets: 105 MB of
// fresh pages for a subset of 1,154).
BoxPairs box_subset_pairs(std::size_t num_boxes, const std::function<Box3(std::size_t)>& box_at,
                          const std::vector<Index>& subset, BoxContact contact, std::int64_t max_pairs);

// The same pairs as box_self_pairs(boxes, closed, max_pairs), found through
// groups: the boxes of group g are boxes[first[g] .. first[g+1]) (first has
// one entry more than there are groups). The search runs on each group's
// bounding box and tests the boxes of two groups whose bounds meet, and the
// boxes inside each group, directly. For boxes that come in small clusters
// of near neighbours (a boundary quad's 4 fan triangles): a quarter of the
// boxes for CGAL to sort and split. The budget counts box pairs, as there.
BoxPairs grouped_box_self_pairs(const std::vector<Box3>& boxes, const std::vector<Index>& first, std::int64_t max_pairs);

// The pairs {g, h}, g < h, of groups (as there) whose bounds meet (closed),
// each once, in the search's order (the same for any thread count: from
// 16,384 groups on, the search runs in parallel over 16 fixed slabs of the
// first axis and joins them in slab order; each slab's search is
// sequential); nullopt when there are more than max_pairs (the search stops
// there). The caller tests the boxes of each pair itself.
std::optional<std::vector<std::array<Index, 2>>> group_bound_pairs(const std::vector<Box3>& boxes,
                                                                   const std::vector<Index>& first,
                                                                   std::int64_t max_pairs);

// The same, each group's bounds given by bounds_of(g) for g < num_groups
// (nullopt: a group without boxes, left out): the caller needs no array of
// every box (a 1M-quad surface's 2.2 M triangles: 105 MB of fresh pages).
std::optional<std::vector<std::array<Index, 2>>> group_bound_pairs(
    std::size_t num_groups, const std::function<std::optional<Box3>(std::size_t)>& bounds_of, std::int64_t max_pairs);

}  // namespace hq::detail
