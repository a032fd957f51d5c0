#include "hqview/fem/poisson_check.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "hqview/fem/laplace_system.h"
#include "hqview/fem/metric_correlation.h"
#include "hqview/fem/pcg.h"
#include "hqview/quality/corner_jacobian.h"
#include "hqview/quality/hex_metrics.h"
#include "support/fixtures.h"

namespace hq {
namespace {

// An n^3 box of side 1 (h = 1/n); with `perturbation` > 0 every interior vertex
// moved by up to perturbation * h along each axis (a fixed pseudo-random pattern).
HexMesh unit_box(int n, double perturbation = 0) {
  HexMesh mesh = test::grid(n);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    Vec3& p = mesh.points[v];
    const bool interior = p.x > 0 && p.x < n && p.y > 0 && p.y < n && p.z > 0 && p.z < n;
    if (interior && perturbation > 0) {
      for (int a = 0; a < 3; ++a) {
        const double t = std::sin(12.9898 * static_cast<double>(v) + 78.233 * a) * 43758.5453;
        p[a] += perturbation * 2 * (t - std::floor(t) - 0.5);
      }
    }
    p = p / static_cast<double>(n);
  }
  return mesh;
}

PoissonCheck check(const HexMesh& mesh, const PoissonOptions& options = {}) {
  const Topology topology = build_topology(mesh);
  return run_poisson_check(mesh, topology, compute_fem_elements(mesh), options);
}

// Q1 converges as h^2 in L2 and h in the H1 semi-norm.
TEST(PoissonCheck, ConvergesAtTheQ1Rates) {
  std::vector<PoissonCheck> runs;
  for (int n : {4, 8, 16, 32}) runs.push_back(check(unit_box(n)));
  for (std::size_t i = 0; i < runs.size(); ++i) {
    ASSERT_TRUE(runs[i].skipped.empty()) << runs[i].skipped;
    for (const PoissonSolutionResult& s : runs[i].solutions) EXPECT_TRUE(s.converged) << s.name;
  }
  for (std::size_t i = 1; i < runs.size(); ++i)
    for (std::size_t s = 0; s < 3; ++s) {
      const double l2 = runs[i - 1].solutions[s].l2_error / runs[i].solutions[s].l2_error;
      const double h1 = runs[i - 1].solutions[s].h1_error / runs[i].solutions[s].h1_error;
      EXPECT_GE(l2, 3.8) << i << " " << s;
      EXPECT_LE(l2, 4.2) << i << " " << s;
      EXPECT_GE(h1, 1.9) << i << " " << s;
      EXPECT_LE(h1, 2.1) << i << " " << s;
    }
  // The cube's three solutions are the same problem turned: the same errors.
  EXPECT_NEAR(runs[1].solutions[0].l2_error, runs[1].solutions[2].l2_error, 1e-9 * runs[1].solutions[0].l2_error);
}

// The Jacobi-scaled matrix of the uniform grid has closed-form eigenvalues:
// K = h (K1 (x) M1 (x) M1 + M1 (x) K1 (x) M1 + M1 (x) M1 (x) K1) with the 1D
// stiffness K1 = tridiag(-1, 2, -1) and mass M1 = tridiag(1, 4, 1) / 6, whose
// eigenvalues are 2 - 2 cos t and (2 + cos t) / 3, t = j pi / n, j = 1 .. n-1;
// the diagonal is 8 h / 3.
TEST(PoissonCheck, LanczosEstimatesMatchTheGridsEigenvalues) {
  const int n = 12;
  const PoissonCheck c = check(unit_box(n));
  ASSERT_TRUE(c.skipped.empty());
  const double h = 1.0 / n;
  double lambda_min = INFINITY, lambda_max = 0;
  auto k1 = [&](int j) { return 2 - 2 * std::cos(j * std::numbers::pi / n); };
  auto m1 = [&](int j) { return (2 + std::cos(j * std::numbers::pi / n)) / 3; };
  for (int a = 1; a < n; ++a)
    for (int b = 1; b < n; ++b)
      for (int d = 1; d < n; ++d) {
        const double lambda = h * (k1(a) * m1(b) * m1(d) + m1(a) * k1(b) * m1(d) + m1(a) * m1(b) * k1(d));
        lambda_min = std::min(lambda_min, lambda);
        lambda_max = std::max(lambda_max, lambda);
      }
  const double diagonal = 8.0 / 3.0 * h;
  EXPECT_NEAR(c.scaled_lambda_min, lambda_min / diagonal, 1e-6 * lambda_min / diagonal);
  EXPECT_NEAR(c.scaled_lambda_max, lambda_max / diagonal, 1e-6 * lambda_max / diagonal);
  EXPECT_NEAR(c.scaled_condition, lambda_max / lambda_min, 1e-5 * lambda_max / lambda_min);
  // Lanczos on K: a lower bound, close after a few steps; Fried's bound above it.
  EXPECT_LE(c.stiffness_lambda_max, lambda_max * (1 + 1e-12));
  EXPECT_GE(c.stiffness_lambda_max, 0.97 * lambda_max);
  EXPECT_EQ(c.max_hexes_at_vertex, 8);
  EXPECT_NEAR(c.fried_bound, 8 * 0.5 * h, 1e-14);
  EXPECT_LE(c.stiffness_lambda_max, c.fried_bound);
}

// Perturbed grids: larger errors and kappa; the Galerkin solution is the best
// approximation in energy, so its H1 error is at most the interpolant's (a
// check that an interpolation in place of the solve fails).
TEST(PoissonCheck, PerturbedGridsAreWorseAndGalerkinBeatsTheInterpolant) {
  for (int n : {4, 8, 16}) {
    const HexMesh regular = unit_box(n), perturbed = unit_box(n, 0.3);
    const PoissonCheck a = check(regular), b = check(perturbed);
    ASSERT_TRUE(b.skipped.empty()) << b.skipped;
    EXPECT_GT(b.mean_l2_error, a.mean_l2_error) << n;
    EXPECT_GT(b.mean_h1_error, a.mean_h1_error) << n;
    EXPECT_GT(compute_fem_elements(perturbed).kappa_stats.max, compute_fem_elements(regular).kappa_stats.max);
    EXPECT_GT(b.scaled_condition, a.scaled_condition) << n;
    for (const HexMesh* mesh : {&regular, &perturbed}) {
      const Topology topology = build_topology(*mesh);
      const PoissonCheck solved = run_poisson_check(*mesh, topology, compute_fem_elements(*mesh));
      const auto solutions = default_harmonic_solutions();
      const Normalization norm = used_points_normalization(*mesh, topology);
      const Q1FieldErrors interpolant =
          q1_field_errors(*mesh, interpolate_solutions(*mesh, solutions, norm), solutions, norm);
      for (std::size_t s = 0; s < 3; ++s) {
        const double interpolant_h1 = std::sqrt(interpolant.total_h1_squared[s] / interpolant.total_grad_squared[s]);
        EXPECT_LE(solved.solutions[s].h1_error, interpolant_h1 * (1 + 1e-9)) << n << " " << s;
        EXPECT_GT(solved.solutions[s].nodal_error, 0) << "the interior was solved, not interpolated";
      }
    }
  }
}

// The patch test: a linear u is reproduced exactly on a distorted mesh.
TEST(PoissonCheck, PatchTest) {
  PoissonOptions options;
  options.solutions = {{"linear", HarmonicSolution::Kind::linear, 0, {0.3, -1.2, 2.0}}};
  const PoissonCheck c = check(unit_box(6, 0.35), options);
  ASSERT_TRUE(c.skipped.empty());
  EXPECT_LE(c.solutions[0].nodal_error, 1e-10);
  EXPECT_LE(c.solutions[0].l2_error, 1e-10);
  EXPECT_LE(c.solutions[0].h1_error, 1e-10);
}

// Shares sum to one and point at the perturbed corner.
TEST(PoissonCheck, PerHexSharesAndDensity) {
  HexMesh mesh = unit_box(8);
  const std::size_t moved = 3 + 9 * (3 + 9 * 3);  // vertex (3, 3, 3)
  mesh.points[moved] = mesh.points[moved] + Vec3{0.05, 0.04, -0.045};
  const PoissonCheck c = check(mesh);
  ASSERT_TRUE(c.skipped.empty());
  double l2 = 0, h1 = 0;
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) {
    l2 += c.cell_l2_share[h];
    h1 += c.cell_h1_share[h];
  }
  EXPECT_NEAR(l2, 1, 1e-12);
  EXPECT_NEAR(h1, 1, 1e-12);
  std::size_t worst = 0;
  for (std::size_t h = 1; h < mesh.hexes.size(); ++h)
    if (c.cell_error_density[h] > c.cell_error_density[worst]) worst = h;
  bool touches = false;
  for (Index v : mesh.hexes[worst]) touches = touches || static_cast<std::size_t>(v) == moved;
  EXPECT_TRUE(touches) << "the densest hex " << worst << " does not use the moved vertex";
  EXPECT_EQ(c.error_density_stats.count, static_cast<std::int64_t>(mesh.hexes.size()));
}

// The density shows where the mesh is bad: on a 12^3 box whose interior
// vertices near the centre moved by up to 0.3 h, the hexes using a moved
// vertex have a higher density than the rest, and across all hexes the
// density falls as the scaled Jacobian rises (Spearman rho < 0). With h_e the
// hex's diameter (the first version: it grows with distortion and divides
// the shape's effect out) the median ratio is 0.95 and rho(SJ) +0.08.
TEST(PoissonCheck, DensityIsHigherWhereTheMeshIsBad) {
  const int n = 12;
  HexMesh mesh = unit_box(n);
  std::vector<char> moved(mesh.points.size(), 0);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    Vec3& p = mesh.points[v];
    if (std::abs(p.x - 0.5) < 0.2 && std::abs(p.y - 0.5) < 0.2 && std::abs(p.z - 0.5) < 0.2) {
      for (int a = 0; a < 3; ++a) {
        const double t = std::sin(12.9898 * static_cast<double>(v) + 78.233 * a) * 43758.5453;
        p[a] += 0.3 * 2 * (t - std::floor(t) - 0.5) / n;
      }
      moved[v] = 1;
    }
  }
  const PoissonCheck c = check(mesh);
  ASSERT_TRUE(c.skipped.empty()) << c.skipped;
  std::vector<double> in_region, elsewhere, sj;
  for (std::size_t h = 0; h < mesh.hexes.size(); ++h) {
    bool uses_moved = false;
    for (Index v : mesh.hexes[h]) uses_moved = uses_moved || moved[static_cast<std::size_t>(v)];
    (uses_moved ? in_region : elsewhere).push_back(c.cell_error_density[h]);
    sj.push_back(hex_scaled_jacobian(hex_corners(mesh, static_cast<Index>(h))));
  }
  ASSERT_GT(in_region.size(), 100u);
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  EXPECT_GT(median(in_region), 1.15 * median(elsewhere));
  EXPECT_LT(spearman_correlation(c.cell_error_density, sj).rho, -0.1);
  // h_e = |e|^(1/3) per hex (the volume the errors integrate), and the
  // scaled Jacobian still ranks the density with the size held fixed.
  ASSERT_EQ(c.cell_size.size(), mesh.hexes.size());
  for (std::size_t h = 0; h < mesh.hexes.size(); h += 97)
    EXPECT_NEAR(c.cell_size[h], std::cbrt(hex_volume(hex_corners(mesh, static_cast<Index>(h)))), 1e-12);
  EXPECT_DOUBLE_EQ(c.size_correlation, spearman_correlation(c.cell_error_density, c.cell_size).rho);
  EXPECT_LT(partial_rank_correlation(spearman_correlation(c.cell_error_density, sj).rho, c.size_correlation,
                                     spearman_correlation(sj, c.cell_size).rho),
            -0.1);
}

TEST(PoissonCheck, SkipsInvalidAndOneLayerMeshes) {
  HexMesh inverted = unit_box(4);
  std::swap(inverted.hexes[5][0], inverted.hexes[5][4]);
  std::swap(inverted.hexes[5][1], inverted.hexes[5][5]);
  std::swap(inverted.hexes[5][2], inverted.hexes[5][6]);
  std::swap(inverted.hexes[5][3], inverted.hexes[5][7]);
  const PoissonCheck a = check(inverted);
  EXPECT_EQ(a.skipped, "1 hex is not a valid trilinear element (a Gauss-point det J <= 0)");
  EXPECT_TRUE(a.solutions.empty());
  EXPECT_TRUE(a.cell_error_density.empty());
  const PoissonCheck b = check(test::box_grid(20, 20, 1));
  EXPECT_EQ(b.skipped, "0 free (interior) vertices, fewer than 27");
  const PoissonCheck c = check(test::box_grid(4, 4, 2));  // 9 interior vertices
  EXPECT_EQ(c.num_free_vertices, 9);
  EXPECT_FALSE(c.skipped.empty());
}

// Bit for bit the same on one thread and on two.
TEST(PoissonCheck, SameBitsForAnyThreadCount) {
  const HexMesh mesh = unit_box(14, 0.3);
  PoissonCheck one, two;
  {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, 1);
    one = check(mesh);
  }
  {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, 2);
    two = check(mesh);
  }
  ASSERT_EQ(one.solutions.size(), 3u);
  for (std::size_t s = 0; s < 3; ++s) {
    EXPECT_EQ(std::memcmp(&one.solutions[s].l2_error, &two.solutions[s].l2_error, sizeof(double)), 0);
    EXPECT_EQ(one.solutions[s].iterations, two.solutions[s].iterations);
  }
  EXPECT_EQ(std::memcmp(&one.scaled_lambda_min, &two.scaled_lambda_min, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&one.stiffness_lambda_max, &two.stiffness_lambda_max, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(one.cell_error_density.data(), two.cell_error_density.data(),
                        one.cell_error_density.size() * sizeof(double)),
            0);
}

}  // namespace
}  // namespace hq
