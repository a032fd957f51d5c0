#include "hqview/fem/laplace_system.h"

#include <algorithm>

#include "hqview/fem/fixed_chunks.h"
#include "hqview/fem/q1_element.h"
#include "hqview/fem/symmetric_product.h"

namespace hq {
namespace {

// The rows >= v's own of the free vertices sharing a hex with `v` (v
// included), ascending, into `out`: v's row of the upper triangle.
void row_pattern(const HexMesh& mesh, const Topology& topology, const std::vector<Index>& vertex_row, Index v,
                 std::vector<Index>& out) {
  out.clear();
  const Index row = vertex_row[static_cast<std::size_t>(v)];
  for (Index h : topology.hexes_of(v))
    for (Index w : mesh.hexes[static_cast<std::size_t>(h)])
      if (vertex_row[static_cast<std::size_t>(w)] >= row) out.push_back(vertex_row[static_cast<std::size_t>(w)]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

bool is_free(const Topology& topology, std::size_t v) {
  return topology.vertex_hex_offsets[v + 1] > topology.vertex_hex_offsets[v] && !topology.is_boundary_vertex[v];
}

// Breadth-first search over the free vertices sharing a hex, from `start`,
// appending to `order` (Cuthill-McKee: a vertex's unvisited neighbours in
// ascending (number of hexes, id)); marks `level` (0 = unvisited) with the
// depth + 1. Returns the last vertex reached.
Index cuthill_mckee_search(const HexMesh& mesh, const Topology& topology, Index start, std::vector<Index>& level,
                           std::vector<Index>& order) {
  std::vector<Index> next;
  const auto hexes_at = [&](Index w) {
    return topology.vertex_hex_offsets[static_cast<std::size_t>(w) + 1] -
           topology.vertex_hex_offsets[static_cast<std::size_t>(w)];
  };
  std::size_t head = order.size();
  order.push_back(start);
  level[static_cast<std::size_t>(start)] = 1;
  for (; head < order.size(); ++head) {
    const Index v = order[head];
    next.clear();
    for (Index h : topology.hexes_of(v))
      for (Index w : mesh.hexes[static_cast<std::size_t>(h)])
        if (level[static_cast<std::size_t>(w)] == 0 && is_free(topology, static_cast<std::size_t>(w))) {
          level[static_cast<std::size_t>(w)] = level[static_cast<std::size_t>(v)] + 1;
          next.push_back(w);
        }
    std::sort(next.begin(), next.end(), [&](Index a, Index b) {
      const Index ha = hexes_at(a), hb = hexes_at(b);
      return ha != hb ? ha < hb : a < b;
    });
    order.insert(order.end(), next.begin(), next.end());
  }
  return order.back();
}

// Phase 1: which vertices are unknowns, numbered in reverse Cuthill-McKee
// order (George and Liu, "Computer Solution of Large Sparse Positive
// Definite Systems", 4.3): per connected part (in order of its lowest
// vertex id) from the end of a search started at that vertex (a
// pseudo-peripheral start), so that a row's columns sit near it and the
// sparse product reads x from cache. Sequential and deterministic.
void number_free_vertices(const HexMesh& mesh, const Topology& topology, LaplaceSystem& s) {
  s.vertex_row.assign(mesh.points.size(), kNoIndex);
  std::vector<Index> level(mesh.points.size(), 0), order, probe;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const Index used = topology.vertex_hex_offsets[v + 1] - topology.vertex_hex_offsets[v];
    s.max_hexes_at_vertex = std::max(s.max_hexes_at_vertex, used);
    if (!is_free(topology, v) || level[v] != 0) continue;
    // A first search finds a far vertex of this part; its marks are undone.
    probe.clear();
    const Index far = cuthill_mckee_search(mesh, topology, static_cast<Index>(v), level, probe);
    for (Index w : probe) level[static_cast<std::size_t>(w)] = 0;
    cuthill_mckee_search(mesh, topology, far, level, order);
  }
  std::reverse(order.begin(), order.end());
  s.row_vertex = std::move(order);
  for (std::size_t r = 0; r < s.row_vertex.size(); ++r)
    s.vertex_row[static_cast<std::size_t>(s.row_vertex[r])] = static_cast<Index>(r);
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
      std::copy(pattern.begin(), pattern.end(), m.columns.begin() + m.offsets[r]);
    }
  });
  for (std::size_t r = 0; r < rows; ++r)
    if (m.offsets[r + 1] > m.offsets[r])
      m.bandwidth = std::max(m.bandwidth,
                             static_cast<std::size_t>(m.columns[static_cast<std::size_t>(m.offsets[r + 1] - 1)]) - r);
  // Fixed chunks of 16,384 rows, or the band rounded up to 4,096 when wider.
  m.chunk_rows = std::max<std::size_t>(4 * detail::kFemChunk, detail::num_fem_chunks(m.bandwidth) * detail::kFemChunk);
}

// Phase 3: the values and right-hand sides, row by row. A chunk of rows
// computes the element matrices of its rows' hexes once (ascending hex ids)
// and gathers from them: a hex whose vertices fall in one chunk is computed
// once instead of once per vertex; the sums are the same either way. The
// chunks are the product's (CsrMatrix::chunk_rows, at least the band): the
// wider the chunk against the band, the fewer hexes straddle two chunks and
// are computed twice.
void gather_rows(const HexMesh& mesh, const Topology& topology, const std::vector<double>& dirichlet,
                 LaplaceSystem& s) {
  const int k = s.num_rhs;
  CsrMatrix& m = s.matrix;
  detail::for_chunks_of(s.row_vertex.size(), m.chunk_rows, [&](std::size_t first, std::size_t last) {
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
            if (col >= static_cast<Index>(r)) {
              vals[std::lower_bound(cols, cols_end, col) - cols] += kab;
            } else if (col == kNoIndex) {
              for (int i = 0; i < k; ++i) rhs[i] -= kab * dirichlet[static_cast<std::size_t>(w) * k + i];
            }
          }
        }
      }
      s.diagonal[r] = vals[0];  // the first column of an upper-triangle row
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
  compact_column_steps(s.matrix);
  return s;
}

bool compact_column_steps(CsrMatrix& a) {
  a.column_steps.clear();
  if (a.bandwidth > 0xffffu) return false;
  a.column_steps.resize(a.columns.size());
  for (std::size_t r = 0; r + 1 < a.offsets.size(); ++r)
    for (auto e = static_cast<std::size_t>(a.offsets[r]); e < static_cast<std::size_t>(a.offsets[r + 1]); ++e)
      a.column_steps[e] = static_cast<std::uint16_t>(static_cast<std::size_t>(a.columns[e]) - r);
  return true;
}

void multiply(const CsrMatrix& a, const std::vector<double>& x, std::vector<double>& y, int k) {
  y.assign(x.size(), 0.0);
  std::vector<double> overflow(x.size(), 0.0);
  switch (k) {
    case 1:
      detail::symmetric_product<1>(a, x.data(), y.data(), overflow.data(), x.data());
      break;
    case 2:
      detail::symmetric_product<2>(a, x.data(), y.data(), overflow.data(), x.data());
      break;
    case 3:
      detail::symmetric_product<3>(a, x.data(), y.data(), overflow.data(), x.data());
      break;
    default:
      detail::symmetric_product<4>(a, x.data(), y.data(), overflow.data(), x.data());
      break;
  }
}

}  // namespace hq
