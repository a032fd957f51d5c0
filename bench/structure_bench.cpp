// Hex structure (edge valences, singular edges, the singularity graph, size
// gradation) on the benchmark mesh refined once (Dolphin_padded: 363,520
// hexes) against a baseline: edge valences counted in a std::map of sorted
// vertex pairs, the simple way. Both start from the built topology.

#include <benchmark/benchmark.h>

#include "bench_data.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/mesh/topology.h"
#include "hqview/structure/structure.h"

namespace {

struct Input {
  hq::HexMesh mesh;
  hq::Topology topology;
};

const Input& input() {
  static const Input in = [] {
    Input i{hq::bench::refine_1_to_8(hq::read_hex_mesh(hq::bench::largest_mesh()).mesh), {}};
    i.topology = hq::build_topology(i.mesh);
    return i;
  }();
  return in;
}

void BM_Structure_HQView(benchmark::State& state) {
  const Input& in = input();
  for (auto _ : state) {
    hq::HexStructure s = hq::compute_structure(in.mesh, in.topology);
    benchmark::DoNotOptimize(s.num_edges);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(in.mesh.hexes.size()));
}

void BM_Structure_BaselineMap(benchmark::State& state) {
  const Input& in = input();
  for (auto _ : state) {
    auto valences = hq::edge_valences_by_map(in.mesh);
    benchmark::DoNotOptimize(valences.size());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(in.mesh.hexes.size()));
}

}  // namespace

BENCHMARK(BM_Structure_HQView)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Structure_BaselineMap)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
