// All 22 Verdict hex metrics (hexes/s) on the largest real mesh and on a
// 1->8 refined copy of it (363,520 hexes from Dolphin_padded), on 1 and 2
// threads, against a baseline measured in the same run: one metric per pass
// over the mesh on one thread, each pass recomputing what it needs, the way
// VTK's vtkMeshQuality is driven (one metric per filter execution, after a
// pass for the mean volume when a size metric is asked for).
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

void BM_HexMetrics_HQView(benchmark::State& state) { run_hqview(state, mesh()); }
void BM_HexMetrics_BaselinePerMetric(benchmark::State& state) { run_baseline(state, mesh()); }
void BM_HexMetricsRefined_HQView(benchmark::State& state) { run_hqview(state, refined_mesh()); }
void BM_HexMetricsRefined_BaselinePerMetric(benchmark::State& state) { run_baseline(state, refined_mesh()); }

BENCHMARK(BM_HexMetrics_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexMetrics_BaselinePerMetric)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexMetricsRefined_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HexMetricsRefined_BaselinePerMetric)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnnotatedVtuRefined_HQView)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AnnotatedVtuRefined_BaselineCsv)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
