#include "hqview/fem/pcg.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdint>

#include "hqview/core/stop.h"
#include "hqview/fem/fixed_chunks.h"

namespace hq {
namespace {

constexpr int kMaxColumns = 4;
using Sums = std::array<double, kMaxColumns>;

// Per column: sum_i a[i*k+s] * b[i*k+s] (optionally divided by d[i]).
Sums column_dots(const std::vector<double>& a, const std::vector<double>& b, std::size_t rows, int k) {
  const std::size_t uk = static_cast<std::size_t>(k);
  return detail::sum_fem_chunks<kMaxColumns>(rows, [&](std::size_t first, std::size_t last) {
    Sums s{};
    for (std::size_t i = first; i < last; ++i)
      for (std::size_t c = 0; c < uk; ++c) s[c] += a[i * uk + c] * b[i * uk + c];
    return s;
  });
}

// q = A p for K interleaved columns, and per column p . q (fixed chunks).
template <std::size_t K>
Sums multiply_and_dot(const CsrMatrix& a, const std::vector<double>& p, std::vector<double>& q) {
  return detail::sum_fem_chunks<kMaxColumns>(a.num_rows(), [&](std::size_t first, std::size_t last) {
    Sums s{};
    for (std::size_t r = first; r < last; ++r) {
      std::array<double, K> sum{};
      for (std::int64_t e = a.offsets[r]; e < a.offsets[r + 1]; ++e) {
        const double v = a.values[static_cast<std::size_t>(e)];
        const double* pc = p.data() + static_cast<std::size_t>(a.columns[static_cast<std::size_t>(e)]) * K;
        for (std::size_t c = 0; c < K; ++c) sum[c] += v * pc[c];
      }
      for (std::size_t c = 0; c < K; ++c) {
        q[r * K + c] = sum[c];
        s[c] += p[r * K + c] * sum[c];
      }
    }
    return s;
  });
}

Sums multiply_and_dot(const CsrMatrix& a, const std::vector<double>& p, std::vector<double>& q, int k) {
  switch (k) {
    case 1:
      return multiply_and_dot<1>(a, p, q);
    case 2:
      return multiply_and_dot<2>(a, p, q);
    case 3:
      return multiply_and_dot<3>(a, p, q);
    default:
      return multiply_and_dot<4>(a, p, q);
  }
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

}  // namespace

PcgResult solve_pcg(const CsrMatrix& a, const std::vector<double>& diagonal, const std::vector<double>& b, int k,
                    const PcgOptions& options) {
  const std::size_t rows = a.num_rows(), uk = static_cast<std::size_t>(k), n = rows * uk;
  PcgResult out;
  out.x.assign(n, 0.0);
  out.columns.resize(uk);
  std::vector<double> r = b, z(n), p(n), q(n);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t c = 0; c < uk; ++c) z[i * uk + c] = r[i * uk + c] / diagonal[i];
  p = z;
  const Sums bb = column_dots(b, b, rows, k);
  Sums rz = column_dots(r, z, rows, k);
  std::array<bool, kMaxColumns> active{};
  std::array<double, kMaxColumns> target{};
  std::array<RitzExtremes, kMaxColumns> last_ritz{};
  for (std::size_t c = 0; c < uk; ++c) {
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
    bool any = false;
    for (std::size_t c = 0; c < uk; ++c) any = any || active[c];
    if (!any) break;
    stop::check();  // a signal or --mesh-timeout lands between iterations
    const Sums pq = multiply_and_dot(a, p, q, k);
    std::array<double, kMaxColumns> alpha{};
    for (std::size_t c = 0; c < uk; ++c) {
      if (!active[c]) continue;
      if (!(pq[c] > 0) || !std::isfinite(pq[c])) {  // not positive definite along p (or at rounding level): stop
        active[c] = false;
        continue;
      }
      alpha[c] = rz[c] / pq[c];
      out.columns[c].alphas.push_back(alpha[c]);
      ++out.columns[c].lanczos_steps;
      if (!out.columns[c].converged) ++out.columns[c].iterations;
    }
    // x += alpha p; r -= alpha q; z = D^-1 r; and the new (r, r), (r, z).
    const auto sums = detail::sum_fem_chunks<2 * kMaxColumns>(rows, [&](std::size_t first, std::size_t last) {
      std::array<double, 2 * kMaxColumns> s{};
      for (std::size_t i = first; i < last; ++i)
        for (std::size_t c = 0; c < uk; ++c) {
          if (!active[c]) continue;
          const std::size_t j = i * uk + c;
          out.x[j] += alpha[c] * p[j];
          r[j] -= alpha[c] * q[j];
          z[j] = r[j] / diagonal[i];
          s[c] += r[j] * r[j];
          s[kMaxColumns + c] += r[j] * z[j];
        }
      return s;
    });
    std::array<double, kMaxColumns> beta{};
    for (std::size_t c = 0; c < uk; ++c) {
      if (!active[c]) continue;
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
    detail::for_fem_chunks(rows, [&](std::size_t first, std::size_t last) {
      for (std::size_t i = first; i < last; ++i)
        for (std::size_t c = 0; c < uk; ++c)
          if (active[c]) p[i * uk + c] = z[i * uk + c] + beta[c] * p[i * uk + c];
    });
  }
  return out;
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

double lanczos_largest_eigenvalue(const CsrMatrix& a, int steps) {
  const std::size_t n = a.num_rows();
  if (n == 0 || steps <= 0) return 0;
  // A fixed start (splitmix64 of the row), normalised.
  std::vector<double> v(n), v_prev(n, 0.0), w(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t z = (i + 1) * 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    v[i] = static_cast<double>(z >> 11) / 9007199254740992.0 - 0.5;
  }
  const double norm0 = std::sqrt(column_dots(v, v, n, 1)[0]);
  for (double& x : v) x /= norm0;
  std::vector<double> alphas, betas;
  double beta = 0;
  for (int j = 0; j < steps && static_cast<std::size_t>(j) < n; ++j) {
    stop::check();
    multiply(a, v, w, 1);
    const double alpha = column_dots(w, v, n, 1)[0];
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
    detail::for_fem_chunks(n, [&](std::size_t first, std::size_t last) {
      for (std::size_t i = first; i < last; ++i) {
        v_prev[i] = v[i];
        v[i] = w[i] / next;
      }
    });
  }
  betas.resize(alphas.empty() ? 0 : alphas.size() - 1);
  return tridiagonal_extremes(alphas, betas).max;
}

}  // namespace hq
