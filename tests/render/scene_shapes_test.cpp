// Arrows, arrow layout and the back-to-front sort, without OpenGL.
#include "hqview/render/scene_shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hq {
namespace HQ_TEST_UNIT {

Camera looking_down_z() {
  Camera camera;
  camera.eye = {0, 0, 5};
  camera.target = {0, 0, 0};
  camera.up = {0, 1, 0};
  return camera;
}

TEST(AppendArrow, SpansTailToTipWithTheConeAtTheTip) {
  TriangleSet set;
  const ArrowShape shape{0.05f, 0.15f, 0.3f, 12};
  append_arrow(set, {0, 0, 0}, {0, 0, 2}, shape, Rgba8{10, 20, 30, 255});
  ASSERT_FALSE(set.indices.empty());
  EXPECT_EQ(set.indices.size() % 3, 0u);
  EXPECT_EQ(set.normals.size(), set.positions.size());
  EXPECT_EQ(set.colors.size(), set.positions.size());
  float zmin = 1e9f, zmax = -1e9f, widest_near_tip = 0.0f, widest_near_tail = 0.0f;
  for (const Vec3f& p : set.positions) {
    zmin = std::min(zmin, p.z);
    zmax = std::max(zmax, p.z);
    const float r = std::hypot(p.x, p.y);
    if (p.z > 1.0f) widest_near_tip = std::max(widest_near_tip, r);
    else widest_near_tail = std::max(widest_near_tail, r);
  }
  EXPECT_FLOAT_EQ(zmin, 0.0f);
  EXPECT_FLOAT_EQ(zmax, 2.0f);
  EXPECT_NEAR(widest_near_tip, 0.15f, 1e-5f) << "the cone is at the tip end";
  EXPECT_NEAR(widest_near_tail, 0.05f, 1e-5f) << "only the shaft at the tail end";
  for (std::uint32_t i : set.indices) EXPECT_LT(i, set.positions.size());
}

TEST(AppendArrow, ZeroLengthAddsNothing) {
  TriangleSet set;
  append_arrow(set, {1, 1, 1}, {1, 1, 1}, {0.1f, 0.2f, 0.3f, 8}, Rgba8{});
  EXPECT_TRUE(set.positions.empty());
  EXPECT_TRUE(set.indices.empty());
}

TEST(ArrowDirections, SpreadEvenlyInTheImagePlaneFromAFixedAngle) {
  const Camera camera = looking_down_z();
  const auto d = arrow_directions(camera, 4, 0.0);
  ASSERT_EQ(d.size(), 4u);
  // The first arrow sits on the image's +x side of its target and points to -x.
  EXPECT_NEAR(d[0].x, -1.0, 1e-12);
  EXPECT_NEAR(d[0].y, 0.0, 1e-12);
  EXPECT_NEAR(d[1].y, -1.0, 1e-12) << "90 degrees later: above the target, pointing down";
  for (const Vec3& v : d) {
    EXPECT_NEAR(v.z, 0.0, 1e-12) << "in the image plane";
    EXPECT_NEAR(norm(v), 1.0, 1e-12);
  }
  for (std::size_t i = 0; i < d.size(); ++i)
    EXPECT_NEAR(dot(d[i], d[(i + 1) % d.size()]), 0.0, 1e-12) << "360/4 degrees apart";
  EXPECT_EQ(arrow_directions(camera, 3, 45.0), arrow_directions(camera, 3, 45.0)) << "deterministic";
  EXPECT_TRUE(arrow_directions(camera, 0).empty());
}

TEST(BackToFront, FarthestTriangleFirst) {
  TriangleSet set;
  for (float z : {0.0f, -2.0f, 1.0f}) {
    const auto base = static_cast<std::uint32_t>(set.positions.size());
    set.positions.insert(set.positions.end(), {{0, 0, z}, {1, 0, z}, {0, 1, z}});
    set.colors.insert(set.colors.end(), 3, Rgba8{});
    set.indices.insert(set.indices.end(), {base, base + 1, base + 2});
  }
  const Camera camera = looking_down_z();
  const auto order = back_to_front_order(set, view_matrix(camera));
  EXPECT_EQ(order, (std::vector<std::uint32_t>{1, 0, 2}));
  const auto indices = sorted_indices(set, order);
  EXPECT_EQ(indices, (std::vector<std::uint32_t>{3, 4, 5, 0, 1, 2, 6, 7, 8}));
}

}  // namespace
}  // namespace hq
