#include "hqview/views/overview_viewpoint.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "hqview/render/camera.h"
#include "hqview/render/upright.h"
#include "hqview/views/overview_views.h"

namespace hq {

WorstFaces worst_boundary_faces(const Topology& topology, std::span<const double> vertex_quality,
                                std::span<const Index> worst_cluster) {
  WorstFaces out;
  const std::size_t n = topology.boundary_faces.size();
  out.flagged.assign(n, 0);
  auto flag_if = [&](auto&& is_worst) {
    bool any = false;
    for (std::size_t i = 0; i < n; ++i) {
      const Quad& q = topology.faces[static_cast<std::size_t>(topology.boundary_faces[i])];
      for (int k = 0; k < 4; ++k)
        if (is_worst(q[static_cast<std::size_t>(k)])) {
          out.flagged[i] = static_cast<char>(out.flagged[i] | (1 << k));
          any = true;
        }
    }
    return any;
  };
  if (flag_if([&](Index v) {
        const auto k = static_cast<std::size_t>(v);
        return k < vertex_quality.size() && vertex_quality[k] < 0.0;
      })) {
    out.kind = WorstFaces::Kind::inverted;
    return out;
  }
  if (!worst_cluster.empty()) {
    std::vector<char> in_cluster(vertex_quality.size(), 0);
    for (Index v : worst_cluster)
      if (v >= 0 && static_cast<std::size_t>(v) < in_cluster.size()) in_cluster[static_cast<std::size_t>(v)] = 1;
    if (flag_if([&](Index v) {
          const auto k = static_cast<std::size_t>(v);
          return k < in_cluster.size() && in_cluster[k];
        })) {
      out.kind = WorstFaces::Kind::worst_cluster;
      return out;
    }
  }
  return out;
}

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDepthTolerance = 0.01;  // of the boundary's depth range along the view

// Edge function: twice the signed area of (a, b, p) in the grid plane.
double edge(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

}  // namespace

double visible_flagged_area(const HexMesh& mesh, const Topology& topology, std::span<const char> flagged,
                            const Vec3& direction, const Vec3& up) {
  // The overview's own camera (perspective, fitted to the boundary), so
  // that what is in sight here is in sight there.
  const std::vector<Vec3> points = boundary_points(mesh, topology);
  const Camera camera = fit_camera_to_points(points, direction, 1.0, {.up = up});
  const Mat4 to_ndc = projection_matrix(camera, 1.0) * view_matrix(camera);
  const Vec3 forward = normalized(camera.target - camera.eye);
  constexpr int g = kViewpointGrid;
  // Grid coordinates (x, y in cells) and the distance along the view
  // direction (z, model units) of each face corner.
  auto grid_of = [&](Index v) {
    const Vec3& p = mesh.points[static_cast<std::size_t>(v)];
    const Vec3 ndc = transform_point(to_ndc, p);
    return Vec3{0.5 * (ndc.x + 1.0) * g, 0.5 * (ndc.y + 1.0) * g, dot(p - camera.eye, forward)};
  };
  std::vector<double> depth(static_cast<std::size_t>(g) * g, std::numeric_limits<double>::infinity());
  auto cell = [&](double x, double y) {
    const int cx = std::clamp(static_cast<int>(std::floor(x)), 0, g - 1);
    const int cy = std::clamp(static_cast<int>(std::floor(y)), 0, g - 1);
    return static_cast<std::size_t>(cy) * g + static_cast<std::size_t>(cx);
  };
  // 1. The depth buffer of every boundary face (two triangles each), sampled at cell centres.
  double nearest = std::numeric_limits<double>::infinity(), farthest = -nearest;
  for (Index face : topology.boundary_faces) {
    const Quad& q = topology.faces[static_cast<std::size_t>(face)];
    const Vec3 p[4] = {grid_of(q[0]), grid_of(q[1]), grid_of(q[2]), grid_of(q[3])};
    for (const Vec3& c : p) {
      nearest = std::min(nearest, c.z);
      farthest = std::max(farthest, c.z);
    }
    for (const auto& t : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
      const Vec3 &a = p[t[0]], &b = p[t[1]], &c = p[t[2]];
      const double area = edge(a.x, a.y, b.x, b.y, c.x, c.y);
      if (!std::isfinite(area) || std::abs(area) < 1e-12) continue;
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}) - 0.5)));
      const int x1 = std::min(g - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}) - 0.5)));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}) - 0.5)));
      const int y1 = std::min(g - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}) - 0.5)));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const double px = x + 0.5, py = y + 0.5;
          const double w0 = edge(b.x, b.y, c.x, c.y, px, py) / area;
          const double w1 = edge(c.x, c.y, a.x, a.y, px, py) / area;
          const double w2 = 1.0 - w0 - w1;
          if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
          double& d = depth[static_cast<std::size_t>(y) * g + static_cast<std::size_t>(x)];
          d = std::min(d, w0 * a.z + w1 * b.z + w2 * c.z);
        }
    }
  }
  // 2. Each flagged face whose centre is not behind the nearest surface
  // there (within kDepthTolerance of the boundary's depth range: the face
  // itself, or a neighbour at its depth when it covers no cell centre)
  // counts its projected area, in model units at the camera's target.
  const double tolerance = kDepthTolerance * std::max(farthest - nearest, 0.0);
  const double frame = 2.0 * norm(camera.target - camera.eye) * std::tan(0.5 * camera.fov_y_degrees * kPi / 180.0);
  const double cell_side = frame / g;
  double area = 0.0;
  for (std::size_t i = 0; i < topology.boundary_faces.size(); ++i) {
    if (!flagged[i]) continue;
    const Quad& q = topology.faces[static_cast<std::size_t>(topology.boundary_faces[i])];
    const Vec3 p[4] = {grid_of(q[0]), grid_of(q[1]), grid_of(q[2]), grid_of(q[3])};
    // The projected quad's area, half the cross product of its diagonals.
    const double cells =
        0.5 * std::abs((p[2].x - p[0].x) * (p[3].y - p[1].y) - (p[2].y - p[0].y) * (p[3].x - p[1].x));
    Vec3 centre3;
    for (Index v : q) centre3 = centre3 + 0.25 * mesh.points[static_cast<std::size_t>(v)];
    for (int k = 0; k < 4; ++k) {
      if (!(flagged[i] & (1 << k))) continue;
      // The corner's share of the face (where the overview paints its
      // colour), sampled three quarters of the way from the centre to it.
      const Vec3 model = centre3 + 0.75 * (mesh.points[static_cast<std::size_t>(q[static_cast<std::size_t>(k)])] - centre3);
      const Vec3 ndc = transform_point(to_ndc, model);
      const Vec3 at{0.5 * (ndc.x + 1.0) * g, 0.5 * (ndc.y + 1.0) * g, dot(model - camera.eye, forward)};
      if (!std::isfinite(at.x) || !std::isfinite(at.y) || at.x < 0 || at.y < 0 || at.x >= g || at.y >= g) continue;
      if (at.z > depth[cell(at.x, at.y)] + tolerance) continue;
      area += 0.125 * cells * cell_side * cell_side;
    }
  }
  return area;
}

OverviewViewpoint choose_overview_viewpoint(const HexMesh& mesh, const Topology& topology, const WorstFaces& worst,
                                            const Vec3& up) {
  OverviewViewpoint out;
  out.direction = three_quarter_view(up);
  out.target = worst.kind;
  if (worst.kind == WorstFaces::Kind::none) return out;
  auto scores = [&](const std::vector<Vec3>& candidates) {
    std::vector<double> s(candidates.size());
    tbb::parallel_for(std::size_t{0}, candidates.size(), [&](std::size_t i) {
      s[i] = visible_flagged_area(mesh, topology, worst.flagged, candidates[i], up);
    });
    return s;
  };
  std::vector<Vec3> candidates{out.direction};
  const std::vector<Vec3> upright = upright_view_candidates(up);
  candidates.insert(candidates.end(), upright.begin(), upright.end());
  std::vector<double> score = scores(candidates);
  out.default_area = out.chosen_area = score[0];
  if (*std::max_element(score.begin(), score.end()) <= 0.0) {
    candidates = below_view_candidates(up);
    score = scores(candidates);
  }
  const auto best = static_cast<std::size_t>(std::max_element(score.begin(), score.end()) - score.begin());
  // Inverted cells turn the eye by the fraction rule; a worst cluster (no
  // inverted corner) only when the three-quarter view shows none of it.
  const bool keep = worst.kind == WorstFaces::Kind::worst_cluster ? out.default_area > 0.0
                                                                   : out.default_area >= kKeepDefaultFraction * score[best];
  if (score[best] <= 0.0 || keep) return out;
  out.direction = candidates[best];
  out.is_default = false;
  out.chosen_area = score[best];
  return out;
}

}  // namespace hq
