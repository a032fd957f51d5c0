// Overlap stages A-G (check_overlap) on generated grids:
//   OverlapCertificate  a clean n^3 grid, certificate mode (A-F, no pair tests),
//                       args: n, threads (100 = 1M hexes; target < 5 s on 2 threads)
//   OverlapExhaustive   an n^3 grid, pair tests on every pair of overlapping
//                       boxes, args: n, threads, jitter in % of the spacing
//                       (47 = 103,823 hexes; target < 3 s on 2 threads)
//   OverlapSmall        a 24^3 grid (13,824 hexes) with one folded vertex:
//                       HQView's certificate against the paper's approach
//                       (every vertex against every vertex, every vertex
//                       against every cell), the baseline
//   OverlapMedium       the same on a 32^3 grid (32,768 hexes): the baseline
//                       grows with the square of the size, HQView linearly

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cstdint>

#include "hqview/core/hex_topology.h"
#include "hqview/overlap/overlap.h"

namespace {

using hq::Hex;
using hq::HexMesh;
using hq::Index;
using hq::Vec3;

// n^3 unit hexes; every vertex moved by up to `jitter` per axis (fixed seed).
HexMesh grid(int n, double jitter) {
  HexMesh mesh;
  const int m = n + 1;
  std::uint64_t state = 12345;
  auto noise = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return jitter * (static_cast<double>(state >> 11) * 0x1p-53 * 2.0 - 1.0);
  };
  auto id = [m](int i, int j, int k) { return static_cast<Index>(i + m * (j + m * k)); };
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) mesh.points.push_back({i + noise(), j + noise(), k + noise()});
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        mesh.hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                              id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
  return mesh;
}

void run(benchmark::State& state, const HexMesh& mesh, hq::OverlapMode mode, int threads) {
  const hq::Topology topo = hq::build_topology(mesh);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  std::int64_t pairs = 0;
  for (auto _ : state) {
    const hq::OverlapReport r = hq::check_overlap(mesh, topo, {.mode = mode});
    pairs = static_cast<std::int64_t>(r.intersecting_pairs.size());
    benchmark::DoNotOptimize(r.cell_intersecting.data());
  }
  state.counters["pairs"] = static_cast<double>(pairs);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * mesh.num_hexes());
}

void BM_OverlapCertificate_HQView(benchmark::State& state) {
  static const HexMesh mesh = grid(static_cast<int>(state.range(0)), 0.0);
  run(state, mesh, hq::OverlapMode::certificate, static_cast<int>(state.range(1)));
}

void BM_OverlapExhaustive_HQView(benchmark::State& state) {
  const HexMesh mesh = grid(static_cast<int>(state.range(0)), 0.01 * static_cast<double>(state.range(2)));
  run(state, mesh, hq::OverlapMode::exhaustive, static_cast<int>(state.range(1)));
}

// An n^3 grid whose centre vertex is pushed into the next cell but one.
HexMesh folded(int n) {
  HexMesh m = grid(n, 0.0);
  const int c = n / 2;
  const auto v = static_cast<std::size_t>(c + (n + 1) * (c + (n + 1) * c));
  m.points[v] = m.points[v] + Vec3{1.3, 0.4, 0.45};
  return m;
}

const HexMesh& small_folded() {
  static const HexMesh mesh = folded(24);
  return mesh;
}

const HexMesh& medium_folded() {
  static const HexMesh mesh = folded(32);
  return mesh;
}

void BM_OverlapSmall_HQView(benchmark::State& state) { run(state, small_folded(), hq::OverlapMode::certificate, 1); }
void BM_OverlapMedium_HQView(benchmark::State& state) { run(state, medium_folded(), hq::OverlapMode::certificate, 1); }

// sign det[b - a, c - a, d - a] in plain doubles, as the reference
// implementation's floating-point tests.
int orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double v = hq::det(b - a, c - a, d - a);
  return (v > 0) - (v < 0);
}

void paper_all_pairs(benchmark::State& state, const HexMesh& mesh) {
  const auto& p = mesh.points;
  std::int64_t found = 0;
  for (auto _ : state) {
    found = 0;
    // Coincident vertices: every pair compared.
    for (std::size_t a = 0; a < p.size(); ++a)
      for (std::size_t b = a + 1; b < p.size(); ++b) found += p[a] == p[b];
    // Every vertex against every cell (box first, then the 24 tets).
    for (const Hex& hex : mesh.hexes) {
      std::array<Vec3, 8> q;
      Vec3 lo = p[hex[0]], hi = p[hex[0]], centre{};
      for (int i = 0; i < 8; ++i) {
        q[i] = p[hex[i]];
        lo = {std::min(lo.x, q[i].x), std::min(lo.y, q[i].y), std::min(lo.z, q[i].z)};
        hi = {std::max(hi.x, q[i].x), std::max(hi.y, q[i].y), std::max(hi.z, q[i].z)};
        centre = centre + q[i] * 0.125;
      }
      for (std::size_t v = 0; v < p.size(); ++v) {
        const Vec3& x = p[v];
        if (!(lo.x < x.x && x.x < hi.x && lo.y < x.y && x.y < hi.y && lo.z < x.z && x.z < hi.z)) continue;
        bool inside = false;
        for (const auto& f : hq::kHexFaces) {
          const Vec3 fc = (q[f[0]] + q[f[1]] + q[f[2]] + q[f[3]]) * 0.25;
          for (int e = 0; e < 4 && !inside; ++e) {
            const Vec3 &pi = q[f[e]], &pj = q[f[(e + 1) % 4]];
            const int s = orient(pj, pi, fc, centre);
            inside = s != 0 && orient(x, pi, fc, centre) * s > 0 && orient(pj, x, fc, centre) * s > 0 &&
                     orient(pj, pi, x, centre) * s > 0 && orient(pj, pi, fc, x) * s > 0;
          }
        }
        found += inside;
      }
    }
    benchmark::DoNotOptimize(found);
  }
  state.counters["found"] = static_cast<double>(found);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * mesh.num_hexes());
}

BENCHMARK(BM_OverlapCertificate_HQView)->Args({100, 1})->Args({100, 2})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OverlapExhaustive_HQView)
    ->Args({47, 1, 10})
    ->Args({47, 2, 10})
    ->Args({47, 2, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
void BM_OverlapSmall_BaselinePaper(benchmark::State& state) { paper_all_pairs(state, small_folded()); }
void BM_OverlapMedium_BaselinePaper(benchmark::State& state) { paper_all_pairs(state, medium_folded()); }

BENCHMARK(BM_OverlapSmall_HQView)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OverlapSmall_BaselinePaper)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OverlapMedium_HQView)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OverlapMedium_BaselinePaper)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
