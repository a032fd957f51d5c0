// The finite-element check's phases on the benchmark mesh refined once
// (Dolphin_padded: 363,520 hexes, 350,833 free vertices): the element
// conditioning, the row-gather assembly, the CG solve of the three
// solutions, the errors, the metric correlations, and the whole check. The
// baseline is the Verdict metric field of the same mesh (every metric): the
// check is judged against the work a --no-render run already does.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "bench_data.h"
#include "hqview/fem/laplace_system.h"
#include "hqview/fem/metric_correlation.h"
#include "hqview/fem/pcg.h"
#include "hqview/fem/poisson_check.h"
#include "hqview/fem/principal_frame.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/hex_metric_field.h"

namespace {

struct Input {
  hq::HexMesh mesh;
  hq::Topology topology;
  hq::FemElementField elements;
  hq::Normalization normalization;
  std::vector<double> dirichlet;
};

const Input& input() {
  static const Input in = [] {
    Input i{hq::bench::refine_1_to_8(hq::read_hex_mesh(hq::bench::largest_mesh()).mesh), {}, {}, {}, {}};
    i.topology = hq::build_topology(i.mesh);
    i.elements = hq::compute_fem_elements(i.mesh);
    i.normalization = hq::principal_normalization(i.mesh, i.topology, hq::volume_moments(i.mesh));
    i.dirichlet = hq::interpolate_solutions(i.mesh, hq::default_harmonic_solutions(), i.normalization);
    return i;
  }();
  return in;
}

const hq::LaplaceSystem& system() {
  static const hq::LaplaceSystem s = hq::assemble_laplace_system(input().mesh, input().topology, input().dirichlet, 3);
  return s;
}

// The process's CPU seconds (every thread): steadier than wall time on a
// shared machine.
double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

void per_hex(benchmark::State& state) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(input().mesh.hexes.size()));
}

void BM_Fem_Baseline_VerdictMetrics(benchmark::State& state) {
  const Input& in = input();
  for (auto _ : state) {
    hq::HexMetricField f = hq::compute_hex_metrics(in.mesh, hq::all_hex_metrics(), hq::progress::Reporting::silent);
    benchmark::DoNotOptimize(f.values[0].data());
  }
  per_hex(state);
}

void BM_Fem_ElementConditioning(benchmark::State& state) {
  const Input& in = input();
  for (auto _ : state) {
    hq::FemElementField f = hq::compute_fem_elements(in.mesh);
    benchmark::DoNotOptimize(f.kappa.data());
  }
  per_hex(state);
}

void BM_Fem_Assembly(benchmark::State& state) {
  const Input& in = input();
  for (auto _ : state) {
    const double t0 = process_cpu_seconds();
    hq::LaplaceSystem s = hq::assemble_laplace_system(in.mesh, in.topology, in.dirichlet, 3);
    state.counters["cpu_s"] = process_cpu_seconds() - t0;
    benchmark::DoNotOptimize(s.matrix.values.data());
  }
  per_hex(state);
}

void BM_Fem_Solve(benchmark::State& state) {
  const hq::LaplaceSystem& s = system();
  for (auto _ : state) {
    const double t0 = process_cpu_seconds();
    hq::PcgResult r = hq::solve_pcg(s.matrix, s.diagonal, s.rhs, 3);
    state.counters["cpu_s"] = process_cpu_seconds() - t0;
    benchmark::DoNotOptimize(r.x.data());
    state.counters["iterations"] = r.columns[0].lanczos_steps;
  }
  per_hex(state);
}

void BM_Fem_Errors(benchmark::State& state) {
  const Input& in = input();
  for (auto _ : state) {
    hq::Q1FieldErrors e =
        hq::q1_field_errors(in.mesh, in.dirichlet, hq::default_harmonic_solutions(), in.normalization);
    benchmark::DoNotOptimize(e.volume.data());
  }
  per_hex(state);
}

void BM_Fem_Correlations(benchmark::State& state) {
  const Input& in = input();
  static const hq::HexMetricField metrics =
      hq::compute_hex_metrics(in.mesh, hq::all_hex_metrics(), hq::progress::Reporting::silent);
  for (auto _ : state) {
    auto c = hq::correlate_metrics(in.elements.kappa, metrics, in.elements);
    benchmark::DoNotOptimize(c.data());
  }
  per_hex(state);
}

void BM_Fem_WholeCheck(benchmark::State& state) {
  const Input& in = input();
  for (auto _ : state) {
    const double t0 = process_cpu_seconds();
    hq::FemElementField elements = hq::compute_fem_elements(in.mesh);
    hq::PoissonCheck c = hq::run_poisson_check(in.mesh, in.topology, elements);
    state.counters["cpu_s"] = process_cpu_seconds() - t0;
    benchmark::DoNotOptimize(c.mean_l2_error);
  }
  per_hex(state);
}

}  // namespace

BENCHMARK(BM_Fem_Baseline_VerdictMetrics)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Fem_ElementConditioning)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Fem_Assembly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Fem_Solve)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Fem_Errors)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Fem_Correlations)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Fem_WholeCheck)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
