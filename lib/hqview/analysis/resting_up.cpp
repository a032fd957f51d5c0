#include "hqview/analysis/resting_up.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "hqview/mesh/boundary_polygons.h"

namespace hq {

namespace {

using Point2 = std::array<double, 2>;

double cross2(const Point2& o, const Point2& a, const Point2& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// The convex hull, counter-clockwise, without collinear points (Andrew's
// monotone chain). Sorts `points`.
std::vector<Point2> convex_hull(std::vector<Point2>& points) {
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Point2> hull(2 * points.size());
  std::size_t k = 0;
  for (const Point2& p : points) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  const std::size_t lower = k + 1;
  for (std::size_t i = points.size() - 1; i-- > 0;) {
    while (k >= lower && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

double polygon_area(const std::vector<Point2>& hull) {
  double twice = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Point2& a = hull[i];
    const Point2& b = hull[(i + 1) % hull.size()];
    twice += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * std::abs(twice);
}

double segment_distance(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  const double length2 = dx * dx + dy * dy;
  double t = length2 > 0.0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2 : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  return std::hypot(p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy));
}

// Distance from p to the hull's boundary, positive inside, negative outside.
double signed_hull_distance(const Point2& p, const std::vector<Point2>& hull) {
  if (hull.empty()) return -std::numeric_limits<double>::infinity();
  if (hull.size() == 1) return -std::hypot(p[0] - hull[0][0], p[1] - hull[0][1]);
  double distance = std::numeric_limits<double>::infinity();
  bool inside = hull.size() >= 3;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Point2& a = hull[i];
    const Point2& b = hull[(i + 1) % hull.size()];
    distance = std::min(distance, segment_distance(p, a, b));
    if (cross2(a, b, p) < 0.0) inside = false;
  }
  return inside ? distance : -distance;
}

int axis_of(const Vec3& u) { return u.x != 0.0 ? 0 : u.y != 0.0 ? 1 : 2; }

struct Solid {
  Vec3 centre;
  double volume = 0.0;
  Vec3 lo, hi;
};

// Bounding box of the boundary, and the enclosed volume and its centroid
// (tetrahedra from the box centre to each boundary triangle, two per quad).
Solid solid_of(const HexMesh& mesh, const Topology& topology) {
  Solid s;
  const double inf = std::numeric_limits<double>::infinity();
  s.lo = {inf, inf, inf};
  s.hi = {-inf, -inf, -inf};
  for (Index v : topology.boundary_vertices) {
    const Vec3& p = mesh.points[static_cast<std::size_t>(v)];
    for (int i = 0; i < 3; ++i) {
      s.lo[i] = std::min(s.lo[i], p[i]);
      s.hi[i] = std::max(s.hi[i], p[i]);
    }
  }
  const Vec3 origin = 0.5 * (s.lo + s.hi);
  Vec3 moment{0.0, 0.0, 0.0};
  // Every kind's boundary faces (a hybrid mesh's hex quads alone are not a
  // closed surface); a pure-hex mesh sums exactly as before.
  for (const BoundaryPolygon& face : boundary_polygons(topology)) {
    std::array<Vec3, 4> p;
    for (int i = 0; i < face.size; ++i) p[i] = mesh.points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])] - origin;
    for (int t = 0; t < face.size - 2; ++t) {
      const Vec3& a = p[0];
      const Vec3& b = p[t + 1];
      const Vec3& c = p[t + 2];
      const double v = dot(a, cross(b, c)) / 6.0;
      s.volume += v;
      moment = moment + (v / 4.0) * (a + b + c);
    }
  }
  s.centre = s.volume != 0.0 ? origin + (1.0 / s.volume) * moment : origin;
  return s;
}

RestingCandidate evaluate(const HexMesh& mesh, const Topology& topology, const Solid& solid, const Vec3& up) {
  RestingCandidate c;
  c.up = up;
  const int k = axis_of(up);
  const double sign = up[k];
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const double band = kRestingBaseBand * norm(solid.hi - solid.lo);
  // Heights along up, the base at height 0.
  const double base = sign > 0.0 ? solid.lo[k] : -solid.hi[k];
  auto height = [&](const Vec3& p) { return sign * p[k] - base; };

  std::vector<Point2> band_points;
  for (Index v : topology.boundary_vertices) {
    const Vec3& p = mesh.points[static_cast<std::size_t>(v)];
    if (height(p) <= band) band_points.push_back({p[i], p[j]});
  }
  const std::vector<Point2> hull = convex_hull(band_points);
  c.support_area = polygon_area(hull);

  const double centre_height = height(solid.centre);
  const double margin = signed_hull_distance({solid.centre[i], solid.centre[j]}, hull);
  c.tip = centre_height > 0.0 ? margin / centre_height : (margin > 0.0 ? std::numeric_limits<double>::infinity() : -1.0);
  c.rests = c.tip > -kRestingTipTolerance;
  return c;
}

}  // namespace

std::vector<Vec3> resting_up_candidates() {
  return {{0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, {0.0, -1.0, 0.0}, {-1.0, 0.0, 0.0}};
}

bool resting_up_undecided(const RestingUp& resting) {
  if (resting.candidates.size() != 6) return false;
  double area = 0.0, tip = 1.0;
  for (const RestingCandidate& c : resting.candidates) {
    if (!c.rests) return false;
    area = std::max(area, c.support_area);
    tip = std::max(tip, std::abs(c.tip));
  }
  return std::all_of(resting.candidates.begin(), resting.candidates.end(), [&](const RestingCandidate& c) {
    return std::abs(c.support_area - resting.candidates[0].support_area) <= kRestingAlike * area &&
           std::abs(c.tip - resting.candidates[0].tip) <= kRestingAlike * tip;
  });
}

RestingUp choose_resting_up(const HexMesh& mesh, const Topology& topology) {
  RestingUp result;
  if (num_boundary_faces_all_kinds(topology) == 0) return result;
  const Solid solid = solid_of(mesh, topology);
  if (!(std::abs(solid.volume) > 0.0) || !std::isfinite(solid.volume) || !is_finite(solid.centre)) return result;
  result.candidates.reserve(6);
  for (const Vec3& up : resting_up_candidates()) result.candidates.push_back(evaluate(mesh, topology, solid, up));
  // 1. Alike opposite poses (both rest, support areas and tips within
  // kRestingAlike): the model is about mirror-symmetric across the plane
  // between them, so either pose lies on its side (an L bracket flat on its
  // L); they are left out while another candidate rests.
  const std::size_t n = result.candidates.size();  // 6: candidate k and k + 3 are opposite
  auto alike = [](double a, double b, double scale) { return std::abs(a - b) <= kRestingAlike * scale; };
  std::vector<char> on_side(n, 0);
  for (std::size_t k = 0; k < 3; ++k) {
    const RestingCandidate &a = result.candidates[k], &b = result.candidates[k + 3];
    if (a.rests && b.rests && alike(a.support_area, b.support_area, std::max(a.support_area, b.support_area)) &&
        alike(a.tip, b.tip, std::max({1.0, std::abs(a.tip), std::abs(b.tip)})))
      on_side[k] = on_side[k + 3] = 1;
  }
  // Left out only for a pose that stands firmly (its centre inside its
  // support: tip > 0): a twisted bar's sides rest on an edge within the
  // tolerance only, and it keeps its alike ends.
  bool upright_rests = false;
  for (std::size_t k = 0; k < n; ++k)
    upright_rests = upright_rests || (result.candidates[k].rests && !on_side[k] && result.candidates[k].tip > 0.0);
  // A box-like solid (it fills kRestingBoxFill of its bounding box: a box,
  // a tower, a plain slab) whose every resting pose has an alike opposite:
  // its flat sides cannot be told apart, so the file's axes win, as for a
  // cube (issue 46: a tower modelled z-up lay on its long side): the first
  // resting candidate in the prior order. (A stepped slab has unlike faces
  // and goes on below: it lies on its larger one.)
  const Vec3 extent = solid.hi - solid.lo;
  if (!upright_rests && std::abs(solid.volume) >= kRestingBoxFill * extent.x * extent.y * extent.z)
    for (const RestingCandidate& c : result.candidates)
      if (c.rests && c.support_area > 0.0) {
        result.up = c.up;
        result.from_data = true;
        return result;
      }
  auto eligible = [&](std::size_t k) { return result.candidates[k].rests && (!on_side[k] || !upright_rests); };
  double largest = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    if (eligible(k)) largest = std::max(largest, result.candidates[k].support_area);
  if (!(largest > 0.0)) return result;
  // 2. The first eligible candidate in the prior order whose support area
  // is within the margin of the largest.
  std::size_t chosen = n;
  for (std::size_t k = 0; k < n && chosen == n; ++k)
    if (eligible(k) && result.candidates[k].support_area * kRestingPriorMargin >= largest) chosen = k;
  // 3. A slab rests on either face: the larger base wins when it is larger by
  // more than kRestingFlipMargin, whatever the file's axes (so a turned copy
  // is not drawn upside down).
  const std::size_t opposite = (chosen + 3) % n;
  if (eligible(opposite) &&
      result.candidates[opposite].support_area > (1.0 + kRestingFlipMargin) * result.candidates[chosen].support_area)
    chosen = opposite;
  result.up = result.candidates[chosen].up;
  result.from_data = true;
  return result;
}

}  // namespace hq
