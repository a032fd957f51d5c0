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
#include <span>
#include <vector>

#include "hqview/core/vec3.h"
#include "hqview/mesh/mesh.h"

namespace hq {

// 1e-6 of the diagonal: far above the rounding of coordinates written with
// 7 significant digits (float), far below any intended relief.
inline constexpr double kPlanarTolerance = 1e-6;

// The least-squares plane of points: through their centroid, its normal
// the unit eigenvector of the smallest eigenvalue of their covariance
// (Eigen's SelfAdjointEigenSolver), signed so that its largest component
// is positive. No points: the origin and +z.
struct LeastSquaresPlane {
  Vec3 centroid;
  Vec3 normal{0, 0, 1};   // the axis the points vary least along (unit)
  Vec3 longest{1, 0, 0};  // the axis they vary most along (unit; its sign arbitrary)
};
LeastSquaresPlane least_squares_plane(std::span<const Vec3> points);

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

// Coordinates in a planar mesh's plane, where check_surface_overlap decides
// it (docs/analysis.md, "Overlap"): to_plane(p) = (u, v, 0), from_plane
// back. A mesh whose vertices share one coordinate exactly (it lies in a
// coordinate plane) keeps its two others as they are (u, v in cyclic order
// after the shared axis): no rounding. Any other plane: u = (p - c) . e1,
// v = (p - c) . e2 about the centroid c, e1 the unit normal x the
// coordinate axis the normal is farthest from (the lowest such axis on a
// tie), e2 = normal x e1: a basis fixed by the normal alone, so a rotated
// or mirrored copy of a mesh gets the same (u, v) up to a turn or a flip of
// the plane and rounding.
struct PlaneFrame {
  int shared_axis = -1;  // 0-2 when the vertices share that coordinate exactly, else -1
  double shared_value = 0;
  Vec3 origin, e1, e2;

  Vec3 to_plane(const Vec3& p) const;
  Vec3 from_plane(const Vec3& uv) const;  // uv.z ignored
};
PlaneFrame plane_frame(const Mesh& mesh, const Planarity& planarity);

}  // namespace hq
