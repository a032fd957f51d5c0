#include "hqview/fem/metric_correlation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hq {
namespace {

TEST(Spearman, MonotoneAndReversed) {
  const std::vector<double> x = {1, 2, 3, 4, 5};
  EXPECT_DOUBLE_EQ(spearman_correlation(x, std::vector<double>{1, 4, 9, 16, 25}).rho, 1.0);
  EXPECT_DOUBLE_EQ(spearman_correlation(x, std::vector<double>{5, 3, 2, 1, -7}).rho, -1.0);
}

// Hand computation with ties: x ranks (1, 2.5, 2.5, 4), y ranks (1, 3, 2, 4);
// mean 2.5; sum dx dy = 2.25 + 0 + 0 + 2.25 = 4.5; sum dx^2 = 4.5; sum dy^2 = 5.
TEST(Spearman, TiesShareTheirMeanRank) {
  const RankCorrelation r = spearman_correlation(std::vector<double>{1, 2, 2, 3}, std::vector<double>{10, 30, 20, 40});
  EXPECT_EQ(r.count, 4);
  EXPECT_NEAR(r.rho, 4.5 / std::sqrt(4.5 * 5.0), 1e-15);
}

TEST(Spearman, SkipsUnusablePairsAndConstants) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const RankCorrelation r =
      spearman_correlation(std::vector<double>{1, nan, 2, 3, 4}, std::vector<double>{1, 5, 1e30, 2, 3});
  EXPECT_EQ(r.count, 3);
  EXPECT_DOUBLE_EQ(r.rho, 1.0);
  EXPECT_TRUE(std::isnan(spearman_correlation(std::vector<double>{1, 2, 3}, std::vector<double>{7, 7, 7}).rho));
  EXPECT_TRUE(std::isnan(spearman_correlation(std::vector<double>{1, 2}, std::vector<double>{1, 2}).rho));
}

// p-values against scipy (tests/fem: brute force over itertools.permutations
// with scipy.stats.spearmanr, and spearmanr's own t-based p for n = 20).
TEST(SpearmanTest, ExactPermutationPValueForFewPairsAndTAboveIt) {
  // n = 6, one adjacent swap in each pair: rho = 1 - 6 * 6 / 210; 42 of the
  // 720 orders are as extreme (21 with sum d^2 <= 6, 21 mirrored).
  RankCorrelationTest t = spearman_test(std::vector<double>{0, 1, 2, 3, 4, 5}, std::vector<double>{2, 1, 4, 3, 6, 5});
  EXPECT_NEAR(t.correlation.rho, 1.0 - 36.0 / 210.0, 1e-15);
  EXPECT_NEAR(t.p_value, 42.0 / 720.0, 1e-15);
  // Ties in x: scipy's brute force gives 12 / 720.
  t = spearman_test(std::vector<double>{1, 2, 2, 3, 4, 5}, std::vector<double>{10, 30, 20, 40, 60, 50});
  EXPECT_NEAR(t.correlation.rho, 0.9276336570439174, 1e-12);
  EXPECT_NEAR(t.p_value, 1.0 / 60.0, 1e-15);
  // n = 20: the t approximation, as scipy.stats.spearmanr (1.2059368966099282e-09).
  std::vector<double> x(20), y = {3, 1, 2, 5, 4, 8, 6, 7, 10, 9, 14, 11, 12, 20, 13, 15, 19, 16, 17, 18};
  for (int i = 0; i < 20; ++i) x[static_cast<std::size_t>(i)] = i;
  t = spearman_test(x, y);
  EXPECT_NEAR(t.correlation.rho, 0.9368421052631578, 1e-12);
  EXPECT_NEAR(t.p_value, 1.2059368966099282e-09, 1e-9 * 1.2059368966099282e-09);
  // A perfect order of 5: 2 of 120 orders are as extreme.
  EXPECT_NEAR(spearman_test(std::vector<double>{1, 2, 3, 4, 5}, std::vector<double>{1, 2, 3, 4, 5}).p_value, 2.0 / 120.0,
              1e-15);
  EXPECT_TRUE(std::isnan(spearman_test(std::vector<double>{1, 2, 3}, std::vector<double>{7, 7, 7}).p_value));
}

// The direction of every Verdict hex metric, by hand from the Verdict manual
// (ideal value 1 at the top: higher is better; ideal at the bottom: lower;
// a size: none).
TEST(MetricDirection, FollowsTheVerdictManual) {
  for (const char* m : {"scaled_jacobian", "shape", "shear", "stretch", "diagonal", "distortion",
                        "relative_size_squared", "shape_and_size", "shear_and_size", "nodal_jacobian_ratio"})
    EXPECT_EQ(metric_direction(m), +1) << m;
  for (const char* m : {"edge_ratio", "max_edge_ratio", "max_aspect_frobenius", "med_aspect_frobenius", "skew",
                        "taper", "oddy", "condition", "equiangle_skew", "fem_kappa"})
    EXPECT_EQ(metric_direction(m), -1) << m;
  for (const char* m : {"volume", "dimension", "jacobian", "fem_lambda_max", "fem_det_j_min", "no_such_metric"})
    EXPECT_EQ(metric_direction(m), 0) << m;
}

}  // namespace
}  // namespace hq
