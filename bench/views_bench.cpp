// Every view (render_views: 3D views, detail views, charts; PNG encoding
// excluded) of the largest real mesh (Dolphin_padded, 45k hexes) and of a
// 1->8 refined copy (363k hexes), at 1600x1200 on 2 threads. Targets
// (issue 7): all views of Dolphin_padded with its reference under 5 s for the
// whole run, of the refined copy under 15 s.

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>

#include "bench_data.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/overlap/overlap.h"
#include "hqview/quality/quality_field.h"
#include "hqview/render/osmesa_renderer.h"
#include "hqview/render/views.h"

namespace {

struct Analysed {
  hq::HexMesh mesh;
  hq::Topology topology;
  hq::QualityField field;
  hq::GlyphResult glyphs;
  hq::OverlapReport overlap;
};


Analysed analyse(hq::HexMesh mesh) {
  Analysed a;
  a.mesh = std::move(mesh);
  a.topology = hq::build_topology(a.mesh);
  a.field = hq::compute_quality(a.mesh, a.topology);
  double sum = 0.0;
  for (const hq::Edge& e : a.topology.edges)
    sum += norm(a.mesh.points[static_cast<std::size_t>(e[0])] - a.mesh.points[static_cast<std::size_t>(e[1])]);
  a.glyphs = hq::compute_glyphs(a.mesh.points, a.field.vertex_quality, sum / std::max<std::size_t>(1, a.topology.edges.size()),
                                hq::GlyphOptions{});
  a.overlap = hq::check_overlap(a.mesh, a.topology, hq::OverlapOptions{});
  return a;
}

const Analysed& coarse() {
  static const Analysed a = analyse(hq::read_hex_mesh(hq::bench::largest_mesh()).mesh);
  return a;
}

const Analysed& refined() {
  static const Analysed a = analyse(hq::bench::refine_1_to_8(coarse().mesh));
  return a;
}

void run_views(benchmark::State& state, const Analysed& a) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  const auto renderer = hq::make_osmesa_renderer();
  const hq::ViewInputs inputs{&a.mesh, &a.topology, &a.field.vertex_quality, &a.field.cell_scaled_jacobian, &a.glyphs,
                              &a.overlap, "bench"};
  for (auto _ : state) {
    const auto views = hq::render_views(inputs, {}, *renderer);
    benchmark::DoNotOptimize(views.data());
  }
  state.counters["hexes"] = static_cast<double>(a.mesh.hexes.size());
}

void BM_AllViews_Dolphin(benchmark::State& state) { run_views(state, coarse()); }
void BM_AllViews_Refined(benchmark::State& state) { run_views(state, refined()); }

BENCHMARK(BM_AllViews_Dolphin)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_AllViews_Refined)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
