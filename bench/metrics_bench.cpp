// All 22 Verdict hex metrics (hexes/s) on the largest real mesh and on a
// 1->8 refined copy of it (363,520 hexes from Dolphin_padded), on 1 and 2
// threads, against a baseline measured in the same run: one metric per pass
// over the mesh on one thread, each pass recomputing what it needs, the way
// VTK's vtkMeshQuality is driven (one metric per filter execution, after a
// pass for the mean volume when a size metric is asked for).

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <map>

#include "bench_data.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/quality/hex_metric_field.h"

namespace {

const hq::HexMesh& mesh() {
  static const hq::HexMesh m = hq::read_hex_mesh(hq::bench::largest_mesh()).mesh;
  return m;
}

// Each hex split into 2x2x2 by its edge midpoints, face centres and centre
// (trilinear positions), shared points merged: a conforming mesh 8 times the
// size.
hq::HexMesh refine(const hq::HexMesh& coarse) {
  hq::HexMesh fine;
  fine.points = coarse.points;
  std::map<std::vector<hq::Index>, hq::Index> made;  // sorted corner ids -> new point
  auto point_of = [&](std::vector<hq::Index> ids) {
    std::sort(ids.begin(), ids.end());
    if (ids.size() == 1) return ids[0];
    if (const auto it = made.find(ids); it != made.end()) return it->second;
    hq::Vec3 sum;
    for (hq::Index id : ids) sum = sum + coarse.points[static_cast<std::size_t>(id)];
    fine.points.push_back(sum / static_cast<double>(ids.size()));
    const auto id = static_cast<hq::Index>(fine.points.size() - 1);
    made.emplace(std::move(ids), id);
    return id;
  };
  // Corner of reference bits (r, s, t) in VTK order.
  static constexpr int kCorner[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}};
  for (const hq::Hex& hex : coarse.hexes) {
    hq::Index local[3][3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) {
          std::vector<hq::Index> ids;
          for (int r = 0; r < 2; ++r)
            for (int s = 0; s < 2; ++s)
              for (int t = 0; t < 2; ++t)
                if ((i == 1 || i == 2 * r) && (j == 1 || j == 2 * s) && (k == 1 || k == 2 * t))
                  ids.push_back(hex[kCorner[r][s][t]]);
          local[i][j][k] = point_of(std::move(ids));
        }
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int c = 0; c < 2; ++c)
          fine.hexes.push_back({local[a][b][c], local[a + 1][b][c], local[a + 1][b + 1][c], local[a][b + 1][c],
                                local[a][b][c + 1], local[a + 1][b][c + 1], local[a + 1][b + 1][c + 1],
                                local[a][b + 1][c + 1]});
  }
  return fine;
}

const hq::HexMesh& refined_mesh() {
  static const hq::HexMesh m = refine(mesh());
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
