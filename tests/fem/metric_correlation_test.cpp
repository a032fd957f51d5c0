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

}  // namespace
}  // namespace hq
