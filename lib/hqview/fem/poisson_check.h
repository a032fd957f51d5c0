#pragma once
// The Poisson check (docs/analysis.md "Finite-element check"): on a hex mesh
// whose every hex is a valid trilinear element, -Laplace u_h = 0 with Q1
// elements and u_h = u at every boundary vertex, for each manufactured
// harmonic u (harmonic_solution.h), solved by Jacobi-preconditioned CG
// (pcg.h) to ||r|| <= 1e-10 ||b||. Reports the relative L2 and H1
// semi-norm errors (3 x 3 x 3 Gauss per hex), the largest nodal error, the
// iterations, the extreme eigenvalues of the Jacobi-scaled matrix from CG's
// Lanczos coefficients, lambda_max of the stiffness matrix beside Fried's
// bound, and per hex the shares of the squared errors and the normalised
// error density. Pure: reads the mesh, writes nothing, never throws on a
// bad mesh (it is skipped with the reason).
//
// Fried, "Bounds on the extreme eigenvalues of finite element matrices",
// Int. J. Numer. Meth. Eng. 4 (1972): lambda_max(K) <= m max_e lambda_max(K_e),
// m the largest number of elements at a vertex.

#include <limits>
#include <string>
#include <vector>

#include "hqview/fem/fem_element_field.h"
#include "hqview/fem/harmonic_solution.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/statistics.h"

namespace hq {

struct PoissonOptions {
  std::vector<HarmonicSolution> solutions = default_harmonic_solutions();  // 1 to 4
  double tolerance = 1e-10;                                                // CG: ||r||_2 <= tolerance ||b||_2
  Index min_free_vertices = 27;                                            // fewer free (interior) vertices: skipped
  int stiffness_lanczos_steps = 40;
};

struct PoissonSolutionResult {
  std::string name;
  double l2_error = 0;     // sqrt(sum int (u_h - u)^2) / sqrt(sum int u^2)
  double h1_error = 0;     // sqrt(sum int |grad(u_h - u)|^2) / sqrt(sum int |grad u|^2)
  double nodal_error = 0;  // max_v |u_h(v) - u(v)| / max_v |u(v)|
  int iterations = 0;      // CG iterations to ||r|| <= tolerance ||b||
  int lanczos_steps = 0;   // CG iterations in all (until the Ritz values settled; pcg.h)
  bool converged = false;
  double relative_residual = 0;  // at the end
};

struct PoissonCheck {
  std::string skipped;  // why nothing was solved; empty when solved
  Index num_free_vertices = 0;
  Index min_free_vertices = 0;
  Normalization normalization;  // the principal frame of the mesh's volume (principal_frame.h)
  // The placement-free length of the mesh's volume (moment_length.h),
  // model units: the batch's h/L divides by it.
  double mesh_length = std::numeric_limits<double>::quiet_NaN();
  std::vector<PoissonSolutionResult> solutions;
  // Means over the solutions.
  double mean_l2_error = 0, mean_h1_error = 0, mean_nodal_error = 0, mean_iterations = 0;
  // Jacobi-scaled D^-1/2 K D^-1/2: extreme Ritz values over the solutions' CG runs.
  double scaled_lambda_min = 0, scaled_lambda_max = 0, scaled_condition = 0;
  // The unscaled K_ff (model units): largest Ritz value after a few Lanczos steps.
  double stiffness_lambda_max = 0;
  int stiffness_lanczos_steps = 0;
  double fried_bound = 0;  // max_hexes_at_vertex * max_e lambda_max(K_e)
  Index max_hexes_at_vertex = 0;
  // Per hex (#hexes when solved, else empty): mean over the solutions of the
  // hex's share of the squared L2 and H1 errors (each sums to 1), and the
  // normalised error density sum_s |u_h - u|^2_{H1(e)} / (|e| h_e^2 sum_s |D^2 u_s(x_e)|^2),
  // h_e = |e|^(1/3) (the side of the cube of the hex's volume), x_e the mean
  // of its corners (NaN for |e| <= 0).
  std::vector<double> cell_l2_share, cell_h1_share, cell_error_density;
  // Per hex (#hexes when solved): h_e = |e|^(1/3), model units (the size the
  // density divides by; metric_correlation.h controls for it).
  std::vector<double> cell_size;
  // Spearman's rho over the hexes between the error density and h_e: how much
  // of the density's ranking is the hex size (metric_correlation.h).
  double size_correlation = 0;
  Statistics error_density_stats;
};

// The errors of a nodal Q1 field against the solutions, per hex and in total.
struct Q1FieldErrors {
  int num_solutions = 0;
  // Per hex and solution, [h * k + s]: int_e (u_h - u)^2 and int_e |grad(u_h - u)|^2.
  std::vector<double> l2_squared, h1_squared;
  std::vector<double> volume;  // per hex: int_e |det J| (3 x 3 x 3 Gauss)
  // Per solution: the sums over the hexes (fixed-chunk sums) and of int u^2, int |grad u|^2.
  std::vector<double> total_l2_squared, total_h1_squared, total_u_squared, total_grad_squared;
};

// `nodal`: #vertices x k interleaved values (k = solutions.size()).
Q1FieldErrors q1_field_errors(const HexMesh& mesh, const std::vector<double>& nodal,
                              const std::vector<HarmonicSolution>& solutions, const Normalization& normalization);

// The solutions sampled at every vertex (#vertices x k interleaved): the interpolant I_h u.
std::vector<double> interpolate_solutions(const HexMesh& mesh, const std::vector<HarmonicSolution>& solutions,
                                          const Normalization& normalization);

// The check; `elements` from compute_fem_elements(mesh).
PoissonCheck run_poisson_check(const HexMesh& mesh, const Topology& topology, const FemElementField& elements,
                               const PoissonOptions& options = {});

}  // namespace hq
