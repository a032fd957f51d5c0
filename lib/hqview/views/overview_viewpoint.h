#pragma once
// The overview's and thumbnail's viewpoint: the three-quarter view of the up
// axis unless the worst region (inverted corners, else the worst glyph
// cluster) lies on a side it does not show; then the upright view, among a
// fixed set, that shows the most of it (docs/analysis.md, "Upright
// cameras"). The model keeps the pose --up gives it; only the eye moves
// around (or, when no upright eye sees the region, below) it.

#include <span>
#include <vector>

#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"

namespace hq {

// What the overview aims at: per topology.boundary_faces entry, a bit mask
// of its worst corners (bit k: corner k of the face's quad), 0 for none.
struct WorstFaces {
  std::vector<char> flagged;
  enum class Kind { none, inverted, worst_cluster } kind = Kind::none;
};

// The boundary faces with a corner whose vertex quality is < 0; when no
// boundary face has one, those with a corner in worst_cluster (the worst
// glyph cluster's vertex ids); else none (kind none).
WorstFaces worst_boundary_faces(const Topology& topology, std::span<const double> vertex_quality,
                                std::span<const Index> worst_cluster);

// The area (model units squared at the camera's target) of the flagged
// corners' parts of the boundary faces that are in sight from direction,
// through the overview's camera (perspective, fitted to the boundary): a
// flagged corner counts an eighth of its face's projected area (the part
// the overview paints in that corner's colour) when the point three
// quarters of the way from the face's centre to it passes a depth test (1 %
// of the boundary's depth range as tolerance) against all boundary faces,
// rasterised on a kViewpointGrid x kViewpointGrid grid framing the boundary
// (a face smaller than a cell counts too).
inline constexpr int kViewpointGrid = 200;
double visible_flagged_area(const HexMesh& mesh, const Topology& topology, std::span<const char> flagged,
                            const Vec3& direction, const Vec3& up);

// The rule. Candidates: the three-quarter view (three_quarter_view(up))
// first, then upright_view_candidates(up); when none shows any flagged
// face, below_view_candidates(up). The best is the first candidate of the
// largest visible_flagged_area. The three-quarter view is kept when no
// face is flagged, when nothing flagged is visible from any candidate, or
// when it shows at least kKeepDefaultFraction of the best's area (inverted
// corners) or any of it (the worst cluster: a softer target, and the
// three-quarter view is the pose a reader recognises: Dolphin_padded's
// flukes seen end-on made an unrecognisable thumbnail); else the best is
// taken. Deterministic (one task per candidate, fixed order).
inline constexpr double kKeepDefaultFraction = 0.5;
struct OverviewViewpoint {
  Vec3 direction;             // from the eye towards the model
  bool is_default = true;     // the three-quarter view
  double default_area = 0.0;  // visible_flagged_area of the three-quarter view
  double chosen_area = 0.0;   // and of the chosen one
  WorstFaces::Kind target = WorstFaces::Kind::none;  // what was aimed at
};
OverviewViewpoint choose_overview_viewpoint(const HexMesh& mesh, const Topology& topology, const WorstFaces& worst,
                                            const Vec3& up);

}  // namespace hq
