#include "hqview/fem/laplace_system.h"

#include <algorithm>

#include "hqview/fem/fixed_chunks.h"
#include "hqview/fem/q1_element.h"

namespace hq {
namespace {

// The free vertices sharing a hex with `v` (v included), ascending, into `out`.
void row_pattern(const HexMesh& mesh, const Topology& topology, const std::vector<Index>& vertex_row, Index v,
                 std::vector<Index>& out) {
  out.clear();
  for (Index h : topology.hexes_of(v))
    for (Index w : mesh.hexes[static_cast<std::size_t>(h)])
      if (vertex_row[static_cast<std::size_t>(w)] != kNoIndex) out.push_back(w);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

// Phase 1: which vertices are unknowns, numbered in vertex order.
void number_free_vertices(const HexMesh& mesh, const Topology& topology, LaplaceSystem& s) {
  s.vertex_row.assign(mesh.points.size(), kNoIndex);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const Index used = topology.vertex_hex_offsets[v + 1] - topology.vertex_hex_offsets[v];
    s.max_hexes_at_vertex = std::max(s.max_hexes_at_vertex, used);
    if (used > 0 && !topology.is_boundary_vertex[v]) {
      s.vertex_row[v] = static_cast<Index>(s.row_vertex.size());
      s.row_vertex.push_back(static_cast<Index>(v));
    }
  }
}

// Phase 2: the sparsity pattern (count, prefix sum, fill).
void build_pattern(const HexMesh& mesh, const Topology& topology, LaplaceSystem& s) {
  const std::size_t rows = s.row_vertex.size();
  std::vector<std::int64_t> counts(rows);
  detail::for_fem_chunks(rows, [&](std::size_t first, std::size_t last) {
    std::vector<Index> pattern;
    for (std::size_t r = first; r < last; ++r) {
      row_pattern(mesh, topology, s.vertex_row, s.row_vertex[r], pattern);
      counts[r] = static_cast<std::int64_t>(pattern.size());
    }
  });
  CsrMatrix& m = s.matrix;
  m.offsets.assign(rows + 1, 0);
  for (std::size_t r = 0; r < rows; ++r) m.offsets[r + 1] = m.offsets[r] + counts[r];
  m.columns.resize(static_cast<std::size_t>(m.offsets[rows]));
  m.values.assign(m.columns.size(), 0.0);
  detail::for_fem_chunks(rows, [&](std::size_t first, std::size_t last) {
    std::vector<Index> pattern;
    for (std::size_t r = first; r < last; ++r) {
      row_pattern(mesh, topology, s.vertex_row, s.row_vertex[r], pattern);
      for (std::size_t i = 0; i < pattern.size(); ++i)
        m.columns[static_cast<std::size_t>(m.offsets[r]) + i] = s.vertex_row[static_cast<std::size_t>(pattern[i])];
    }
  });
}

// Phase 3: the values and right-hand sides, row by row. A chunk of rows
// computes the element matrices of its rows' hexes once (ascending hex ids)
// and gathers from them: a hex whose vertices fall in one chunk is computed
// once instead of once per vertex; the sums are the same either way.
void gather_rows(const HexMesh& mesh, const Topology& topology, const std::vector<double>& dirichlet,
                 LaplaceSystem& s) {
  const int k = s.num_rhs;
  CsrMatrix& m = s.matrix;
  detail::for_fem_chunks(s.row_vertex.size(), [&](std::size_t first, std::size_t last) {
    std::vector<Index> chunk_hexes;
    for (std::size_t r = first; r < last; ++r)
      for (Index h : topology.hexes_of(s.row_vertex[r])) chunk_hexes.push_back(h);
    std::sort(chunk_hexes.begin(), chunk_hexes.end());
    chunk_hexes.erase(std::unique(chunk_hexes.begin(), chunk_hexes.end()), chunk_hexes.end());
    std::vector<Q1Matrix> element(chunk_hexes.size());
    for (std::size_t i = 0; i < chunk_hexes.size(); ++i)
      element[i] = q1_laplace_stiffness(hex_corners(mesh, chunk_hexes[i]));
    for (std::size_t r = first; r < last; ++r) {
      const Index v = s.row_vertex[r];
      const Index* cols = m.columns.data() + m.offsets[r];
      const Index* cols_end = m.columns.data() + m.offsets[r + 1];
      double* vals = m.values.data() + m.offsets[r];
      double* rhs = s.rhs.data() + r * static_cast<std::size_t>(k);
      for (Index h : topology.hexes_of(v)) {
        const Hex& hex = mesh.hexes[static_cast<std::size_t>(h)];
        const Q1Matrix& ke = element[static_cast<std::size_t>(
            std::lower_bound(chunk_hexes.begin(), chunk_hexes.end(), h) - chunk_hexes.begin())];
        for (int a = 0; a < 8; ++a) {
          if (hex[a] != v) continue;
          for (int b = 0; b < 8; ++b) {
            const double kab = ke[8 * a + b];
            const Index w = hex[b];
            const Index col = s.vertex_row[static_cast<std::size_t>(w)];
            if (col != kNoIndex) {
              vals[std::lower_bound(cols, cols_end, col) - cols] += kab;
            } else {
              for (int i = 0; i < k; ++i) rhs[i] -= kab * dirichlet[static_cast<std::size_t>(w) * k + i];
            }
          }
        }
      }
      s.diagonal[r] = vals[std::lower_bound(cols, cols_end, static_cast<Index>(r)) - cols];
    }
  });
}

}  // namespace

LaplaceSystem assemble_laplace_system(const HexMesh& mesh, const Topology& topology,
                                      const std::vector<double>& dirichlet, int num_rhs) {
  LaplaceSystem s;
  s.num_rhs = num_rhs;
  number_free_vertices(mesh, topology, s);
  build_pattern(mesh, topology, s);
  s.diagonal.assign(s.row_vertex.size(), 0.0);
  s.rhs.assign(s.row_vertex.size() * static_cast<std::size_t>(num_rhs), 0.0);
  gather_rows(mesh, topology, dirichlet, s);
  return s;
}

void multiply(const CsrMatrix& a, const std::vector<double>& x, std::vector<double>& y, int k) {
  const std::size_t uk = static_cast<std::size_t>(k);
  detail::for_fem_chunks(a.num_rows(), [&](std::size_t first, std::size_t last) {
    for (std::size_t r = first; r < last; ++r) {
      double sum[4] = {0, 0, 0, 0};
      for (std::int64_t e = a.offsets[r]; e < a.offsets[r + 1]; ++e) {
        const double v = a.values[static_cast<std::size_t>(e)];
        const double* xc = x.data() + static_cast<std::size_t>(a.columns[static_cast<std::size_t>(e)]) * uk;
        for (std::size_t i = 0; i < uk && i < 4; ++i) sum[i] += v * xc[i];
      }
      for (std::size_t i = 0; i < uk && i < 4; ++i) y[r * uk + i] = sum[i];
    }
  });
}

}  // namespace hq
