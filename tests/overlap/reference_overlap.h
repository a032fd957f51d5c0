#pragma once
// An independent, brute-force reference for the overlap tests: every vertex
// against every cell, with CGAL's exact-construction kernel (Epeck). It
// shares nothing with lib/hqview/overlap but the definition in overlap.h
// (face and cell centres, the 24 tets, "inside", "intersect").

#include <array>
#include <vector>

#include "hqview/mesh/hex_mesh.h"

namespace hq::test {

// All pairs {a, b}, a < b, of intersecting cells: a vertex of one (not of
// the other) inside the other, or the same 8 vertices. Sorted.
// O(#cells^2): for small meshes only.
std::vector<std::array<Index, 2>> reference_intersecting_pairs(const HexMesh& mesh);

}  // namespace hq::test
