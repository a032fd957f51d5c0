#pragma once
// The Q1 Laplace system of a hex mesh with Dirichlet values at its boundary
// vertices eliminated: K_ff u_f = -K_fb g_b for the free (interior) vertices,
// for k right-hand sides at once. Assembled row by row: each row gathers the
// rows of the element matrices of its vertex's hexes (ascending hex ids; the
// matrices of a chunk of rows' hexes, the product's chunk, are computed for
// that chunk and dropped after it: no element matrix is kept, no atomics), so every entry
// is summed in the same order for any thread count.

#include <cstdint>
#include <vector>

#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"

namespace hq {

// A symmetric matrix as the compressed sparse rows of its upper triangle:
// row r holds the columns >= r, ascending (the diagonal first).
// symmetric_product.h multiplies it.
struct CsrMatrix {
  std::vector<std::int64_t> offsets;  // rows + 1
  std::vector<Index> columns;
  // column - row of each entry, when the bandwidth is at most 65,535 (else
  // empty): what the product reads instead of `columns` (issue 48's speed:
  // the product is memory-bound). compact_column_steps fills it.
  std::vector<std::uint16_t> column_steps;
  std::vector<double> values;
  std::size_t bandwidth = 0;   // max over the entries of column - row
  std::size_t chunk_rows = 0;  // the product's fixed row chunks: >= bandwidth
  std::size_t num_rows() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

struct LaplaceSystem {
  CsrMatrix matrix;               // K_ff (model units, upper triangle), symmetric positive definite on a valid mesh
  std::vector<double> diagonal;   // its diagonal
  std::vector<Index> row_vertex;  // row -> vertex id (reverse Cuthill-McKee order: neighbours get near rows)
  std::vector<Index> vertex_row;  // vertex -> row, kNoIndex for a boundary or unused vertex
  int num_rhs = 0;
  std::vector<double> rhs;        // rows x num_rhs, rhs[row * num_rhs + s] = -(K_fb g_s)
  Index max_hexes_at_vertex = 0;  // m of Fried's bound
};

// Fills a.column_steps from a.columns when every column - row fits in 16
// bits (clears it otherwise); returns whether it did.
bool compact_column_steps(CsrMatrix& a);

// Free vertices: used by a hex and not on a boundary face.
// `dirichlet`: #vertices x num_rhs values (interleaved), read at boundary vertices only.
LaplaceSystem assemble_laplace_system(const HexMesh& mesh, const Topology& topology,
                                      const std::vector<double>& dirichlet, int num_rhs);

// y = A x for k (1 to 4) interleaved columns (x, y: rows x k), A from its
// upper triangle (symmetric_product.h): the same bits for any thread count.
void multiply(const CsrMatrix& a, const std::vector<double>& x, std::vector<double>& y, int k);

}  // namespace hq
