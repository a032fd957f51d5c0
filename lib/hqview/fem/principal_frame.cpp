#include "hqview/fem/principal_frame.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>
#include <vector>

#include "hqview/core/box3.h"

namespace hq {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<Vec3> used_points(const HexMesh& mesh, const Topology& topology) {
  std::vector<Vec3> points;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (topology.vertex_hex_offsets[v + 1] > topology.vertex_hex_offsets[v]) points.push_back(mesh.points[v]);
  return points;
}

// The model axes' rule for a sign: the axis's largest component positive
// (the first of equal ones).
Vec3 signed_by_input(const Vec3& axis) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(axis[i]) > std::abs(axis[k])) k = i;
  return axis[k] < 0 ? -axis : axis;
}

// The third moments that fix an axis's sign (the volume's, then the used
// points' about their mean), each with its scale sigma^3.
struct Skew {
  const VolumeMoments& volume;
  double volume_sigma3 = 0;
  const std::vector<Vec3>& points;
  Vec3 points_mean;
  double points_sigma3 = 0;
};

// Phase: an axis turned to the side its volume (else its points) is skewed to.
Vec3 signed_axis(const Skew& skew, const Vec3& axis, Normalization& n) {
  const double by_volume = third_moment_along(skew.volume, axis);
  if (std::abs(by_volume) > kSkewTolerance * skew.volume_sigma3) return by_volume < 0 ? -axis : axis;
  double by_points = 0;
  for (const Vec3& p : skew.points) by_points += std::pow(dot(p - skew.points_mean, axis), 3);
  by_points /= static_cast<double>(skew.points.size());
  if (std::abs(by_points) > kSkewTolerance * skew.points_sigma3) {
    ++n.signs_from_points;
    return by_points < 0 ? -axis : axis;
  }
  ++n.signs_from_input;
  return signed_by_input(axis);
}

// Phase: two axes spanning the plane normal to `distinct` (unit), from the
// model axis most orthogonal to it (the first of equal ones).
std::array<Vec3, 2> plane_axes_from_input(const Vec3& distinct) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(distinct[i]) < std::abs(distinct[k])) k = i;
  Vec3 e;
  e[k] = 1;
  const Vec3 a = normalized(e - distinct[k] * distinct);
  return {a, cross(distinct, a)};
}

// Phase: the centre and diagonal of the points' bounding box in n's frame
// (coordinates about `origin`, a point near the mesh).
void fit_box(const std::vector<Vec3>& points, const Vec3& origin, Normalization& n) {
  Box3 box;
  for (const Vec3& p : points) {
    const Vec3 y = p - origin;
    box.add({dot(n.axes[0], y), dot(n.axes[1], y), dot(n.axes[2], y)});
  }
  const Vec3 mid = 0.5 * (box.lo + box.hi);
  n.center = origin + mid[0] * n.axes[0] + mid[1] * n.axes[1] + mid[2] * n.axes[2];
  n.diagonal = box.diagonal();
  if (!(n.diagonal > 0)) n.diagonal = 1;
}

}  // namespace

Normalization principal_normalization(const HexMesh& mesh, const Topology& topology, const VolumeMoments& m) {
  Normalization n;
  const std::vector<Vec3> points = used_points(mesh, topology);
  if (points.empty()) return n;
  if (!(m.volume > 0) || !is_finite(m.centroid)) {
    n.principal_variances = {kNaN, kNaN, kNaN};
    n.axes_from_input = 3;
    fit_box(points, points.front(), n);
    return n;
  }
  Eigen::Matrix3d c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c(i, j) = m.second[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(c);
  // Descending: lambda[0] >= lambda[1] >= lambda[2].
  std::array<Vec3, 3> vectors;
  for (int i = 0; i < 3; ++i) {
    n.principal_variances[static_cast<std::size_t>(i)] = solver.eigenvalues()(2 - i);
    const auto v = solver.eigenvectors().col(2 - i);
    vectors[static_cast<std::size_t>(i)] = normalized(Vec3{v(0), v(1), v(2)});
  }
  const auto& lambda = n.principal_variances;
  const double tolerance = kDegenerateGap * lambda[0];
  const bool top_pair = lambda[0] - lambda[1] <= tolerance, bottom_pair = lambda[1] - lambda[2] <= tolerance;
  Vec3 points_mean;
  for (const Vec3& p : points) points_mean = points_mean + p / static_cast<double>(points.size());
  double points_variance = 0;
  for (const Vec3& p : points) points_variance += squared_norm(p - points_mean) / static_cast<double>(points.size());
  const Skew skew{m, std::pow(lambda[0] + lambda[1] + lambda[2], 1.5), points, points_mean,
                  std::pow(points_variance, 1.5)};
  if (top_pair && bottom_pair) {
    n.axes_from_input = 3;  // the model axes, as constructed
  } else if (top_pair || bottom_pair) {
    // The distinct axis keeps its place by its variance (last for a top
    // pair, first for a bottom pair); the plane's two fill the others.
    const std::size_t distinct = top_pair ? 2 : 0, first = top_pair ? 0 : 1;
    n.axes[distinct] = signed_axis(skew, vectors[distinct], n);
    const auto plane = plane_axes_from_input(n.axes[distinct]);
    n.axes[first] = plane[0];
    n.axes[first + 1] = plane[1];
    n.axes_from_input = 2;
  } else {
    for (std::size_t i = 0; i < 3; ++i) n.axes[i] = signed_axis(skew, vectors[i], n);
  }
  fit_box(points, m.centroid, n);
  return n;
}

}  // namespace hq
