#include "hqview/mesh/planarity.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

#include "hqview/mesh/surface_topology.h"

namespace hq {
namespace {

// The side the faces' own normals point to, against n: +1 when more point
// along n than against it (quads decide; triangles when there is no quad),
// -1 when fewer, 0 on a tie.
int majority_side(const Mesh& mesh, const Vec3& n) {
  long along = 0, against = 0;
  const bool quads = !mesh.quads.empty();
  for_each_surface_cell(mesh, [&](const std::array<Index, 4>& c, int size) {
    if (quads != (size == 4)) return;
    const auto p = [&](int i) { return mesh.points[static_cast<std::size_t>(c[static_cast<std::size_t>(i)])]; };
    // The area vector: (P2 - P0) x (P3 - P1) for a quad, (P1 - P0) x (P2 - P0) for a triangle.
    const Vec3 area = size == 4 ? cross(p(2) - p(0), p(3) - p(1)) : cross(p(1) - p(0), p(2) - p(0));
    const double s = dot(area, n);
    if (s > 0) ++along;
    if (s < 0) ++against;
  });
  return along > against ? 1 : along < against ? -1 : 0;
}

}  // namespace

LeastSquaresPlane least_squares_plane(std::span<const Vec3> points) {
  LeastSquaresPlane plane;
  if (points.empty()) return plane;
  Vec3 sum;
  for (const Vec3& p : points) sum = sum + p;
  plane.centroid = sum / static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) {
    const Vec3 d = p - plane.centroid;
    const Eigen::Vector3d e(d.x, d.y, d.z);
    covariance += e * e.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d e = solver.eigenvectors().col(0);  // smallest eigenvalue first
  Vec3 normal{e.x(), e.y(), e.z()};
  // A sign that does not depend on the solver: the largest component positive.
  const double largest = std::abs(normal.x) >= std::abs(normal.y) && std::abs(normal.x) >= std::abs(normal.z) ? normal.x
                         : std::abs(normal.y) >= std::abs(normal.z)                                          ? normal.y
                                                                                                              : normal.z;
  plane.normal = largest < 0 ? -normal : normal;
  const Eigen::Vector3d l = solver.eigenvectors().col(2);
  plane.longest = Vec3{l.x(), l.y(), l.z()};
  return plane;
}

Planarity measure_planarity(const Mesh& mesh, double diagonal) {
  Planarity out;
  std::vector<char> used(mesh.points.size(), 0);
  for_each_surface_cell(mesh, [&](const std::array<Index, 4>& c, int size) {
    for (int i = 0; i < size; ++i) used[static_cast<std::size_t>(c[static_cast<std::size_t>(i)])] = 1;
  });
  std::vector<Vec3> points;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (used[v]) points.push_back(mesh.points[v]);
  if (points.empty()) {
    out.is_planar = true;
    return out;
  }
  const LeastSquaresPlane plane = least_squares_plane(points);
  out.centroid = plane.centroid;
  Vec3 normal = plane.normal;
  if (majority_side(mesh, normal) < 0) normal = -normal;
  out.normal = normal;
  for (const Vec3& p : points) out.max_distance = std::max(out.max_distance, std::abs(dot(p - out.centroid, normal)));
  out.planarity = diagonal > 0 ? out.max_distance / diagonal : 0.0;
  out.is_planar = out.planarity <= kPlanarTolerance;
  return out;
}

Vec3 PlaneFrame::to_plane(const Vec3& p) const {
  if (shared_axis >= 0) return {p[(shared_axis + 1) % 3], p[(shared_axis + 2) % 3], 0.0};
  const Vec3 d = p - origin;
  return {dot(d, e1), dot(d, e2), 0.0};
}

Vec3 PlaneFrame::from_plane(const Vec3& uv) const {
  if (shared_axis < 0) return origin + uv.x * e1 + uv.y * e2;
  Vec3 p;
  p[shared_axis] = shared_value;
  p[(shared_axis + 1) % 3] = uv.x;
  p[(shared_axis + 2) % 3] = uv.y;
  return p;
}

PlaneFrame plane_frame(const Mesh& mesh, const Planarity& planarity) {
  PlaneFrame frame;
  const Vec3& n = planarity.normal;
  // The axis the normal is nearest to: shared exactly by every vertex?
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
  bool shared = true, seen = false;
  double value = 0;
  for_each_surface_cell(mesh, [&](const std::array<Index, 4>& c, int size) {
    for (int i = 0; i < size && shared; ++i) {
      const double x = mesh.points[static_cast<std::size_t>(c[static_cast<std::size_t>(i)])][axis];
      if (seen && x != value) shared = false;
      value = x;
      seen = true;
    }
  });
  if (shared) {
    frame.shared_axis = axis;
    frame.shared_value = value;
    return frame;
  }
  int farthest = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[farthest])) farthest = k;
  Vec3 a;
  a[farthest] = 1.0;
  frame.origin = planarity.centroid;
  frame.e1 = normalized(cross(n, a));
  frame.e2 = cross(n, frame.e1);
  return frame;
}

}  // namespace hq
