// All 22 Verdict hex metrics (hexes/s) on the largest real mesh and on a
// 1->8 refined copy of it (363,520 hexes from Dolphin_padded), on 1 and 2
// threads, against a baseline measured in the same run: one metric per pass
// over the mesh on one thread, each pass recomputing what it needs, the way
// VTK's vtkMeshQuality is driven (one metric per filter execution, after a
// pass for the mean volume when a size metric is asked for).

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>


#include "bench_data.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/quality/hex_metric_field.h"

namespace {

const hq::HexMesh& mesh() {
  static const hq::HexMesh m = hq::read_hex_mesh(hq::bench::largest_mesh()).mesh;
  return m;
}


const hq::HexMesh& refined_mesh() {
  static const hq::HexMesh m = hq::bench::refine_1_to_8(mesh());
  return m;
}

void run_hqview(benchmark::State& state, const hq::HexMesh& m) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    const hq::HexMetricField field = hq::compute_hex_metrics(m, hq::all_hex_metrics());
    benchmark::DoNotOptimize(field.values[0].data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
  state.counters["hexes"] = static_cast<double>(m.hexes.size());
}

void run_baseline(benchmark::State& state, const hq::HexMesh& m) {
  std::vector<double> out(m.hexes.size());
  for (auto _ : state) {
    double sum = 0;
    for (std::size_t h = 0; h < m.hexes.size(); ++h)
      sum += hq::hex_volume(hq::hex_corners(m, static_cast<hq::Index>(h)));
    const double average = sum / static_cast<double>(m.hexes.size());
    for (int metric = 0; metric < hq::kNumHexMetrics; ++metric) {
      for (std::size_t h = 0; h < m.hexes.size(); ++h)
        out[h] =
            hq::hex_metric(static_cast<hq::HexMetric>(metric), hq::hex_corners(m, static_cast<hq::Index>(h)), average);
      benchmark::DoNotOptimize(out.data());
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
  state.counters["hexes"] = static_cast<double>(m.hexes.size());
}

void BM_HexMetrics_HQView(benchmark::State& state) { run_hqview(state, mesh()); }
void BM_HexMetrics_BaselinePerMetric(benchmark::State& state) { run_baseline(state, mesh()); }
void BM_HexMetricsRefined_HQView(benchmark::State& state) { run_hqview(state, refined_mesh()); }
void BM_HexMetricsRefined_BaselinePerMetric(benchmark::State& state) { run_baseline(state, refined_mesh()); }

BENCHMARK(BM_HexMetrics_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexMetrics_BaselinePerMetric)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexMetricsRefined_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexMetricsRefined_BaselinePerMetric)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
