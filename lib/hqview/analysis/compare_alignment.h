#pragma once
// Bringing MESH2 of --compare into MESH's frame for the pictures: meshes of
// one model from two methods often come in different units or placements
// (armadillo.mesh of the shared data has a bounding-box diagonal near 2.6,
// the same model from another paper near 105). A uniform scale and a
// translation map MESH2's bounding box onto MESH's (centres matched,
// diagonals equal). Only views use it: every number of report.json stays in
// each mesh's own units. --reference-align bbox uses the same transform to
// bring the reference surface into the mesh's frame (there the boundary
// error is then measured in the mesh's units).

#include <array>
#include <string>

#include "hqview/core/box3.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"

namespace hq {

enum class CompareAlign {
  none,  // never align
  bbox,  // always align by bounding box
  auto_, // align when the diagonals differ by more than 2x or the boxes do not overlap
};

inline constexpr double kAutoAlignDiagonalRatio = 2.0;

struct CompareAlignment {
  CompareAlign requested = CompareAlign::auto_;
  bool aligned = false;  // the transform below is applied in the views
  double scale = 1.0;    // p' = scale * p + translation, MESH2 -> MESH
  Vec3 translation{};
  double diagonal_ratio = 1.0;  // MESH2's bounding-box diagonal / MESH's
  bool boxes_overlap = true;
};

// Boxes of the vertices used by hexes. Degenerate boxes (a point) are never aligned.
CompareAlignment align_compare_mesh(const HexMesh& mesh, const HexMesh& other, CompareAlign requested);

// The same rule for any two boxes: the transform takes `moving` onto `fixed`.
CompareAlignment align_boxes(const Box3& fixed, const Box3& moving, CompareAlign requested);

// p -> scale * p + translation (the identity when not aligned).
Vec3 aligned_point(const Vec3& p, const CompareAlignment& alignment);

// MESH2's points moved into MESH's frame (a copy; the identity when not aligned).
HexMesh aligned_copy(const HexMesh& other, const CompareAlignment& alignment);

const char* compare_align_name(CompareAlign mode);

}  // namespace hq
