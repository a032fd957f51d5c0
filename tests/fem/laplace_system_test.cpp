#include "hqview/fem/laplace_system.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>

#include "hqview/fem/pcg.h"
#include "hqview/fem/q1_element.h"
#include "hqview/fem/symmetric_product.h"
#include "hqview/mesh/topology.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

// A 32^3 grid with every interior vertex moved by up to 0.3 h: 29,791 free
// vertices, more than one 16,384-row chunk of the product, so the scatters
// that cross a chunk's end are exercised.
HexMesh perturbed_grid(int n) {
  HexMesh mesh = test::grid(n);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    Vec3& p = mesh.points[v];
    if (p.x > 0 && p.x < n && p.y > 0 && p.y < n && p.z > 0 && p.z < n)
      for (int a = 0; a < 3; ++a) {
        const double t = std::sin(12.9898 * static_cast<double>(v) + 78.233 * a) * 43758.5453;
        p[a] += 0.6 * (t - std::floor(t) - 0.5);
      }
  }
  return mesh;
}

struct Fixture {
  HexMesh mesh = perturbed_grid(32);
  Topology topology = build_topology(mesh);
  LaplaceSystem system = assemble_laplace_system(mesh, topology, std::vector<double>(mesh.points.size() * 3, 0.0), 3);
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

// Three columns of fixed pseudo-random values.
std::vector<double> some_columns(std::size_t rows) {
  std::vector<double> x(rows * 3);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = std::sin(7.31 * static_cast<double>(i) + 0.5) * 917.13;
    x[i] = t - std::floor(t) - 0.5;
  }
  return x;
}

// The stored upper triangle: rows in reverse Cuthill-McKee order, the
// diagonal first, columns ascending, the band within a chunk.
TEST(LaplaceSystem, UpperTriangleInABandedOrder) {
  const LaplaceSystem& s = fixture().system;
  const std::size_t rows = s.matrix.num_rows();
  ASSERT_EQ(rows, 31u * 31u * 31u);
  EXPECT_GT(rows, s.matrix.chunk_rows);
  std::size_t band = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    const auto first = static_cast<std::size_t>(s.matrix.offsets[r]),
               last = static_cast<std::size_t>(s.matrix.offsets[r + 1]);
    ASSERT_LT(first, last);
    EXPECT_EQ(s.matrix.columns[first], static_cast<Index>(r));
    EXPECT_EQ(s.matrix.values[first], s.diagonal[r]);
    for (std::size_t e = first + 1; e < last; ++e) EXPECT_GT(s.matrix.columns[e], s.matrix.columns[e - 1]);
    band = std::max(band, static_cast<std::size_t>(s.matrix.columns[last - 1]) - r);
    EXPECT_EQ(s.vertex_row[static_cast<std::size_t>(s.row_vertex[r])], static_cast<Index>(r));
  }
  EXPECT_EQ(s.matrix.bandwidth, band);
  EXPECT_LE(band, s.matrix.chunk_rows);
  // Reverse Cuthill-McKee from a corner of the grid runs through shells
  // max(i, j, k) = const (a hex's corners are neighbours), of up to
  // 3 * 31^2 rows: the band is about two shells' width at the far corner
  // (2,965 here). A numbering that ignored the mesh would have a band near
  // the row count (29,791).
  EXPECT_LT(band, 3u * 32u * 32u);
}

// y = K x from the upper triangle equals K x summed hex by hex from the
// element matrices (no CSR): the assembly and the symmetric product both.
TEST(LaplaceSystem, ProductEqualsTheElementByElementSum) {
  const Fixture& f = fixture();
  const LaplaceSystem& s = f.system;
  const std::size_t rows = s.matrix.num_rows();
  const std::vector<double> x = some_columns(rows);
  std::vector<double> y;
  multiply(s.matrix, x, y, 3);
  std::vector<double> expected(rows * 3, 0.0);
  for (std::size_t h = 0; h < f.mesh.hexes.size(); ++h) {
    const Hex& hex = f.mesh.hexes[h];
    const Q1Matrix k = q1_laplace_stiffness(hex_corners(f.mesh, static_cast<Index>(h)));
    for (int a = 0; a < 8; ++a) {
      const Index ra = s.vertex_row[static_cast<std::size_t>(hex[a])];
      if (ra == kNoIndex) continue;
      for (int b = 0; b < 8; ++b) {
        const Index rb = s.vertex_row[static_cast<std::size_t>(hex[b])];
        if (rb == kNoIndex) continue;
        for (std::size_t c = 0; c < 3; ++c)
          expected[static_cast<std::size_t>(ra) * 3 + c] += k[8 * a + b] * x[static_cast<std::size_t>(rb) * 3 + c];
      }
    }
  }
  double scale = 0;
  for (double v : expected) scale = std::max(scale, std::abs(v));
  ASSERT_GT(scale, 0);
  for (std::size_t i = 0; i < y.size(); ++i) ASSERT_NEAR(y[i], expected[i], 1e-12 * scale) << i;
}

// The 16-bit column steps (what the product reads when the band fits): each
// equals column - row, and the product (CG's only use of the matrix) gives
// the same bits as from the 32-bit ids (the steps cleared: the other path); a band over
// 65,535 keeps the ids only.
TEST(LaplaceSystem, ColumnStepsGiveTheSameBits) {
  const LaplaceSystem& s = fixture().system;
  ASSERT_EQ(s.matrix.column_steps.size(), s.matrix.columns.size());
  for (std::size_t r = 0; r < s.matrix.num_rows(); ++r)
    for (auto e = static_cast<std::size_t>(s.matrix.offsets[r]); e < static_cast<std::size_t>(s.matrix.offsets[r + 1]);
         ++e)
      ASSERT_EQ(r + s.matrix.column_steps[e], static_cast<std::size_t>(s.matrix.columns[e])) << r;
  CsrMatrix wide = s.matrix;
  wide.column_steps.clear();
  const std::vector<double> x = some_columns(s.matrix.num_rows());
  std::vector<double> y_narrow, y_wide;
  multiply(s.matrix, x, y_narrow, 3);
  multiply(wide, x, y_wide, 3);
  EXPECT_EQ(std::memcmp(y_narrow.data(), y_wide.data(), y_narrow.size() * sizeof(double)), 0);
  // A 2 x 2 matrix with its off-diagonal entry 70,000 columns out: no steps.
  CsrMatrix far;
  far.offsets = {0, 2, 3};
  far.columns = {0, 70000, 70000};
  far.values = {1, 2, 3};
  far.bandwidth = 70000;
  EXPECT_FALSE(compact_column_steps(far));
  EXPECT_TRUE(far.column_steps.empty());
  wide.bandwidth = s.matrix.bandwidth;
  EXPECT_TRUE(compact_column_steps(wide));
  EXPECT_EQ(wide.column_steps, s.matrix.column_steps);
}

// The product's documented summation order (symmetric_product.h), one row
// at a time on one thread: y_j gets the scatters of its chunk's earlier rows
// in row order, then its own row's gathers, then the previous chunk's
// scatters.
std::vector<double> product_in_documented_order(const CsrMatrix& a, const std::vector<double>& x, std::size_t k) {
  const std::size_t n = a.num_rows(), chunk = a.chunk_rows;
  std::vector<double> y(n * k, 0.0), overflow(n * k, 0.0);
  for (std::size_t first = 0; first < n; first += chunk) {
    const std::size_t last = std::min(n, first + chunk);
    for (std::size_t r = first; r < last; ++r) {
      std::vector<double> sum(y.begin() + static_cast<std::ptrdiff_t>(r * k),
                              y.begin() + static_cast<std::ptrdiff_t>((r + 1) * k));
      for (auto e = static_cast<std::size_t>(a.offsets[r]); e < static_cast<std::size_t>(a.offsets[r + 1]); ++e) {
        const auto j = static_cast<std::size_t>(a.columns[e]);
        for (std::size_t s = 0; s < k; ++s) sum[s] += a.values[e] * x[j * k + s];
        if (j == r) continue;
        for (std::size_t s = 0; s < k; ++s) (j < last ? y : overflow)[j * k + s] += a.values[e] * x[r * k + s];
      }
      std::copy(sum.begin(), sum.end(), y.begin() + static_cast<std::ptrdiff_t>(r * k));
    }
  }
  for (std::size_t i = 0; i < y.size(); ++i) y[i] += overflow[i];  // zeros outside the chunks' first rows
  return y;
}

// The product gives the bits of the documented order, for the fixture's
// two chunks of unequal length and for nine chunks (an odd count: the last
// task has one chunk); four columns (CG's padded three) both through the
// AVX2 build of the chunk loop, where the processor has it, and the portable one.
TEST(LaplaceSystem, ProductKeepsItsSummationOrder) {
  const LaplaceSystem& s = fixture().system;
  std::vector<double> x = some_columns(s.matrix.num_rows());
  x.insert(x.end(), x.begin(), x.begin() + static_cast<std::ptrdiff_t>(s.matrix.num_rows()));  // a fourth column
  CsrMatrix nine = s.matrix;
  nine.chunk_rows = 3500;
  ASSERT_GE(nine.chunk_rows, nine.bandwidth);
  for (const CsrMatrix* m : {&s.matrix, static_cast<const CsrMatrix*>(&nine)}) {
    const std::size_t n = m->num_rows();
    const std::vector<double> x4(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n * 4));
    CsrMatrix one = *m;  // one chunk: every scatter in row order
    one.chunk_rows = n;
    const std::vector<double> expected4 = product_in_documented_order(one, x4, 4);
    std::vector<double> portable(n * 4), overflow(n * 4, 0.0);
    detail::product_chunk<4>(*m, detail::WideColumns{m->columns.data()}, 0, n, 0, x4.data(), portable.data(),
                             overflow.data(), x4.data());  // one chunk: no overflow
    EXPECT_EQ(std::memcmp(portable.data(), expected4.data(), portable.size() * sizeof(double)), 0) << n;
    for (int k : {1, 3, 4}) {
      const std::vector<double> xk(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(m->num_rows() * k));
      std::vector<double> y;
      multiply(*m, xk, y, k);
      const std::vector<double> expected = product_in_documented_order(*m, xk, static_cast<std::size_t>(k));
      ASSERT_EQ(y.size(), expected.size());
      EXPECT_EQ(std::memcmp(y.data(), expected.data(), y.size() * sizeof(double)), 0) << m->chunk_rows << " " << k;
    }
  }
}

// The product and a CG solve across chunks: the same bits on one thread and two.
TEST(LaplaceSystem, SameBitsForAnyThreadCount) {
  const LaplaceSystem& s = fixture().system;
  const std::vector<double> x = some_columns(s.matrix.num_rows());
  std::vector<double> y1, y2;
  PcgResult one, two;
  {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, 1);
    multiply(s.matrix, x, y1, 3);
    one = solve_pcg(s.matrix, s.diagonal, x, 3);
  }
  {
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, 2);
    multiply(s.matrix, x, y2, 3);
    two = solve_pcg(s.matrix, s.diagonal, x, 3);
  }
  EXPECT_EQ(std::memcmp(y1.data(), y2.data(), y1.size() * sizeof(double)), 0);
  ASSERT_EQ(one.x.size(), two.x.size());
  EXPECT_EQ(std::memcmp(one.x.data(), two.x.data(), one.x.size() * sizeof(double)), 0);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_TRUE(one.columns[c].converged);
    ASSERT_EQ(one.columns[c].alphas.size(), two.columns[c].alphas.size());
    EXPECT_EQ(std::memcmp(one.columns[c].alphas.data(), two.columns[c].alphas.data(),
                          one.columns[c].alphas.size() * sizeof(double)),
              0);
  }
}

}  // namespace
}  // namespace hq
