// Per-corner scaled Jacobians and orientation of tets, wedges, pyramids,
// quads and triangles: ideal cells score 1 at every corner; the minimum over
// the corners relates to Verdict 1.4.5's scaled_jacobian as documented in
// cell_corner_jacobian.h on every case of cell_oracle_cases.json; mirrored,
// tangled and flat cells are told apart.

#include "hqview/quality/cell_corner_jacobian.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "hqview/core/cell_kinds.h"

#include "support/verdict_oracle.h"

namespace hq {
namespace HQ_TEST_UNIT {

const double s3 = std::sqrt(3.0);
const std::array<Vec3, 4> kTet = {Vec3{0, 0, 0}, {1, 0, 0}, {0.5, s3 / 2, 0}, {0.5, s3 / 6, std::sqrt(2.0 / 3.0)}};
// VTK order: the normal of (0,1,2) points away from (3,4,5).
const std::array<Vec3, 6> kWedge = {Vec3{0, 0, 0}, {0, 1, 0}, {s3 / 2, 0.5, 0}, {0, 0, 1}, {0, 1, 1}, {s3 / 2, 0.5, 1}};
const std::array<Vec3, 5> kPyramid = {Vec3{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, std::sqrt(0.5)}};
const std::array<Vec3, 4> kQuad = {Vec3{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::array<Vec3, 3> kTriangle = {Vec3{0, 0, 0}, {1, 0, 0}, {0.5, s3 / 2, 0}};

template <std::size_t C>
double min_of(const KindCornerJacobians<C>& c) {
  return *std::min_element(c.value.begin(), c.value.end());
}
template <std::size_t C>
double max_of(const KindCornerJacobians<C>& c) {
  return *std::max_element(c.value.begin(), c.value.end());
}

template <std::size_t N>
std::array<Vec3, N> mirrored(std::array<Vec3, N> p) {
  for (auto& v : p) v.x = -v.x;
  return p;
}

TEST(CellCornerJacobian, IdealCellsScoreOneAtEveryCorner) {
  for (double v : tet_corner_scaled_jacobians(kTet).value) EXPECT_NEAR(v, 1.0, 1e-15);
  for (double v : wedge_corner_scaled_jacobians(kWedge).value) EXPECT_NEAR(v, 1.0, 1e-15);
  for (double v : pyramid_corner_scaled_jacobians(kPyramid).value) EXPECT_NEAR(v, 1.0, 1e-15);
  for (double v : quad_corner_scaled_jacobians(kQuad).value) EXPECT_NEAR(v, 1.0, 1e-15);
  for (double v : triangle_corner_scaled_jacobians(kTriangle).value) EXPECT_NEAR(v, 1.0, 1e-15);
  EXPECT_EQ(tet_validity(kTet), CellValidity::valid);
  EXPECT_EQ(wedge_validity(kWedge), CellValidity::valid);
  EXPECT_EQ(pyramid_validity(kPyramid), CellValidity::valid);
  EXPECT_EQ(quad_validity(kQuad), CellValidity::valid);
  EXPECT_EQ(triangle_validity(kTriangle), CellValidity::valid);
}

TEST(CellCornerJacobian, HandComputedCorners) {
  // Right-corner tet: corner 0 has orthogonal unit edges (sqrt(2), clamped
  // to 1); corner 1: edges (-1,0,0), (-1,1,0), (-1,0,1): det 1 over
  // 1 * sqrt(2) * sqrt(2), times sqrt(2) = 0.7071.
  const std::array<Vec3, 4> right = {Vec3{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const auto t = tet_corner_scaled_jacobians(right);
  EXPECT_EQ(t.value[0], 1.0);
  EXPECT_NEAR(t.value[1], std::sqrt(0.5), 1e-15);
  // Pyramid with the apex one edge high: base corner det 1 over
  // 1 * 1 * sqrt(1.5), times sqrt(2) = 1.1547, folded to 2 - 1.1547.
  auto tall = kPyramid;
  tall[4].z = 1.0;
  for (double v : pyramid_corner_scaled_jacobians(tall).value) EXPECT_NEAR(v, 2.0 - 2.0 / s3, 1e-15);
  // A parallelogram quad sheared by 0.5: every corner 1 / sqrt(1.25).
  const std::array<Vec3, 4> sheared = {Vec3{0, 0, 0}, {1, 0, 0}, {1.5, 1, 0}, {0.5, 1, 0}};
  for (double v : quad_corner_scaled_jacobians(sheared).value) EXPECT_NEAR(v, 1.0 / std::sqrt(1.25), 1e-15);
  // A collapsed tet edge is degenerate at its two ends.
  auto collapsed = kTet;
  collapsed[1] = collapsed[0];
  EXPECT_EQ(tet_corner_scaled_jacobians(collapsed).degenerate_mask, 0b0011);
}

TEST(CellCornerJacobian, MinimumOverCornersRelatesToVerdictOnEveryOracleCase) {
  const auto oracle = test::load_cell_oracle();
  if (oracle.is_null()) GTEST_SKIP() << "../shared/data absent: Verdict oracle not available";
  int compared = 0;
  for (const auto& c : oracle["cases"]) {
    const std::string kind = c["kind"];
    const auto& co = c["coords"];
    auto at = [&](int i) { return Vec3{co[i][0].get<double>(), co[i][1].get<double>(), co[i][2].get<double>()}; };
    const double verdict = c["verdict_1_4_5_built_locally"]["scaled_jacobian"].get<double>();
    SCOPED_TRACE(kind + " " + c["name"].get<std::string>());
    if (kind == "tet") {
      const std::array<Vec3, 4> p = {at(0), at(1), at(2), at(3)};
      const auto corners = tet_corner_scaled_jacobians(p);
      if (corners.degenerate_mask) continue;  // Verdict: 1e30 (all coincident) or 0
      const bool inverted = is_inverted(tet_validity(p));
      EXPECT_NEAR(inverted ? max_of(corners) : min_of(corners), verdict, 1e-12);
      ++compared;
    } else if (kind == "wedge") {
      const std::array<Vec3, 6> p = {at(0), at(1), at(2), at(3), at(4), at(5)};
      const auto corners = wedge_corner_scaled_jacobians(p);
      if (corners.degenerate_mask) continue;
      EXPECT_NEAR(min_of(corners), verdict, 1e-12);
      ++compared;
    } else if (kind == "pyramid") {
      const std::array<Vec3, 5> p = {at(0), at(1), at(2), at(3), at(4)};
      const auto corners = pyramid_corner_scaled_jacobians(p);
      // Verdict's 0 (never negative) and a corner <= 0 go together.
      if (std::abs(verdict) < 1e30) {
        EXPECT_EQ(verdict == 0.0, pyramid_validity(p) != CellValidity::valid);
        EXPECT_EQ(verdict == 0.0, min_of(corners) <= 0.0);
        ++compared;
      }
    } else if (kind == "quad") {
      const std::array<Vec3, 4> p = {at(0), at(1), at(2), at(3)};
      const auto corners = quad_corner_scaled_jacobians(p);
      if (corners.degenerate_mask) continue;  // includes P3 == P2 (Verdict scores the triangle)
      EXPECT_NEAR(min_of(corners), verdict, 1e-12);
      ++compared;
    } else if (kind == "tri") {
      const std::array<Vec3, 3> p = {at(0), at(1), at(2)};
      const auto corners = triangle_corner_scaled_jacobians(p);
      if (corners.degenerate_mask) continue;
      EXPECT_NEAR(min_of(corners), verdict, 1e-12);
      ++compared;
    }
  }
  EXPECT_EQ(compared, 25 + 17 + 19 + 20 + 17);  // the non-degenerate cases per kind
}

TEST(CellCornerJacobian, MirroredTangledAndFlatCells) {
  // Mirrored: inverted, every corner -1 for the ideal cells.
  EXPECT_EQ(tet_validity(mirrored(kTet)), CellValidity::inverted);
  EXPECT_EQ(wedge_validity(mirrored(kWedge)), CellValidity::inverted);
  EXPECT_EQ(pyramid_validity(mirrored(kPyramid)), CellValidity::inverted);
  EXPECT_NEAR(max_of(tet_corner_scaled_jacobians(mirrored(kTet))), -1.0, 1e-15);
  EXPECT_NEAR(max_of(wedge_corner_scaled_jacobians(mirrored(kWedge))), -1.0, 1e-15);
  EXPECT_NEAR(max_of(pyramid_corner_scaled_jacobians(mirrored(kPyramid))), -1.0, 1e-15);
  // Tangled wedge: the top triangle's corners 4 and 5 swapped (its top
  // corners' frames turn left-handed, its bottom ones stay right-handed).
  auto tangled = kWedge;
  std::swap(tangled[4], tangled[5]);
  EXPECT_EQ(wedge_validity(tangled), CellValidity::inverted);
  EXPECT_LT(min_of(wedge_corner_scaled_jacobians(tangled)), 0.0);
  // A pyramid whose apex pokes through its base: inverted, Verdict's 0.
  auto poked = kPyramid;
  poked[4].z = -0.1;
  EXPECT_EQ(pyramid_validity(poked), CellValidity::inverted);
  // A pyramid with a reflex base corner (a dart) is inverted too.
  auto dart = kPyramid;
  dart[2] = {0.3, 0.3, 0};
  EXPECT_EQ(pyramid_validity(dart), CellValidity::inverted);
  // Flat cells: exactly zero determinants are flat, not inverted.
  auto flat_tet = kTet;
  flat_tet[3].z = 0;
  EXPECT_EQ(tet_validity(flat_tet), CellValidity::flat);
  auto flat_pyramid = kPyramid;
  flat_pyramid[4].z = 0;
  EXPECT_EQ(pyramid_validity(flat_pyramid), CellValidity::flat);
  auto flat_wedge = kWedge;
  for (int i = 3; i < 6; ++i) flat_wedge[i].z = 0;
  EXPECT_EQ(wedge_validity(flat_wedge), CellValidity::flat);
  // A tet flat only to rounding (0.1 + 0.2 != 0.3) is decided exactly.
  const std::array<Vec3, 4> nearly = {Vec3{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0.1 + 0.2, 0, 0.3 - 0.1 - 0.2}};
  EXPECT_EQ(tet_validity(nearly), (0.3 - 0.1 - 0.2) > 0   ? CellValidity::valid
                                  : (0.3 - 0.1 - 0.2) < 0 ? CellValidity::inverted
                                                          : CellValidity::flat);
}

TEST(CellCornerJacobian, TetValidityAgreesWithEveryCornerFrameOnNearlyFlatTets) {
  // tet_validity decides by corner 0 alone (the frames are even permutations
  // of one another): compare with the sign of every corner determinant,
  // exact here because the coordinates are small integers.
  std::mt19937 rng(46);
  std::uniform_int_distribution<int> coordinate(-3, 3);
  int counts[3] = {0, 0, 0};
  for (int n = 0; n < 4000; ++n) {
    std::array<Vec3, 4> p;
    for (auto& v : p) v = {double(coordinate(rng)), double(coordinate(rng)), double(coordinate(rng))};
    const auto& frames = CellKindTable<CellKind::tet>::corner_frames;
    bool negative = false, zero = false;
    for (int i = 0; i < 4; ++i) {
      const double d = det(p[frames[i][0]] - p[i], p[frames[i][1]] - p[i], p[frames[i][2]] - p[i]);
      negative = negative || d < 0;
      zero = zero || d == 0;
    }
    const CellValidity expected = negative ? CellValidity::inverted : zero ? CellValidity::flat : CellValidity::valid;
    EXPECT_EQ(tet_validity(p), expected);
    ++counts[static_cast<int>(expected)];
  }
  EXPECT_GT(counts[0], 100);  // valid, flat and inverted tets all occur
  EXPECT_GT(counts[1], 100);
  EXPECT_GT(counts[2], 100);
}

TEST(CellCornerJacobian, SurfaceCellsAgainstTheirOwnOrAGivenNormal) {
  const Vec3 up{0, 0, 1};
  auto reversed = kQuad;
  std::reverse(reversed.begin(), reversed.end());
  // No orientation of its own: a reversed quad scores the same...
  EXPECT_EQ(quad_corner_scaled_jacobians(reversed).value, quad_corner_scaled_jacobians(kQuad).value);
  EXPECT_EQ(quad_validity(reversed), CellValidity::valid);
  // ...but against the plane's normal it is inverted, every corner -1.
  EXPECT_EQ(quad_validity(reversed, up), CellValidity::inverted);
  EXPECT_NEAR(max_of(quad_corner_scaled_jacobians(reversed, up)), -1.0, 1e-15);
  EXPECT_EQ(quad_validity(kQuad, up), CellValidity::valid);
  // A concave (dart) quad is folded against its own normal.
  const std::array<Vec3, 4> dart = {Vec3{0, 0, 0}, {2, 0, 0}, {0.5, 0.5, 0}, {0, 2, 0}};
  EXPECT_EQ(quad_validity(dart), CellValidity::inverted);
  EXPECT_LT(min_of(quad_corner_scaled_jacobians(dart)), 0.0);
  // A planar bow-tie has no centre normal (flat) until a normal is given.
  const std::array<Vec3, 4> bowtie = {Vec3{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(quad_validity(bowtie), CellValidity::flat);
  EXPECT_EQ(quad_validity(bowtie, up), CellValidity::inverted);
  // Triangles: never inverted against their own normal; reversed against +z.
  const std::array<Vec3, 3> cw = {kTriangle[0], kTriangle[2], kTriangle[1]};
  EXPECT_EQ(triangle_validity(cw), CellValidity::valid);
  EXPECT_EQ(triangle_validity(cw, up), CellValidity::inverted);
  EXPECT_NEAR(min_of(triangle_corner_scaled_jacobians(cw, up)), -1.0, 1e-15);
  const std::array<Vec3, 3> collinear = {Vec3{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_EQ(triangle_validity(collinear), CellValidity::flat);
}

}  // namespace
}  // namespace hq
