#include "hqview/quality/quality_field.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "hqview/quality/corner_jacobian.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

HexMesh perturbed_grid(int n) {
  HexMesh mesh = test::grid(n);
  // Deterministic perturbation, strong enough to invert a few corners.
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    const double t = static_cast<double>(i);
    mesh.points[i] = mesh.points[i] + 0.45 * Vec3{std::sin(1.3 * t), std::cos(2.1 * t), std::sin(0.7 * t + 1)};
  }
  return mesh;
}

TEST(QualityField, PerfectGridIsOne) {
  const HexMesh mesh = test::grid(3);
  const QualityField q = compute_quality(mesh, build_topology(mesh));
  for (double v : q.corner_scaled_jacobian) EXPECT_DOUBLE_EQ(v, 1.0);
  for (double v : q.vertex_quality) EXPECT_DOUBLE_EQ(v, 1.0);
  for (double v : q.cell_scaled_jacobian) EXPECT_DOUBLE_EQ(v, 1.0);
}

TEST(QualityField, VertexQualityIsMinOverIncidentCorners) {
  const HexMesh mesh = perturbed_grid(4);
  const QualityField q = compute_quality(mesh, build_topology(mesh));
  bool saw_negative = false;
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    double expected = INFINITY;
    for (Index h = 0; h < mesh.num_hexes(); ++h) {
      const auto cj = corner_scaled_jacobians(hex_corners(mesh, h));
      for (int i = 0; i < 8; ++i)
        if (mesh.hexes[h][i] == v) expected = std::min(expected, cj.value[i]);
    }
    EXPECT_EQ(q.vertex_quality[v], expected) << "vertex " << v;
    saw_negative |= expected < 0;
  }
  EXPECT_TRUE(saw_negative) << "the fixture should contain inverted corners";
}

TEST(QualityField, UnreferencedVertexHasNoQuality) {
  HexMesh mesh = test::unit_cube();
  mesh.points.push_back({3, 3, 3});
  const QualityField q = compute_quality(mesh, build_topology(mesh));
  EXPECT_TRUE(std::isnan(q.vertex_quality[8]));
}

TEST(QualityField, IdenticalForOneAndTwoThreads) {
  const HexMesh mesh = perturbed_grid(12);
  const Topology topo = build_topology(mesh);
  QualityField one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = compute_quality(mesh, topo);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = compute_quality(mesh, topo);
  }
  EXPECT_EQ(one.corner_scaled_jacobian, two.corner_scaled_jacobian);
  EXPECT_EQ(one.cell_scaled_jacobian, two.cell_scaled_jacobian);
  EXPECT_EQ(one.vertex_quality, two.vertex_quality);
}

}  // namespace
}  // namespace hq
