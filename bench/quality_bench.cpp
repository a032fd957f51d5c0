// Corner scaled Jacobian throughput (hexes/s) on 1 and 2 threads against a
// baseline: the direct per-corner formula (three square roots per corner,
// one thread), the way the paper's reference implementation computes it.

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>

#include "bench_data.h"
#include "hqview/core/hex_topology.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/quality/quality_field.h"

namespace {

const hq::HexMesh& mesh() {
  static const hq::HexMesh m = hq::read_hex_mesh(hq::bench::largest_mesh()).mesh;
  return m;
}

void BM_CornerSJ_HQView(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  std::vector<double> out(8 * m.hexes.size());
  std::vector<std::uint8_t> mask(m.hexes.size());
  for (auto _ : state) {
    hq::compute_corner_scaled_jacobians(m, out, mask);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

void BM_CornerSJ_BaselinePerCorner(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  std::vector<double> out(8 * m.hexes.size());
  for (auto _ : state) {
    for (std::size_t h = 0; h < m.hexes.size(); ++h) {
      const auto p = hq::hex_corners(m, static_cast<hq::Index>(h));
      for (int i = 0; i < 8; ++i) {
        const auto& f = hq::kCornerFrames[i];
        const hq::Vec3 a = p[f[0]] - p[i], b = p[f[1]] - p[i], c = p[f[2]] - p[i];
        out[8 * h + i] = hq::det(a, b, c) / (hq::norm(a) * hq::norm(b) * hq::norm(c));
      }
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

void BM_QualityField_HQView(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  const hq::Topology topo = hq::build_topology(m);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    auto q = hq::compute_quality(m, topo);
    benchmark::DoNotOptimize(q.vertex_quality.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

void BM_Topology_HQView(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  for (auto _ : state) {
    auto topo = hq::build_topology(m);
    benchmark::DoNotOptimize(topo.edges.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

BENCHMARK(BM_CornerSJ_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CornerSJ_BaselinePerCorner)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_QualityField_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Topology_HQView)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
