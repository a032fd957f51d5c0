// Every view (render_views: 3D views, detail views, charts) of the largest
// real mesh (Dolphin_padded, 45k hexes, with its reference surface
// dolphin.off) and of a 1->8 refined copy (363k hexes, same reference), at
// 1600x1200 on 2 threads. Targets (issue 7): all views of Dolphin_padded
// with its reference under 5 s for the whole `hqview analyze` run, of the
// refined copy under 15 s.
//
// BM_AllViews_* render every view and encode every PNG (render_views does
// both, the encoding on a second thread while later frames render);
// BM_View_Dolphin/<k> renders the k-th selectable view of kViews alone (its label names it),
// for a per-view profile.

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <memory>
#include <optional>

#include "bench_data.h"
#include "hqview/analysis/analysis.h"
#include "hqview/boundary/boundary_error.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/overlap/overlap.h"
#include "hqview/quality/quality_field.h"
#include "hqview/render/osmesa_renderer.h"
#include "hqview/uv/uv_atlas.h"
#include "hqview/views/views.h"

namespace {

// The reference surface next to the benchmark mesh (dolphin.off), if any.
std::optional<hq::TriSurface> reference_surface() {
  const std::filesystem::path path = hq::bench::largest_mesh().parent_path() / "dolphin.off";
  if (!std::filesystem::exists(path)) return std::nullopt;
  return hq::read_surface(path);
}

hq::Analysis analyse(hq::HexMesh mesh) {
  hq::Analysis a;
  a.mesh_input.path = "bench";
  a.mesh = std::move(mesh);
  a.topology = hq::build_topology(a.mesh);
  a.field = hq::compute_quality(a.mesh, a.topology);
  double sum = 0.0;
  for (const hq::Edge& e : a.topology.edges)
    sum += norm(a.mesh.points[static_cast<std::size_t>(e[0])] - a.mesh.points[static_cast<std::size_t>(e[1])]);
  a.glyphs = hq::compute_glyphs(a.mesh.points, a.field.vertex_quality,
                                sum / std::max<std::size_t>(1, a.topology.edges.size()), hq::GlyphOptions{});
  a.overlap = hq::check_overlap(a.mesh, a.topology, hq::OverlapOptions{});
  a.reference_surface = reference_surface();
  if (a.reference_surface) {
    a.boundary_error = hq::compute_boundary_error(a.mesh, a.topology, *a.reference_surface);
    a.uv_atlas = hq::build_uv_atlas(*a.reference_surface, hq::UvOptions{.improve_with_lscm = true});
  }
  return a;
}

const hq::Analysis& coarse() {
  static const hq::Analysis a = analyse(hq::read_hex_mesh(hq::bench::largest_mesh()).mesh);
  return a;
}

const hq::Analysis& refined() {
  static const hq::Analysis a = analyse(hq::bench::refine_1_to_8(coarse().mesh));
  return a;
}

// The ids --views accepts, in table order (BM_View_*'s argument indexes them).
const std::vector<std::string>& view_ids() {
  static const std::vector<std::string> ids = [] {
    std::vector<std::string> out;
    for (const hq::ViewSpec& spec : hq::kViews)
      if (spec.is_selectable) out.emplace_back(spec.id);
    return out;
  }();
  return ids;
}

// A renderer that draws nothing (a white frame): what a view costs besides
// OpenGL (scene building, viewpoint choice, annotation, PNG encoding).
class BlankRenderer final : public hq::Renderer {
 public:
  hq::Image render(const hq::Scene&, const hq::Camera&, int width, int height) override {
    return {width, height, std::vector<std::uint8_t>(4 * static_cast<std::size_t>(width) * height, 255)};
  }
};

void run_views(benchmark::State& state, const hq::Analysis& a, std::vector<std::string> ids = {}, bool blank = false) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
  const std::unique_ptr<hq::Renderer> renderer = blank ? std::make_unique<BlankRenderer>() : hq::make_osmesa_renderer();
  hq::ViewOptions options;
  options.views = std::move(ids);
  std::size_t images = 0;
  for (auto _ : state) {
    const auto views = hq::render_views(a, options, *renderer);
    images = 0;
    for (const hq::RenderedView& view : views) images += view.files.size();
    benchmark::DoNotOptimize(views.data());
  }
  state.counters["hexes"] = static_cast<double>(a.mesh.hexes.size());
  state.counters["files"] = static_cast<double>(images);
}

void BM_AllViews_Dolphin(benchmark::State& state) { run_views(state, coarse()); }
void BM_AllViews_Refined(benchmark::State& state) { run_views(state, refined()); }
void BM_View_Dolphin(benchmark::State& state) {
  const std::string& id = view_ids()[static_cast<std::size_t>(state.range(0))];
  state.SetLabel(id);
  run_views(state, coarse(), {id});
}

// The fixed cost of one 1600x1200 frame: an empty scene (clear, resolve,
// read back).
void BM_EmptyFrame(benchmark::State& state) {
  const auto renderer = hq::make_osmesa_renderer();
  const hq::Camera camera;
  for (auto _ : state) benchmark::DoNotOptimize(renderer->render(hq::Scene{}, camera, 1600, 1200).rgba.data());
}

BENCHMARK(BM_EmptyFrame)->Unit(benchmark::kMillisecond)->UseRealTime();
void BM_ViewWithoutGl_Dolphin(benchmark::State& state) {
  const std::string& id = view_ids()[static_cast<std::size_t>(state.range(0))];
  state.SetLabel(id);
  run_views(state, coarse(), {id}, true);
}
BENCHMARK(BM_ViewWithoutGl_Dolphin)
    ->DenseRange(0, static_cast<int>(view_ids().size()) - 1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();
// Plain names (bench/report.py's targets): one iteration takes more than the
// minimum time of main-thread CPU, and the JSON's real_time is what counts.
BENCHMARK(BM_AllViews_Dolphin)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_View_Dolphin)
    ->DenseRange(0, static_cast<int>(view_ids().size()) - 1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK(BM_AllViews_Refined)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
