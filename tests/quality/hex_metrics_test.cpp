// Every Verdict hex metric against the oracle of ../shared/data/verdict
// (Verdict 1.4.5 built locally, and the values Verdict's own unit tests
// publish), plus properties over fixtures and random perturbed cubes.

#include "hqview/quality/hex_metrics.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "support/fixtures.h"
#include "support/verdict_oracle.h"

namespace hq {
namespace HQ_TEST_UNIT {

using Corners = HexCorners;

using test::oracle_corners;

nlohmann::json load_oracle() { return test::load_verdict_oracle(); }

HexMetric metric(int i) { return static_cast<HexMetric>(i); }

// Equal to 1e-12 relative (absolute below 1), or the same sentinel.
::testing::AssertionResult same_as_verdict(double got, double expected) {
  if (is_verdict_sentinel(expected) || is_verdict_sentinel(got)) {
    if (got == expected) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "got " << got << ", Verdict " << expected;
  }
  if (std::abs(got - expected) <= 1e-12 * std::max(1.0, std::abs(expected))) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "got " << got << ", Verdict " << expected << " (difference " << got - expected
                                       << ")";
}

// The unit in the last significant digit `v` was printed with; 0 for values
// printed with fewer than 6 digits (1.0, 0.5: exact values).
double printed_unit(double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::scientific);
  const std::string text(buffer, r.ptr);
  const auto e = text.find('e');
  const int exponent = std::stoi(text.substr(e + 1));
  int digits = 0;
  for (std::size_t i = 0; i < e; ++i) digits += std::isdigit(static_cast<unsigned char>(text[i])) != 0;
  if (digits < 6) return 0.0;
  return std::pow(10.0, exponent - digits + 1);
}

// A published value's precision: its printed unit, and never below a few
// ulps (full-precision values may differ in the last bit: Verdict 1.4.5
// rescales each element before some metrics).
double published_precision(double v) { return std::max(printed_unit(v), 1e-14 * std::max(1.0, std::abs(v))); }

TEST(HexMetrics, TableHasEveryVerdictNameInOrder) {
  const char* names[] = {"edge_ratio",
                         "max_edge_ratio",
                         "max_aspect_frobenius",
                         "med_aspect_frobenius",
                         "skew",
                         "taper",
                         "volume",
                         "stretch",
                         "diagonal",
                         "dimension",
                         "oddy",
                         "condition",
                         "jacobian",
                         "scaled_jacobian",
                         "shear",
                         "shape",
                         "relative_size_squared",
                         "shape_and_size",
                         "shear_and_size",
                         "distortion",
                         "nodal_jacobian_ratio",
                         "equiangle_skew"};
  for (int i = 0; i < kNumHexMetrics; ++i) {
    EXPECT_EQ(hex_metric_name(metric(i)), names[i]);
    EXPECT_EQ(hex_metric_from_name(names[i]), metric(i));
    EXPECT_LE(hex_metric_info(metric(i)).acceptable_min, hex_metric_info(metric(i)).acceptable_max);
  }
  EXPECT_FALSE(hex_metric_from_name("aspect_ratio").has_value());
  EXPECT_EQ(hex_metric_info(HexMetric::scaled_jacobian).acceptable_min, 0.5);
  EXPECT_EQ(hex_metric_info(HexMetric::skew).acceptable_max, 0.5);
  EXPECT_EQ(hex_metric_info(HexMetric::taper).acceptable_max, 0.5);
}

TEST(HexMetrics, EveryOracleCaseMatchesVerdict145) {
  const auto oracle = load_oracle();
  if (oracle.is_null()) GTEST_SKIP() << "../shared/data absent: Verdict oracle not available";
  int checked = 0;
  for (const auto& c : oracle["cases"]) {
    const Corners p = oracle_corners(c);
    const double average = c["avg_hex_volume"];
    const auto& reference = c["verdict_1_4_5_built_locally"];
    const HexMetricValues all = hex_metrics(p, average);
    for (int i = 0; i < kNumHexMetrics; ++i) {
      const std::string name(hex_metric_name(metric(i)));
      ASSERT_TRUE(reference.contains(name)) << name;
      const double expected = reference[name];
      EXPECT_TRUE(same_as_verdict(hex_metric(metric(i), p, average), expected)) << c["name"] << " " << name;
      // The shared kernel gives exactly the single-metric kernels' values.
      EXPECT_EQ(all[static_cast<std::size_t>(i)], hex_metric(metric(i), p, average)) << c["name"] << " " << name;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 13 * kNumHexMetrics);
}

TEST(HexMetrics, VerdictPublishedUnitTestValuesToTheirPrecision) {
  const auto oracle = load_oracle();
  if (oracle.is_null()) GTEST_SKIP() << "../shared/data absent: Verdict oracle not available";
  int checked = 0;
  for (const auto& c : oracle["cases"]) {
    if (c.value("expected_source", "") != "Verdict unit test (published)") continue;
    const Corners p = oracle_corners(c);
    for (const auto& [name, value] : c["expected"].items()) {
      const auto m = hex_metric_from_name(name);
      if (!m) continue;  // e.g. the timestep, not a quality metric
      const double expected = value;
      const double got = hex_metric(*m, p, c["avg_hex_volume"]);
      if (is_verdict_sentinel(expected))
        EXPECT_EQ(got, expected) << c["name"] << " " << name;
      else
        EXPECT_NEAR(got, expected, published_precision(expected)) << c["name"] << " " << name;
      ++checked;
    }
  }
  EXPECT_GE(checked, 60);
}

TEST(HexMetrics, TangledHexIsCaughtAtTheCentre) {
  const auto oracle = load_oracle();
  if (oracle.is_null()) GTEST_SKIP() << "../shared/data absent: Verdict oracle not available";
  for (const auto& c : oracle["cases"]) {
    if (c["name"] != "center_inverted_corners_valid") continue;
    const Corners p = oracle_corners(c);
    const CornerJacobians corners = corner_scaled_jacobians(p);
    EXPECT_GE(*std::min_element(corners.value.begin(), corners.value.end()), 0.7155);
    EXPECT_NEAR(hex_metrics(p, 1.0)[static_cast<std::size_t>(HexMetric::scaled_jacobian)], -0.987, 5e-4);
    return;
  }
  FAIL() << "case center_inverted_corners_valid missing from the oracle";
}

// Verdict's edge_ratio looks at the longest of edges 0-5 only.
TEST(HexMetrics, EdgeRatioQuirkOnATallBox) {
  Corners p = test::cube_corners();
  for (int i = 4; i < 8; ++i) p[i].z = 3;
  EXPECT_EQ(hex_edge_ratio(p), 1.0);
  EXPECT_DOUBLE_EQ(hex_max_edge_ratio(p), 3.0);
  Corners wide = test::cube_corners();
  wide[1].x = wide[2].x = wide[5].x = wide[6].x = 3;  // edges 0 and 2 are long
  EXPECT_DOUBLE_EQ(hex_edge_ratio(wide), 3.0);
}

TEST(HexMetrics, UnitCubeValues) {
  const HexMetricValues v = hex_metrics(test::cube_corners(), 1.0);
  auto at = [&](HexMetric m) { return v[static_cast<std::size_t>(m)]; };
  using M = HexMetric;
  for (M m : {M::edge_ratio, M::max_edge_ratio, M::max_aspect_frobenius, M::med_aspect_frobenius, M::volume, M::stretch,
              M::diagonal, M::condition, M::jacobian, M::scaled_jacobian, M::shear, M::shape, M::relative_size_squared,
              M::shape_and_size, M::shear_and_size, M::distortion, M::nodal_jacobian_ratio})
    EXPECT_NEAR(at(m), 1.0, 1e-15) << hex_metric_name(m);
  for (M m : {M::skew, M::taper, M::oddy, M::equiangle_skew}) EXPECT_NEAR(at(m), 0.0, 1e-15) << hex_metric_name(m);
  EXPECT_NEAR(at(M::dimension), 1 / std::sqrt(3.0), 1e-15);
}

TEST(HexMetrics, SubsetLeavesTheOthersNaN) {
  HexMetricSet which;
  insert(which, HexMetric::skew);
  insert(which, HexMetric::shape_and_size);
  const Corners p = test::twisted_hex(0.4);
  const HexMetricValues v = hex_metrics(p, 0.8, which);
  for (int i = 0; i < kNumHexMetrics; ++i) {
    if (which.test(static_cast<std::size_t>(i)))
      EXPECT_EQ(v[static_cast<std::size_t>(i)], hex_metric(metric(i), p, 0.8));
    else
      EXPECT_TRUE(std::isnan(v[static_cast<std::size_t>(i)])) << hex_metric_name(metric(i));
  }
}

TEST(HexMetrics, AllCornersAtOnePointIsDegenerateNotNaN) {
  Corners p;
  p.fill({0.5, 0.5, 0.5});
  const HexMetricValues v = hex_metrics(p, 1.0);
  for (int i = 0; i < kNumHexMetrics; ++i)
    EXPECT_FALSE(std::isnan(v[static_cast<std::size_t>(i)])) << hex_metric_name(metric(i));
  EXPECT_EQ(v[static_cast<std::size_t>(HexMetric::scaled_jacobian)], kVerdictDegenerate);
  EXPECT_EQ(v[static_cast<std::size_t>(HexMetric::dimension)], kVerdictDegenerate);
}

// ---------------------------------------------------------------------------
// Properties over fixtures and random perturbed cubes.

std::vector<Corners> perturbed_cubes(int count, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  std::vector<Corners> out;
  for (int n = 0; n < count; ++n) {
    Corners p = test::cube_corners();
    for (Vec3& v : p) v = v + Vec3{u(rng), u(rng), u(rng)};
    out.push_back(p);
  }
  return out;
}

std::vector<Corners> fixtures() {
  std::vector<Corners> all = {test::cube_corners(), test::twisted_hex(0.3), test::twisted_hex(1.2),
                              test::inverted_hex()};
  const auto random = perturbed_cubes(200, 0.3, 7);
  all.insert(all.end(), random.begin(), random.end());
  return all;
}

Corners rigid_motion(const Corners& p, const Vec3& translation, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  const Vec3 k = normalized(Vec3{1, 2, 3});
  Corners q;
  for (int i = 0; i < 8; ++i) {
    const Vec3 v = p[i];
    q[i] = c * v + s * cross(k, v) + (1 - c) * dot(k, v) * k + translation;  // Rodrigues
  }
  return q;
}

::testing::AssertionResult close(double a, double b, double relative) {
  if (is_verdict_sentinel(a) || is_verdict_sentinel(b)) {
    if (a == b) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << a << " vs " << b;
  }
  if (std::abs(a - b) <= relative * std::max(1.0, std::max(std::abs(a), std::abs(b))))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << " (difference " << a - b << ")";
}

TEST(HexMetrics, InvariantUnderRotationAndTranslation) {
  for (const Corners& p : fixtures()) {
    const Corners q = rigid_motion(p, {10, -4, 2.5}, 0.9);
    const HexMetricValues a = hex_metrics(p, 0.9), b = hex_metrics(q, 0.9);
    for (int i = 0; i < kNumHexMetrics; ++i)
      EXPECT_TRUE(close(a[static_cast<std::size_t>(i)], b[static_cast<std::size_t>(i)], 1e-10))
          << hex_metric_name(metric(i));
  }
}

TEST(HexMetrics, ScaleBehaviourPerMetric) {
  using M = HexMetric;
  const double s = 3.5;
  for (const Corners& p : fixtures()) {
    Corners q;
    for (int i = 0; i < 8; ++i) q[i] = s * p[i];
    // The size metrics compare with the mean volume: scaling both keeps them.
    const HexMetricValues a = hex_metrics(p, 0.9), b = hex_metrics(q, 0.9 * s * s * s);
    for (int i = 0; i < kNumHexMetrics; ++i) {
      const M m = metric(i);
      double factor = 1;  // scale-invariant metrics
      if (m == M::volume || m == M::jacobian) factor = s * s * s;
      if (m == M::dimension) factor = s;
      const double va = a[static_cast<std::size_t>(i)], vb = b[static_cast<std::size_t>(i)];
      EXPECT_TRUE(close(is_verdict_sentinel(va) ? va : va * factor, vb, 1e-11)) << hex_metric_name(m);
    }
    // Against the unscaled mean, relative size drops as 1/s^6 for a hex that
    // was the mean's size.
  }
  const Corners cube = test::cube_corners();
  Corners big;
  for (int i = 0; i < 8; ++i) big[i] = 2.0 * cube[i];
  EXPECT_NEAR(hex_relative_size_squared(big, 1.0), 1.0 / 64.0, 1e-15);
}

// An affine image of the cube has the same frame at every corner and at the
// centre, so mirroring it negates the scaled Jacobian and the Jacobian.
TEST(HexMetrics, MirrorImageNegatesScaledJacobianAndJacobian) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (int n = 0; n < 100; ++n) {
    const Vec3 a{1 + u(rng), u(rng), u(rng)}, b{u(rng), 1 + u(rng), u(rng)}, c{u(rng), u(rng), 1 + u(rng)};
    Corners p;
    const Corners cube = test::cube_corners();
    for (int i = 0; i < 8; ++i) p[i] = cube[i].x * a + cube[i].y * b + cube[i].z * c;
    Corners m = p;
    for (Vec3& v : m) v.x = -v.x;
    EXPECT_NEAR(hex_scaled_jacobian(m), -hex_scaled_jacobian(p), 1e-14);
    EXPECT_NEAR(hex_jacobian(m), -hex_jacobian(p), 1e-14);
    EXPECT_NEAR(hex_volume(m), -hex_volume(p), 1e-14);
  }
}

TEST(HexMetrics, CellScaledJacobianIsAtMostTheCornerMinimum) {
  for (const Corners& p : perturbed_cubes(500, 0.45, 3)) {
    const CornerJacobians corners = corner_scaled_jacobians(p);
    const double corner_min = *std::min_element(corners.value.begin(), corners.value.end());
    EXPECT_LE(hex_scaled_jacobian(p), corner_min + 1e-15);
  }
}

TEST(HexMetrics, RangesOfBoundedMetrics) {
  using M = HexMetric;
  for (const Corners& p : perturbed_cubes(500, 0.2, 5)) {
    const HexMetricValues v = hex_metrics(p, 1.0);
    auto at = [&](M m) { return v[static_cast<std::size_t>(m)]; };
    EXPECT_GE(at(M::edge_ratio), 1.0);
    EXPECT_GE(at(M::max_aspect_frobenius), 1.0 - 1e-15);
    EXPECT_GE(at(M::med_aspect_frobenius), 1.0 - 1e-15);
    EXPECT_LE(at(M::med_aspect_frobenius), at(M::max_aspect_frobenius) + 1e-15);
    EXPECT_EQ(at(M::condition), at(M::max_aspect_frobenius));
    for (M m : {M::skew, M::shear, M::shape, M::relative_size_squared, M::diagonal, M::nodal_jacobian_ratio}) {
      EXPECT_GE(at(m), 0.0) << hex_metric_name(m);
      EXPECT_LE(at(m), 1.0) << hex_metric_name(m);
    }
    EXPECT_GE(at(M::oddy), 0.0);
    EXPECT_NEAR(at(M::shape_and_size), at(M::shape) * at(M::relative_size_squared), 1e-15);
    EXPECT_NEAR(at(M::shear_and_size), at(M::shear) * at(M::relative_size_squared), 1e-15);
  }
}

// Plain, slow transcriptions of Verdict's shape, oddy and equiangle skew
// (every corner's pow, every angle's acos), against the kernels' shortcuts.
namespace plain {

const int kFrames[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7}, {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};

double shape(const Corners& p) {
  double m = 1.0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 a = p[kFrames[i][0]] - p[i], b = p[kFrames[i][1]] - p[i], c = p[kFrames[i][2]] - p[i];
    const double d = det(a, b, c);
    if (!(d > 1e-30)) return 0;
    m = std::min(m, 3 * std::pow(d, 2.0 / 3.0) / (dot(a, a) + dot(b, b) + dot(c, c)));
  }
  return m;
}

double oddy_frame(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double d = det(a, b, c);
  if (!(d > 2.220446049250313e-16)) return 1e30;
  const double g11 = dot(a, a), g12 = dot(a, b), g13 = dot(a, c), g22 = dot(b, b), g23 = dot(b, c), g33 = dot(c, c);
  const double g2 = g11 * g11 + 2 * g12 * g12 + 2 * g13 * g13 + g22 * g22 + 2 * g23 * g23 + g33 * g33;
  const double j2 = g11 + g22 + g33;
  return (g2 - j2 * j2 / 3) / std::pow(d, 4.0 / 3.0);
}

double oddy(const Corners& p) {
  const Vec3 x1 = p[1] + p[2] + p[5] + p[6] - p[0] - p[3] - p[4] - p[7];
  const Vec3 x2 = p[2] + p[3] + p[6] + p[7] - p[0] - p[1] - p[4] - p[5];
  const Vec3 x3 = p[4] + p[5] + p[6] + p[7] - p[0] - p[1] - p[2] - p[3];
  double o = std::max(0.0, oddy_frame(x1, x2, x3));
  for (int i = 0; i < 8; ++i)
    o = std::max(o, oddy_frame(p[kFrames[i][0]] - p[i], p[kFrames[i][1]] - p[i], p[kFrames[i][2]] - p[i]));
  return std::min(o, 1e30);
}

double equiangle_skew(const Corners& p) {
  const int faces[6][4] = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}, {3, 2, 1, 0}};
  double lo = 360, hi = 0;
  for (const auto& f : faces) {
    const Vec3 e[4] = {p[f[1]] - p[f[0]], p[f[2]] - p[f[1]], p[f[3]] - p[f[2]], p[f[0]] - p[f[3]]};
    double a_lo = 360, a_hi = 0;
    for (int k = 0; k < 4; ++k) {
      const double angle = std::acos(-dot(e[k], e[(k + 1) % 4]) / (norm(e[k]) * norm(e[(k + 1) % 4])));
      a_lo = std::fmin(angle, a_lo);
      a_hi = std::fmax(angle, a_hi);
    }
    a_lo = a_lo * 180 / 3.1415926535897932384626;
    a_hi = a_hi * 180 / 3.1415926535897932384626;
    const Vec3 n = normalized(cross(e[0] - e[2], e[1] - e[3]));
    for (int k = 0; k < 4; ++k)
      if (dot(n, cross(e[(k + 3) % 4], e[k])) < 0) {
        a_hi = 360 - a_hi;
        break;
      }
    lo = std::min(lo, a_lo);
    hi = std::max(hi, a_hi);
  }
  return std::max((hi - 90) / 90, (90 - lo) / 90);
}

}  // namespace plain

TEST(HexMetrics, ShortcutsEqualThePlainFormulas) {
  // Strongly perturbed cubes: many inverted corners and reflex face angles.
  int reflex = 0;
  for (const Corners& p : perturbed_cubes(3000, 0.6, 13)) {
    EXPECT_TRUE(close(hex_shape(p), plain::shape(p), 1e-13));
    EXPECT_TRUE(close(hex_oddy(p), plain::oddy(p), 1e-13));
    const double skew = hex_equiangle_skew(p);
    EXPECT_TRUE(close(skew, plain::equiangle_skew(p), 1e-13));
    reflex += skew > 1.0;  // a largest angle beyond 180 degrees
  }
  EXPECT_GT(reflex, 10);
}

}  // namespace
}  // namespace hq
