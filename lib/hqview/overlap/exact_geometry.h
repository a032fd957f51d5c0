#pragma once
// The exact geometric parts of the overlap stages (C, E, F, G), implemented
// with CGAL's Epick predicates in exact_geometry.cpp. Plain data in and out.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/box_pairs.h"
#include "hqview/overlap/tet_geometry.h"

namespace hq::detail {

// Stage C: CellOrientation flags (overlap.h) of every cell (any kind), from
// the exact orientation of its solid's tets and of its corner tets (the
// corner frames of its kind). TBB, deterministic.
std::vector<std::uint8_t> classify_cell_orientations(const VolumeCells& cells, const Topology& topo,
                                                     const TetPoints& tp);

// Stage E: pairs {i, j} (i <= j, indices into faces) whose fans (a quad's 4
// triangles, a triangle itself) intersect other than in the vertices and
// edges they share by id; i == j when a fan folds onto itself. Triangles
// with collinear corners are skipped (their cells are flagged by stage C).
// Sorted. At most max_pairs candidate triangle pairs are tested: beyond,
// the result is empty and budget.is_complete false (box_pairs.h).
struct FacePairs {
  std::vector<std::array<Index, 2>> pairs;
  BoxPairs budget;  // its pairs are cleared; is_complete, num_found, is_count_exact
};
FacePairs intersecting_face_pairs(const TetPoints& tp, const std::vector<BoundaryFace>& faces, std::int64_t max_pairs);

// Surface meshes (check_surface_overlap): the same exact test on given
// triangles. The triangles of face f are triangles[first[f] .. first[f+1])
// (ids into points); pairs {f, g} (f <= g, face ids) whose triangles meet
// other than in the vertex ids they share; f == g when two triangles of one
// face overlap (a folded quad). Triangles with collinear corners are
// skipped (their faces have zero area; warned by the analysis). Sorted,
// each with `positions[i]`, a point where the pair meets (double
// arithmetic, for the arrows only). At most max_pairs candidate triangle
// pairs are tested: beyond, the result is empty and budget.is_complete
// false (box_pairs.h). num_tested: the candidate triangle pairs tested.
struct SurfaceFacePairs {
  std::vector<std::array<Index, 2>> pairs;
  std::vector<Vec3> positions;
  BoxPairs budget;  // its pairs are cleared
  std::int64_t num_tested = 0;
};
SurfaceFacePairs intersecting_surface_faces(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                                            const std::vector<Index>& first, std::int64_t max_pairs);

// Stage F: the winding number of the closed surface made of all the fans of
// `faces`, at points just behind faces[q] (its cell's side), counted exactly
// along a ray from its centre (a quad's face centre; a triangle's centroid,
// taken exactly in rational arithmetic). `bounds` must contain every fan.
// nullopt when no ray avoided every degenerate contact (the caller then
// treats the sheet as not certified). Assumes the faces' tets are
// positively oriented and no other fan meets the start.
std::optional<int> winding_behind_face(const TetPoints& tp, const std::vector<BoundaryFace>& faces, Index q,
                                       const Box3& bounds);

// Stage G narrow phase, one result per pair (same order): do the cells
// intersect (overlap.h's definition), and which vertex lies inside the other.
// The exact test of interiors that meet with no vertex inside runs on the
// pairs with a flagged cell (flagged: per cell, 0 or 1; pairs of two
// unflagged cells, certified by stages A-F, get the vertex test only) that
// share no vertex and do not both touch one folded cell (folded: per cell,
// a non-positive tet). Cells of any kind; ids over the blocks.
// TBB, deterministic.
struct CellPairTest {
  bool intersect = false;
  Index inside_vertex = kNoIndex;
  // inside_vertex's position; for duplicate cells, the first one's centre;
  // for interiors meeting with no vertex inside, the mean of the corners of
  // the first two tets (one of each cell) whose interiors meet.
  Vec3 position;
};
std::vector<CellPairTest> test_cell_pairs(const VolumeCells& cells, const VertexCells& vertex_cells,
                                          const Topology& topo, const TetPoints& tp,
                                          const std::vector<std::array<Index, 2>>& pairs,
                                          const std::vector<char>& flagged, const std::vector<char>& folded);

}  // namespace hq::detail
