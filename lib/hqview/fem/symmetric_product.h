#pragma once
// y = A x for a symmetric matrix stored as its upper triangle (CsrMatrix,
// laplace_system.h: each row's columns >= the row, the diagonal first), for
// K interleaved columns, with the per-column dots (w, y) fused in: half the
// matrix bytes of a full CSR product, which is what a CG iteration on a
// hex mesh's Laplace matrix spends most of its time reading.
//
// Row r gathers A_rj x_j (j >= r) and scatters A_rj x_r into y_j (j > r).
// Columns are read as 16-bit steps from the row (CsrMatrix::column_steps)
// when the band allows: a sixth fewer bytes per entry than 32-bit ids.
// Rows go in fixed chunks of a.chunk_rows (at least the bandwidth, so a
// chunk's scatters land in its own rows or the next chunk's first ones):
// pass 1, in parallel over chunks, writes a chunk's own rows to y and its
// scatters past its end to `overflow`; pass 2 adds the overflow into the
// next chunk's first rows. Each y_j is summed in one fixed order (the
// scatters of the earlier rows of its chunk in row order, its own row,
// then the previous chunk's scatters), and the dots are fixed-chunk sums:
// the same bits for any thread count. Four columns (CG's three, padded)
// move as one four-double value; the chunk loop for them is also built for
// AVX2 (symmetric_product_avx2.cpp) and chosen at run time (no FMA: the
// same bits on either path).
//
// Everything here but product_chunk_avx2 has internal linkage (an unnamed
// namespace), so that the AVX2 file's copies of these functions never stand
// in for a baseline file's at link time.

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "hqview/core/cpu_features.h"
#include "hqview/fem/laplace_system.h"

namespace hq::detail {

// product_chunk<4> (below) built for AVX2, with the 16-bit column steps
// (NarrowColumns) or the column ids: call only where HQ_AVX2_KERNELS and
// has_avx2() (core/cpu_features.h).
std::array<double, 4> product_chunk_avx2(const CsrMatrix& a, bool narrow_columns, std::size_t first, std::size_t last,
                                         std::size_t head_end, const double* x, double* y, double* overflow,
                                         const double* w);

namespace {

// Two doubles as one value (GCC/Clang vector extension: SSE2 on x86-64,
// NEON on ARM; the same IEEE products and sums as scalar code, so the same bits).
using Pair = double __attribute__((vector_size(16)));

inline Pair load_pair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store_pair(double* p, Pair v) { std::memcpy(p, &v, sizeof v); }

// A row entry's column: from the 32-bit ids, or from the 16-bit steps
// column - row (CsrMatrix::column_steps: 2 bytes an entry fewer to read).
struct WideColumns {
  const Index* columns;
  std::size_t operator()(std::size_t e, std::size_t) const { return static_cast<std::size_t>(columns[e]); }
};
struct NarrowColumns {
  const std::uint16_t* steps;
  std::size_t operator()(std::size_t e, std::size_t r) const { return r + steps[e]; }
};

// Four doubles as one value: two SSE2 pairs on baseline x86-64, one AVX
// register in the chunk loop built for AVX2 (product_chunk_avx2; never FMA:
// separate products and sums, so the same bits on either path).
using Quad = double __attribute__((vector_size(32)));

// By reference: a 32-byte vector by value would change the ABI without AVX.
inline void load_quad(Quad& v, const double* p) { std::memcpy(&v, p, sizeof v); }

inline void store_quad(double* p, const Quad& v) { std::memcpy(p, &v, sizeof v); }

// One row of the four-column product (CG's three columns padded with a zero
// fourth, pcg.cpp): the first entry is the diagonal (gathered only); the
// rest scatter into y, or past the chunk's end into `overflow`. The same
// operations, in the same order, as the generic loop.
template <class Columns>
[[gnu::always_inline]] inline void row_product_4(const double* values, Columns columns, std::size_t begin,
                                                 std::size_t end, std::size_t r, std::size_t last, const double* x,
                                                 double* y, double* overflow, double sum[4]) {
  Quad xr, s, xj, t;
  load_quad(xr, x + r * 4);
  load_quad(s, sum);
  if (begin < end && columns(begin, r) == r) s += values[begin++] * xr;
  for (std::size_t e = begin; e < end; ++e) {
    const double v = values[e];
    const std::size_t j = columns(e, r);
    load_quad(xj, x + j * 4);
    s += v * xj;
    double* target = (j < last ? y : overflow) + j * 4;
    load_quad(t, target);
    store_quad(target, t + v * xr);
  }
  store_quad(sum, s);
}

// One row of the three-column product: columns 0 and 1 as a pair, column 2
// alone (the same operations, in the same order, as the generic loop).
template <class Columns>
inline void row_product_3(const double* values, Columns columns, std::size_t begin, std::size_t end, std::size_t r,
                          std::size_t last, const double* x, double* y, double* overflow, double sum[3]) {
  const Pair xr01 = load_pair(x + r * 3);
  const double xr2 = x[r * 3 + 2];
  Pair sum01 = load_pair(sum);
  double sum2 = sum[2];
  for (std::size_t e = begin; e < end; ++e) {
    const double v = values[e];
    const std::size_t j = columns(e, r);
    const double* xj = x + j * 3;
    sum01 += v * load_pair(xj);
    sum2 += v * xj[2];
    if (j == r) continue;
    double* target = (j < last ? y : overflow) + j * 3;
    store_pair(target, load_pair(target) + v * xr01);
    target[2] += v * xr2;
  }
  store_pair(sum, sum01);
  sum[2] = sum2;
}

// Pass 1 of one chunk [first, last): its rows' products into y (its
// scatters past `last` into overflow); returns the dots (w, y) of its rows
// from head_end on.
template <std::size_t K, class Columns>
[[gnu::always_inline]] inline std::array<double, K> product_chunk(const CsrMatrix& a, Columns columns,
                                                                  std::size_t first, std::size_t last,
                                                                  std::size_t head_end, const double* x, double* y,
                                                                  double* overflow, const double* w) {
  const double* values = a.values.data();
  std::fill(y + first * K, y + last * K, 0.0);
  std::array<double, K> dots{};
  for (std::size_t r = first; r < last; ++r) {
    const std::size_t begin = static_cast<std::size_t>(a.offsets[r]), end = static_cast<std::size_t>(a.offsets[r + 1]);
    const double* xr = x + r * K;
    std::array<double, K> sum{};
    for (std::size_t s = 0; s < K; ++s) sum[s] = y[r * K + s];
    if constexpr (K == 3) {
      row_product_3(values, columns, begin, end, r, last, x, y, overflow, sum.data());
    } else if constexpr (K == 4) {
      row_product_4(values, columns, begin, end, r, last, x, y, overflow, sum.data());
    } else {
      for (std::size_t e = begin; e < end; ++e) {
        const double v = values[e];
        const std::size_t j = columns(e, r);
        const double* xj = x + j * K;
        for (std::size_t s = 0; s < K; ++s) sum[s] += v * xj[s];
        if (j == r) continue;
        double* target = (j < last ? y : overflow) + j * K;
        for (std::size_t s = 0; s < K; ++s) target[s] += v * xr[s];
      }
    }
    for (std::size_t s = 0; s < K; ++s) {
      y[r * K + s] = sum[s];
      if (r >= head_end) dots[s] += w[r * K + s] * sum[s];
    }
  }
  return dots;
}

// `overflow`: a.num_rows() * K zeros, left zeros. `w`: the vector the dots
// take y against (rows x K; may be x itself).
template <std::size_t K, class Columns>
std::array<double, K> symmetric_product(const CsrMatrix& a, Columns columns, const double* x, double* y,
                                        double* overflow, const double* w) {
  const std::size_t n = a.num_rows();
  // A chunk narrower than the band (never so from assemble_laplace_system) is one chunk.
  const std::size_t chunk = std::max<std::size_t>(1, a.chunk_rows >= a.bandwidth ? a.chunk_rows : n);
  const std::size_t num_chunks = (n + chunk - 1) / chunk, band = std::min(chunk, a.bandwidth);
  std::vector<std::array<double, K>> partial(num_chunks), partial_head(num_chunks);
  // Pass 1: the chunk's rows; the dots of the rows no earlier chunk reaches.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_chunks), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t c = range.begin(); c != range.end(); ++c) {
      const std::size_t first = c * chunk, last = std::min(n, first + chunk);
      const std::size_t head_end = c == 0 ? first : std::min(last, first + band);
#if HQ_AVX2_KERNELS
      if constexpr (K == 4) {
        if (has_avx2()) {
          partial[c] =
              product_chunk_avx2(a, std::is_same_v<Columns, NarrowColumns>, first, last, head_end, x, y, overflow, w);
          continue;
        }
      }
#endif
      partial[c] = product_chunk<K>(a, columns, first, last, head_end, x, y, overflow, w);
    }
  });
  // Pass 2: the previous chunk's scatters into a chunk's first rows, and their dots.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_chunks), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t c = range.begin(); c != range.end(); ++c) {
      const std::size_t first = c * chunk, last = std::min(n, first + chunk);
      const std::size_t head_end = c == 0 ? first : std::min(last, first + band);
      std::array<double, K> dots{};
      for (std::size_t r = first; r < head_end; ++r)
        for (std::size_t s = 0; s < K; ++s) {
          const std::size_t i = r * K + s;
          y[i] += overflow[i];
          overflow[i] = 0;
          dots[s] += w[i] * y[i];
        }
      partial_head[c] = dots;
    }
  });
  std::array<double, K> total{};
  for (std::size_t c = 0; c < num_chunks; ++c)
    for (std::size_t s = 0; s < K; ++s) total[s] += partial_head[c][s] + partial[c][s];
  return total;
}

// The product with the 16-bit column steps when the matrix has them, else
// with the column ids (the same entries in the same order: the same bits).
template <std::size_t K>
std::array<double, K> symmetric_product(const CsrMatrix& a, const double* x, double* y, double* overflow,
                                        const double* w) {
  if (!a.column_steps.empty() && a.column_steps.size() == a.columns.size())
    return symmetric_product<K>(a, NarrowColumns{a.column_steps.data()}, x, y, overflow, w);
  return symmetric_product<K>(a, WideColumns{a.columns.data()}, x, y, overflow, w);
}

}  // namespace
}  // namespace hq::detail
