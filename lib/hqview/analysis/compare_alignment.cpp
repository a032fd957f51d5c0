#include "hqview/analysis/compare_alignment.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "hqview/boundary/boundary_error.h"
#include "hqview/boundary/surface_distance.h"

namespace hq {
namespace {

Box3 used_box(const HexMesh& mesh) {
  std::vector<std::uint8_t> used(mesh.points.size(), 0);
  for (const Hex& h : mesh.hexes)
    for (Index v : h) used[static_cast<std::size_t>(v)] = 1;
  // A surface mesh (no volume cells): the points of its faces.
  if (is_surface_mesh(mesh)) {
    for (const auto& q : mesh.quads)
      for (Index v : q) used[static_cast<std::size_t>(v)] = 1;
    for (const auto& t : mesh.triangles)
      for (Index v : t) used[static_cast<std::size_t>(v)] = 1;
  }
  Box3 box;
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if (used[i]) box.add(mesh.points[i]);
  return box;
}

Vec3 centre(const Box3& box) { return 0.5 * (box.lo + box.hi); }

double determinant(const Matrix3& m) {
  return det(Vec3{m[0][0], m[0][1], m[0][2]}, Vec3{m[1][0], m[1][1], m[1][2]}, Vec3{m[2][0], m[2][1], m[2][2]});
}

// A similarity p -> scale * rotation * p + translation (rotation may be improper here).
struct Placement {
  double scale = 1.0;
  Matrix3 rotation = kIdentity3;
  Vec3 translation{};
  Vec3 apply(const Vec3& p) const { return scale * (rotation * p) + translation; }
  Vec3 inverse(const Vec3& p) const { return transposed(rotation) * ((p - translation) / scale); }
};

// Area-uniform, deterministic samples of a surface: systematic sampling of
// the cumulative area (sample i at (i + 0.5) / n of it), the position inside
// the triangle from the leftover fraction and a golden-ratio sequence.
std::vector<Vec3> sample_surface(const TriSurface& s, int n) {
  std::vector<double> cumulative;
  cumulative.reserve(s.triangles.size());
  double total = 0;
  for (const auto& t : s.triangles) {
    const Vec3 &a = s.points[static_cast<std::size_t>(t[0])], &b = s.points[static_cast<std::size_t>(t[1])],
               &c = s.points[static_cast<std::size_t>(t[2])];
    const double area = 0.5 * norm(cross(b - a, c - a));
    total += std::isfinite(area) ? area : 0.0;
    cumulative.push_back(total);
  }
  std::vector<Vec3> samples;
  if (!(total > 0.0)) return samples;
  samples.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double target = (i + 0.5) / n * total;
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
    const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()), cumulative.size() - 1);
    const double before = k == 0 ? 0.0 : cumulative[k - 1], area = cumulative[k] - before;
    const double u = area > 0 ? std::clamp((target - before) / area, 0.0, 1.0) : 0.5;
    const double v = std::fmod(0.5 + i * 0.6180339887498949, 1.0);
    const auto& t = s.triangles[k];
    const Vec3 &a = s.points[static_cast<std::size_t>(t[0])], &b = s.points[static_cast<std::size_t>(t[1])],
               &c = s.points[static_cast<std::size_t>(t[2])];
    const double r = std::sqrt(u);
    samples.push_back((1 - r) * a + (r * (1 - v)) * b + (r * v) * c);
  }
  return samples;
}

// The mean distance of each placement, both ways: moving's samples placed
// onto the fixed surface, and fixed's samples taken back onto the moving one
// (times the scale: in fixed's units). One closest-point call per surface.
std::vector<double> mean_distances(const TriSurface& fixed, const std::vector<Vec3>& fixed_samples,
                                   const TriSurface& moving, const std::vector<Vec3>& moving_samples,
                                   const std::vector<Placement>& placements) {
  std::vector<Vec3> forward, backward;
  forward.reserve(placements.size() * moving_samples.size());
  backward.reserve(placements.size() * fixed_samples.size());
  for (const Placement& p : placements) {
    for (const Vec3& q : moving_samples) forward.push_back(p.apply(q));
    for (const Vec3& q : fixed_samples) backward.push_back(p.inverse(q));
  }
  const std::vector<ClosestPoint> on_fixed = closest_points(fixed, forward);
  const std::vector<ClosestPoint> on_moving = closest_points(moving, backward);
  std::vector<double> result;
  const std::size_t nm = moving_samples.size(), nf = fixed_samples.size();
  for (std::size_t k = 0; k < placements.size(); ++k) {
    double f = 0, b = 0;
    for (std::size_t i = 0; i < nm; ++i) f += on_fixed[k * nm + i].distance;
    for (std::size_t i = 0; i < nf; ++i) b += on_moving[k * nf + i].distance;
    result.push_back(0.5 * (f / static_cast<double>(nm) + placements[k].scale * b / static_cast<double>(nf)));
  }
  return result;
}

// The mean distance of every placement: all of them on kCoarseAlignmentSamples
// samples per surface, then again on kAlignmentSamples those that matter
// (the identity (index 0), the kRefinedCandidates best proper and improper
// ones, the last (the box rule's own placement)); the others are out
// (infinite distance).
std::vector<double> scored_placements(const TriSurface& fixed, const TriSurface& moving,
                                      const std::vector<Placement>& placements) {
  std::vector<double> d = mean_distances(fixed, sample_surface(fixed, kCoarseAlignmentSamples), moving,
                                         sample_surface(moving, kCoarseAlignmentSamples), placements);
  std::vector<std::size_t> chosen{0, placements.size() - 1};
  for (const auto& [begin, end] : {std::pair<std::size_t, std::size_t>{0, 24}, {24, 48}}) {
    std::vector<std::size_t> order;
    for (std::size_t k = begin; k < end; ++k) order.push_back(k);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return d[a] < d[b]; });
    order.resize(std::min<std::size_t>(order.size(), kRefinedCandidates));
    chosen.insert(chosen.end(), order.begin(), order.end());
  }
  std::sort(chosen.begin(), chosen.end());
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  std::vector<Placement> fine;
  for (std::size_t k : chosen) fine.push_back(placements[k]);
  const std::vector<double> refined = mean_distances(fixed, sample_surface(fixed, kAlignmentSamples), moving,
                                                     sample_surface(moving, kAlignmentSamples), fine);
  std::fill(d.begin(), d.end(), INFINITY);
  for (std::size_t i = 0; i < chosen.size(); ++i) d[chosen[i]] = refined[i];
  return d;
}

// The box rule's placement `base` with `moving` turned by `rotation` about
// its box's centre first (the centre lands where the box rule puts it: only
// the rotation differs between candidates).
Placement turned_placement(const Matrix3& rotation, const Placement& base, const Box3& moving_box) {
  const Vec3 c = centre(moving_box);
  Placement p{base.scale, rotation, {}};
  p.translation = base.apply(c) - base.scale * (rotation * c);
  return p;
}

// The unit normal of a surface's triangle.
Vec3 triangle_normal(const TriSurface& s, Index triangle) {
  const auto& t = s.triangles[static_cast<std::size_t>(triangle)];
  const Vec3 &p0 = s.points[static_cast<std::size_t>(t[0])], &p1 = s.points[static_cast<std::size_t>(t[1])],
             &p2 = s.points[static_cast<std::size_t>(t[2])];
  return normalized(cross(p1 - p0, p2 - p0));
}

// Rigid symmetric point-to-plane ICP (Chen and Medioni 1992; the linearised
// step of Low 2004 solved as a 6 x 6 system, the rotation then made exact by
// Rodrigues' formula), the scale too when free (a bounding-box fit's scale is
// off by the box's growth under a turn that is no axis rotation). Both ways, as the distance is measured:
// moving's samples placed against their closest points on the fixed surface
// (its normals), and fixed's samples against their closest points on the
// placed moving surface (its normals turned): one way alone lets a blocky
// part slide along its faces and stall. Returns the refined placement.
Placement refine_by_icp(const TriSurface& fixed, const std::vector<Vec3>& fixed_samples, const TriSurface& moving,
                        const std::vector<Vec3>& moving_samples, const Placement& start, bool free_scale,
                        int& iterations) {
  Placement current = start, accepted = start;
  double previous = INFINITY;
  iterations = 0;
  for (int it = 0; it <= kIcpMaxIterations; ++it) {
    std::vector<Vec3> placed, back;
    placed.reserve(moving_samples.size());
    back.reserve(fixed_samples.size());
    for (const Vec3& q : moving_samples) placed.push_back(current.apply(q));
    for (const Vec3& q : fixed_samples) back.push_back(current.inverse(q));
    const std::vector<ClosestPoint> on_fixed = closest_points(fixed, placed);
    const std::vector<ClosestPoint> on_moving = closest_points(moving, back);
    // Unknowns: rotation vector, translation, relative scale change (about
    // the origin; kept 0 unless free_scale).
    Eigen::Matrix<double, 7, 7> a = Eigen::Matrix<double, 7, 7>::Zero();
    Eigen::Matrix<double, 7, 1> b = Eigen::Matrix<double, 7, 1>::Zero();
    // p (a placed point) should move onto the plane through q with normal n.
    const auto add = [&](const Vec3& p, const Vec3& q, const Vec3& n) {
      const Vec3 pn = cross(p, n);
      Eigen::Matrix<double, 7, 1> row;
      row << pn.x, pn.y, pn.z, n.x, n.y, n.z, free_scale ? dot(p, n) : 0.0;
      a += row * row.transpose();
      b += row * dot(q - p, n);
    };
    double forward = 0, backward = 0;
    for (std::size_t i = 0; i < placed.size(); ++i) {
      forward += on_fixed[i].distance;
      if (on_fixed[i].triangle != kNoIndex) add(placed[i], on_fixed[i].point, triangle_normal(fixed, on_fixed[i].triangle));
    }
    for (std::size_t i = 0; i < back.size(); ++i) {
      backward += on_moving[i].distance;
      if (on_moving[i].triangle == kNoIndex) continue;
      add(current.apply(on_moving[i].point), fixed_samples[i],
          current.rotation * triangle_normal(moving, on_moving[i].triangle));
    }
    const double mean = 0.5 * (forward / static_cast<double>(placed.size()) +
                               current.scale * backward / static_cast<double>(back.size()));
    if (!(mean < previous * (1 - 1e-6))) break;  // the last step did not help: keep the one before
    previous = mean;
    accepted = current;
    iterations = it;
    if (it == kIcpMaxIterations) break;
    if (!free_scale) a(6, 6) = 1.0;  // sigma = 0
    const Eigen::Matrix<double, 7, 1> x = a.ldlt().solve(b);
    if (!x.allFinite() || !(1.0 + x(6) > 0.5)) break;
    const Eigen::Vector3d omega(x(0), x(1), x(2));
    const double angle = omega.norm();
    const Eigen::Matrix3d r =
        angle > 0 ? Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
    Matrix3 step;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) step[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = r(i, j);
    const double grow = 1.0 + x(6);
    current.scale *= grow;
    current.rotation = step * current.rotation;
    current.translation = grow * (step * current.translation) + Vec3{x(3), x(4), x(5)};
  }
  return accepted;
}

// The axis of a rotation (unit; for 180 degrees the one with its first
// non-zero component positive).
Vec3 rotation_axis(const Matrix3& r) {
  const Vec3 skew{r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]};
  if (norm(skew) > 1e-9) return normalized(skew);
  // 180 degrees (or the identity): R + I = 2 a a^T; the largest column.
  Vec3 best{};
  for (int j = 0; j < 3; ++j) {
    const Vec3 col{r[0][static_cast<std::size_t>(j)] + (j == 0), r[1][static_cast<std::size_t>(j)] + (j == 1),
                   r[2][static_cast<std::size_t>(j)] + (j == 2)};
    if (norm(col) > norm(best) + 1e-12) best = col;
  }
  best = normalized(best);
  for (int i = 0; i < 3; ++i) {
    if (std::abs(best[i]) < 1e-9) continue;
    if (best[i] < 0) best = -best;
    break;
  }
  return best;
}

std::string axis_name(const Vec3& axis) {
  std::string name;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(axis[i]) < 1e-6) continue;
    name += axis[i] > 0 ? '+' : '-';
    name += static_cast<char>('x' + i);
  }
  return name;
}

std::string fixed3(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", std::abs(v) < 5e-4 ? 0.0 : v);
  return buf;
}

std::string display_scale(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", s);
  return buf;
}

// The rotation part of `a` (improper or proper) after the box rule: the
// whole search for auto.
void search_placements(const TriSurface& fixed, const Box3& fixed_box, const TriSurface& moving,
                       const Box3& moving_box, CompareAlignment& a) {
  const std::vector<Vec3> fixed_samples = sample_surface(fixed, kAlignmentSamples);
  const std::vector<Vec3> moving_samples = sample_surface(moving, kAlignmentSamples);
  if (fixed_samples.empty() || moving_samples.empty()) return;
  const double diagonal = fixed_box.diagonal();
  // Candidates: the box rule's placement (the identity rotation), the 23
  // other proper rotations, then the 24 improper ones (-R).
  const std::array<Matrix3, 24> rotations = axis_rotations();
  // The rotations are compared with the centres matched (whatever the box
  // rule did), so that an offset never passes for a rotation; the box
  // rule's own placement is scored last (index 48).
  const double scale = a.aligned ? a.scale : 1.0;
  const Placement box_rule{scale, kIdentity3, a.aligned ? a.translation : Vec3{}};
  const Placement centred{scale, kIdentity3, centre(fixed_box) - scale * centre(moving_box)};
  std::vector<Placement> placements;
  for (const Matrix3& r : rotations) placements.push_back(turned_placement(r, centred, moving_box));
  for (const Matrix3& r : rotations) {
    Matrix3 m = r;
    for (auto& row : m)
      for (double& x : row) x = -x;
    placements.push_back(turned_placement(m, centred, moving_box));
  }
  placements.push_back(box_rule);
  const std::vector<double> d = scored_placements(fixed, moving, placements);
  std::size_t best = 0;
  for (std::size_t k = 1; k < 24; ++k)
    if (d[k] < d[best]) best = k;
  if (!(d[best] < kRotationWinRatio * d[0])) best = 0;  // the identity unless clearly beaten
  std::size_t best_mirror = 24;
  for (std::size_t k = 25; k < 48; ++k)
    if (d[k] < d[best_mirror]) best_mirror = k;
  a.searched = true;
  a.identity_distance = d[48] / diagonal;
  a.axis_rotation = rotations[best];
  a.mirror_distance = d[best_mirror] / diagonal;
  a.mirrored = d[best_mirror] < kRotationWinRatio * d[best];
  if (a.mirrored) {
    // -R is the mirror across the plane normal to R's axis, turned about it.
    a.mirror_normal = rotation_axis(rotations[best_mirror - 24]);
  }
  // The identity keeps the box rule's placement (maybe none at all).
  Placement chosen = best == 0 ? box_rule : placements[best];
  double distance = best == 0 ? d[48] : d[best];
  a.axis_rotation_distance = distance / diagonal;
  const bool moved = best != 0 || a.aligned;
  if (moved) {
    int iterations = 0;
    const Placement refined =
        refine_by_icp(fixed, fixed_samples, moving, moving_samples, chosen, chosen.scale != 1.0, iterations);
    const double refined_distance = mean_distances(fixed, fixed_samples, moving, moving_samples, {refined})[0];
    if (iterations > 0 && refined_distance < (1.0 - kIcpMinGain) * distance) {
      chosen = refined;
      distance = refined_distance;
      a.icp_applied = true;
      a.icp_iterations = iterations;
    }
  }
  a.distance = distance / diagonal;
  a.aligned = moved;
  a.scale = chosen.scale;
  a.rotation = chosen.rotation;
  a.translation = chosen.translation;
}

}  // namespace

Vec3 operator*(const Matrix3& m, const Vec3& p) {
  return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z, m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z,
          m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z};
}

Matrix3 operator*(const Matrix3& a, const Matrix3& b) {
  Matrix3 m{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t k = 0; k < 3; ++k) m[i][j] += a[i][k] * b[k][j];
  return m;
}

Matrix3 transposed(const Matrix3& m) {
  Matrix3 t{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) t[i][j] = m[j][i];
  return t;
}

std::array<Matrix3, 24> axis_rotations() {
  std::array<Matrix3, 24> result{};
  std::size_t n = 0;
  std::array<int, 3> perm{0, 1, 2};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      Matrix3 m{};
      for (std::size_t i = 0; i < 3; ++i)
        m[i][static_cast<std::size_t>(perm[i])] = (signs >> i) & 1 ? -1.0 : 1.0;
      if (determinant(m) > 0) result[n++] = m;
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return result;  // the first permutation with no sign change is the identity
}

double rotation_angle_degrees(const Matrix3& r) {
  const double c = std::clamp((r[0][0] + r[1][1] + r[2][2] - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

std::string rotation_name(const Matrix3& r) {
  const double angle = rotation_angle_degrees(r);
  if (angle < 1e-6) return "identity";
  const Vec3 axis = rotation_axis(r);
  const double rounded = std::round(angle);
  bool is_axis = std::abs(angle - rounded) < 1e-6;
  for (int i = 0; i < 3 && is_axis; ++i)
    for (int j = 0; j < 3; ++j) {
      const double x = r[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      is_axis = is_axis && (std::abs(x) < 1e-9 || std::abs(std::abs(x) - 1.0) < 1e-9);
    }
  if (is_axis) return std::to_string(static_cast<int>(rounded)) + " deg about " + axis_name(axis);
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.1f deg about (%s, %s, %s)", angle, fixed3(axis.x).c_str(), fixed3(axis.y).c_str(),
                fixed3(axis.z).c_str());
  return buf;
}

CompareAlignment align_compare_mesh(const HexMesh& mesh, const Topology& topology, const HexMesh& other,
                                    const Topology& other_topology, CompareAlign requested) {
  const Box3 mine = used_box(mesh), theirs = used_box(other);
  if (requested != CompareAlign::auto_) return align_boxes(mine, theirs, requested);
  return align_surfaces(boundary_triangles(mesh, topology), mine, boundary_triangles(other, other_topology), theirs,
                        requested);
}

CompareAlignment align_boxes(const Box3& mine, const Box3& theirs, CompareAlign requested) {
  CompareAlignment a;
  a.requested = requested;
  if (mine.is_empty() || theirs.is_empty()) return a;
  const double dm = mine.diagonal(), dt = theirs.diagonal();
  if (!(dm > 0.0) || !(dt > 0.0) || !std::isfinite(dm) || !std::isfinite(dt)) return a;
  a.diagonal_ratio = dt / dm;
  a.boxes_overlap = mine.overlaps(theirs);
  const bool differ = a.diagonal_ratio > kAutoAlignDiagonalRatio || a.diagonal_ratio < 1.0 / kAutoAlignDiagonalRatio;
  a.aligned = requested == CompareAlign::bbox || (requested == CompareAlign::auto_ && (differ || !a.boxes_overlap));
  if (!a.aligned) return a;
  a.scale = dm / dt;
  a.translation = centre(mine) - a.scale * centre(theirs);
  return a;
}

CompareAlignment align_surfaces(const TriSurface& fixed, const Box3& fixed_box, const TriSurface& moving,
                                const Box3& moving_box, CompareAlign requested) {
  CompareAlignment a = align_boxes(fixed_box, moving_box, requested);
  const double dm = fixed_box.diagonal(), dt = moving_box.diagonal();
  if (requested != CompareAlign::auto_ || !(dm > 0.0) || !(dt > 0.0) || !std::isfinite(dm) || !std::isfinite(dt))
    return a;
  search_placements(fixed, fixed_box, moving, moving_box, a);
  return a;
}

Vec3 aligned_point(const Vec3& p, const CompareAlignment& alignment) {
  return alignment.aligned ? alignment.scale * (alignment.rotation * p) + alignment.translation : p;
}

HexMesh aligned_copy(const HexMesh& other, const CompareAlignment& alignment) {
  HexMesh copy = other;
  for (Vec3& p : copy.points) p = aligned_point(p, alignment);
  return copy;
}

std::string alignment_description(const CompareAlignment& a) {
  std::string text;
  if (a.aligned) {
    const bool turned = rotation_angle_degrees(a.rotation) > 1e-6;
    if (!turned) {
      text = "aligned by bounding box (scale " + display_scale(a.scale) + ")";
    } else {
      text = rotation_angle_degrees(a.axis_rotation) > 1e-6 ? "turned " + rotation_name(a.axis_rotation)
                                                            : "placed by bounding box";
      text += " (scale " + display_scale(a.scale) + ")";
      if (a.icp_applied) text += ", refined by ICP";
    }
  }
  if (a.mirrored)
    text += std::string(text.empty() ? "" : "; ") + "mirror image: no rotation fits (mirrored across the plane normal to " +
            axis_name(a.mirror_normal) + ")";
  return text;
}

const char* compare_align_name(CompareAlign mode) {
  switch (mode) {
    case CompareAlign::none:
      return "none";
    case CompareAlign::bbox:
      return "bbox";
    case CompareAlign::auto_:
      return "auto";
  }
  return "auto";
}

}  // namespace hq
