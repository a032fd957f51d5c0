#pragma once
// Per-corner scaled Jacobians and the inverted test of tets, wedges,
// pyramids, quads and triangles: the per-kind counterpart of
// corner_jacobian.h (hexes), so vertex quality, glyphs and clusters work on
// any mix of kinds.
//
// A volume corner's value is det[Pa-Pi, Pb-Pi, Pc-Pi] / (|Pa-Pi||Pb-Pi||Pc-Pi|)
// in the corner frames of core/cell_kinds.h (CellKindTable<K>::corner_frames,
// VTK corner order), times Verdict's factor that makes the kind's ideal cell
// score 1 at every corner:
//   tet      sqrt(2)     (regular tet),
//   wedge    2/sqrt(3)   (right prism on an equilateral triangle),
//   pyramid  sqrt(2)     (the 4 base corners; square base, equilateral
//                         triangular faces; the apex has no corner value),
// clamped to [-1, 1] (a right-angled tet corner, 1.41 before the clamp,
// scores 1 like the ideal one; Verdict's tet value never uses it), except
// that a pyramid corner above 1 (an apex too high) is folded to 2 - value as
// Verdict folds its pyramid scaled_jacobian; 0 at a corner with a zero-length
// frame edge (bit i of degenerate_mask).
//
// How the minimum over the corners relates to Verdict's scaled_jacobian
// (tested on ../shared/data/verdict/cell_oracle_cases.json):
//   tet:     equal when the tet is not inverted; an inverted tet has four
//            negative corners and Verdict reports the one closest to 0
//            (sqrt(2) det / the largest edge-length product): the maximum;
//   wedge:   equal (Verdict takes the same six frames), when no corner is
//            degenerate;
//   pyramid: Verdict splits the pyramid into 4 tets through the base
//            diagonals, not the corner frames: no identity; both score 1 on
//            the ideal pyramid, and Verdict's 0 goes with a corner <= 0
//            (pyramid_validity not valid) on every oracle case;
//   quad:    equal (Verdict's signed corner areas against the quad's centre
//            normal), unless P3 == P2 (Verdict then scores the triangle);
//   triangle: equal (no orientation: never negative against its own normal).
// Surface corners: the signed area (e(i-1) x e(i)) . n / (|e(i-1)||e(i)|)
// (times 2/sqrt(3) for a triangle) against a unit normal n: by default the
// cell's own (for a quad Verdict's centre normal, the normal of the bilinear
// surface at its centre, (P1+P2-P0-P3) x (P2+P3-P0-P1); a triangle's own
// normal makes every corner >= 0), or a normal the caller gives (the plane's
// normal of a planar mesh, so a reversed or folded cell is negative). A
// planar bow-tie quad has no centre normal: every corner 0 (flat) without a
// normal, negative corners with one.

#include <array>
#include <cstdint>
#include <optional>

#include "hqview/core/vec3.h"

namespace hq {

template <std::size_t C>
struct KindCornerJacobians {
  std::array<double, C> value{};     // in [-1, 1]; 0 at a degenerate corner
  std::uint8_t degenerate_mask = 0;  // bit i: corner i has a zero-length frame edge
};

KindCornerJacobians<4> tet_corner_scaled_jacobians(const std::array<Vec3, 4>& p);
KindCornerJacobians<6> wedge_corner_scaled_jacobians(const std::array<Vec3, 6>& p);    // VTK order
KindCornerJacobians<4> pyramid_corner_scaled_jacobians(const std::array<Vec3, 5>& p);  // base corners 0-3
KindCornerJacobians<4> quad_corner_scaled_jacobians(const std::array<Vec3, 4>& p,
                                                    const std::optional<Vec3>& normal = std::nullopt);
KindCornerJacobians<3> triangle_corner_scaled_jacobians(const std::array<Vec3, 3>& p,
                                                        const std::optional<Vec3>& normal = std::nullopt);

// How a cell's corners are oriented.
enum class CellValidity : std::uint8_t {
  valid,     // every corner determinant > 0
  flat,      // none < 0, one = 0 (a flat or collapsed corner)
  inverted,  // a corner determinant < 0
};

// Volume cells: the signs of the corner determinants in the kind's corner
// frames, decided exactly (CGAL's orientation predicate on the input
// doubles). A pyramid counts every base corner (the apex has no frame): one
// with its apex below the base, or a reflex base corner, is inverted even
// though Verdict's pyramid scaled_jacobian is then 0, never negative.
CellValidity tet_validity(const std::array<Vec3, 4>& p);
CellValidity wedge_validity(const std::array<Vec3, 6>& p);  // VTK order
CellValidity pyramid_validity(const std::array<Vec3, 5>& p);
// Surface cells: the signs of the corner areas against `normal` (in double
// precision: the normal is itself computed), or, without one, against the
// cell's own normal as above: a quad is then inverted when it is folded
// (concave or bow-tie: a corner against the centre normal), a triangle never.
CellValidity quad_validity(const std::array<Vec3, 4>& p, const std::optional<Vec3>& normal = std::nullopt);
CellValidity triangle_validity(const std::array<Vec3, 3>& p, const std::optional<Vec3>& normal = std::nullopt);

inline bool is_inverted(CellValidity o) { return o == CellValidity::inverted; }

}  // namespace hq
