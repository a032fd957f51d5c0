#include "hqview/fem/q1_element.h"

#include <gtest/gtest.h>

#include <cmath>

#include "hqview/fem/fem_element_field.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

Q1Corners transformed(Q1Corners p, double scale, const Vec3& shift, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  for (Vec3& q : p) {
    const Vec3 r{c * q.x - s * q.z, q.y, s * q.x + c * q.z};  // about y
    q = scale * r + shift;
  }
  return p;
}

// Closed form: K_e of the unit cube has eigenvalues {0, 1/6, 1/3 (x3), 1/2 (x3)}.
TEST(Q1Element, UnitCubeEigenvalues) {
  const Q1Conditioning c = q1_conditioning(test::cube_corners());
  ASSERT_TRUE(c.is_valid);
  const std::array<double, 8> expected = {0, 1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 3, 0.5, 0.5, 0.5};
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(c.eigenvalues[i], expected[i], 1e-14) << i;
  EXPECT_NEAR(c.kappa, 3.0, 1e-13);
  EXPECT_NEAR(c.lambda_max, 0.5, 1e-14);
  EXPECT_DOUBLE_EQ(c.det_j_min, 0.125);
  EXPECT_DOUBLE_EQ(c.det_j_max, 0.125);
}

// A cube of side s: every eigenvalue times s, kappa unchanged, det J times s^3;
// rotations and translations change nothing else.
TEST(Q1Element, ScalesWithSideAndIgnoresRigidMotions) {
  const Q1Conditioning unit = q1_conditioning(test::twisted_hex(0.4));
  for (double s : {0.01, 2.5, 1000.0}) {
    const Q1Conditioning c = q1_conditioning(transformed(test::twisted_hex(0.4), s, {3, -7, 11}, 0.7));
    for (int i = 1; i < 8; ++i) EXPECT_NEAR(c.eigenvalues[i], s * unit.eigenvalues[i], 1e-12 * s) << s << " " << i;
    EXPECT_NEAR(c.kappa, unit.kappa, 1e-11 * unit.kappa);
    EXPECT_NEAR(c.det_j_min, s * s * s * unit.det_j_min, 1e-12 * s * s * s);
  }
  const Q1Conditioning cube = q1_conditioning(transformed(test::cube_corners(), 3.0, {1, 2, 3}, 0.3));
  EXPECT_NEAR(cube.lambda_max, 1.5, 1e-13);
  EXPECT_NEAR(cube.kappa, 3.0, 1e-12);
}

// K_e is symmetric, its rows sum to zero (constants are in its null space), and
// for a parallelepiped det J = volume / 8 at every Gauss point.
TEST(Q1Element, StiffnessIsSymmetricWithConstantNullSpace) {
  Q1Corners p = test::twisted_hex(0.5);
  p[6] = p[6] + Vec3{0.2, -0.1, 0.3};
  const Q1Matrix k = q1_laplace_stiffness(p);
  for (int i = 0; i < 8; ++i) {
    double row = 0;
    for (int j = 0; j < 8; ++j) {
      EXPECT_DOUBLE_EQ(k[8 * i + j], k[8 * j + i]);
      row += k[8 * i + j];
    }
    EXPECT_NEAR(row, 0, 1e-14);
    EXPECT_GT(k[8 * i + i], 0);
  }
  Q1Corners sheared = test::cube_corners();
  for (int i = 4; i < 8; ++i) sheared[i] = sheared[i] + Vec3{0.6, 0.3, 1.0};  // volume 2
  for (double d : q1_gauss_det_j(sheared)) EXPECT_NEAR(d, 0.25, 1e-15);
  EXPECT_GT(q1_conditioning(sheared).kappa, 3.0);
}

// Distortion raises kappa; an inverted or flattened hex is not a valid element.
TEST(Q1Element, DistortedAndInvalidElements) {
  double previous = 3.0 - 1e-12;
  for (double theta : {0.0, 0.3, 0.6, 0.9}) {
    const Q1Conditioning c = q1_conditioning(test::twisted_hex(theta));
    EXPECT_TRUE(c.is_valid);
    EXPECT_GT(c.kappa, previous) << theta;
    previous = c.kappa;
  }
  const Q1Conditioning inverted = q1_conditioning(test::inverted_hex());
  EXPECT_FALSE(inverted.is_valid);
  EXPECT_TRUE(std::isnan(inverted.kappa));
  EXPECT_NEAR(inverted.det_j_max, -0.125, 1e-15);
  Q1Corners flat = test::cube_corners();
  for (int i = 4; i < 8; ++i) flat[i].z = 0;
  EXPECT_FALSE(q1_conditioning(flat).is_valid);
}

// A corner pushed to the cube's centre: det J > 0 at every Gauss point (a
// valid Q1 element: its K_e is positive semi-definite), but the corner's
// edges (1/2)(1, -1, -1), (1/2)(-1, 1, -1), (1/2)(-1, -1, 1) have det -1/2,
// so det J there is -1/16: the trilinear map folds over near that corner.
// num_invalid (the Gauss points) misses it; num_not_invertible counts it.
TEST(FemElementField, CountsHexesWithANegativeCornerAsNotInvertible) {
  Q1Corners p = test::cube_corners();
  p[0] = {0.5, 0.5, 0.5};
  const Q1Conditioning c = q1_conditioning(p);
  EXPECT_TRUE(c.is_valid);
  EXPECT_GT(c.det_j_min, 0.008);
  EXPECT_NEAR(c.corner_det_j_min, -0.0625, 1e-15);
  EXPECT_FALSE(c.is_invertible);
  EXPECT_GT(c.eigenvalues[1], 0);  // still SPD off the constants
  EXPECT_TRUE(q1_conditioning(test::cube_corners()).is_invertible);
  HexMesh mesh = test::grid(1);
  mesh.points[static_cast<std::size_t>(mesh.hexes[0][0])] = p[0];
  const FemElementField f = compute_fem_elements(mesh);
  EXPECT_EQ(f.num_invalid, 0);
  EXPECT_EQ(f.num_not_invertible, 1);
  EXPECT_EQ(compute_fem_elements(test::grid(2)).num_not_invertible, 0);
}

TEST(FemElementField, CountsInvalidHexesAndKeepsFriedFactor) {
  HexMesh mesh = test::grid(3);
  mesh.points[static_cast<std::size_t>(mesh.hexes[13][6])] = {0.9, 0.9, 0.9};  // the centre hex turns over
  const FemElementField f = compute_fem_elements(mesh);
  ASSERT_EQ(f.kappa.size(), 27u);
  EXPECT_GE(f.num_invalid, 1);
  EXPECT_GE(f.num_not_invertible, f.num_invalid);  // an invalid hex is not invertible either
  EXPECT_TRUE(std::isnan(f.kappa[13]));
  EXPECT_LE(f.det_j_min[13], 0);
  EXPECT_EQ(f.kappa_stats.count + f.num_invalid, 27);
  const FemElementField g = compute_fem_elements(test::grid(2));
  EXPECT_EQ(g.num_invalid, 0);
  EXPECT_NEAR(g.max_lambda_max, 0.5, 1e-14);
  EXPECT_NEAR(g.kappa_stats.max, 3.0, 1e-12);
}

}  // namespace
}  // namespace hq
