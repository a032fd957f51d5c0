#pragma once
// Exact 2D checks of UV triangles (CGAL's filtered exact predicates; CGAL
// stays inside uv_validation.cpp).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "hqview/core/types.h"

namespace hq {

using Uv = std::array<double, 2>;

// Signed area of the UV triangle p[0], p[1], p[2] (positive: counter-clockwise), in floating point.
inline double uv_signed_area(const Uv* p) {
  return 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
}

// 1 for each triangle (corners uvs[3t], uvs[3t+1], uvs[3t+2]) whose exact
// orientation is not strictly counter-clockwise (flipped or degenerate).
std::vector<std::uint8_t> uv_flipped_triangles(std::span<const Uv> uvs);

// Pairs (a < b) of triangles whose interiors intersect (exact: sharing a
// vertex or an edge, or touching, is not an overlap), ascending. Only the
// triangles in `subset` are considered (all when empty) and only pairs with
// the same `group` value (all pairs when `group` is empty). Triangles must be
// counter-clockwise (see uv_flipped_triangles). Candidates come from
// CGAL::box_self_intersection_d.
std::vector<std::array<Index, 2>> uv_overlapping_pairs(std::span<const Uv> uvs, std::span<const Index> group = {},
                                                       std::span<const Index> subset = {});

// True when the border alone proves the layout one-to-one: every triangle
// is strictly counter-clockwise (exact) and the edges that no other triangle
// runs the other way (the border of the sum of the triangles) form one
// simple closed polygon (exact). The number of triangles over a point off
// their edges is then the polygon's winding number around it, 0 or 1, so no
// two interiors meet and uv_overlapping_pairs(uvs) is empty. False proves
// nothing (a chart with a hole, a border that touches itself, a fold): search.
bool uv_border_certifies_one_to_one(std::span<const Uv> uvs);

// uv_overlapping_pairs(uvs).empty() for counter-clockwise triangles: the
// border certificate first; two border segments that cross, or an edge
// two triangles run the same way, prove an overlap (each border segment
// has a triangle on its left); the search, stopped at its first pair, runs
// only where neither is found.
bool uv_one_to_one(std::span<const Uv> uvs);

// The same pairs as uv_overlapping_pairs(uvs), found part by part
// (`part_of[t]`: t's part, e.g. its chart, 0-based): inside each part, and
// between two parts whose bounding boxes meet, among the triangles inside
// the other part's box; the parts are searched in parallel (a part that
// uv_border_certifies_one_to_one has no pair inside it). Much faster
// than one search over all triangles when the parts lie mostly apart, as
// packed charts do.
std::vector<std::array<Index, 2>> uv_overlapping_pairs_by_part(std::span<const Uv> uvs, std::span<const Index> part_of);

}  // namespace hq
