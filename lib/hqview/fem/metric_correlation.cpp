#include "hqview/fem/metric_correlation.h"

#include <boost/math/distributions/normal.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>

#include <boost/math/special_functions/beta.hpp>

#include "hqview/quality/hex_metrics.h"

namespace hq {
namespace {

bool is_usable(double v) { return std::isfinite(v) && !is_verdict_sentinel(v); }

// A finite double's order as an unsigned key: flip the sign bit of a
// positive one, every bit of a negative one (-0 and +0 end up adjacent, so
// the tie scan below still joins them).
std::uint64_t order_key(double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  return (bits >> 63) != 0 ? ~bits : bits | (std::uint64_t{1} << 63);
}

// (value, index) pairs in ascending value order: an LSD radix sort on the
// order keys, 16 bits a pass (4 passes; a pass whose digit is the same for
// every key is skipped). Above kRadixMin values it takes a fraction of
// std::sort's time on the hundreds of thousands of hexes a mesh has (issue 48's
// speed: one sort per metric); ties may come out in any order, which the
// ranks do not see.
constexpr std::size_t kRadixMin = 4096;
void sort_pairs(std::vector<std::pair<double, std::size_t>>& pairs) {
  if (pairs.size() < kRadixMin) {
    std::sort(pairs.begin(), pairs.end());
    return;
  }
  std::vector<std::pair<std::uint64_t, std::size_t>> a(pairs.size()), b(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) a[i] = {order_key(pairs[i].first), pairs[i].second};
  std::vector<std::size_t> count(65536);
  for (int shift = 0; shift < 64; shift += 16) {
    std::fill(count.begin(), count.end(), 0);
    for (const auto& e : a) ++count[(e.first >> shift) & 0xffffu];
    if (count[(a[0].first >> shift) & 0xffffu] == a.size()) continue;
    std::size_t sum = 0;
    for (std::size_t& c : count) {
      const std::size_t n = c;
      c = sum;
      sum += n;
    }
    for (const auto& e : a) b[count[(e.first >> shift) & 0xffffu]++] = e;
    a.swap(b);
  }
  // Back to the values (the key's inverse), in order.
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::uint64_t key = a[i].first;
    const std::uint64_t bits = (key >> 63) != 0 ? key & ~(std::uint64_t{1} << 63) : ~key;
    double v = 0;
    std::memcpy(&v, &bits, sizeof v);
    pairs[i] = {v, a[i].second};
  }
}

// Ranks 1..n, ties sharing their mean rank.
std::vector<double> average_ranks(const std::vector<double>& values) {
  // (value, index) pairs sorted directly: no indirect comparisons. A tie
  // group's members share one rank, so their order does not matter.
  std::vector<std::pair<double, std::size_t>> sorted(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) sorted[i] = {values[i], i};
  sort_pairs(sorted);
  std::vector<double> ranks(values.size());
  for (std::size_t i = 0; i < sorted.size();) {
    std::size_t j = i;
    while (j + 1 < sorted.size() && sorted[j + 1].first == sorted[i].first) ++j;
    const double rank = 0.5 * static_cast<double>(i + j) + 1.0;
    for (std::size_t t = i; t <= j; ++t) ranks[sorted[t].second] = rank;
    i = j + 1;
  }
  return ranks;
}

// Pearson's r of two rank vectors of n entries (both with mean (n + 1) / 2).
double rank_pearson(const std::vector<double>& ra, const std::vector<double>& rb) {
  const double mean = 0.5 * (static_cast<double>(ra.size()) + 1.0);
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    sab += (ra[i] - mean) * (rb[i] - mean);
    saa += (ra[i] - mean) * (ra[i] - mean);
    sbb += (rb[i] - mean) * (rb[i] - mean);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : std::numeric_limits<double>::quiet_NaN();
}

// The usable pairs.
void usable_pairs(std::span<const double> x, std::span<const double> y, std::vector<double>& a,
                  std::vector<double>& b) {
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i)
    if (is_usable(x[i]) && is_usable(y[i])) {
      a.push_back(x[i]);
      b.push_back(y[i]);
    }
}

}  // namespace

RankCorrelationTest spearman_test(std::span<const double> x, std::span<const double> y) {
  std::vector<double> a, b;
  usable_pairs(x, y, a, b);
  RankCorrelationTest out;
  const std::size_t n = a.size();
  out.correlation.count = static_cast<std::int64_t>(n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (n < 3) {
    out.correlation.rho = out.p_value = nan;
    return out;
  }
  const std::vector<double> ra = average_ranks(a);
  std::vector<double> rb = average_ranks(b);
  const double rho = rank_pearson(ra, rb);
  out.correlation.rho = rho;
  if (!std::isfinite(rho)) {
    out.p_value = nan;
    return out;
  }
  if (n <= static_cast<std::size_t>(kExactSpearmanMaxCount)) {
    // Every distinct arrangement of the y ranks (each stands for the same
    // number of permutations, so counting them gives the permutation p).
    std::sort(rb.begin(), rb.end());
    std::int64_t total = 0, as_extreme = 0;
    const double bound = std::abs(rho) - 1e-12;
    do {
      ++total;
      as_extreme += std::abs(rank_pearson(ra, rb)) >= bound;
    } while (std::next_permutation(rb.begin(), rb.end()));
    out.p_value = static_cast<double>(as_extreme) / static_cast<double>(total);
    return out;
  }
  const double df = static_cast<double>(n) - 2.0;
  const double r2 = std::min(rho * rho, 1.0);
  // Two-sided p = I_{df / (df + t^2)}(df / 2, 1 / 2), df / (df + t^2) = 1 - rho^2.
  out.p_value = r2 >= 1.0 ? 0.0 : boost::math::ibeta(0.5 * df, 0.5, 1.0 - r2);
  return out;
}

std::vector<double> benjamini_hochberg(std::span<const double> p) {
  std::vector<double> q(p.size(), std::numeric_limits<double>::quiet_NaN());
  std::vector<std::pair<double, std::size_t>> sorted;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::isfinite(p[i])) sorted.push_back({p[i], i});
  std::sort(sorted.begin(), sorted.end());
  const double m = static_cast<double>(sorted.size());
  double running = 1.0;
  for (std::size_t k = sorted.size(); k-- > 0;) {
    running = std::min(running, m * sorted[k].first / static_cast<double>(k + 1));
    q[sorted[k].second] = running;
  }
  return q;
}

int metric_direction(std::string_view metric) {
  if (metric == "fem_kappa") return -1;
  const std::optional<HexMetric> m = hex_metric_from_name(metric);
  if (!m) return 0;
  const HexMetricInfo& info = hex_metric_info(*m);
  if (std::isinf(info.acceptable_max)) return 0;
  return info.acceptable_max == 1.0 ? +1 : -1;
}

bool metric_is_size(std::string_view metric) {
  return metric_direction(metric) == 0 || metric == "relative_size_squared" || metric == "shape_and_size" ||
         metric == "shear_and_size";
}

double metric_agreement(int direction, double rho) {
  if (direction == 0 || !std::isfinite(rho)) return std::numeric_limits<double>::quiet_NaN();
  return -static_cast<double>(direction) * rho;
}

RankCorrelationInterval spearman_interval(double rho, std::int64_t count, double z_level) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (count < 4 || !std::isfinite(rho)) return {nan, nan};
  if (std::abs(rho) >= 1.0) return {rho, rho};
  const double z = std::atanh(rho);
  const double se = std::sqrt((1.0 + 0.5 * rho * rho) / (static_cast<double>(count) - 3.0));
  return {std::tanh(z - z_level * se), std::tanh(z + z_level * se)};
}

double bonferroni_interval_z(int m) {
  if (m <= 1) return kCorrelationIntervalZ;
  return boost::math::quantile(boost::math::complement(boost::math::normal(), 0.05 / (2.0 * m)));
}

int verdict_family_size(std::span<const MetricCorrelation> correlations) {
  int m = 0;
  for (const MetricCorrelation& c : correlations) m += metric_direction(c.metric) != 0 && std::isfinite(c.correlation.rho);
  return m;
}

RankCorrelation spearman_correlation(std::span<const double> x, std::span<const double> y) {
  std::vector<double> a, b;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i)
    if (is_usable(x[i]) && is_usable(y[i])) {
      a.push_back(x[i]);
      b.push_back(y[i]);
    }
  RankCorrelation out;
  out.count = static_cast<std::int64_t>(a.size());
  out.rho = a.size() < 3 ? std::numeric_limits<double>::quiet_NaN() : rank_pearson(average_ranks(a), average_ranks(b));
  return out;
}

double partial_rank_correlation(double r_xy, double r_xz, double r_yz) {
  // A side that ranks (almost) as z leaves nothing to correlate: NaN, not noise.
  if (!(std::abs(r_xz) < kPartialMaxAbsRho) || !(std::abs(r_yz) < kPartialMaxAbsRho) || !std::isfinite(r_xy))
    return std::numeric_limits<double>::quiet_NaN();
  const double denominator = (1.0 - r_xz * r_xz) * (1.0 - r_yz * r_yz);
  return std::clamp((r_xy - r_xz * r_yz) / std::sqrt(denominator), -1.0, 1.0);
}

RankCorrelation size_correlation(std::span<const double> error_density, std::span<const double> cell_size) {
  if (cell_size.empty()) return {std::numeric_limits<double>::quiet_NaN(), 0};
  return spearman_correlation(error_density, cell_size);
}

namespace {

// rho(x, y) and the partial rho given z over the hexes where all three are usable.
MetricCorrelation correlate_three(std::span<const double> x, std::span<const double> y, std::span<const double> z) {
  MetricCorrelation out;
  out.correlation = spearman_correlation(x, y);
  out.rho_given_size = std::numeric_limits<double>::quiet_NaN();
  if (z.empty()) return out;
  std::vector<double> a, b, c;
  for (std::size_t i = 0; i < std::min({x.size(), y.size(), z.size()}); ++i)
    if (is_usable(x[i]) && is_usable(y[i]) && is_usable(z[i])) {
      a.push_back(x[i]);
      b.push_back(y[i]);
      c.push_back(z[i]);
    }
  if (a.size() < 4) return out;
  const std::vector<double> ra = average_ranks(a), rb = average_ranks(b), rc = average_ranks(c);
  out.rho_given_size = partial_rank_correlation(rank_pearson(ra, rb), rank_pearson(ra, rc), rank_pearson(rb, rc));
  return out;
}

}  // namespace

std::vector<MetricCorrelation> correlate_metrics(std::span<const double> error_density, const HexMetricField& metrics,
                                                 const FemElementField& elements, std::span<const double> cell_size) {
  std::vector<MetricCorrelation> out;
  std::vector<const std::vector<double>*> columns;
  for (int m = 0; m < kNumHexMetrics; ++m) {
    const auto metric = static_cast<HexMetric>(m);
    if (metrics.of(metric).empty()) continue;
    out.push_back({std::string(hex_metric_name(metric)), {}, 0, {}});
    columns.push_back(&metrics.of(metric));
  }
  out.push_back({"fem_kappa", {}, 0, {}});
  columns.push_back(&elements.kappa);
  out.push_back({"fem_lambda_max", {}, 0, {}});
  columns.push_back(&elements.lambda_max);
  out.push_back({"fem_det_j_min", {}, 0, {}});
  columns.push_back(&elements.det_j_min);
  // The density's ranks (and the size's) once, over the hexes where the
  // density (and the size) is usable; a metric usable on all of them reuses
  // them (the same numbers as spearman_correlation / correlate_three).
  const bool has_size = cell_size.size() == error_density.size() && !cell_size.empty();
  std::vector<std::size_t> hexes;
  std::vector<double> density, size;
  bool size_usable = has_size;
  for (std::size_t h = 0; h < error_density.size(); ++h)
    if (is_usable(error_density[h])) {
      hexes.push_back(h);
      density.push_back(error_density[h]);
      if (has_size) {
        size.push_back(cell_size[h]);
        size_usable = size_usable && is_usable(cell_size[h]);
      }
    }
  const std::vector<double> density_ranks = average_ranks(density);
  const std::vector<double> size_ranks = size_usable ? average_ranks(size) : std::vector<double>{};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double density_size = size_usable && hexes.size() >= 4 ? rank_pearson(density_ranks, size_ranks) : nan;
  tbb::parallel_for(std::size_t{0}, out.size(), [&](std::size_t i) {
    const std::vector<double>& metric = *columns[i];
    std::vector<double> values(hexes.size());
    bool all_usable = metric.size() == error_density.size() && (size_usable || !has_size);
    for (std::size_t j = 0; j < hexes.size() && all_usable; ++j) {
      values[j] = metric[hexes[j]];
      all_usable = is_usable(values[j]);
    }
    if (!all_usable) {
      const MetricCorrelation three =
          correlate_three(error_density, metric, has_size ? cell_size : std::span<const double>{});
      out[i].correlation = three.correlation;
      out[i].rho_given_size = three.rho_given_size;
      return;
    }
    out[i].correlation.count = static_cast<std::int64_t>(hexes.size());
    out[i].rho_given_size = nan;
    if (hexes.size() < 3) {
      out[i].correlation.rho = nan;
      return;
    }
    const std::vector<double> metric_ranks = average_ranks(values);
    out[i].correlation.rho = rank_pearson(density_ranks, metric_ranks);
    if (size_usable && hexes.size() >= 4)
      out[i].rho_given_size =
          partial_rank_correlation(out[i].correlation.rho, rank_pearson(metric_ranks, size_ranks), density_size);
  });
  const double adjusted_z = bonferroni_interval_z(verdict_family_size(out));
  for (MetricCorrelation& m : out) {
    m.interval = spearman_interval(m.correlation.rho, m.correlation.count);
    m.adjusted_interval = spearman_interval(m.correlation.rho, m.correlation.count, adjusted_z);
  }
  return out;
}

}  // namespace hq
