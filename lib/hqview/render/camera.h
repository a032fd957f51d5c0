#pragma once
// Camera: where a view looks from, and the matrices OpenGL needs. A tiny
// column-major 4x4 matrix type keeps the renderer free of GLM.
//
// Conventions (OpenGL): eye space is right-handed with the camera at the
// origin looking down -z, +y up; clip space maps the view volume to the NDC
// cube [-1, 1]^3, NDC +y up (the top of the image).

#include <array>
#include <span>

#include "hqview/core/vec3.h"

namespace hq {

// A 4x4 matrix, column-major like OpenGL: element (row, col) is m[4 * col + row].
struct Mat4 {
  std::array<double, 16> m{};

  double& operator()(int row, int col) { return m[static_cast<std::size_t>(4 * col + row)]; }
  double operator()(int row, int col) const { return m[static_cast<std::size_t>(4 * col + row)]; }
};

Mat4 identity_matrix();
Mat4 translation_matrix(const Vec3& offset);
Mat4 operator*(const Mat4& a, const Mat4& b);
// a * (p, 1), then divided by w (points at w = 0 come back as infinities).
Vec3 transform_point(const Mat4& a, const Vec3& p);

struct Camera {
  Vec3 eye{0.0, 0.0, 1.0};       // model units
  Vec3 target{0.0, 0.0, 0.0};    // the point at the image centre
  Vec3 up{0.0, 0.0, 1.0};        // need not be orthogonal to target - eye, must not be parallel
  double fov_y_degrees = 30.0;   // full vertical field of view (perspective)
  double ortho_height = 2.0;     // full view height in model units (orthographic)
  double near_plane = 0.01;      // distances from the eye along the view direction, > 0
  double far_plane = 100.0;
  bool is_perspective = true;
};

// World -> eye: a rigid motion (rotation + translation), so normals transform
// with its upper 3x3 block.
Mat4 view_matrix(const Camera& camera);
// Eye -> clip for an image of width / height = aspect.
Mat4 projection_matrix(const Camera& camera, double aspect);
// A model point in NDC: x, y in [-1, 1] inside the image (y up), z in
// [-1, 1] between the near and far planes.
Vec3 project_to_ndc(const Camera& camera, double aspect, const Vec3& p);
// The unit axes of the image plane in model space: right and up on screen
// (right from the view direction and camera.up; x when they are parallel).
struct ScreenAxes {
  Vec3 right, up;
};
ScreenAxes screen_axes(const Camera& camera);

struct CameraFitOptions {
  Vec3 up{0.0, 0.0, 1.0};        // replaced by another axis when parallel to the view direction
  double fov_y_degrees = 30.0;
  double margin = 0.08;          // free border, as a fraction of the image half-size
  bool is_perspective = true;
};

// A camera looking along view_direction (from the eye towards the scene; any
// non-zero length, a zero vector means (-1, -1, -1)) that frames the given
// points as tightly as the margin allows: all of them project inside the
// image of the given aspect (width / height), their projection is centred,
// and the near / far planes enclose them. The camera's target lies in the
// plane through the points' bounding-box centre facing the camera. Fewer
// than two distinct points are padded to a unit-size box. Non-finite points
// are ignored.
Camera fit_camera_to_points(std::span<const Vec3> points, const Vec3& view_direction, double aspect,
                            const CameraFitOptions& options = {});

// fit_camera_to_points() over the 8 corners of the box [bbox_min, bbox_max]:
// the whole box is in view.
Camera fit_camera(const Vec3& bbox_min, const Vec3& bbox_max, const Vec3& view_direction, double aspect,
                  const CameraFitOptions& options = {});

}  // namespace hq
