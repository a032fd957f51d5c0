#pragma once
// Jacobi-preconditioned conjugate gradients on k right-hand sides at once
// (one sparse product per iteration serves all columns; each column keeps
// its own scalars and stops at ||r||_2 <= tolerance ||b||_2), with the
// Lanczos coefficients of each run, and a few plain Lanczos steps for the
// largest eigenvalue of a matrix. The matrix is read from its upper
// triangle (symmetric_product.h, with p . Ap fused in); an iteration is that
// product and two vector passes (r -= alpha q with the new dots; x += alpha p
// with p = D^-1 r + beta p; D^-1 r is never stored). Every dot product is a
// fixed-chunk sum (fixed_chunks.h): the iterates have the same bits for any
// thread count. Three columns are kept as four (a fourth of zeros) so that
// the product moves a row's values as one four-double value.
//
// Lanczos from CG (Saad, "Iterative Methods for Sparse Linear Systems",
// 2nd ed., 6.7.3): with CG's alpha_j, beta_j the tridiagonal T has
// T_00 = 1/alpha_0, T_jj = 1/alpha_j + beta_{j-1}/alpha_{j-1},
// T_{j,j+1} = sqrt(beta_j)/alpha_j; its eigenvalues (Ritz values) lie in
// [lambda_min, lambda_max] of D^-1/2 A D^-1/2 and its extreme ones converge
// to them first.

#include <vector>

#include "hqview/fem/laplace_system.h"

namespace hq {

struct PcgOptions {
  double tolerance = 1e-10;  // relative to ||b||_2
  // Once the residual is below the tolerance, a column goes on until its
  // extreme Ritz values change by at most ritz_tolerance (relative) over
  // ritz_check_every iterations, for at most max_ritz_iterations more: on
  // small meshes CG converges before its Lanczos estimate of lambda_max
  // does. The iterate keeps improving meanwhile.
  double ritz_tolerance = 1e-9;
  int ritz_check_every = 5;
  int max_ritz_iterations = 50;
  int max_iterations = 0;  // 0: 10 * rows + 100
};

struct PcgColumn {
  int iterations = 0;                 // to ||r|| <= tolerance ||b|| (the total when never reached)
  int lanczos_steps = 0;              // iterations in all (the Ritz values' steps)
  bool converged = false;             // the residual reached the tolerance
  double relative_residual = 0;       // ||r||_2 / ||b||_2 at the end (0 for b = 0)
  std::vector<double> alphas, betas;  // betas: one fewer than alphas (or as many when stopped by the cap)
};

struct PcgResult {
  std::vector<double> x;  // rows x k interleaved
  std::vector<PcgColumn> columns;
};

// Solves A x_s = b_s for the k interleaved columns of b (1 <= k <= 4), from x = 0.
// `diagonal`: A's diagonal (positive). Never throws on a bad matrix: a
// column whose p.Ap is not positive stops, not converged. Polls hq::stop
// each iteration (throws what stop::check() throws).
PcgResult solve_pcg(const CsrMatrix& a, const std::vector<double>& diagonal, const std::vector<double>& b, int k,
                    const PcgOptions& options = {});

struct RitzExtremes {
  double min = 0, max = 0;
};
// The extreme eigenvalues of CG's Lanczos tridiagonal (Eigen's tridiagonal QR).
RitzExtremes cg_ritz_extremes(const PcgColumn& column);

// The largest Ritz value after `steps` Lanczos steps on A (no
// reorthogonalisation: three vectors in memory), from a fixed
// pseudo-random start: a lower bound of lambda_max(A) that converges fast.
// The start's entry of a row is a hash of row_ids[row] (of the row number
// when row_ids is empty), so that a renumbering of the rows keeps the start.
double lanczos_largest_eigenvalue(const CsrMatrix& a, int steps, const std::vector<Index>& row_ids = {});

}  // namespace hq
