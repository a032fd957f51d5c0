#pragma once
// `--up auto`: the up axis of a mesh, among the six coordinate half-axes,
// chosen as the pose the model would rest in on a table (a simplified form
// of the "upright orientation" of Fu et al. 2008: the candidate bases are
// the six axis-aligned supporting planes of the boundary, not every face of
// its convex hull). docs/analysis.md "Up axis: auto" gives the rule and the
// table it was judged on.
//
// For each candidate up axis u (down is -u):
//   base band     the boundary vertices within kRestingBaseBand x the
//                 bounding-box diagonal of the lowest one along u;
//   support area  the area of the 2D convex hull of the band's vertices,
//                 projected on the plane orthogonal to u (model units^2):
//                 the polygon the model stands on;
//   centre        the centre of mass of the solid (the boundary's enclosed
//                 volume, by the divergence theorem on its faces);
//   tip           the distance from the centre's projection to the hull's
//                 edge (negative outside) / the centre's height above the
//                 base: the tangent of the angle it must be tipped by to
//                 fall over. The pose rests when tip > -kRestingTipTolerance
//                 (a scan has lost its pedestal, the thin band misses toes:
//                 the armadillo's centre is 2-3 % of its height outside the
//                 hull of its feet).
// Opposite candidates that both rest with alike support areas and tips
// (within kRestingAlike) mean a model about mirror-symmetric across the
// plane between them: either pose lies on its side (an L bracket flat on
// its L; the upright of a symmetric part has its symmetry plane vertical,
// as in Fu et al.), so they are left out while another candidate rests
// with its centre inside its support (tip > 0; a twisted bar's sides rest
// on an edge within the tolerance only) (issue 45e). When every resting candidate is so and the solid is
// box-like (its volume at least kRestingBoxFill of its bounding box's: a
// box, a tower, a plain slab, whose flat sides the data cannot tell apart;
// issue 46), the first resting candidate in the prior order. Else the chosen axis: the first remaining resting candidate, in
// the prior order +z, +y, +x, -z, -y, -x, whose support area is at least
// 1/kRestingPriorMargin of the largest support area of a remaining
// resting candidate (so data that cannot tell, a cube, keeps the file's own
// axis: z-up, then y-up); then, when its opposite rests too with a support
// area over (1 + kRestingFlipMargin) times its own, the opposite (a slab
// lies on its larger face, whichever way the file has it: issue 45e's
// rockarm). No resting candidate with an area: +z (the default),
// from_data false.
//
// Deterministic (no hashing, fixed orders, no threads) and O(#boundary
// faces + #boundary vertices + #band vertices log #band vertices) per
// candidate.

#include <string>
#include <vector>

#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"

namespace hq {

inline constexpr double kRestingBaseBand = 0.01;      // of the bounding-box diagonal
inline constexpr double kRestingTipTolerance = 0.05;  // of the centre's height
inline constexpr double kRestingPriorMargin = 1.1;    // the largest support area over the chosen one's, at most (1.5 before issue 45f)
inline constexpr double kRestingAlike = 0.02;         // opposite poses alike: relative to the larger area, the larger |tip| (at least 1)
inline constexpr double kRestingFlipMargin = 0.05;    // the opposite base wins when larger by this fraction
inline constexpr double kRestingBoxFill = 0.9;        // solid volume / bounding-box volume of a box-like solid

struct RestingCandidate {
  Vec3 up;
  double support_area = 0.0;  // model units^2
  double tip = 0.0;           // dimensionless, see above
  bool rests = false;         // tip > -kRestingTipTolerance
};

struct RestingUp {
  Vec3 up{0.0, 0.0, 1.0};
  std::vector<RestingCandidate> candidates;  // in the prior order +z +y +x -z -y -x
  bool from_data = false;                    // false: no resting candidate; the default +z
};

// Whether the data could not tell up at all: all six candidates rest with
// alike support areas and tips (within kRestingAlike, as opposite poses are
// compared): a ball, a cube; the chosen +z is then the file's, not the
// model's (issue 45g: a turned ball was drawn from another side).
bool resting_up_undecided(const RestingUp& resting);

// The six candidates in the prior order.
std::vector<Vec3> resting_up_candidates();

// The resting up axis of the solid bounded by the mesh's boundary faces of every kind
// (oriented outward, as build_topology gives them). A mesh without boundary
// faces or without volume gets +z, from_data false.
RestingUp choose_resting_up(const HexMesh& mesh, const Topology& topology);

}  // namespace hq
