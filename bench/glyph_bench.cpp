// Glyph clustering (issue 4): the grid + union-find clustering on 1M and 20k
// vertices against the paper's approach, all pairs then merging (here with a
// union-find, which only makes the baseline faster), on the same 20k glyphs
// in the same run. Inputs are perturbed structured grids (made in code, so
// the benchmark needs no data files): every vertex gets a glyph (threshold 0,
// the hardest case for the clustering), rmax = the mean edge length.
// BM_GlyphStage runs the whole stage (radii, clusters, aggregated glyphs,
// ranks) with the default options.

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>

#include "hqview/glyph/glyph_clusters.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/quality_field.h"

namespace {

// A uniform number in [−1, 1) from an integer (splitmix64), so the meshes do
// not depend on a standard library's distributions.
double noise(std::uint64_t i) {
  std::uint64_t z = i + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1p-52 - 1.0;
}

// An n×n×n grid of unit hexes, every vertex moved by up to 0.3 per axis:
// vertex quality from about −0.67 to 1, median 0.69, 19 % below 0.5.
struct Input {
  hq::HexMesh mesh;
  std::vector<double> vertex_quality;
  double mean_edge = 0;
  std::vector<double> radii;  // every vertex: (1 − Jm) · mean edge
};

const Input& input(int vertices_per_side) {
  static std::map<int, Input> cache;
  auto [it, is_new] = cache.try_emplace(vertices_per_side);
  Input& in = it->second;
  if (!is_new) return in;
  const int v = vertices_per_side, n = v - 1;
  for (int z = 0; z < v; ++z)
    for (int y = 0; y < v; ++y)
      for (int x = 0; x < v; ++x) {
        const auto id = static_cast<std::uint64_t>(in.mesh.points.size());
        in.mesh.points.push_back({x + 0.3 * noise(3 * id), y + 0.3 * noise(3 * id + 1), z + 0.3 * noise(3 * id + 2)});
      }
  auto at = [v](int x, int y, int z) { return static_cast<hq::Index>(x + v * (y + v * z)); };
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        in.mesh.hexes.push_back({at(x, y, z), at(x + 1, y, z), at(x + 1, y + 1, z), at(x, y + 1, z), at(x, y, z + 1),
                                 at(x + 1, y, z + 1), at(x + 1, y + 1, z + 1), at(x, y + 1, z + 1)});
  const hq::Topology topo = hq::build_topology(in.mesh);
  in.vertex_quality = hq::compute_quality(in.mesh, topo).vertex_quality;
  double sum = 0;
  for (const hq::Edge& e : topo.edges) sum += hq::norm(in.mesh.points[e[1]] - in.mesh.points[e[0]]);
  in.mean_edge = sum / static_cast<double>(topo.edges.size());
  in.radii = hq::glyph_radii(in.vertex_quality, in.mean_edge, -1.0);  // threshold below 0: every vertex
  return in;
}

int side_for(std::int64_t vertices) { return static_cast<int>(std::lround(std::cbrt(static_cast<double>(vertices)))); }

void BM_GlyphClusters_HQView(benchmark::State& state) {
  const Input& in = input(side_for(state.range(0)));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
  hq::Index clusters = 0;
  for (auto _ : state) {
    const hq::GlyphClusters c = hq::cluster_glyphs(in.mesh.points, in.radii);
    clusters = c.num_clusters();
    benchmark::DoNotOptimize(c.members.data());
  }
  state.counters["vertices"] = static_cast<double>(in.mesh.points.size());
  state.counters["clusters"] = clusters;
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(in.mesh.points.size()));
}

// The paper's approach: every pair tested, then components (a union-find
// instead of its repeated set merging), on one thread.
void BM_GlyphClusters_BaselineAllPairs(benchmark::State& state) {
  const Input& in = input(side_for(state.range(0)));
  const auto& p = in.mesh.points;
  const auto& r = in.radii;
  const std::size_t n = p.size();
  std::vector<hq::Index> parent(n);
  std::size_t clusters = 0;
  for (auto _ : state) {
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](hq::Index x) {
      while (parent[static_cast<std::size_t>(x)] != x)
        x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      return x;
    };
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (hq::glyphs_overlap(p[i], r[i], p[j], r[j])) {
          const hq::Index a = find(static_cast<hq::Index>(i)), b = find(static_cast<hq::Index>(j));
          if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
        }
    clusters = 0;
    for (std::size_t i = 0; i < n; ++i) clusters += find(static_cast<hq::Index>(i)) == static_cast<hq::Index>(i);
    benchmark::DoNotOptimize(clusters);
  }
  state.counters["vertices"] = static_cast<double>(n);
  state.counters["clusters"] = static_cast<double>(clusters);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(n));
}

// The whole stage with the default options (threshold 0.5, rmax 1× mean edge).
void BM_GlyphStage_HQView(benchmark::State& state) {
  const Input& in = input(side_for(state.range(0)));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
  hq::GlyphResult result;
  for (auto _ : state) {
    result = hq::compute_glyphs(in.mesh.points, in.vertex_quality, in.mean_edge, hq::GlyphOptions{});
    benchmark::DoNotOptimize(result.clusters.data());
  }
  state.counters["glyphs"] = result.num_glyphs;
  state.counters["clusters"] = static_cast<double>(result.clusters.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(in.mesh.points.size()));
}

// 27³ = 19,683 and 100³ = 1,000,000 vertices.
BENCHMARK(BM_GlyphClusters_HQView)
    ->Args({19683, 1})
    ->Args({19683, 2})
    ->Args({1000000, 1})
    ->Args({1000000, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GlyphClusters_BaselineAllPairs)->Arg(19683)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GlyphStage_HQView)->Args({1000000, 2})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
