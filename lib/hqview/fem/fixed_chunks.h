#pragma once
// Parallel loops and sums over fixed chunks of an index range: the chunk
// boundaries depend only on the range, and the chunks' partial sums are
// added in chunk order, so every sum has the same bits for any thread count
// (STYLE.md "Determinism").

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace hq::detail {

inline constexpr std::size_t kFemChunk = 4096;

inline std::size_t num_fem_chunks(std::size_t n) { return (n + kFemChunk - 1) / kFemChunk; }

// f(first, last) on every chunk of `chunk` indices of [0, n), in parallel.
template <class F>
void for_chunks_of(std::size_t n, std::size_t chunk, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, (n + chunk - 1) / chunk),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c != r.end(); ++c) f(c * chunk, std::min(n, (c + 1) * chunk));
                    });
}

// f(first, last) on every chunk of [0, n), in parallel.
template <class F>
void for_fem_chunks(std::size_t n, F&& f) {
  for_chunks_of(n, kFemChunk, f);
}

// The sums of K terms: f(first, last) returns a chunk's K partial sums
// (each summed in index order); the partials are added in chunk order.
template <std::size_t K, class F>
std::array<double, K> sum_fem_chunks(std::size_t n, F&& f) {
  std::vector<std::array<double, K>> partial(num_fem_chunks(n));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, partial.size()), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) partial[c] = f(c * kFemChunk, std::min(n, (c + 1) * kFemChunk));
  });
  std::array<double, K> total{};
  for (const auto& p : partial)
    for (std::size_t k = 0; k < K; ++k) total[k] += p[k];
  return total;
}

}  // namespace hq::detail
