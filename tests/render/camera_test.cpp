#include "hqview/render/camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace hq {
namespace HQ_TEST_UNIT {

struct Case {
  Vec3 lo, hi, direction;
  double aspect;
  bool is_perspective;
};

std::vector<Case> cases() {
  const Vec3 boxes[][2] = {{{0, 0, 0}, {1, 1, 1}},
                           {{-5, 2, 100}, {15, 3, 101}},   // long and flat, far from the origin
                           {{0, 0, 0}, {0.01, 0.01, 10}}};  // a needle
  const Vec3 directions[] = {{-1, -0.8, -0.6}, {0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {0.3, -1, 0.2}, {-1, -1, -1}};
  const double aspects[] = {4.0 / 3.0, 1.0, 0.5, 2.5};
  std::vector<Case> out;
  for (const auto& box : boxes)
    for (const Vec3& d : directions)
      for (double a : aspects)
        for (bool persp : {true, false}) out.push_back({box[0], box[1], d, a, persp});
  return out;
}

TEST(FitCamera, AllCornersProjectInsideTheViewport) {
  for (const Case& c : cases()) {
    const Camera camera = fit_camera(c.lo, c.hi, c.direction, c.aspect, {.is_perspective = c.is_perspective});
    double reach = 0.0;  // how far the box extends towards the image border, in NDC
    for (int i = 0; i < 8; ++i) {
      const Vec3 corner{(i & 1) ? c.hi.x : c.lo.x, (i & 2) ? c.hi.y : c.lo.y, (i & 4) ? c.hi.z : c.lo.z};
      const Vec3 ndc = project_to_ndc(camera, c.aspect, corner);
      EXPECT_LE(std::abs(ndc.x), 1.0) << "corner " << i << " aspect " << c.aspect;
      EXPECT_LE(std::abs(ndc.y), 1.0) << "corner " << i << " aspect " << c.aspect;
      EXPECT_GT(ndc.z, -1.0) << "corner " << i << " behind the near plane";
      EXPECT_LT(ndc.z, 1.0) << "corner " << i << " beyond the far plane";
      reach = std::max({reach, std::abs(ndc.x), std::abs(ndc.y)});
    }
    // Tight: the box fills the image up to the margin on at least one side.
    EXPECT_GT(reach, 0.9) << "aspect " << c.aspect << " perspective " << c.is_perspective;
  }
}

TEST(FitCamera, LooksAlongTheViewDirectionAndCentresTheBox) {
  for (bool persp : {true, false}) {
    const double aspect = 4.0 / 3.0;
    const Camera camera = fit_camera({0, 0, 0}, {2, 2, 2}, {-1, -0.8, -0.6}, aspect, {.is_perspective = persp});
    const Vec3 view = normalized(camera.target - camera.eye);
    EXPECT_NEAR(dot(view, normalized(Vec3{-1, -0.8, -0.6})), 1.0, 1e-12);
    // The projected box is centred: exactly along the axis that limits the
    // distance, closely along the other (perspective shrinks far points).
    double x_lo = 2, x_hi = -2, y_lo = 2, y_hi = -2;
    for (int i = 0; i < 8; ++i) {
      const Vec3 ndc = project_to_ndc(camera, aspect, {(i & 1) ? 2.0 : 0.0, (i & 2) ? 2.0 : 0.0, (i & 4) ? 2.0 : 0.0});
      x_lo = std::min(x_lo, ndc.x), x_hi = std::max(x_hi, ndc.x);
      y_lo = std::min(y_lo, ndc.y), y_hi = std::max(y_hi, ndc.y);
    }
    EXPECT_NEAR(x_lo, -x_hi, 0.02);
    EXPECT_NEAR(y_lo, -y_hi, 1e-9);
    // The default margin (8%) is met exactly on the limiting axis.
    EXPECT_NEAR(std::max(x_hi, y_hi), 0.92, 1e-9);
    // +z points up in the image.
    const Vec3 below = project_to_ndc(camera, aspect, {1, 1, 0.5}), above = project_to_ndc(camera, aspect, {1, 1, 1.5});
    EXPECT_GT(above.y, below.y + 0.1);
    EXPECT_NEAR(above.x, below.x, 0.05);
  }
}

TEST(FitCameraToPoints, FramesPointsTighterThanTheirBox) {
  // Points on a sphere of radius 1: their box's corners stick out, the
  // points themselves fill the image up to the margin.
  std::vector<Vec3> points;
  for (int i = 0; i < 40; ++i)
    for (int j = 1; j < 20; ++j) {
      const double theta = i * 2 * 3.141592653589793 / 40, phi = j * 3.141592653589793 / 20;
      points.push_back({5 + std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta), std::cos(phi)});
    }
  const double aspect = 1.5;
  const Vec3 direction{-1, -0.8, -0.6};
  const Camera tight = fit_camera_to_points(points, direction, aspect);
  const Camera loose = fit_camera({4, -1, -1}, {6, 1, 1}, direction, aspect);
  EXPECT_LT(norm(tight.eye - tight.target), norm(loose.eye - loose.target));
  double reach = 0.0;
  for (const Vec3& p : points) {
    const Vec3 ndc = project_to_ndc(tight, aspect, p);
    EXPECT_LE(std::abs(ndc.x), 0.92 + 1e-9);
    EXPECT_LE(std::abs(ndc.y), 0.92 + 1e-9);
    EXPECT_GT(ndc.z, -1.0);
    EXPECT_LT(ndc.z, 1.0);
    reach = std::max({reach, std::abs(ndc.x), std::abs(ndc.y)});
  }
  EXPECT_NEAR(reach, 0.92, 1e-9);
}

TEST(FitCamera, DegenerateInputStillGivesAUsableCamera) {
  for (const Camera& camera : {fit_camera({1, 1, 1}, {1, 1, 1}, {0, 0, -1}, 1.0),   // a point, looking along up
                               fit_camera({0, 0, 0}, {1, 1, 1}, {0, 0, 0}, 1.0)}) {  // no direction
    const Vec3 ndc = project_to_ndc(camera, 1.0, camera.target);
    EXPECT_TRUE(is_finite(ndc));
    EXPECT_LT(camera.near_plane, camera.far_plane);
    EXPECT_GT(camera.near_plane, 0.0);
  }
}

TEST(Matrices, ViewMatrixIsRigidAndProjectionMapsNearFar) {
  Camera camera;
  camera.eye = {3, -2, 5};
  camera.target = {0, 1, 0};
  camera.up = {0, 0, 1};
  camera.near_plane = 0.5;
  camera.far_plane = 20.0;
  const Mat4 view = view_matrix(camera);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double d = 0.0;
      for (int k = 0; k < 3; ++k) d += view(i, k) * view(j, k);
      EXPECT_NEAR(d, i == j ? 1.0 : 0.0, 1e-12);
    }
  const Vec3 eye = transform_point(view, camera.eye);
  EXPECT_NEAR(norm(eye), 0.0, 1e-12);
  const Vec3 forward = normalized(camera.target - camera.eye);
  const Vec3 near_point = project_to_ndc(camera, 1.0, camera.eye + 0.5 * forward);
  const Vec3 far_point = project_to_ndc(camera, 1.0, camera.eye + 20.0 * forward);
  EXPECT_NEAR(near_point.z, -1.0, 1e-9);
  EXPECT_NEAR(far_point.z, 1.0, 1e-9);
  const Mat4 product = identity_matrix() * translation_matrix({1, 2, 3});
  const Vec3 moved = transform_point(product, {1, 1, 1});
  EXPECT_EQ(moved, (Vec3{2, 3, 4}));
}

}  // namespace
}  // namespace hq
