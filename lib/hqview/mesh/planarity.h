#pragma once
// Whether a surface mesh lies in a plane (report.json mesh.planar,
// mesh.planarity; docs/analysis.md, "Surface meshes"): the least-squares
// plane of the vertices its cells use (through their centroid, normal the
// eigenvector of the smallest eigenvalue of their covariance), the largest
// distance of a vertex from it, and that distance over the bounding-box
// diagonal. A mesh is planar when this ratio is at most kPlanarTolerance.
// The normal points to the side the majority of the faces' own normals
// (quads first; triangles when there is no quad) point to.

#include <optional>
#include <vector>

#include "hqview/core/vec3.h"
#include "hqview/mesh/mesh.h"

namespace hq {

// 1e-6 of the diagonal: far above the rounding of coordinates written with
// 7 significant digits (float), far below any intended relief.
inline constexpr double kPlanarTolerance = 1e-6;

struct Planarity {
  Vec3 normal{0, 0, 1};  // unit
  Vec3 centroid;
  double max_distance = 0;  // model units
  double planarity = 0;     // max_distance / bounding-box diagonal (0 for a single point)
  bool is_planar = false;
};

// Over the vertices the surface cells use (none: planar, planarity 0).
// `diagonal` is the bounding-box diagonal of those vertices.
Planarity measure_planarity(const Mesh& mesh, double diagonal);

}  // namespace hq
