// Every view (render_views: 3D views, detail views, charts; PNG encoding
// excluded) of the largest real mesh (Dolphin_padded, 45k hexes) and of a
// 1->8 refined copy (363k hexes), at 1600x1200 on 2 threads. Targets
// (issue 7): all views of Dolphin_padded with its reference under 5 s for the
// whole run, of the refined copy under 15 s.

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <map>

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

// Each hex split into 2x2x2 at edge midpoints, face centres and its centre;
// shared points merged.
hq::HexMesh refine(const hq::HexMesh& coarse) {
  hq::HexMesh fine;
  fine.points = coarse.points;
  std::map<std::vector<hq::Index>, hq::Index> made;
  auto point_of = [&](std::vector<hq::Index> ids) {
    std::sort(ids.begin(), ids.end());
    if (ids.size() == 1) return ids[0];
    if (const auto it = made.find(ids); it != made.end()) return it->second;
    hq::Vec3 sum;
    for (hq::Index id : ids) sum = sum + coarse.points[static_cast<std::size_t>(id)];
    fine.points.push_back(sum / static_cast<double>(ids.size()));
    made.emplace(std::move(ids), static_cast<hq::Index>(fine.points.size() - 1));
    return static_cast<hq::Index>(fine.points.size() - 1);
  };
  static constexpr int kCorner[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}};
  for (const hq::Hex& hex : coarse.hexes) {
    hq::Index g[3][3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) {
          std::vector<hq::Index> ids;
          for (int r = 0; r < 2; ++r)
            for (int s = 0; s < 2; ++s)
              for (int t = 0; t < 2; ++t)
                if ((i == 1 || i == 2 * r) && (j == 1 || j == 2 * s) && (k == 1 || k == 2 * t))
                  ids.push_back(hex[kCorner[r][s][t]]);
          g[i][j][k] = point_of(std::move(ids));
        }
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int c = 0; c < 2; ++c)
          fine.hexes.push_back({g[a][b][c], g[a + 1][b][c], g[a + 1][b + 1][c], g[a][b + 1][c], g[a][b][c + 1],
                                g[a + 1][b][c + 1], g[a + 1][b + 1][c + 1], g[a][b + 1][c + 1]});
  }
  return fine;
}

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
  static const Analysed a = analyse(refine(coarse().mesh));
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
