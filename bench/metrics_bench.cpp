// All 22 Verdict hex metrics (hexes/s) on the largest real mesh and on a
// 1->8 refined copy of it (363,520 hexes from Dolphin_padded), on 1 and 2
// threads, against a baseline measured in the same run: one metric per pass
// over the mesh on one thread, each pass recomputing what it needs, the way
// VTK's vtkMeshQuality is driven (one metric per filter execution, after a
// pass for the mean volume when a size metric is asked for).
//
// TetMetricsSplitRefined: every Verdict tet metric, corner scaled Jacobian
// and orientation (cell_metric_field.h) of the refined mesh split into 6
// tets per hex (2,181,120 tets, Kuhn's split along each hex's 0-6
// diagonal), on 1 and 2 threads, against the hex metric field of the same
// 363,520 hexes on 2 threads in the same run (issue 46: a tet mesh made from
// the hexes should take at most 3x the hex time); items are source hexes,
// so the ratio column is the time ratio.
//
// AnnotatedVtuRefined: writing data/annotated.vtu of the refined mesh (every
// metric, the quality field) to a file, against writing cells.csv and
// vertices.csv of the same model.

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <fstream>

#include "bench_data.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/quality/cell_metric_field.h"
#include "hqview/quality/hex_metric_field.h"
#include "hqview/report/report_csv.h"
#include "hqview/report/report_vtu.h"
#include "hqview/structure/structure.h"

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

// The refined mesh's model as the bundle writer gets it (no glyph, overlap
// or reference stage: their arrays are a few per-vertex columns; the
// structure stage's are required).
const hq::ReportModel& refined_model() {
  static const hq::ReportModel model = [] {
    hq::ReportModel m;
    m.analysis.mesh = refined_mesh();
    m.analysis.topology = hq::build_topology(m.analysis.mesh);
    m.analysis.field = hq::compute_quality(m.analysis.mesh, m.analysis.topology);
    m.analysis.metrics = hq::compute_hex_metrics(m.analysis.mesh, hq::all_hex_metrics());
    m.analysis.structure = hq::compute_structure(m.analysis.mesh, m.analysis.topology);
    return m;
  }();
  return model;
}

template <class Write>
void run_writer(benchmark::State& state, Write write) {
  const hq::ReportModel& model = refined_model();
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "hqview_bench_annotated.out";
  for (auto _ : state) {
    std::ofstream out(path, std::ios::binary);
    write(model, out);
    out.close();
  }
  std::filesystem::remove(path);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(model.analysis.mesh.hexes.size()));
  state.counters["hexes"] = static_cast<double>(model.analysis.mesh.hexes.size());
}

void BM_AnnotatedVtuRefined_HQView(benchmark::State& state) {
  run_writer(state, [](const hq::ReportModel& m, std::ostream& out) { hq::write_annotated_vtu(m, out); });
}
void BM_AnnotatedVtuRefined_BaselineCsv(benchmark::State& state) {
  run_writer(state, [](const hq::ReportModel& m, std::ostream& out) {
    hq::write_cells_csv(m, out);
    hq::write_vertices_csv(m, out);
  });
}

// Six positively oriented tets per hex (VTK corners), along the 0-6 diagonal.
const std::vector<std::array<hq::Index, 4>>& split_tets() {
  static const std::vector<std::array<hq::Index, 4>> tets = [] {
    static constexpr int kKuhn[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                        {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
    std::vector<std::array<hq::Index, 4>> out;
    out.reserve(6 * refined_mesh().hexes.size());
    for (const auto& h : refined_mesh().hexes)
      for (const auto& t : kKuhn) out.push_back({h[t[0]], h[t[1]], h[t[2]], h[t[3]]});
    return out;
  }();
  return tets;
}

void BM_TetMetricsSplitRefined_HQView(benchmark::State& state) {
  const auto& tets = split_tets();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    const hq::CellBlockMetricField field = hq::compute_tet_block_metrics(refined_mesh().points, tets);
    benchmark::DoNotOptimize(field.values[0].data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(refined_mesh().hexes.size()));
  state.counters["tets"] = static_cast<double>(tets.size());
}

void BM_TetMetricsSplitRefined_BaselineHexField(benchmark::State& state) {
  state.range(0);  // (2 threads, as the HQView/2 row it is compared with)
  run_hqview(state, refined_mesh());
}

void BM_HexMetrics_HQView(benchmark::State& state) { run_hqview(state, mesh()); }
void BM_HexMetrics_BaselinePerMetric(benchmark::State& state) { run_baseline(state, mesh()); }
void BM_HexMetricsRefined_HQView(benchmark::State& state) { run_hqview(state, refined_mesh()); }
void BM_HexMetricsRefined_BaselinePerMetric(benchmark::State& state) { run_baseline(state, refined_mesh()); }

BENCHMARK(BM_HexMetrics_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexMetrics_BaselinePerMetric)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexMetricsRefined_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexMetricsRefined_BaselinePerMetric)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetMetricsSplitRefined_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TetMetricsSplitRefined_BaselineHexField)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnnotatedVtuRefined_HQView)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnnotatedVtuRefined_BaselineCsv)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
