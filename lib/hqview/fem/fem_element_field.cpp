#include "hqview/fem/fem_element_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "hqview/fem/q1_element.h"

namespace hq {

FemElementField compute_fem_elements(const HexMesh& mesh) {
  const std::size_t n = mesh.hexes.size();
  FemElementField f;
  f.kappa.resize(n);
  f.lambda_max.resize(n);
  f.det_j_min.resize(n);
  f.det_j_max.resize(n);
  std::vector<char> invertible(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t h = r.begin(); h != r.end(); ++h) {
      const Q1Conditioning c = q1_conditioning(hex_corners(mesh, static_cast<Index>(h)));
      f.kappa[h] = c.kappa;
      f.lambda_max[h] = c.lambda_max;
      f.det_j_min[h] = c.det_j_min;
      f.det_j_max[h] = c.det_j_max;
      invertible[h] = c.is_invertible ? 1 : 0;
    }
  });
  for (std::size_t h = 0; h < n; ++h) {
    if (!invertible[h]) ++f.num_not_invertible;
    if (std::isnan(f.kappa[h]))
      ++f.num_invalid;
    else
      f.max_lambda_max = std::max(f.max_lambda_max, f.lambda_max[h]);
  }
  f.kappa_stats = compute_statistics(f.kappa);
  f.lambda_max_stats = compute_statistics(f.lambda_max);
  f.det_j_min_stats = compute_statistics(f.det_j_min);
  f.det_j_max_stats = compute_statistics(f.det_j_max);
  return f;
}

}  // namespace hq
