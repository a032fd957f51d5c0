#include "hqview/fem/pcg.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "hqview/core/stop.h"
#include "hqview/fem/fixed_chunks.h"
#include "hqview/fem/symmetric_product.h"

namespace hq {
namespace {

constexpr int kMaxColumns = 4;
using Sums = std::array<double, kMaxColumns>;

// Per column: sum_i a[i*stride+s] * b[i*stride+s], s < k (stride: k, or 4
// in CG's padded layout of three columns).
Sums column_dots(const std::vector<double>& a, const std::vector<double>& b, std::size_t rows, int k,
                 std::size_t stride) {
  const std::size_t uk = static_cast<std::size_t>(k);
  return detail::sum_fem_chunks<kMaxColumns>(rows, [&](std::size_t first, std::size_t last) {
    Sums s{};
    for (std::size_t i = first; i < last; ++i)
      for (std::size_t c = 0; c < uk; ++c) s[c] += a[i * stride + c] * b[i * stride + c];
    return s;
  });
}

// CG's vectors hold K columns in rows of L doubles: three columns get a
// fourth that stays zero, so that the sparse product moves a row's values
// as one four-double value (symmetric_product.h, one AVX2 register).
template <std::size_t K>
inline constexpr std::size_t kLayout = K == 3 ? 4 : K;

using Mask = std::array<bool, kMaxColumns>;

// r -= alpha q for the columns that stepped, and per column (r, r) and
// (r, D^-1 r) (the second in s[kMaxColumns + c]). K columns in rows of L.
template <std::size_t K, std::size_t L>
std::array<double, 2 * kMaxColumns> update_residual(std::vector<double>& r, const std::vector<double>& q,
                                                    const std::vector<double>& inverse_diagonal,
                                                    const std::array<double, kMaxColumns>& alpha, const Mask& stepped) {
  const bool all = std::all_of(stepped.begin(), stepped.begin() + K, [](bool b) { return b; });
  return detail::sum_fem_chunks<2 * kMaxColumns>(inverse_diagonal.size(), [&](std::size_t first, std::size_t last) {
    std::array<double, 2 * kMaxColumns> s{};
    if constexpr (L == 4) {
      if (all) {  // a row as one four-double value (a padding column: alpha 0, its zeros stay)
        const detail::Quad a = {alpha[0], alpha[1], alpha[2], alpha[3]};
        detail::Quad rr{}, rz{}, ri, qi;
        for (std::size_t i = first; i < last; ++i) {
          detail::load_quad(ri, &r[i * 4]);
          detail::load_quad(qi, &q[i * 4]);
          ri = ri - a * qi;
          detail::store_quad(&r[i * 4], ri);
          rr += ri * ri;
          rz += ri * (ri * inverse_diagonal[i]);
        }
        for (std::size_t c = 0; c < K; ++c) {
          s[c] = rr[c];
          s[kMaxColumns + c] = rz[c];
        }
        return s;
      }
    }
    for (std::size_t i = first; i < last; ++i) {
      const double d = inverse_diagonal[i];
      for (std::size_t c = 0; c < K; ++c) {
        if (!all && !stepped[c]) continue;
        const std::size_t j = i * L + c;
        const double rj = r[j] - alpha[c] * q[j];
        r[j] = rj;
        s[c] += rj * rj;
        s[kMaxColumns + c] += rj * (rj * d);
      }
    }
    return s;
  });
}

// x += alpha p for the columns that stepped, then p = D^-1 r + beta p for
// those still active.
template <std::size_t K, std::size_t L>
void update_iterate(std::vector<double>& x, std::vector<double>& p, const std::vector<double>& r,
                    const std::vector<double>& inverse_diagonal, const std::array<double, kMaxColumns>& alpha,
                    const std::array<double, kMaxColumns>& beta, const Mask& stepped, const Mask& active) {
  const bool all = std::all_of(stepped.begin(), stepped.begin() + K, [](bool b) { return b; }) &&
                   std::all_of(active.begin(), active.begin() + K, [](bool b) { return b; });
  detail::for_fem_chunks(inverse_diagonal.size(), [&](std::size_t first, std::size_t last) {
    if constexpr (L == 4) {
      if (all) {  // as update_residual's
        const detail::Quad a = {alpha[0], alpha[1], alpha[2], alpha[3]}, b = {beta[0], beta[1], beta[2], beta[3]};
        detail::Quad xi, pi, ri;
        for (std::size_t i = first; i < last; ++i) {
          detail::load_quad(xi, &x[i * 4]);
          detail::load_quad(pi, &p[i * 4]);
          detail::load_quad(ri, &r[i * 4]);
          detail::store_quad(&x[i * 4], xi + a * pi);
          detail::store_quad(&p[i * 4], ri * inverse_diagonal[i] + b * pi);
        }
        return;
      }
    }
    for (std::size_t i = first; i < last; ++i) {
      const double d = inverse_diagonal[i];
      for (std::size_t c = 0; c < K; ++c) {
        const std::size_t j = i * L + c;
        if (all || stepped[c]) x[j] += alpha[c] * p[j];
        if (all || active[c]) p[j] = r[j] * d + beta[c] * p[j];
      }
    }
  });
}

// Ritz values of the symmetric tridiagonal (diag, sub).
RitzExtremes tridiagonal_extremes(const std::vector<double>& diag, const std::vector<double>& sub) {
  if (diag.empty()) return {};
  Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(diag.data(), static_cast<Eigen::Index>(diag.size()));
  Eigen::VectorXd e(static_cast<Eigen::Index>(diag.size() - 1));
  for (std::size_t i = 0; i + 1 < diag.size(); ++i) e[static_cast<Eigen::Index>(i)] = sub[i];
  if (diag.size() == 1) return {d[0], d[0]};
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  solver.computeFromTridiagonal(d, e, Eigen::EigenvaluesOnly);
  return {solver.eigenvalues().minCoeff(), solver.eigenvalues().maxCoeff()};
}

template <std::size_t K>
PcgResult solve_pcg(const CsrMatrix& a, const std::vector<double>& diagonal, const std::vector<double>& b,
                    const PcgOptions& options) {
  constexpr std::size_t L = kLayout<K>;
  const std::size_t rows = a.num_rows(), n = rows * L;
  PcgResult out;
  out.columns.resize(K);
  std::vector<double> inverse_diagonal(rows);
  for (std::size_t i = 0; i < rows; ++i) inverse_diagonal[i] = 1.0 / diagonal[i];
  std::vector<double> x(n, 0.0), r(n, 0.0), p(n, 0.0), q(n), overflow(n, 0.0);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t c = 0; c < K; ++c) {
      r[i * L + c] = b[i * K + c];
      p[i * L + c] = r[i * L + c] * inverse_diagonal[i];
    }
  const Sums bb = column_dots(b, b, rows, K, K);
  Sums rz = column_dots(r, p, rows, K, L);
  Mask active{}, stepped{};
  std::array<double, kMaxColumns> target{};
  std::array<RitzExtremes, kMaxColumns> last_ritz{};
  for (std::size_t c = 0; c < K; ++c) {
    target[c] = options.tolerance * std::sqrt(bb[c]);
    active[c] = bb[c] > 0;
    out.columns[c].converged = !active[c];
  }
  const int max_iterations = options.max_iterations > 0
                                 ? options.max_iterations
                                 : static_cast<int>(std::min<std::size_t>(10 * rows + 100, 1'000'000));
  // After convergence: whether the Ritz values have settled (checked every
  // ritz_check_every iterations; the extension is capped).
  const auto ritz_settled = [&](std::size_t c) {
    PcgColumn& column = out.columns[c];
    const int extra = column.lanczos_steps - column.iterations;
    if (extra >= options.max_ritz_iterations) return true;
    if (extra % std::max(1, options.ritz_check_every) != 0) return false;
    const RitzExtremes now = cg_ritz_extremes(column);
    const bool settled = extra > 0 && std::abs(now.min - last_ritz[c].min) <= options.ritz_tolerance * now.min &&
                         std::abs(now.max - last_ritz[c].max) <= options.ritz_tolerance * now.max;
    last_ritz[c] = now;
    return settled;
  };
  for (int it = 0; it < max_iterations; ++it) {
    if (std::none_of(active.begin(), active.begin() + K, [](bool x) { return x; })) break;
    stop::check();  // a signal or --mesh-timeout lands between iterations
    const std::array<double, L> pq = detail::symmetric_product<L>(a, p.data(), q.data(), overflow.data(), p.data());
    std::array<double, kMaxColumns> alpha{};
    for (std::size_t c = 0; c < K; ++c) {
      stepped[c] = false;
      if (!active[c]) continue;
      if (!(pq[c] > 0) || !std::isfinite(pq[c])) {  // not positive definite along p (or at rounding level): stop
        active[c] = false;
        continue;
      }
      stepped[c] = true;
      alpha[c] = rz[c] / pq[c];
      out.columns[c].alphas.push_back(alpha[c]);
      ++out.columns[c].lanczos_steps;
      if (!out.columns[c].converged) ++out.columns[c].iterations;
    }
    // r -= alpha q, and the new (r, r), (r, D^-1 r).
    const auto sums = update_residual<K, L>(r, q, inverse_diagonal, alpha, stepped);
    std::array<double, kMaxColumns> beta{};
    for (std::size_t c = 0; c < K; ++c) {
      if (!stepped[c]) continue;
      PcgColumn& column = out.columns[c];
      column.relative_residual = std::sqrt(sums[c] / bb[c]);
      if (!column.converged) column.converged = std::sqrt(sums[c]) <= target[c];
      if ((column.converged && ritz_settled(c)) || !(sums[kMaxColumns + c] > 0)) {
        active[c] = false;
        continue;
      }
      beta[c] = sums[kMaxColumns + c] / rz[c];
      rz[c] = sums[kMaxColumns + c];
      column.betas.push_back(beta[c]);
    }
    // x += alpha p (with the p alpha was for), then p = D^-1 r + beta p.
    update_iterate<K, L>(x, p, r, inverse_diagonal, alpha, beta, stepped, active);
  }
  out.x.resize(rows * K);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t c = 0; c < K; ++c) out.x[i * K + c] = x[i * L + c];
  return out;
}

}  // namespace

PcgResult solve_pcg(const CsrMatrix& a, const std::vector<double>& diagonal, const std::vector<double>& b, int k,
                    const PcgOptions& options) {
  switch (k) {
    case 1:
      return solve_pcg<1>(a, diagonal, b, options);
    case 2:
      return solve_pcg<2>(a, diagonal, b, options);
    case 3:
      return solve_pcg<3>(a, diagonal, b, options);
    default:
      return solve_pcg<4>(a, diagonal, b, options);
  }
}

RitzExtremes cg_ritz_extremes(const PcgColumn& column) {
  const std::size_t m = column.alphas.size();
  std::vector<double> diag(m), sub(m > 0 ? m - 1 : 0);
  for (std::size_t j = 0; j < m; ++j) {
    diag[j] = 1.0 / column.alphas[j] + (j > 0 ? column.betas[j - 1] / column.alphas[j - 1] : 0.0);
    if (j + 1 < m) sub[j] = std::sqrt(column.betas[j]) / column.alphas[j];
  }
  return tridiagonal_extremes(diag, sub);
}

double lanczos_largest_eigenvalue(const CsrMatrix& a, int steps, const std::vector<Index>& row_ids) {
  const std::size_t n = a.num_rows();
  if (n == 0 || steps <= 0) return 0;
  // A fixed start (splitmix64 of the row's id), normalised.
  std::vector<double> v(n), v_prev(n, 0.0), w(n), overflow(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t id = row_ids.size() == n ? static_cast<std::uint64_t>(row_ids[i]) : i;
    std::uint64_t z = (id + 1) * 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    v[i] = static_cast<double>(z >> 11) / 9007199254740992.0 - 0.5;
  }
  const double norm0 = std::sqrt(column_dots(v, v, n, 1, 1)[0]);
  for (double& x : v) x /= norm0;
  std::vector<double> alphas, betas;
  double beta = 0;
  for (int j = 0; j < steps && static_cast<std::size_t>(j) < n; ++j) {
    stop::check();
    // w = A v (one overflow for all), and alpha = (v, A v) fused in.
    const double alpha = detail::symmetric_product<1>(a, v.data(), w.data(), overflow.data(), v.data())[0];
    alphas.push_back(alpha);
    const double next = std::sqrt(detail::sum_fem_chunks<1>(n, [&](std::size_t first, std::size_t last) {
      double s = 0;
      for (std::size_t i = first; i < last; ++i) {
        w[i] -= alpha * v[i] + beta * v_prev[i];
        s += w[i] * w[i];
      }
      return std::array<double, 1>{s};
    })[0]);
    if (!(next > 1e-14 * std::abs(alpha))) break;  // an invariant subspace: its Ritz values are exact
    betas.push_back(next);
    beta = next;
    std::swap(v_prev, v);
    detail::for_fem_chunks(n, [&](std::size_t first, std::size_t last) {
      for (std::size_t i = first; i < last; ++i) v[i] = w[i] / next;
    });
  }
  betas.resize(alphas.empty() ? 0 : alphas.size() - 1);
  return tridiagonal_extremes(alphas, betas).max;
}

}  // namespace hq
