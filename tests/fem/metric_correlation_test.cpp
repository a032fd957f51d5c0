#include "hqview/fem/metric_correlation.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>

#include <cmath>
#include <limits>
#include <string_view>

namespace hq {
namespace HQ_TEST_UNIT {

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

// Above the radix sort's threshold (thousands of hexes): the same rho as
// average ranks computed here by a plain comparison sort, with ties (values
// rounded to a few levels), negatives, -0 and +0 (equal: one tie group) and
// values of every magnitude.
TEST(Spearman, LargeInputsRankAsAComparisonSort) {
  const std::size_t n = 20000;
  std::vector<double> x(n), y(n);
  std::uint64_t z = 12345;
  const auto next = [&] {  // splitmix64 in [0, 1)
    z += 0x9e3779b97f4a7c15ULL;
    std::uint64_t t = z;
    t = (t ^ (t >> 30)) * 0xbf58476d1ce4e5b9ULL;
    t = (t ^ (t >> 27)) * 0x94d049bb133111ebULL;
    return static_cast<double>((t ^ (t >> 31)) >> 11) / 9007199254740992.0;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double u = next();
    x[i] = i % 7 == 0 ? std::round(8 * u - 4) : (u - 0.5) * std::pow(10.0, 40 * next() - 20);
    if (i % 97 == 0) x[i] = i % 2 ? -0.0 : 0.0;
    y[i] = x[i] * 0.3 + next() - 0.5;
  }
  const auto ranks = [](const std::vector<double>& v) {
    std::vector<std::size_t> order(v.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
    std::vector<double> r(v.size());
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i;
      while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
      for (std::size_t t = i; t <= j; ++t) r[order[t]] = 0.5 * static_cast<double>(i + j) + 1.0;
      i = j + 1;
    }
    return r;
  };
  const std::vector<double> rx = ranks(x), ry = ranks(y);
  const double mean = 0.5 * (static_cast<double>(n) + 1.0);
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (rx[i] - mean) * (ry[i] - mean);
    saa += (rx[i] - mean) * (rx[i] - mean);
    sbb += (ry[i] - mean) * (ry[i] - mean);
  }
  // The same ranks summed in the same order: the same bits.
  EXPECT_EQ(spearman_correlation(x, y).rho, sab / std::sqrt(saa * sbb));
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

// The partial correlation from the formula equals the Pearson correlation
// of the residuals of x and y after a least-squares line on z (computed
// here by regression, another route); NaN when a side ranks as z.
TEST(PartialRankCorrelation, EqualsTheCorrelationOfRegressionResiduals) {
  const std::vector<double> x = {3, 1, 4, 1.5, 5, 9, 2, 6, 5.5, 3.5}, y = {2, 7, 1, 8, 2.5, 8.5, 1.8, 2.8, 4.5, 9},
                            z = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  // Ranks (no ties among x, y; z is its own rank).
  const auto ranks = [](const std::vector<double>& v) {
    std::vector<double> r(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
      for (std::size_t j = 0; j < v.size(); ++j) r[i] += v[j] <= v[i] ? 1.0 : 0.0;
    return r;
  };
  const std::vector<double> rx = ranks(x), ry = ranks(y), rz = ranks(z);
  const auto residual = [&](const std::vector<double>& a) {
    double ma = 0, mz = 0;
    for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / a.size(), mz += rz[i] / a.size();
    double saz = 0, szz = 0;
    for (std::size_t i = 0; i < a.size(); ++i) saz += (a[i] - ma) * (rz[i] - mz), szz += (rz[i] - mz) * (rz[i] - mz);
    std::vector<double> e(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) e[i] = a[i] - ma - saz / szz * (rz[i] - mz);
    return e;
  };
  const std::vector<double> ex = residual(rx), ey = residual(ry);
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < ex.size(); ++i) sxy += ex[i] * ey[i], sxx += ex[i] * ex[i], syy += ey[i] * ey[i];
  const double expected = sxy / std::sqrt(sxx * syy);
  const double got = partial_rank_correlation(spearman_correlation(x, y).rho, spearman_correlation(x, z).rho,
                                              spearman_correlation(y, z).rho);
  EXPECT_NEAR(got, expected, 1e-12);
  EXPECT_GT(std::abs(got - spearman_correlation(x, y).rho), 0.05);  // the control moved it
  EXPECT_TRUE(std::isnan(partial_rank_correlation(0.3, 1.0, 0.2)));
  EXPECT_TRUE(std::isnan(partial_rank_correlation(0.3, 0.2, -0.9995)));
}

// correlate_metrics' shared-rank path gives what spearman_correlation and
// partial_rank_correlation give one by one; a metric with a sentinel takes
// the pairwise path; the size itself has no partial rho.
TEST(CorrelateMetrics, PartialGivenSizeAsComputedOneByOne) {
  const std::size_t n = 200;
  std::vector<double> density(n), size(n), skew(n), volume(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = std::sin(1.7 * static_cast<double>(i)), b = std::cos(0.37 * static_cast<double>(i * i));
    size[i] = 1.0 + 0.5 * a;
    volume[i] = size[i] * size[i] * size[i];
    skew[i] = 0.5 + 0.4 * b;
    density[i] = size[i] * (1.0 + skew[i]) + 0.1 * std::sin(3.1 * static_cast<double>(i));
  }
  density[7] = std::nan("");
  HexMetricField metrics;
  metrics.values[static_cast<std::size_t>(HexMetric::skew)] = skew;
  metrics.values[static_cast<std::size_t>(HexMetric::volume)] = volume;
  std::vector<double> shear = skew;
  shear[11] = 1e30;  // a sentinel: the pairwise path
  metrics.values[static_cast<std::size_t>(HexMetric::shear)] = shear;
  FemElementField elements;
  elements.kappa = elements.lambda_max = elements.det_j_min = skew;
  const std::vector<MetricCorrelation> c = correlate_metrics(density, metrics, elements, size);
  const auto find = [&](std::string_view name) {
    for (const MetricCorrelation& m : c)
      if (m.metric == name) return m;
    ADD_FAILURE() << name;
    return MetricCorrelation{};
  };
  const double r_ds = spearman_correlation(density, size).rho;
  const MetricCorrelation s = find("skew");
  EXPECT_DOUBLE_EQ(s.correlation.rho, spearman_correlation(density, skew).rho);
  // Over the hexes with a density (#7 has none).
  std::vector<double> skew_used = skew, size_used = size;
  skew_used[7] = size_used[7] = std::nan("");
  EXPECT_NEAR(s.rho_given_size,
              partial_rank_correlation(s.correlation.rho, r_ds, spearman_correlation(skew_used, size_used).rho),
              1e-14);
  EXPECT_GT(s.rho_given_size, s.correlation.rho);  // the size hid part of it
  const MetricCorrelation sh = find("shear");
  EXPECT_EQ(sh.correlation.count, static_cast<std::int64_t>(n - 2));
  EXPECT_TRUE(std::isfinite(sh.rho_given_size));
  EXPECT_TRUE(std::isnan(find("volume").rho_given_size));  // ranks as the size
  EXPECT_NEAR(size_correlation(density, size).rho, r_ds, 1e-15);
  // Without sizes: no partial rho.
  EXPECT_TRUE(std::isnan(correlate_metrics(density, metrics, elements)[0].rho_given_size));
  // The verdict family: skew, shear and fem_kappa have a better direction
  // (volume, fem_lambda_max, fem_det_j_min do not): m = 3, z = 2.39398.
  EXPECT_EQ(verdict_family_size(c), 3);
  const RankCorrelationInterval adjusted =
      spearman_interval(s.correlation.rho, s.correlation.count, 2.3939797998185095);
  EXPECT_NEAR(s.adjusted_interval.lo, adjusted.lo, 1e-13);
  EXPECT_NEAR(s.adjusted_interval.hi, adjusted.hi, 1e-13);
  EXPECT_LT(s.adjusted_interval.lo, s.interval.lo);
}

// By hand: m = 4 finite p sorted 0.01, 0.03, 0.04, 0.5 give m p / rank
// 0.04, 0.06, 0.0533, 0.5, then the running min from the top.
TEST(BenjaminiHochberg, HandComputed) {
  const std::vector<double> q = benjamini_hochberg(std::vector<double>{0.01, 0.04, 0.03, std::nan(""), 0.5});
  ASSERT_EQ(q.size(), 5u);
  EXPECT_DOUBLE_EQ(q[0], 0.04);
  EXPECT_DOUBLE_EQ(q[1], 4 * 0.04 / 3);
  EXPECT_DOUBLE_EQ(q[2], 4 * 0.04 / 3);
  EXPECT_TRUE(std::isnan(q[3]));
  EXPECT_DOUBLE_EQ(q[4], 0.5);
  EXPECT_DOUBLE_EQ(benjamini_hochberg(std::vector<double>{0.9, 0.8})[0], 0.9);
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

// The metric-direction normalisation by hand: agreement = -direction * rho.
// On six hexes, a higher-is-better metric (scaled Jacobian) whose values fall
// as the error density rises agrees; a lower-is-better one (edge ratio) with
// the same values disagrees; a size has none. rho by hand: ranks of the
// density 1..6 against (6, 5, 4, 3, 1, 2): d = (-5, -3, -1, 1, 4, 4),
// sum d^2 = 68, rho = 1 - 6 * 68 / (6 * 35) = -33/35.
TEST(MetricAgreement, NormalisesTheSignByTheMetricsDirection) {
  const std::vector<double> density = {0.01, 0.02, 0.03, 0.05, 0.08, 0.13};
  const std::vector<double> metric = {0.9, 0.8, 0.7, 0.6, 0.2, 0.3};
  const double rho = spearman_correlation(density, metric).rho;
  EXPECT_NEAR(rho, -33.0 / 35.0, 1e-15);
  EXPECT_NEAR(metric_agreement(metric_direction("scaled_jacobian"), rho), 33.0 / 35.0, 1e-15);  // agrees
  EXPECT_NEAR(metric_agreement(metric_direction("edge_ratio"), rho), -33.0 / 35.0, 1e-15);      // disagrees
  EXPECT_TRUE(std::isnan(metric_agreement(metric_direction("volume"), rho)));
  EXPECT_TRUE(std::isnan(metric_agreement(+1, std::nan(""))));
  EXPECT_EQ(metric_agreement(-1, 0.25), 0.25);
  // Size metrics: no direction, or Verdict's relative-size ones.
  for (const char* m : {"volume", "dimension", "jacobian", "fem_lambda_max", "fem_det_j_min", "relative_size_squared",
                        "shape_and_size", "shear_and_size"})
    EXPECT_TRUE(metric_is_size(m)) << m;
  for (const char* m : {"scaled_jacobian", "shape", "shear", "edge_ratio", "fem_kappa", "condition"})
    EXPECT_FALSE(metric_is_size(m)) << m;
}

// The interval by hand: rho = 29/35 over 6 pairs (x = 1..6 against
// 2, 1, 4, 3, 6, 5: sum d^2 = 6), z = atanh(29/35) = ln(32/3) / 2,
// se = sqrt((1 + (29/35)^2 / 2) / 3); and rho = 1/2 over 103 pairs, z = ln 3 / 2,
// se = sqrt(1.125 / 100). The numbers from Python's math module.
TEST(SpearmanInterval, FisherZWithBonettWrightError) {
  const std::vector<double> x = {1, 2, 3, 4, 5, 6}, y = {2, 1, 4, 3, 6, 5};
  const RankCorrelation r = spearman_correlation(x, y);
  EXPECT_NEAR(r.rho, 29.0 / 35.0, 1e-15);
  RankCorrelationInterval i = spearman_interval(r.rho, r.count);
  const double z = 0.5 * std::log(32.0 / 3.0), se = std::sqrt((1.0 + 0.5 * (29.0 / 35.0) * (29.0 / 35.0)) / 3.0);
  EXPECT_NEAR(i.lo, std::tanh(z - 1.959963984540054 * se), 1e-14);
  EXPECT_NEAR(i.hi, std::tanh(z + 1.959963984540054 * se), 1e-14);
  EXPECT_NEAR(i.lo, -0.12724489572415673, 1e-12);  // crosses 0: six pairs say little
  EXPECT_NEAR(i.hi, 0.9864823442496332, 1e-12);
  i = spearman_interval(0.5, 103);
  EXPECT_NEAR(i.lo, 0.3287450308758815, 1e-12);
  EXPECT_NEAR(i.hi, 0.6394198469997987, 1e-12);
  // Symmetric in the sign; undefined below 4 pairs; a perfect rho has no width.
  const RankCorrelationInterval m = spearman_interval(-0.5, 103);
  EXPECT_NEAR(m.lo, -i.hi, 1e-15);
  EXPECT_NEAR(m.hi, -i.lo, 1e-15);
  EXPECT_TRUE(std::isnan(spearman_interval(0.5, 3).lo));
  EXPECT_TRUE(std::isnan(spearman_interval(std::nan(""), 50).hi));
  EXPECT_EQ(spearman_interval(1.0, 10).lo, 1.0);
}

// The verdicts' interval, simultaneous over m metrics (Bonferroni): z from
// scipy.stats.norm.isf(0.05 / (2 m)) (m = 20: 3.0233414397391476). By hand:
// rho 0.07 over 1003 hexes, se = sqrt((1 + 0.07^2 / 2) / 1000): the one 95 %
// interval [0.00806, 0.131] excludes 0 (a "decided" sign), the simultaneous
// one over 20 metrics [-0.0256, 0.164] does not: undecided.
TEST(SpearmanInterval, SimultaneousOverTheVerdictFamily) {
  EXPECT_NEAR(bonferroni_interval_z(20), 3.0233414397391476, 1e-12);
  EXPECT_NEAR(bonferroni_interval_z(3), 2.3939797998185095, 1e-12);
  EXPECT_EQ(bonferroni_interval_z(1), kCorrelationIntervalZ);
  const RankCorrelationInterval one = spearman_interval(0.07, 1003);
  EXPECT_NEAR(one.lo, 0.00805911449470834, 1e-12);
  EXPECT_NEAR(one.hi, 0.13140576955334957, 1e-12);
  const RankCorrelationInterval all = spearman_interval(0.07, 1003, bonferroni_interval_z(20));
  EXPECT_NEAR(all.lo, -0.02560322981685053, 1e-12);
  EXPECT_NEAR(all.hi, 0.16433439829997493, 1e-12);
}

}  // namespace
}  // namespace hq
