#pragma once
// Broad phase of the overlap stages: pairs of intersecting axis-aligned boxes
// (CGAL::box_intersection_d behind a plain interface).

#include <array>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/overlap/tet_geometry.h"

namespace hq::detail {

// closed: boxes that touch count; open: only boxes whose interiors overlap.
enum class BoxContact { closed, open };

// Every pair {i, j}, i < j, of boxes that intersect. Sorted, no repeats.
std::vector<std::array<Index, 2>> box_self_pairs(const std::vector<Box3>& boxes, BoxContact contact);

// Every pair {i, j}, i < j, with i or j in `subset` (ascending indices into
// boxes), whose boxes intersect. Sorted, no repeats.
std::vector<std::array<Index, 2>> box_subset_pairs(const std::vector<Box3>& boxes, const std::vector<Index>& subset,
                                                   BoxContact contact);

}  // namespace hq::detail
