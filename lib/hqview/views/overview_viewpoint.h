#pragma once
// The overview's and thumbnail's viewpoint: the three-quarter view of the up
// axis unless the worst region (inverted corners, else the worst glyph
// cluster) lies on a side it does not show; then the upright view, among a
// fixed set, that shows the most of it (docs/analysis.md, "Upright
// cameras"). The model keeps the pose --up gives it; only the eye moves
// around (or, when no upright eye sees the region, below) it.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hqview/core/vec3.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/render/camera.h"
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

// That depth test for any faces and camera (the main views of a surface
// mesh aim at the worst cluster's faces with it): the nearest depth of
// `faces` (a quad as two triangles) at the centres of a kViewpointGrid x
// kViewpointGrid grid framing the camera's image of width / height aspect.
class FaceDepthGrid {
 public:
  FaceDepthGrid(const HexMesh& mesh, std::span<const BoundaryPolygon> faces, const Camera& camera, double aspect);
  // p lies in the frame and not behind the nearest face at its cell (1 %
  // of the faces' depth range as tolerance).
  bool in_sight(const Vec3& p) const;
  // A face's area projected on the image plane, model units squared.
  double projected_area(const BoundaryPolygon& face) const;
  // The point three quarters of the way from the face's centre to its corner.
  Vec3 corner_sample(const BoundaryPolygon& face, int corner) const;

 private:
  Vec3 grid_of(const Vec3& p) const;  // grid x, y (cells) and depth along the view (model units)
  const HexMesh* mesh_;
  Mat4 to_ndc_;
  Vec3 eye_, forward_;
  std::vector<double> depth_;
  double tolerance_ = 0.0, cell_area_ = 0.0;
};

// How many of cells have a boundary face (boundary_polygons) in sight
// through camera: a corner sample of it (FaceDepthGrid::corner_sample) in
// sight against every boundary face (the overview's "N in sight" of a
// surface mesh's outlined faces).
Index cells_in_sight(const HexMesh& mesh, const Topology& topology, std::span<const Index> cells, const Camera& camera,
                     double aspect);
// A planar mesh seen along its normal has no far side (the 47c review: "2 in
// sight, 1 on the far side" on an L-shape whose three reversed quads were
// all drawn): the cells (ascending) that have every corner sample of every
// boundary face inside another boundary face's image (the image plane
// through camera, a crossing-number test), the faces under an overlapping
// face (a fold); the others are in sight.
std::vector<Index> cells_under_other_faces(const HexMesh& mesh, const Topology& topology, std::span<const Index> cells,
                                           const Camera& camera);

// The horizontal axis the overview's eye turns around (its azimuth 0), from
// the model, not the file (issue 45f: a copy turned about up or turned over
// and stood up again by --up auto must be seen from the same side): the
// boundary faces' centres, weighted by their areas, projected on the plane
// orthogonal to up; the axis of their smaller spread (the eye faces the
// model's broad side, as a CAD part is drawn), unless the two spreads are
// within kFrontIsotropy of each other (a ball, a square column: the file's
// front_of(up) then); its sign towards the longer tail of the centres along
// it (third moment over the spread cubed above kFrontSkew), else the one
// nearer to front_of(up) (a model symmetric across the plane looks alike
// from either side).
inline constexpr double kFrontIsotropy = 0.05;  // (larger - smaller) / (larger + smaller) spread
inline constexpr double kFrontSkew = 0.1;
Vec3 model_front(const HexMesh& mesh, const Topology& topology, const Vec3& up);
// The same, with whether the shape fixed its axis (the spreads differ) and
// its sign (the skew); model_front is its `front`.
struct ModelFront {
  Vec3 front;
  bool axis_from_shape = false;
  bool sign_from_shape = false;
};
ModelFront model_front_of(const HexMesh& mesh, const Topology& topology, const Vec3& up);

// The view direction of an eye at (azimuth, elevation) degrees around up,
// azimuth 0 on `front` (orthogonal to up), positive turning right-handed
// about up.
Vec3 overview_view_direction(const Vec3& up, const Vec3& front, double azimuth_degrees, double elevation_degrees);

// The overview's eyes: never on a principal axis of the model or straight
// above or below it, where a part reads as a flat grid (the 45e review's T
// beam seen from straight below): azimuths kOverviewAzimuths from the
// model's front, elevations 25, 15, 35 degrees, and, when no such eye sees
// the target, -25, -15, -40 (below).
inline constexpr double kOverviewAzimuths[] = {30, 60, 120, 150, 210, 240, 300, 330};
inline constexpr double kOverviewElevations[] = {25, 15, 35};
inline constexpr double kOverviewBelowElevations[] = {-25, -15, -40};
std::vector<Vec3> overview_view_candidates(const Vec3& up, const Vec3& front, bool below);
// Where such an eye sits, in words: "above" or "below", then the quarter
// around the model's front ("front right" for azimuths in (0, 90), "back
// right", "back left", "front left"), then the numbers (issue 45f round 2:
// the 45f review's title words): "above, front left: azimuth 330,
// elevation 25 deg from the model's front" (azimuth 0..359 turning
// right-handed about up, elevation above the horizontal plane; whole degrees);
// an eye whose elevation rounds to +-90 has no side: "straight above:
// elevation 90 deg" (issue 45g).
// front_name: what the front is ("the inverted hexes' side" for a shape
// without a front of its own, issue 45g).
std::string overview_side_name(const Vec3& view_direction, const Vec3& up, const Vec3& front,
                               const std::string& front_name = "the model's front");

// The rule. Candidates: the three-quarter view (azimuth 30, elevation 25
// from model_front) first, then overview_view_candidates(up, front, false); when none shows any flagged
// face, overview_view_candidates(up, front, true). The best is the first candidate whose
// visible_flagged_area is at least kNearBestFraction of the largest (so
// that near ties go to the view earlier in the order, the recognisable
// three-quarter ones, whatever rounding a turned copy brings). The three-quarter view is kept when no
// face is flagged, when nothing flagged is visible from any candidate, or
// when it shows at least kKeepDefaultFraction of the largest area (inverted
// corners) or any of it (the worst cluster: a softer target, and the
// three-quarter view is the pose a reader recognises: Dolphin_padded's
// flukes seen end-on made an unrecognisable thumbnail); else the best is
// taken. Deterministic (one task per candidate, fixed order).
// Copies (issue 45f round 2): when the shape fixes the front's axis but
// not its sign, the sign goes towards the flagged faces (the mean of their
// flagged corners along the axis against the mean of all boundary corners,
// when they differ by more than kFrontDefectOffset of the boundary's extent
// along it; nothing flagged: the inside_target's offset, issue 45g), so a
// turned copy is seen from the same side of its defect.
inline constexpr double kFrontDefectOffset = 0.01;
// The front's words (issue 45f round 2): when neither the shape nor the
// defect fixes the sign (the defect on the middle plane), `front` is the
// sign on the chosen eye's side after the choice, so a copy drawn alike is
// named alike ("front right", not "back left" for the same pixels); the eye
// itself does not change.
// A shape that fixes neither its front's axis (model_front_of) nor its up
// (free_up given: the up candidates when the data could not tell up, a
// ball; resting_up_undecided) (issue 45g: the ball and its copy turned
// 90 deg about x were drawn from different sides under the same words):
// d = the flagged corners' mean (none flagged: inside_target, the inverted
// cells' corners' mean, when given) less the boundary corners' mean; the up is
// the candidate of free_up with the largest d . up (when it beats the
// next by kFrontDefectOffset of |d|; else the given up), the front d's part
// across the up (when longer than kFrontDefectOffset of the boundary's
// extent along it); both then turn with the model, so a turned copy is
// drawn alike. front_from_target says so (the title's words).
inline constexpr double kKeepDefaultFraction = 0.5;
inline constexpr double kNearBestFraction = 0.8;
struct OverviewViewpoint {
  Vec3 direction;             // from the eye towards the model
  Vec3 front;                 // model_front (its sign as above): the eye's azimuth 0
  bool is_default = true;     // the three-quarter view
  double default_area = 0.0;  // visible_flagged_area of the three-quarter view
  double chosen_area = 0.0;   // and of the chosen one
  WorstFaces::Kind target = WorstFaces::Kind::none;  // what was aimed at
  Vec3 up{0.0, 0.0, 1.0};     // the up the eye turns about (the given one, or one of free_up)
  bool front_from_target = false;  // the front (and the up, when free) from the flagged faces
};
OverviewViewpoint choose_overview_viewpoint(const HexMesh& mesh, const Topology& topology, const WorstFaces& worst,
                                            const Vec3& up, std::span<const Vec3> free_up = {},
                                            const std::optional<Vec3>& inside_target = std::nullopt);

// What the overview's title says of its eye: ", from " and overview_side_name
// (the front named "the model's front", or, taken from the flagged faces,
// "the worst cluster's side" / "the inverted hexes' side"), then, when the
// eye turned from the three-quarter view, ", turned to show the inverted
// hexes" (or "the worst cluster"); cell_noun: the mesh's ("hex", "cell" on a
// hybrid mesh, a surface mesh's "quad", ...), made plural.
std::string overview_eye_words(const OverviewViewpoint& eye, const Vec3& up, const std::string& cell_noun);

}  // namespace hq
