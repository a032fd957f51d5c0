// Upright viewpoints: the up names, the front axes, azimuth and elevation
// round trips, and the candidates (hand-computed directions).
#include "hqview/render/upright.h"

#include <gtest/gtest.h>

#include <cmath>

#include "hqview/render/camera.h"

namespace hq {
namespace HQ_TEST_UNIT {

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Upright, ParsesTheSixAxes) {
  EXPECT_EQ(parse_up_axis("+x"), (Vec3{1, 0, 0}));
  EXPECT_EQ(parse_up_axis("-y"), (Vec3{0, -1, 0}));
  EXPECT_EQ(parse_up_axis("z"), (Vec3{0, 0, 1}));
  EXPECT_FALSE(parse_up_axis("up"));
  EXPECT_FALSE(parse_up_axis("+"));
  EXPECT_FALSE(parse_up_axis("++x"));
  EXPECT_FALSE(parse_up_axis(""));
  for (const char* name : {"+x", "-x", "+y", "-y", "+z", "-z"}) EXPECT_EQ(up_axis_name(*parse_up_axis(name)), name);
  EXPECT_EQ(parse_up_axis(kDefaultUpAxis), (Vec3{0, 0, 1}));
}

TEST(Upright, FrontViewsFollowTheConventions) {
  // y up: the eye on +z, so +x is to the right (Stanford); z up: the eye on -y.
  expect_near(upright_view_direction({0, 1, 0}, 0.0, 0.0), {0, 0, -1});
  expect_near(upright_view_direction({0, 0, 1}, 0.0, 0.0), {0, 1, 0});
  // 90 degrees of azimuth turns the eye counter-clockwise seen from above:
  // y up, from +z to +x (up x front = y x z = x).
  expect_near(upright_view_direction({0, 1, 0}, 90.0, 0.0), {-1, 0, 0});
  // Elevation 30: the eye at (0, sin 30, cos 30).
  expect_near(upright_view_direction({0, 1, 0}, 0.0, 30.0), {0, -0.5, -std::sqrt(3.0) / 2.0});
  expect_near(upright_view_direction({0, 1, 0}, 0.0, -90.0), {0, 1, 0});
  // The right of a front camera is +x for both conventions.
  for (const Vec3 up : {Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
    const Vec3 d = upright_view_direction(up, 0.0, 20.0);
    const Camera camera = fit_camera_to_points(std::vector<Vec3>{{0, 0, 0}, {1, 1, 1}}, d, 1.0, {.up = up});
    const Vec3 right = normalized(cross(camera.target - camera.eye, camera.up));
    EXPECT_GT(right.x, 0.99);
  }
}

TEST(Upright, AzimuthAndElevationRoundTrip) {
  for (const char* name : {"+x", "-x", "+y", "-y", "+z", "-z"}) {
    const Vec3 up = *parse_up_axis(name);
    for (double azimuth : {-150.0, -30.0, 0.0, 45.0, 120.0, 180.0})
      for (double elevation : {-60.0, 0.0, 15.0, 35.0}) {
        const Vec3 d = upright_view_direction(up, azimuth, elevation);
        EXPECT_NEAR(norm(d), 1.0, 1e-12);
        EXPECT_NEAR(view_elevation_degrees(d, up), elevation, 1e-9) << name;
        const double gap = std::remainder(view_azimuth_degrees(d, up) - azimuth, 360.0);
        EXPECT_NEAR(gap, 0.0, 1e-9) << name << " azimuth " << azimuth;
      }
  }
  EXPECT_EQ(view_azimuth_degrees({0, -1, 0}, {0, 1, 0}), 0.0);  // straight above
}

TEST(Upright, CandidatesAreAboveTheHorizonAndFallbacksBelow) {
  const Vec3 up{0, 0, 1};
  const auto upright = upright_view_candidates(up);
  ASSERT_EQ(upright.size(), 36u);
  for (const Vec3& d : upright) {
    const double e = view_elevation_degrees(d, up);
    EXPECT_GE(e, 15.0 - 1e-9);
    EXPECT_LE(e, 35.0 + 1e-9);
  }
  EXPECT_NEAR(view_elevation_degrees(upright.front(), up), kUprightElevations[0], 1e-9);
  const auto below = below_view_candidates(up);
  for (const Vec3& d : below) EXPECT_LE(view_elevation_degrees(d, up), 1e-9);
  EXPECT_NEAR(view_elevation_degrees(below.back(), up), -90.0, 1e-9);
  EXPECT_NEAR(view_elevation_degrees(three_quarter_view(up), up), kThreeQuarterElevation, 1e-9);
  EXPECT_NEAR(view_azimuth_degrees(three_quarter_back_view(up), up), kThreeQuarterAzimuth - 180.0, 1e-9);
}

}  // namespace
}  // namespace hq
