#pragma once
// Bringing MESH2 of --compare into MESH's frame for the pictures: meshes of
// one model from two methods often come in different units, placements or
// axis conventions (armadillo.mesh of the shared data has a bounding-box
// diagonal near 2.6, the same model from another paper near 105; a kitten
// may be y-up in one paper and z-up in another). Only views use it: every
// number of report.json stays in each mesh's own units. --reference-align
// uses the same transforms to bring the reference surface into the mesh's
// frame (there the boundary error is then measured in the mesh's units).
//
// The transform is p' = scale * R p + translation (R a proper rotation).
//   none  p' = p.
//   bbox  R = I; a uniform scale and a translation map the moving box onto
//         the fixed one (centres matched, diagonals equal).
//   auto  the bounding-box rule below decides scale and centring; then the
//         24 proper axis-aligned rotations (about the moving box's centre,
//         centres matched) are scored by the mean closest-point distance
//         between the two boundaries (docs/analysis.md "Compare alignment").
//         The identity placement is kept unless a rotation's distance is
//         below kRotationWinRatio times the identity's; the chosen placement
//         is refined by rigid ICP when that lowers the distance (not when
//         the identity kept the meshes where they were: they share a frame).
//         The 24 improper ones (a mirror and a rotation) are scored too: a
//         pair that only a mirror fits (kRotationWinRatio again) is reported
//         as mirrored; the proper placement is drawn.

#include <array>
#include <string>

#include "hqview/core/box3.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"

namespace hq {

enum class CompareAlign {
  none,  // never align
  bbox,  // always align by bounding box
  auto_, // by bounding box when the diagonals differ by more than 2x or the boxes do not overlap; then rotations
};

inline constexpr double kAutoAlignDiagonalRatio = 2.0;
// A rotation (or a mirror) replaces the identity (or the best rotation) only
// when its mean boundary distance is below this fraction of the other's.
inline constexpr double kRotationWinRatio = 0.5;
// Boundary samples per surface for the distances (area-uniform,
// deterministic): every candidate on the coarse set, the kRefinedCandidates
// best proper and improper ones (and the identity) again on the fine one.
inline constexpr int kCoarseAlignmentSamples = 256;
inline constexpr int kAlignmentSamples = 2048;
inline constexpr std::size_t kRefinedCandidates = 3;
inline constexpr int kIcpMaxIterations = 60;
// ICP's result is used when it lowers the mean distance by more than this fraction.
inline constexpr double kIcpMinGain = 0.01;

// A 3x3 matrix, row-major: (R p)_i = sum_j R[i][j] p_j.
using Matrix3 = std::array<std::array<double, 3>, 3>;
inline constexpr Matrix3 kIdentity3{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
Vec3 operator*(const Matrix3& m, const Vec3& p);
Matrix3 operator*(const Matrix3& a, const Matrix3& b);
Matrix3 transposed(const Matrix3& m);

// The 24 proper axis-aligned rotations (signed permutation matrices of
// determinant +1), the identity first, in a fixed order.
std::array<Matrix3, 24> axis_rotations();
// "identity", "90 deg about +x", "180 deg about +x-y", "120 deg about +x+y+z"
// for an axis-aligned rotation; other rotations as "<angle> deg about
// (ax, ay, az)" (3 digits).
std::string rotation_name(const Matrix3& rotation);
// The rotation angle, degrees in [0, 180].
double rotation_angle_degrees(const Matrix3& rotation);

struct CompareAlignment {
  CompareAlign requested = CompareAlign::auto_;
  bool aligned = false;  // the transform below is applied in the views (not the identity)
  double scale = 1.0;    // p' = scale * rotation * p + translation, MESH2 -> MESH
  Vec3 translation{};
  Matrix3 rotation = kIdentity3;
  double diagonal_ratio = 1.0;  // MESH2's bounding-box diagonal / MESH's
  bool boxes_overlap = true;
  // auto only (searched = true): the search's results. Distances are mean
  // closest-point distances between the two boundaries (both ways, sampled),
  // as fractions of MESH's bounding-box diagonal.
  bool searched = false;
  Matrix3 axis_rotation = kIdentity3;  // the axis-aligned rotation chosen
  double identity_distance = 0;        // the identity placement
  double axis_rotation_distance = 0;   // the chosen axis-aligned placement
  double distance = 0;                 // the final placement (after ICP when applied)
  bool icp_applied = false;            // ICP lowered the distance and its result is used
  int icp_iterations = 0;
  bool mirrored = false;       // only a mirror image fits
  double mirror_distance = 0;  // the best improper placement
  Vec3 mirror_normal{};        // the mirror's plane normal (axis of the best improper placement)
};

// Boxes of the vertices used by hexes (a surface mesh: by its faces).
// Degenerate boxes (a point) are never aligned.
// auto also needs the topologies (the boundaries).
CompareAlignment align_compare_mesh(const HexMesh& mesh, const Topology& topology, const HexMesh& other,
                                    const Topology& other_topology, CompareAlign requested);

// The bounding-box rule for any two boxes: the transform takes `moving` onto
// `fixed` (auto here decides scale and centring only).
CompareAlignment align_boxes(const Box3& fixed, const Box3& moving, CompareAlign requested);

// The whole rule for two triangle surfaces (boxes given: the points that
// count). `fixed` and `moving` need triangles of positive area for auto; with
// none the box rule's result is returned.
CompareAlignment align_surfaces(const TriSurface& fixed, const Box3& fixed_box, const TriSurface& moving,
                                const Box3& moving_box, CompareAlign requested);

// p -> scale * rotation * p + translation (the identity when not aligned).
Vec3 aligned_point(const Vec3& p, const CompareAlignment& alignment);

// MESH2's points moved into MESH's frame (a copy; the identity when not aligned).
HexMesh aligned_copy(const HexMesh& other, const CompareAlignment& alignment);

// What was done, for a view's title: "", "aligned by bounding box (scale 0.025)",
// "turned 90 deg about +x (scale 1), refined by ICP", "mirror image: no rotation fits".
std::string alignment_description(const CompareAlignment& alignment);

const char* compare_align_name(CompareAlign mode);

}  // namespace hq
