#include "hqview/views/overview_viewpoint.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "hqview/core/box3.h"
#include "hqview/core/text.h"
#include "hqview/mesh/boundary_polygons.h"
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

FaceDepthGrid::FaceDepthGrid(const HexMesh& mesh, std::span<const BoundaryPolygon> faces, const Camera& camera,
                             double aspect)
    : mesh_(&mesh),
      to_ndc_(projection_matrix(camera, aspect) * view_matrix(camera)),
      eye_(camera.eye),
      forward_(normalized(camera.target - camera.eye)),
      depth_(static_cast<std::size_t>(kViewpointGrid) * kViewpointGrid, std::numeric_limits<double>::infinity()) {
  constexpr int g = kViewpointGrid;
  // The depth buffer of every face (a quad as two triangles), sampled at cell centres.
  double nearest = std::numeric_limits<double>::infinity(), farthest = -nearest;
  for (const BoundaryPolygon& face : faces) {
    std::array<Vec3, 4> p;
    for (int i = 0; i < face.size; ++i) {
      p[static_cast<std::size_t>(i)] = grid_of(mesh.points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])]);
      nearest = std::min(nearest, p[static_cast<std::size_t>(i)].z);
      farthest = std::max(farthest, p[static_cast<std::size_t>(i)].z);
    }
    for (const auto& t : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
      if (t[2] >= face.size) continue;
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
          double& d = depth_[static_cast<std::size_t>(y) * g + static_cast<std::size_t>(x)];
          d = std::min(d, w0 * a.z + w1 * b.z + w2 * c.z);
        }
    }
  }
  // Within kDepthTolerance of the faces' depth range: the face itself, or a
  // neighbour at its depth when it covers no cell centre.
  tolerance_ = kDepthTolerance * std::max(farthest - nearest, 0.0);
  // The frame's size in model units at the camera's target.
  const double frame = camera.is_perspective
                           ? 2.0 * norm(camera.target - camera.eye) * std::tan(0.5 * camera.fov_y_degrees * kPi / 180.0)
                           : camera.ortho_height;
  cell_area_ = (frame / g) * (frame * aspect / g);
}

Vec3 FaceDepthGrid::grid_of(const Vec3& p) const {
  constexpr int g = kViewpointGrid;
  const Vec3 ndc = transform_point(to_ndc_, p);
  return {0.5 * (ndc.x + 1.0) * g, 0.5 * (ndc.y + 1.0) * g, dot(p - eye_, forward_)};
}

bool FaceDepthGrid::in_sight(const Vec3& p) const {
  constexpr int g = kViewpointGrid;
  const Vec3 at = grid_of(p);
  if (!std::isfinite(at.x) || !std::isfinite(at.y) || at.x < 0 || at.y < 0 || at.x >= g || at.y >= g) return false;
  const int cx = std::clamp(static_cast<int>(std::floor(at.x)), 0, g - 1);
  const int cy = std::clamp(static_cast<int>(std::floor(at.y)), 0, g - 1);
  return !(at.z > depth_[static_cast<std::size_t>(cy) * g + static_cast<std::size_t>(cx)] + tolerance_);
}

double FaceDepthGrid::projected_area(const BoundaryPolygon& face) const {
  std::array<Vec3, 4> p;
  for (int i = 0; i < face.size; ++i)
    p[static_cast<std::size_t>(i)] = grid_of(mesh_->points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])]);
  if (face.size == 3) p[3] = p[0];
  // Half the cross product of the diagonals (a triangle: its fourth corner on its first).
  return 0.5 * std::abs((p[2].x - p[0].x) * (p[3].y - p[1].y) - (p[2].y - p[0].y) * (p[3].x - p[1].x)) * cell_area_;
}

Vec3 FaceDepthGrid::corner_sample(const BoundaryPolygon& face, int corner) const {
  Vec3 centre;
  for (int i = 0; i < face.size; ++i)
    centre = centre + (1.0 / face.size) * mesh_->points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])];
  return centre + 0.75 * (mesh_->points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(corner)])] - centre);
}

double visible_flagged_area(const HexMesh& mesh, const Topology& topology, std::span<const char> flagged,
                            const Vec3& direction, const Vec3& up) {
  // The overview's own camera (perspective, fitted to the boundary), so
  // that what is in sight here is in sight there.
  const std::vector<Vec3> points = boundary_points(mesh, topology);
  const Camera camera = fit_camera_to_points(points, direction, 1.0, {.up = up});
  std::vector<BoundaryPolygon> faces;
  faces.reserve(topology.boundary_faces.size());
  for (Index face : topology.boundary_faces) {
    const Quad& q = topology.faces[static_cast<std::size_t>(face)];
    faces.push_back({{q[0], q[1], q[2], q[3]}, 4, kNoIndex});
  }
  const FaceDepthGrid grid(mesh, faces, camera, 1.0);
  // Each flagged corner whose sample is in sight counts an eighth of its
  // face's projected area, in model units at the camera's target.
  double area = 0.0;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (!flagged[i]) continue;
    for (int k = 0; k < 4; ++k)
      if ((flagged[i] & (1 << k)) && grid.in_sight(grid.corner_sample(faces[i], k)))
        area += 0.125 * grid.projected_area(faces[i]);
  }
  return area;
}

Index cells_in_sight(const HexMesh& mesh, const Topology& topology, std::span<const Index> cells, const Camera& camera,
                     double aspect) {
  const std::vector<BoundaryPolygon> faces = boundary_polygons(topology);
  const FaceDepthGrid grid(mesh, faces, camera, aspect);
  std::size_t n = 0;
  for (Index c : cells) n = std::max(n, static_cast<std::size_t>(std::max<Index>(c, -1) + 1));
  std::vector<char> wanted(n, 0), shown(n, 0);
  for (Index c : cells)
    if (c >= 0) wanted[static_cast<std::size_t>(c)] = 1;
  for (const BoundaryPolygon& face : faces) {
    const auto c = static_cast<std::size_t>(face.cell);
    if (face.cell < 0 || c >= wanted.size() || !wanted[c] || shown[c]) continue;
    for (int k = 0; k < face.size && !shown[c]; ++k) shown[c] = grid.in_sight(grid.corner_sample(face, k)) ? 1 : 0;
  }
  return static_cast<Index>(std::count(shown.begin(), shown.end(), 1));
}

std::vector<Index> cells_under_other_faces(const HexMesh& mesh, const Topology& topology, std::span<const Index> cells,
                                           const Camera& camera) {
  const std::vector<BoundaryPolygon> faces = boundary_polygons(topology);
  const Vec3 forward = normalized(camera.target - camera.eye);
  const Vec3 right = normalized(cross(forward, camera.up)), upward = cross(right, forward);
  auto image = [&](const Vec3& p) { return std::array<double, 2>{dot(p, right), dot(p, upward)}; };
  auto corner = [&](const BoundaryPolygon& f, int i) {
    return image(mesh.points[static_cast<std::size_t>(f.v[static_cast<std::size_t>(i % f.size)])]);
  };
  auto inside = [&](const BoundaryPolygon& f, const std::array<double, 2>& p) {
    bool in = false;
    for (int i = 0; i < f.size; ++i) {
      const auto a = corner(f, i), b = corner(f, i + 1);
      if ((a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1])) in = !in;
    }
    return in;
  };
  const FaceDepthGrid samples(mesh, faces, camera, 1.0);  // corner_sample only
  // The faces' image boxes bucketed in a square grid of about one face per
  // bucket, so that a sample meets only the faces whose box holds it (all
  // pairs took 46 s on 58k quads; review C #2).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<std::array<double, 4>> boxes(faces.size());  // x0, y0, x1, y1
  std::array<double, 4> all_box{kInf, kInf, -kInf, -kInf};
  for (std::size_t i = 0; i < faces.size(); ++i) {
    boxes[i] = {kInf, kInf, -kInf, -kInf};
    for (int k = 0; k < faces[i].size; ++k) {
      const auto q = corner(faces[i], k);
      boxes[i] = {std::min(boxes[i][0], q[0]), std::min(boxes[i][1], q[1]), std::max(boxes[i][2], q[0]),
                  std::max(boxes[i][3], q[1])};
    }
    all_box = {std::min(all_box[0], boxes[i][0]), std::min(all_box[1], boxes[i][1]), std::max(all_box[2], boxes[i][2]),
               std::max(all_box[3], boxes[i][3])};
  }
  const auto side = static_cast<std::size_t>(std::clamp(std::sqrt(static_cast<double>(faces.size())), 1.0, 1024.0));
  const double width = std::max(all_box[2] - all_box[0], 1e-300), height = std::max(all_box[3] - all_box[1], 1e-300);
  auto bucket = [&](double v, double lo, double extent) {
    return std::min(side - 1, static_cast<std::size_t>(std::max(0.0, (v - lo) / extent * static_cast<double>(side))));
  };
  std::vector<std::vector<std::uint32_t>> buckets(side * side);
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (std::size_t by = bucket(boxes[i][1], all_box[1], height); by <= bucket(boxes[i][3], all_box[1], height); ++by)
      for (std::size_t bx = bucket(boxes[i][0], all_box[0], width); bx <= bucket(boxes[i][2], all_box[0], width); ++bx)
        buckets[by * side + bx].push_back(static_cast<std::uint32_t>(i));
  auto under_another = [&](std::size_t i, const std::array<double, 2>& p) {
    if (p[0] < all_box[0] || p[0] > all_box[2] || p[1] < all_box[1] || p[1] > all_box[3]) return false;
    for (std::uint32_t j : buckets[bucket(p[1], all_box[1], height) * side + bucket(p[0], all_box[0], width)]) {
      const auto& b = boxes[j];
      if (j != i && p[0] >= b[0] && p[0] <= b[2] && p[1] >= b[1] && p[1] <= b[3] && inside(faces[j], p)) return true;
    }
    return false;
  };
  const std::vector<Index> sorted = [&] {
    std::vector<Index> s(cells.begin(), cells.end());
    std::sort(s.begin(), s.end());
    return s;
  }();
  std::vector<Index> seen, covered;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (!std::binary_search(sorted.begin(), sorted.end(), faces[i].cell)) continue;
    bool all = true;
    for (int k = 0; k < faces[i].size && all; ++k) all = under_another(i, image(samples.corner_sample(faces[i], k)));
    (all ? covered : seen).push_back(faces[i].cell);
  }
  // A cell with one face in sight is in sight.
  std::sort(seen.begin(), seen.end());
  std::sort(covered.begin(), covered.end());
  covered.erase(std::unique(covered.begin(), covered.end()), covered.end());
  std::erase_if(covered, [&](Index c) { return std::binary_search(seen.begin(), seen.end(), c); });
  return covered;
}

Vec3 overview_view_direction(const Vec3& up, const Vec3& front, double azimuth_degrees, double elevation_degrees) {
  // The front's own azimuth around up (upright.h's, from the file's front).
  return upright_view_direction(up, azimuth_degrees + view_azimuth_degrees(-front, up), elevation_degrees);
}

std::vector<Vec3> overview_view_candidates(const Vec3& up, const Vec3& front, bool below) {
  std::vector<Vec3> directions;
  for (double elevation : below ? std::span<const double>(kOverviewBelowElevations) : std::span<const double>(kOverviewElevations))
    for (double azimuth : kOverviewAzimuths) directions.push_back(overview_view_direction(up, front, azimuth, elevation));
  return directions;
}

std::string overview_side_name(const Vec3& view_direction, const Vec3& up, const Vec3& front, const std::string& front_name) {
  const Vec3 u = normalized(up);
  const Vec3 f = normalized(front - dot(front, u) * u), side = cross(u, f);
  const Vec3 eye = -normalized(view_direction);
  const double azimuth = std::atan2(dot(eye, side), dot(eye, f)) * 180.0 / kPi;  // (-180, 180]
  const std::string height = dot(eye, u) < 0.0 ? "below, " : "above, ";
  const std::string depth = std::abs(azimuth) < 90.0 ? "front " : "back ";
  const long degrees = std::lround(azimuth) < 0 ? std::lround(azimuth) + 360 : std::lround(azimuth) % 360;
  const long elevation = std::lround(std::asin(std::clamp(dot(eye, u), -1.0, 1.0)) * 180.0 / kPi);
  // Straight above or below (a planar mesh seen along its normal): no
  // side, no azimuth (issue 45g: "front left: azimuth 0, elevation 90").
  if (std::abs(elevation) == 90) return std::string(elevation > 0 ? "straight above" : "straight below") + " (elevation " + std::to_string(elevation) + " deg)";
  // The azimuth is from the front, the elevation from the horizontal (issue
  // 45: "azimuth 120, elevation 35 deg from the model's front" read as if
  // both were from the front).
  return height + depth + (azimuth > 0.0 ? "right" : "left") + " (azimuth " + std::to_string(degrees) + " deg from " +
         front_name + ", elevation " + std::to_string(elevation) + " deg)";
}

std::string overview_eye_words(const OverviewViewpoint& eye, const Vec3& up, const std::string& cell_noun) {
  const std::string inverted = "the inverted " + plural(cell_noun);
  const std::string front_name = !eye.front_from_target ? std::string("the model's front")
                                 : eye.target == WorstFaces::Kind::worst_cluster
                                     ? std::string("the worst cluster's side")
                                     : inverted + "' side";
  std::string words = ", from " + overview_side_name(eye.direction, up, eye.front, front_name);
  if (!eye.is_default)
    words += ", turned to show " + (eye.target == WorstFaces::Kind::inverted ? inverted : "the worst cluster");
  return words;
}

Vec3 model_front(const HexMesh& mesh, const Topology& topology, const Vec3& up) {
  return model_front_of(mesh, topology, up).front;
}

ModelFront model_front_of(const HexMesh& mesh, const Topology& topology, const Vec3& up) {
  const Vec3 u = normalized(up);
  Vec3 file_front = front_of(u);
  file_front = normalized(file_front - dot(file_front, u) * u);
  const Vec3 side = cross(u, file_front);
  // The area-weighted centres in (file_front, side) coordinates.
  struct Weighted {
    double x, y, w;
  };
  std::vector<Weighted> centres;
  double total = 0.0, mx = 0.0, my = 0.0;
  for (const BoundaryPolygon& face : boundary_polygons(topology)) {
    Vec3 c;
    for (int i = 0; i < face.size; ++i) c = c + mesh.points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])];
    c = (1.0 / face.size) * c;
    const Vec3& p0 = mesh.points[static_cast<std::size_t>(face.v[0])];
    const Vec3& p1 = mesh.points[static_cast<std::size_t>(face.v[1])];
    const Vec3& p2 = mesh.points[static_cast<std::size_t>(face.v[2])];
    const Vec3& p3 = mesh.points[static_cast<std::size_t>(face.v[face.size == 4 ? 3 : 0])];
    const double w = face.size == 4 ? 0.5 * norm(cross(p2 - p0, p3 - p1)) : 0.5 * norm(cross(p1 - p0, p2 - p0));
    if (!(w > 0.0) || !std::isfinite(w)) continue;
    centres.push_back({dot(c, file_front), dot(c, side), w});
    total += w;
    mx += w * centres.back().x;
    my += w * centres.back().y;
  }
  if (!(total > 0.0)) return {file_front};
  mx /= total, my /= total;
  double cxx = 0.0, cyy = 0.0, cxy = 0.0;
  for (const Weighted& c : centres) {
    cxx += c.w * (c.x - mx) * (c.x - mx);
    cyy += c.w * (c.y - my) * (c.y - my);
    cxy += c.w * (c.x - mx) * (c.y - my);
  }
  cxx /= total, cyy /= total, cxy /= total;
  const double mean = 0.5 * (cxx + cyy), half_gap = std::hypot(0.5 * (cxx - cyy), cxy);
  if (!(mean > 0.0) || half_gap / mean < kFrontIsotropy) return {file_front};
  // The larger spread's angle; the front is orthogonal to it.
  const double major = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
  const double ax = -std::sin(major), ay = std::cos(major);
  double m2 = 0.0, m3 = 0.0;
  for (const Weighted& c : centres) {
    const double t = ax * (c.x - mx) + ay * (c.y - my);
    m2 += c.w * t * t;
    m3 += c.w * t * t * t;
  }
  m2 /= total, m3 /= total;
  const double skew = m2 > 0.0 ? m3 / std::pow(m2, 1.5) : 0.0;
  const double sign = std::abs(skew) > kFrontSkew ? (skew > 0.0 ? 1.0 : -1.0)
                      : (ax != 0.0 ? (ax > 0.0 ? 1.0 : -1.0) : (ay >= 0.0 ? 1.0 : -1.0));
  return {normalized(sign * (ax * file_front + ay * side)), true, std::abs(skew) > kFrontSkew};
}

namespace {

// The flagged corners' mean (else inside_target) less the boundary
// corners' mean, and the boundary's extent (the largest of its bounding
// box's sides); a zero vector when there is no target.
std::pair<Vec3, double> flagged_offset(const HexMesh& mesh, const Topology& topology, const WorstFaces& worst,
                                       const std::optional<Vec3>& inside_target) {
  Vec3 all, mark;
  std::size_t n_all = 0, n_mark = 0;
  Box3 box;
  for (std::size_t i = 0; i < topology.boundary_faces.size(); ++i) {
    const Quad& q = topology.faces[static_cast<std::size_t>(topology.boundary_faces[i])];
    for (int k = 0; k < 4; ++k) {
      const Vec3& p = mesh.points[static_cast<std::size_t>(q[static_cast<std::size_t>(k)])];
      all = all + p, ++n_all, box.add(p);
      if (i < worst.flagged.size() && (worst.flagged[i] & (1 << k))) mark = mark + p, ++n_mark;
    }
  }
  if (n_all == 0 || (n_mark == 0 && !inside_target)) return {Vec3{}, 0.0};
  const Vec3 extent = box.hi - box.lo;
  const Vec3 target = n_mark > 0 ? (1.0 / static_cast<double>(n_mark)) * mark : *inside_target;
  return {target - (1.0 / static_cast<double>(n_all)) * all, std::max({extent.x, extent.y, extent.z})};
}

}  // namespace

OverviewViewpoint choose_overview_viewpoint(const HexMesh& mesh, const Topology& topology, const WorstFaces& worst,
                                            const Vec3& given_up, std::span<const Vec3> free_up,
                                            const std::optional<Vec3>& inside_target) {
  OverviewViewpoint out;
  Vec3 up = given_up;
  ModelFront front = model_front_of(mesh, topology, up);
  // A shape that tells neither its up nor its front (a ball): both from
  // the flagged faces (else the inverted cells inside), so that they turn
  // with the model.
  if (!front.axis_from_shape && !free_up.empty() && (worst.kind != WorstFaces::Kind::none || inside_target)) {
    const auto [d, extent] = flagged_offset(mesh, topology, worst, inside_target);
    if (!free_up.empty() && norm(d) > 0.0) {
      std::vector<double> along;
      for (const Vec3& u : free_up) along.push_back(dot(normalized(u), d));
      const auto best = static_cast<std::size_t>(std::max_element(along.begin(), along.end()) - along.begin());
      double second = -1e300;
      for (std::size_t i = 0; i < along.size(); ++i)
        if (i != best) second = std::max(second, along[i]);
      if (along[best] - second > kFrontDefectOffset * norm(d)) {
        up = normalized(free_up[best]);
        front = model_front_of(mesh, topology, up);
      }
    }
    if (!front.axis_from_shape) {
      const Vec3 u = normalized(up);
      const Vec3 across = d - dot(d, u) * u;
      if (norm(across) > kFrontDefectOffset * extent) {
        front = {normalized(across), true, true};
        out.front_from_target = true;
      }
    }
  }
  out.up = up;
  // A model symmetric across the plane: the front's sign towards the
  // flagged faces (their corners' mean against the boundary's), so that a
  // turned copy is seen from the same side of its defect.
  if (front.axis_from_shape && !front.sign_from_shape && (worst.kind != WorstFaces::Kind::none || inside_target)) {
    double all = 0.0, mark = 0.0, lo = 1e300, hi = -1e300;
    std::size_t n_all = 0, n_mark = 0;
    for (std::size_t i = 0; i < topology.boundary_faces.size(); ++i) {
      const Quad& q = topology.faces[static_cast<std::size_t>(topology.boundary_faces[i])];
      for (int k = 0; k < 4; ++k) {
        const double t = dot(mesh.points[static_cast<std::size_t>(q[static_cast<std::size_t>(k)])], front.front);
        all += t, ++n_all, lo = std::min(lo, t), hi = std::max(hi, t);
        if (i < worst.flagged.size() && (worst.flagged[i] & (1 << k))) mark += t, ++n_mark;
      }
    }
    // Nothing flagged on the boundary: the inverted cells inside (issue
    // 45g: a fandisk with interior defects turned 90 deg about x was seen
    // from the other side under the same words).
    if (n_mark == 0 && inside_target) mark = dot(*inside_target, front.front), n_mark = 1;
    if (n_mark > 0 && n_all > 0) {
      const double d = mark / static_cast<double>(n_mark) - all / static_cast<double>(n_all);
      if (std::abs(d) > kFrontDefectOffset * (hi - lo)) {
        if (d < 0.0) front.front = -front.front;
        front.sign_from_shape = true;
      }
    }
  }
  out.front = front.front;
  out.direction = overview_view_direction(up, out.front, kThreeQuarterAzimuth, kThreeQuarterElevation);
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
  const std::vector<Vec3> upright = overview_view_candidates(up, out.front, false);
  candidates.insert(candidates.end(), upright.begin(), upright.end());
  std::vector<double> score = scores(candidates);
  out.default_area = out.chosen_area = score[0];
  if (*std::max_element(score.begin(), score.end()) <= 0.0) {
    candidates = overview_view_candidates(up, out.front, true);
    score = scores(candidates);
  }
  const double top = *std::max_element(score.begin(), score.end());
  std::size_t best = 0;
  while (best + 1 < score.size() && score[best] < kNearBestFraction * top) ++best;
  // Inverted cells turn the eye by the fraction rule; a worst cluster (no
  // inverted corner) only when the three-quarter view shows none of it.
  const bool keep = worst.kind == WorstFaces::Kind::worst_cluster ? out.default_area > 0.0
                                                                   : out.default_area >= kKeepDefaultFraction * top;
  if (top <= 0.0 || keep) return out;
  out.direction = candidates[best];
  out.is_default = false;
  out.chosen_area = score[best];
  // A symmetric model's front is the side the eye is on (its words).
  if (front.axis_from_shape && !front.sign_from_shape && dot(-out.direction, out.front) < 0.0) out.front = -out.front;
  return out;
}

}  // namespace hq
