#include "hqview/render/camera.h"

#include "hqview/core/box3.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace hq {
namespace {

struct Basis {
  Vec3 right, up, back;  // eye-space x, y, z axes in model coordinates
};

Basis camera_basis(const Vec3& view_direction, const Vec3& up_hint) {
  const Vec3 back = normalized(-view_direction);
  Vec3 right = cross(up_hint, back);
  if (squared_norm(right) < 1e-12 * squared_norm(up_hint)) {
    // Looking straight along the up hint: any perpendicular up will do; pick
    // the model axis least aligned with the view.
    const Vec3 axes[3] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
    Vec3 best = axes[0];
    for (const Vec3& a : axes)
      if (std::abs(dot(a, back)) < std::abs(dot(best, back))) best = a;
    right = cross(best, back);
  }
  right = normalized(right);
  return {right, cross(back, right), back};
}

}  // namespace

Mat4 identity_matrix() {
  Mat4 a;
  for (int i = 0; i < 4; ++i) a(i, i) = 1.0;
  return a;
}

Mat4 translation_matrix(const Vec3& offset) {
  Mat4 a = identity_matrix();
  a(0, 3) = offset.x;
  a(1, 3) = offset.y;
  a(2, 3) = offset.z;
  return a;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 c;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k) s += a(row, k) * b(k, col);
      c(row, col) = s;
    }
  return c;
}

Vec3 transform_point(const Mat4& a, const Vec3& p) {
  double out[4];
  for (int row = 0; row < 4; ++row) out[row] = a(row, 0) * p.x + a(row, 1) * p.y + a(row, 2) * p.z + a(row, 3);
  return {out[0] / out[3], out[1] / out[3], out[2] / out[3]};
}

Mat4 view_matrix(const Camera& camera) {
  const Basis basis = camera_basis(camera.target - camera.eye, camera.up);
  Mat4 a = identity_matrix();
  const Vec3 rows[3] = {basis.right, basis.up, basis.back};
  for (int row = 0; row < 3; ++row) {
    a(row, 0) = rows[row].x;
    a(row, 1) = rows[row].y;
    a(row, 2) = rows[row].z;
    a(row, 3) = -dot(rows[row], camera.eye);
  }
  return a;
}

Mat4 projection_matrix(const Camera& camera, double aspect) {
  const double n = camera.near_plane, f = camera.far_plane;
  Mat4 a;
  if (camera.is_perspective) {
    const double cot = 1.0 / std::tan(0.5 * camera.fov_y_degrees * std::numbers::pi / 180.0);
    a(0, 0) = cot / aspect;
    a(1, 1) = cot;
    a(2, 2) = -(f + n) / (f - n);
    a(2, 3) = -2.0 * f * n / (f - n);
    a(3, 2) = -1.0;
  } else {
    const double half_h = 0.5 * camera.ortho_height, half_w = half_h * aspect;
    a(0, 0) = 1.0 / half_w;
    a(1, 1) = 1.0 / half_h;
    a(2, 2) = -2.0 / (f - n);
    a(2, 3) = -(f + n) / (f - n);
    a(3, 3) = 1.0;
  }
  return a;
}

Vec3 project_to_ndc(const Camera& camera, double aspect, const Vec3& p) {
  return transform_point(projection_matrix(camera, aspect) * view_matrix(camera), p);
}

ScreenAxes screen_axes(const Camera& camera) {
  const Vec3 d = normalized(camera.target - camera.eye);
  Vec3 right = cross(d, camera.up);
  if (!(squared_norm(right) > 0.0)) right = cross(d, Vec3{1.0, 0.0, 0.0});
  right = normalized(right);
  return {right, cross(right, d)};
}

Camera fit_camera_to_points(std::span<const Vec3> points, const Vec3& view_direction, double aspect,
                            const CameraFitOptions& options) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box3 bounds;
  for (const Vec3& p : points)
    if (is_finite(p)) bounds.add(p);
  if (bounds.is_empty()) bounds.lo = bounds.hi = Vec3{};
  const Vec3 lo = bounds.lo, hi = bounds.hi;
  const bool is_degenerate = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) <= 0.0;
  if (is_degenerate) {  // a single point: frame a unit box around it
    const Vec3 c = lo;
    const std::array<Vec3, 8> box = {{c + Vec3{-0.5, -0.5, -0.5}, c + Vec3{0.5, -0.5, -0.5}, c + Vec3{-0.5, 0.5, -0.5},
                                      c + Vec3{0.5, 0.5, -0.5}, c + Vec3{-0.5, -0.5, 0.5}, c + Vec3{0.5, -0.5, 0.5},
                                      c + Vec3{-0.5, 0.5, 0.5}, c + Vec3{0.5, 0.5, 0.5}}};
    return fit_camera_to_points(box, view_direction, aspect, options);
  }
  const Vec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * norm(hi - lo);

  const Vec3 direction = squared_norm(view_direction) > 0.0 ? view_direction : Vec3{-1.0, -1.0, -1.0};
  const Basis basis = camera_basis(direction, options.up);
  const double fill = 1.0 - std::clamp(options.margin, 0.0, 0.9);
  const double tan_y = std::tan(0.5 * std::clamp(options.fov_y_degrees, 1e-3, 179.0) * std::numbers::pi / 180.0) * fill;
  const double tan_x = tan_y * aspect;

  // In the camera basis centred on the box, a point (x, y, z) seen from an
  // eye at (sx, sy, d) projects inside the image when
  //   |x - sx| <= tan_x (d - z)  and  |y - sy| <= tan_y (d - z),
  // i.e. max(x + tan_x z) - tan_x d <= sx <= min(x - tan_x z) + tan_x d.
  // The smallest d that leaves room for sx (and sy) frames the points
  // exactly, and the midpoint of that room centres them.
  double x_plus = -inf, x_minus = inf, y_plus = -inf, y_minus = inf;  // perspective bounds
  double x_lo = inf, x_hi = -inf, y_lo = inf, y_hi = -inf, z_lo = inf, z_hi = -inf;
  for (const Vec3& p : points) {
    if (!is_finite(p)) continue;
    const Vec3 r = p - centre;
    const double x = dot(r, basis.right), y = dot(r, basis.up), z = dot(r, basis.back);
    x_plus = std::max(x_plus, x + tan_x * z);
    x_minus = std::min(x_minus, x - tan_x * z);
    y_plus = std::max(y_plus, y + tan_y * z);
    y_minus = std::min(y_minus, y - tan_y * z);
    x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
    y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    z_lo = std::min(z_lo, z), z_hi = std::max(z_hi, z);
  }

  Camera camera;
  camera.up = basis.up;
  camera.fov_y_degrees = options.fov_y_degrees;
  camera.is_perspective = options.is_perspective;
  double sx = 0.0, sy = 0.0, distance = 0.0;
  if (options.is_perspective) {
    distance = std::max((x_plus - x_minus) / (2.0 * tan_x), (y_plus - y_minus) / (2.0 * tan_y));
    // Keep the eye outside the points' depth range, whatever the field of view.
    distance = std::max(distance, z_hi + 1e-3 * radius);
    sx = 0.5 * (x_plus + x_minus);
    sy = 0.5 * (y_plus + y_minus);
  } else {
    sx = 0.5 * (x_lo + x_hi);
    sy = 0.5 * (y_lo + y_hi);
    camera.ortho_height = std::max(y_hi - y_lo, (x_hi - x_lo) / aspect) / fill;
    if (!(camera.ortho_height > 0.0)) camera.ortho_height = 2.0 * radius;
    distance = z_hi + radius;  // any eye in front of the points will do
  }
  camera.target = centre + sx * basis.right + sy * basis.up;
  camera.eye = camera.target + distance * basis.back;
  const double slack = 0.01 * radius;
  camera.near_plane = std::max(distance - z_hi - slack, 1e-4 * distance);
  camera.far_plane = distance - z_lo + slack;
  return camera;
}

Camera fit_camera(const Vec3& bbox_min, const Vec3& bbox_max, const Vec3& view_direction, double aspect,
                  const CameraFitOptions& options) {
  std::array<Vec3, 8> corners;
  for (int i = 0; i < 8; ++i)
    corners[static_cast<std::size_t>(i)] = {(i & 1) ? bbox_max.x : bbox_min.x, (i & 2) ? bbox_max.y : bbox_min.y,
                                            (i & 4) ? bbox_max.z : bbox_min.z};
  return fit_camera_to_points(corners, view_direction, aspect, options);
}

}  // namespace hq
