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

// All pairs {a, b}, a < b, whose interiors meet by overlap.h's second test:
// cells that share no vertex id and do not both touch one cell with a
// non-positive tet, with positively oriented tets (face centres from the
// corners sorted by position) whose interiors meet. Decided here by
// construction, not by separating axes: the closed intersection of two tets
// is the convex hull of the corners of each in the other and the crossings
// of the edges of each with the triangles of the other (exact, Epeck); the
// interiors meet when those points span a volume. Sorted. For small meshes.
std::vector<std::array<Index, 2>> reference_interior_pairs(const HexMesh& mesh);

// The union of both: what check_overlap must list. Sorted.
std::vector<std::array<Index, 2>> reference_all_pairs(const HexMesh& mesh);

// A surface mesh (quads, then triangles: face ids): all pairs {f, g}, f <= g,
// whose triangles meet other than in the vertices they share, as
// check_surface_overlap defines it (overlap.h) with exact coincidence:
// vertices at one position count as one (the lowest id); a quad is split
// by the rule stated there (coded here on its own); f == g when a face's
// two triangles overlap. Decided by construction (Epeck): the exact
// intersection of two triangles must be empty, their shared vertex, or
// their shared edge. Triangles with collinear corners are skipped. Sorted.
// O(#faces^2): for small meshes only.
std::vector<std::array<Index, 2>> reference_surface_pairs(const Mesh& mesh);

}  // namespace hq::test
