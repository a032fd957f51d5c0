#include "hqview/fem/poisson_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hqview/fem/fixed_chunks.h"
#include "hqview/fem/laplace_system.h"
#include "hqview/fem/metric_correlation.h"
#include "hqview/fem/pcg.h"
#include "hqview/fem/principal_frame.h"
#include "hqview/fem/q1_element.h"

namespace hq {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// 3-point Gauss-Legendre on [-1, 1]: exact for the Q1 products and enough
// for the smooth manufactured solutions.
const std::array<double, 3> kGauss3Points = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
constexpr std::array<double, 3> kGauss3Weights = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

// Phase: the unknown vertices' values from the solve, the boundary's from u.
std::vector<double> nodal_solution(const LaplaceSystem& system, const PcgResult& pcg, std::vector<double> boundary,
                                   int k) {
  const std::size_t uk = static_cast<std::size_t>(k);
  for (std::size_t r = 0; r < system.row_vertex.size(); ++r)
    for (std::size_t s = 0; s < uk; ++s)
      boundary[static_cast<std::size_t>(system.row_vertex[r]) * uk + s] = pcg.x[r * uk + s];
  return boundary;
}

// Phase: the per-solution figures and their means.
void fill_solution_results(const HexMesh& mesh, const Topology& topology, const std::vector<double>& exact,
                           const std::vector<double>& solved, const Q1FieldErrors& errors,
                           const std::vector<PcgColumn>& columns, const PoissonOptions& options, PoissonCheck& out) {
  const std::size_t k = options.solutions.size();
  for (std::size_t s = 0; s < k; ++s) {
    double max_error = 0, max_value = 0;
    for (std::size_t v = 0; v < mesh.points.size(); ++v) {
      if (topology.vertex_hex_offsets[v + 1] == topology.vertex_hex_offsets[v]) continue;
      max_error = std::max(max_error, std::abs(solved[v * k + s] - exact[v * k + s]));
      max_value = std::max(max_value, std::abs(exact[v * k + s]));
    }
    PoissonSolutionResult r;
    r.name = options.solutions[s].name;
    r.l2_error = std::sqrt(errors.total_l2_squared[s] / errors.total_u_squared[s]);
    r.h1_error = std::sqrt(errors.total_h1_squared[s] / errors.total_grad_squared[s]);
    r.nodal_error = max_value > 0 ? max_error / max_value : kNaN;
    r.iterations = columns[s].iterations;
    r.lanczos_steps = columns[s].lanczos_steps;
    r.converged = columns[s].converged;
    r.relative_residual = columns[s].relative_residual;
    out.mean_l2_error += r.l2_error / static_cast<double>(k);
    out.mean_h1_error += r.h1_error / static_cast<double>(k);
    out.mean_nodal_error += r.nodal_error / static_cast<double>(k);
    out.mean_iterations += r.iterations / static_cast<double>(k);
    out.solutions.push_back(std::move(r));
  }
}

// Phase: the eigenvalue estimates.
void estimate_eigenvalues(const LaplaceSystem& system, const PcgResult& pcg, const FemElementField& elements,
                          const PoissonOptions& options, PoissonCheck& out) {
  out.scaled_lambda_min = std::numeric_limits<double>::infinity();
  out.scaled_lambda_max = 0;
  for (const PcgColumn& column : pcg.columns) {
    if (column.alphas.empty()) continue;
    const RitzExtremes e = cg_ritz_extremes(column);
    out.scaled_lambda_min = std::min(out.scaled_lambda_min, e.min);
    out.scaled_lambda_max = std::max(out.scaled_lambda_max, e.max);
  }
  if (!std::isfinite(out.scaled_lambda_min)) out.scaled_lambda_min = kNaN;
  out.scaled_condition = out.scaled_lambda_max / out.scaled_lambda_min;
  out.stiffness_lanczos_steps = static_cast<int>(
      std::min<std::size_t>(static_cast<std::size_t>(options.stiffness_lanczos_steps), system.row_vertex.size()));
  out.stiffness_lambda_max = lanczos_largest_eigenvalue(system.matrix, out.stiffness_lanczos_steps, system.row_vertex);
  out.max_hexes_at_vertex = system.max_hexes_at_vertex;
  out.fried_bound = static_cast<double>(system.max_hexes_at_vertex) * elements.max_lambda_max;
}

// Phase: per hex shares and the normalised error density.
void fill_cell_fields(const HexMesh& mesh, const Q1FieldErrors& errors, const PoissonOptions& options,
                      PoissonCheck& out) {
  const std::size_t n = mesh.hexes.size(), k = options.solutions.size();
  out.cell_l2_share.assign(n, 0.0);
  out.cell_h1_share.assign(n, 0.0);
  out.cell_error_density.assign(n, kNaN);
  out.cell_size.assign(n, kNaN);
  detail::for_fem_chunks(n, [&](std::size_t first, std::size_t last) {
    for (std::size_t h = first; h < last; ++h) {
      double l2 = 0, h1 = 0, h1_sum = 0, factor = 0;
      const Q1Corners p = hex_corners(mesh, static_cast<Index>(h));
      Vec3 centre;
      for (const Vec3& c : p) centre = centre + c / 8.0;
      for (std::size_t s = 0; s < k; ++s) {
        if (errors.total_l2_squared[s] > 0) l2 += errors.l2_squared[h * k + s] / errors.total_l2_squared[s];
        if (errors.total_h1_squared[s] > 0) h1 += errors.h1_squared[h * k + s] / errors.total_h1_squared[s];
        h1_sum += errors.h1_squared[h * k + s];
        factor += solution_hessian_norm2(options.solutions[s], out.normalization, centre);
      }
      out.cell_l2_share[h] = l2 / static_cast<double>(k);
      out.cell_h1_share[h] = h1 / static_cast<double>(k);
      // h_e = |e|^(1/3), the side of the cube of the hex's volume: free of
      // its shape, so the shape's effect stays in the density (the diameter
      // grows with distortion and divided it out: docs/analysis.md).
      const double size = std::cbrt(errors.volume[h]);
      out.cell_size[h] = size;
      const double denominator = errors.volume[h] * size * size * factor;
      if (denominator > 0) out.cell_error_density[h] = h1_sum / denominator;
    }
  });
  out.error_density_stats = compute_statistics(out.cell_error_density);
  out.size_correlation = size_correlation(out.cell_error_density, out.cell_size).rho;
}

}  // namespace

std::vector<double> interpolate_solutions(const HexMesh& mesh, const std::vector<HarmonicSolution>& solutions,
                                          const Normalization& normalization) {
  const std::size_t k = solutions.size();
  std::vector<double> values(mesh.points.size() * k);
  detail::for_fem_chunks(mesh.points.size(), [&](std::size_t first, std::size_t last) {
    for (std::size_t v = first; v < last; ++v)
      for (std::size_t s = 0; s < k; ++s)
        values[v * k + s] = solution_value(solutions[s], normalization, mesh.points[v]);
  });
  return values;
}

Q1FieldErrors q1_field_errors(const HexMesh& mesh, const std::vector<double>& nodal,
                              const std::vector<HarmonicSolution>& solutions, const Normalization& normalization) {
  const std::size_t n = mesh.hexes.size(), k = solutions.size();
  Q1FieldErrors e;
  e.num_solutions = static_cast<int>(k);
  e.l2_squared.assign(n * k, 0.0);
  e.h1_squared.assign(n * k, 0.0);
  e.volume.assign(n, 0.0);
  std::vector<double> u_squared(n * k, 0.0), grad_squared(n * k, 0.0);
  std::array<Q1Reference, 27> reference;
  std::array<double, 27> weight;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int l = 0; l < 3; ++l) {
        reference[static_cast<std::size_t>(9 * i + 3 * j + l)] =
            q1_reference({kGauss3Points[i], kGauss3Points[j], kGauss3Points[l]});
        weight[static_cast<std::size_t>(9 * i + 3 * j + l)] = kGauss3Weights[i] * kGauss3Weights[j] * kGauss3Weights[l];
      }
  detail::for_fem_chunks(n, [&](std::size_t first, std::size_t last) {
    std::vector<double> corner_values(8 * k);  // [a * k + s]
    for (std::size_t h = first; h < last; ++h) {
      const Hex& hex = mesh.hexes[h];
      const Q1Corners p = hex_corners(mesh, static_cast<Index>(h));
      for (int a = 0; a < 8; ++a)
        for (std::size_t s = 0; s < k; ++s)
          corner_values[static_cast<std::size_t>(a) * k + s] = nodal[static_cast<std::size_t>(hex[a]) * k + s];
      for (std::size_t g = 0; g < 27; ++g) {
        const Q1Reference& ref = reference[g];
        // The map's Jacobian columns and the point (as q1_point), without
        // the 8 physical shape gradients: grad u_h = J^-T (reference
        // gradient of u_h), one 3 x 3 map per solution.
        Vec3 ja, jb, jc, position;
        for (int a = 0; a < 8; ++a) {
          ja = ja + ref.grad[a].x * p[a];
          jb = jb + ref.grad[a].y * p[a];
          jc = jc + ref.grad[a].z * p[a];
          position = position + ref.shape[a] * p[a];
        }
        const double det_j = det(ja, jb, jc);
        const Vec3 bc = cross(jb, jc), ca = cross(jc, ja), ab = cross(ja, jb);
        const double inverse = det_j != 0 ? 1.0 / det_j : 0.0;
        // |det J|: a valid element can still turn over between its 2-point
        // Gauss points; the squared errors stay non-negative.
        const double w = weight[g] * std::abs(det_j);
        e.volume[h] += w;
        const Vec3 normalised = normalised_point(normalization, position);
        for (std::size_t s = 0; s < k; ++s) {
          double uh = 0;
          Vec3 ref_grad_uh;
          for (int a = 0; a < 8; ++a) {
            const double value = corner_values[static_cast<std::size_t>(a) * k + s];
            uh += ref.shape[a] * value;
            ref_grad_uh = ref_grad_uh + value * ref.grad[a];
          }
          const Vec3 grad_uh = inverse * (ref_grad_uh.x * bc + ref_grad_uh.y * ca + ref_grad_uh.z * ab);
          double u;
          Vec3 grad_u;
          solution_value_and_gradient_normalised(solutions[s], normalization, normalised, u, grad_u);
          e.l2_squared[h * k + s] += w * (uh - u) * (uh - u);
          e.h1_squared[h * k + s] += w * squared_norm(grad_uh - grad_u);
          u_squared[h * k + s] += w * u * u;
          grad_squared[h * k + s] += w * squared_norm(grad_u);
        }
      }
    }
  });
  const auto totals = detail::sum_fem_chunks<16>(n, [&](std::size_t first, std::size_t last) {
    std::array<double, 16> t{};
    for (std::size_t h = first; h < last; ++h)
      for (std::size_t s = 0; s < k && s < 4; ++s) {
        t[s] += e.l2_squared[h * k + s];
        t[4 + s] += e.h1_squared[h * k + s];
        t[8 + s] += u_squared[h * k + s];
        t[12 + s] += grad_squared[h * k + s];
      }
    return t;
  });
  for (std::size_t s = 0; s < k && s < 4; ++s) {
    e.total_l2_squared.push_back(totals[s]);
    e.total_h1_squared.push_back(totals[4 + s]);
    e.total_u_squared.push_back(totals[8 + s]);
    e.total_grad_squared.push_back(totals[12 + s]);
  }
  return e;
}

PoissonCheck run_poisson_check(const HexMesh& mesh, const Topology& topology, const FemElementField& elements,
                               const PoissonOptions& options) {
  PoissonCheck out;
  out.min_free_vertices = options.min_free_vertices;
  const VolumeMoments moments = volume_moments(mesh);
  out.normalization = principal_normalization(mesh, topology, moments);
  out.mesh_length = moment_length(moments);
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (topology.vertex_hex_offsets[v + 1] > topology.vertex_hex_offsets[v] && !topology.is_boundary_vertex[v])
      ++out.num_free_vertices;
  if (options.solutions.empty() || options.solutions.size() > 4) {
    out.skipped = "the check takes 1 to 4 solutions";
    return out;
  }
  // Q1 elements only: a hex-dominant mesh's hexes alone are not the domain.
  if (!mesh.tets.empty() || !mesh.wedges.empty() || !mesh.pyramids.empty()) {
    out.skipped = "the mesh has cells other than hexahedra (the check solves on Q1 hexahedra only)";
    return out;
  }
  if (elements.num_invalid > 0) {
    out.skipped = std::to_string(elements.num_invalid) + (elements.num_invalid == 1 ? " hex is" : " hexes are") +
                  " not a valid trilinear element (a Gauss-point det J <= 0)";
    return out;
  }
  if (out.num_free_vertices < options.min_free_vertices) {
    out.skipped = std::to_string(out.num_free_vertices) + " free (interior) vertices, fewer than " +
                  std::to_string(options.min_free_vertices);
    return out;
  }
  const int k = static_cast<int>(options.solutions.size());
  const std::vector<double> exact = interpolate_solutions(mesh, options.solutions, out.normalization);
  // The system and the solver's vectors are freed before the errors are
  // integrated (the 2.9M-hex mesh: about 1.4 GB).
  std::vector<PcgColumn> columns;
  std::vector<double> solved;
  {
    const LaplaceSystem system = assemble_laplace_system(mesh, topology, exact, k);
    PcgResult pcg =
        solve_pcg(system.matrix, system.diagonal, system.rhs, k, PcgOptions{.tolerance = options.tolerance});
    estimate_eigenvalues(system, pcg, elements, options, out);
    solved = nodal_solution(system, pcg, exact, k);
    columns = std::move(pcg.columns);
  }
  const Q1FieldErrors errors = q1_field_errors(mesh, solved, options.solutions, out.normalization);
  fill_solution_results(mesh, topology, exact, solved, errors, columns, options, out);
  fill_cell_fields(mesh, errors, options, out);
  return out;
}

}  // namespace hq
