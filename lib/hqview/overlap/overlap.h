#pragma once
// Overlapping vertices and intersecting cells (paper goal G2; ALGORITHMS.md §4),
// over the volume cells of every kind (hexes, tets, wedges, pyramids; cell
// ids over the blocks as Mesh numbers them).
//
// Geometry every stage shares (the "24-tet solid" of a hex; every kind the same way):
//   face centre  c_f = ((p_a + p_b) + (p_c + p_d)) * 0.25, a < b < c < d the
//                face's sorted vertex ids, so both cells of a face get the
//                same double point;
//   cell centre  c_h = (((p0 + p1) + (p2 + p3)) + ((p4 + p5) + (p6 + p7))) * 0.125
//                in corner order;
//   24 tets      for each face (kHexFaces, outward) and each of its edges i -> j,
//                the tet (p_j, p_i, c_f, c_h): positively oriented in a valid hex.
// The solid of a hex is the union of its 24 closed tets; a point is inside
// the cell when it lies in one of those tets with non-zero volume and on
// none of its 24 boundary triangles. Any kind: each face (CellKindTable,
// outward) gives tets joined to the cell centre (the mean of its corners):
// a quad its 4 fan tets as above, a triangle (p0, p1, p2) the one tet
// (p1, p0, p2, c_h). A tet's solid is itself (4 tets around its centre), a
// wedge's 14 tets, a pyramid's 8.
//
// Two distinct cells intersect when a vertex of one that is not a vertex of
// the other lies inside the other (the paper's test of every vertex against
// every cell, made exact and fast), or when both have the same vertices
// (duplicates, of one kind), or when their interiors meet with no vertex inside (two
// cubes shifted along x: coplanar faces overlapping): a positive tet of
// each with interiors in common (exact separating axes; face centres from
// the corners sorted by position), tested on pairs with a cell set aside
// by the certificate that share no vertex and do not both touch a cell
// with a non-positive tet (there the 24-tet solids of valid trilinear hexes
// overlap by construction; docs/analysis.md "Overlap"). Cells that only
// touch (a shared face, edge or vertex, a vertex on another cell's face,
// two coincident vertices) do not intersect. Every decision is exact: CGAL
// Epick predicates on the double points above.
//
// Stages (ALGORITHMS.md §4):
//   A coincident vertices   B zero-length edges   C exact orientation of the
//   8 corner tets (inverted cells) and of the 24 tets (the certificate)
//   D face map: non-manifold faces, duplicate cells, interior faces not seen
//   with opposite winding   E boundary self-intersections   F shell nesting
//   (exact winding number)   G pair tests on candidate pairs from cell boxes.
// Certificate (default): G runs only on pairs with a flagged cell. Cells
// flagged by A-D are removed; E and F are run on the boundary of what is left
// (K'), flagging more cells until that boundary is embedded and unnested.
// Then K' is injective (Lipman, arXiv 1310.0955: positively oriented cells
// with an embedded boundary do not overlap), so no vertex of a K' cell lies
// inside another K' cell, and G on the pairs with a flagged cell finds
// exactly the pairs an all-pairs test finds.
// Exhaustive: G's vertex test runs on every pair of cells whose boxes
// overlap; A-F run to the end as in certificate mode (G's test of interiors
// relies on them).

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/core/cell_kinds.h"
#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/mesh.h"
#include "hqview/mesh/planarity.h"
#include "hqview/mesh/topology.h"

namespace hq {

enum class OverlapMode { certificate, exhaustive };

inline std::string_view overlap_mode_name(OverlapMode mode) {
  return mode == OverlapMode::certificate ? "certificate" : "exhaustive";
}

struct OverlapOptions {
  OverlapMode mode = OverlapMode::certificate;
  // Tolerance of stages A and B, relative to the bounding-box diagonal of the
  // referenced vertices: two vertices coincide when |p - q| <= eps * diagonal,
  // an edge has zero length when its length is <= eps * diagonal. 0 = exact
  // equality.
  double coincident_eps = 0.0;
  // Work budget of the pair stages E and G: each tests at most
  // max(min_pair_budget, pairs_per_box x its number of boxes) candidate
  // pairs (boundary triangles for E, cells for G). Beyond it a stage stops:
  // nothing is certified and OverlapReport says which stage stopped and how
  // many pairs were not tested. Real meshes stay far below (about 30 pairs
  // per box; docs/analysis.md, "Overlap").
  std::int64_t pairs_per_box = 64;
  std::int64_t min_pair_budget = 1'000'000;
};

// Vertices that occupy (within the tolerance) one position. Groups are the
// connected components of the "coincide" relation.
struct CoincidentGroup {
  std::vector<Index> vertices;  // ascending, at least 2
  Vec3 position;                // of the lowest-numbered vertex
};

struct IntersectingPair {
  std::array<Index, 2> cells{};  // cells[0] < cells[1]
  // The lowest vertex of cells[0] inside cells[1], else the lowest of
  // cells[1] inside cells[0]; kNoIndex for duplicate cells and for
  // interiors that meet with no vertex inside.
  Index inside_vertex = kNoIndex;
  Vec3 position;  // where an arrow points: inside_vertex, else into the common part (duplicates: the centre)
  std::array<CellKind, 2> kinds{};               // of cells[0], cells[1]
  std::array<std::int64_t, 2> source_indices{};  // cell_source_index() of each (its file's numbering)
};

enum class MarkerKind { coincident, intersection };

inline std::string_view marker_kind_name(MarkerKind kind) {
  return kind == MarkerKind::coincident ? "coincident" : "intersection";
}

// One arrow target: `count` findings at the same position.
struct OverlapMarker {
  MarkerKind kind = MarkerKind::coincident;
  Vec3 position;
  Index count = 0;
};

// Stage C's verdict on one cell (bit flags).
enum CellOrientation : std::uint8_t {
  kTetNegative = 1,     // one of the solid's tets (24 of a hex) is negatively oriented
  kTetFlat = 2,         // one of the solid's tets has zero volume
  kCornerNegative = 4,  // one of the corner tets (its kind's corner frames, 8 of a hex) is negative
  kCornerFlat = 8,      // one of the corner tets has zero volume
};

struct OverlapReport {
  OverlapMode mode = OverlapMode::certificate;
  double coincident_tolerance = 0.0;  // absolute (eps * diagonal)

  // A. Groups ordered by their lowest vertex id; per vertex, its group or kNoIndex.
  std::vector<CoincidentGroup> coincident_groups;
  std::vector<Index> vertex_coincident_group;  // num_vertices
  Index num_coincident_vertices = 0;           // vertices in some group
  // B. Unique edges (a < b) of zero length, ascending.
  std::vector<Edge> zero_length_edges;
  // C. Per volume cell (ids over the blocks), CellOrientation flags.
  // Inverted: a corner tet is negatively oriented (the exact sign of a
  // corner Jacobian; a pyramid's four base corners, whose frames reach the
  // apex); degenerate: not inverted, a corner tet is flat. Cells whose solid
  // tets are not all positive are not certified (thin twisted cells can be
  // valid and still fail this). Ascending ids.
  std::vector<std::uint8_t> cell_orientation;
  std::vector<Index> inverted_cells;
  std::vector<Index> degenerate_cells;
  std::vector<Index> nonpositive_tet_cells;
  // D. Face ids ascending: the topology's (hex faces) on a pure-hex mesh;
  // otherwise the index of the face among the unique faces of all volume
  // cells (quads and triangles) in the order of their sorted vertex ids.
  // Duplicate cells: cells whose vertex ids (as a set) repeat those of a
  // lower-numbered cell.
  std::vector<Index> non_manifold_faces;
  std::vector<Index> same_winding_faces;  // 2 cells, not opposite windings
  std::vector<Index> duplicate_cells;
  // E. Pairs of boundary faces (face ids, ascending) whose 4-triangle fans
  // intersect other than in shared vertices or edges, on the first boundary
  // checked (the boundary of the cells A-D left unflagged; the mesh boundary
  // when they flag nothing).
  std::vector<std::array<Index, 2>> boundary_self_intersections;
  // F. Boundary sheets of that first boundary whose cell side has a winding
  // number other than 1 (a shell inside another, or overlapping shells).
  Index num_nested_shells = 0;
  // G.
  std::vector<IntersectingPair> intersecting_pairs;  // sorted by cells
  std::vector<char> cell_intersecting;               // per volume cell (ids over the blocks), 0/1
  Index num_intersecting_cells = 0;
  std::vector<OverlapMarker> markers;  // coincident groups, then intersections

  // The work budget (OverlapOptions): a stage whose candidate pairs exceed
  // it is skipped; then certified_clean is false and the intersecting pairs
  // are unknown.
  bool is_over_budget = false;
  std::string over_budget_stage;        // "boundary" (E) or "cells" (G); empty within the budget
  std::int64_t pair_budget = 0;         // the stage's budget, when over it
  std::int64_t num_untested_pairs = 0;  // its candidate pairs, none tested
  bool is_untested_count_exact = true;  // false: num_untested_pairs is a lower bound

  // The certificate: A-F found nothing, so no cells intersect.
  bool certified_clean = false;
  Index num_flagged_cells = 0;           // cells G paired with every cell near them
  std::int64_t num_candidate_pairs = 0;  // cell pairs G tested
  int certificate_rounds = 0;            // E/F passes until the unflagged part was certified

  // A surface mesh's check (check_surface_overlap): cell ids are face ids
  // (quads, then triangles), intersecting_pairs hold distinct faces, and
  // the faces whose own two triangles overlap (a quad folded flat onto
  // itself, a bow-tie) are listed here, ascending, and are intersecting.
  bool is_surface = false;
  std::vector<Index> self_intersecting_faces;
  // A planar surface mesh (planarity.h) is decided in its plane (PlaneFrame).
  bool is_decided_in_plane = false;
};

// Runs stages A-G on every volume cell of the mesh (all blocks; surface
// cells are not volume and are ignored). mesh and topo must belong together
// (build_topology(mesh), with or without the non-hex blocks: only its hex
// tables are read).
// Deterministic: every list is sorted, and the result is the same for any
// number of TBB threads. Throws nothing but std::bad_alloc.
OverlapReport check_overlap(const Mesh& mesh, const Topology& topo, const OverlapOptions& options);

// ---- Surface meshes (issue 47) ---------------------------------------------
// The diagonal a quad (p0, p1, p2, p3) is split along for the surface
// check: 0 = p0-p2, triangles (p0, p1, p2) and (p0, p2, p3); 1 = p1-p3,
// triangles (p0, p1, p3) and (p1, p2, p3). The diagonal whose two triangles
// face the same way (their normals, corner order, have a positive dot
// product) when only one does (so a planar concave quad, a dart, is split
// at its reflex corner and covered exactly); otherwise the shorter one (a
// tie: p0-p2). A bow-tie folds on either diagonal. Double arithmetic: the
// split is a definition; what is decided on its triangles is exact.
int quad_split_diagonal(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3);

// The overlap check of a surface mesh (quads and triangles, no volume
// cell; other meshes: check_overlap). Stages, in the report's fields:
//   A coincident vertices (as for volumes, over the vertices a face uses);
//   B zero-length face edges;   duplicate faces (the vertex ids of a
//   lower-numbered face, as a set: duplicate_cells);
//   S self-intersection: every pair of faces whose triangles (a quad split
//   by quad_split_diagonal, a triangle itself) meet other than in the
//   vertices they share (a shared vertex or edge is a contact, not an
//   intersection; faces meeting beyond it intersect: a flap folded back
//   across its edge, neighbours crossing away from their common vertex),
//   decided exactly (CGAL Epick predicates; coplanar pairs in 2-D). A
//   planar mesh (`planarity`: the mesh's measure_planarity, over the
//   vertices its faces use, as the analysis reports it) is decided in that plane: its points projected by
//   plane_frame, every pair of triangles then coplanar and decided in 2-D
//   (exact on the projected doubles), so that a rotated or mirrored copy
//   finds what the axis-aligned original finds (unless the original holds
//   an exactly degenerate contact, a vertex exactly on another face's
//   edge, which rounding moves to one side). The
//   vertices of one coincident group count as one (its lowest id, at its
//   position), so a seam of duplicated vertices is reported once, by A.
//   A vertex lying on another face without being its vertex (a T-junction)
//   is an intersection. Candidate pairs: triangle boxes that touch, within
//   the work budget (pair_budget over the triangles; over it: nothing
//   listed, over_budget_stage "faces").
// Stage C (orientation) is the quality's (num_inverted): inverted_cells,
// cell_orientation and the volume-only lists stay empty. certified_clean:
// S completed and A, B, duplicates and S found nothing. `topology`: the
// mesh's build_surface_topology (B reads its edges). num_candidate_pairs:
// the triangle pairs S tested. on_self_intersection, when set, is called as
// S starts (the analysis times S as a stage of its own). markers: the
// coincident groups, the intersecting pairs (as for volumes), then one per
// self-intersecting face.
// Deterministic for any number of TBB threads.
OverlapReport check_surface_overlap(const Mesh& mesh, const SurfaceTopology& topology, const Planarity& planarity,
                                    const OverlapOptions& options,
                                    const std::function<void()>& on_self_intersection = {});

}  // namespace hq
