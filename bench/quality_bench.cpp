// Corner scaled Jacobian throughput (hexes/s) on 1 and 2 threads against a
// baseline: the direct per-corner formula (three square roots per corner,
// one thread), the way the paper's reference implementation computes it.
//
// TopologySplitRefined (issue 46): build_topology of the 1->8 refined mesh
// (363,520 hexes) split into 6 tets per hex along each hex's 0-6 diagonal
// (2,181,120 tets, every face matched across the tet block), against the
// hex topology of the same hexes in the same run; items are source hexes,
// so the ratio column is the time ratio.

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "bench_data.h"
#include "hqview/core/hex_topology.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/quality/quality_field.h"
#include "hqview/quality/statistics.h"

namespace {

const hq::HexMesh& mesh() {
  static const hq::HexMesh m = hq::read_hex_mesh(hq::bench::largest_mesh()).mesh;
  return m;
}

void BM_CornerSJ_HQView(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  std::vector<double> out(8 * m.hexes.size());
  std::vector<std::uint8_t> mask(m.hexes.size());
  for (auto _ : state) {
    hq::compute_corner_scaled_jacobians(m, out, mask);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

void BM_CornerSJ_BaselinePerCorner(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  std::vector<double> out(8 * m.hexes.size());
  for (auto _ : state) {
    for (std::size_t h = 0; h < m.hexes.size(); ++h) {
      const auto p = hq::hex_corners(m, static_cast<hq::Index>(h));
      for (int i = 0; i < 8; ++i) {
        const auto& f = hq::kCornerFrames[i];
        const hq::Vec3 a = p[f[0]] - p[i], b = p[f[1]] - p[i], c = p[f[2]] - p[i];
        out[8 * h + i] = hq::det(a, b, c) / (hq::norm(a) * hq::norm(b) * hq::norm(c));
      }
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

void BM_QualityField_HQView(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  const hq::Topology topo = hq::build_topology(m);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    auto q = hq::compute_quality(m, topo);
    benchmark::DoNotOptimize(q.vertex_quality.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

void BM_Topology_HQView(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  for (auto _ : state) {
    auto topo = hq::build_topology(m);
    benchmark::DoNotOptimize(topo.edges.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

const hq::HexMesh& refined() {
  static const hq::HexMesh m = hq::bench::refine_1_to_8(mesh());
  return m;
}

void BM_TopologySplitRefined_HQView(benchmark::State& state) {
  static constexpr int kKuhn[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                      {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  hq::HexMesh points_only;
  points_only.points = refined().points;
  points_only.tets.reserve(6 * refined().hexes.size());
  for (const auto& h : refined().hexes)
    for (const auto& t : kKuhn) points_only.tets.push_back({h[t[0]], h[t[1]], h[t[2]], h[t[3]]});
  for (auto _ : state) {
    auto topo = hq::build_topology(points_only);
    benchmark::DoNotOptimize(topo.boundary_triangles.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(refined().hexes.size()));
}

void BM_TopologySplitRefined_BaselineHexTopology(benchmark::State& state) {
  for (auto _ : state) {
    auto topo = hq::build_topology(refined());
    benchmark::DoNotOptimize(topo.edges.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(refined().hexes.size()));
}

// Baseline of the quality field: the per-corner formula on one thread, the
// cell value as the min of its corners, and vertex quality by scattering
// each corner's value to its vertex (a min per corner; no topology needed).
void BM_QualityField_BaselineScatterMin(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  std::vector<double> corners(8 * m.hexes.size()), cells(m.hexes.size()), vertices(m.points.size());
  for (auto _ : state) {
    std::fill(vertices.begin(), vertices.end(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t h = 0; h < m.hexes.size(); ++h) {
      const auto p = hq::hex_corners(m, static_cast<hq::Index>(h));
      double cell = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 8; ++i) {
        const auto& f = hq::kCornerFrames[i];
        const hq::Vec3 a = p[f[0]] - p[i], b = p[f[1]] - p[i], c = p[f[2]] - p[i];
        const double sj = hq::det(a, b, c) / (hq::norm(a) * hq::norm(b) * hq::norm(c));
        corners[8 * h + i] = sj;
        cell = std::min(cell, sj);
        double& v = vertices[static_cast<std::size_t>(m.hexes[h][i])];
        if (!(v <= sj)) v = sj;
      }
      cells[h] = cell;
    }
    benchmark::DoNotOptimize(vertices.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

// Baseline of the topology: ordered containers keyed by sorted ids, the way
// research codes usually find unique faces and edges (std::map of faces to
// their hexes, std::set of edges, vector-of-vectors vertex -> hexes).
void BM_Topology_BaselineStdMap(benchmark::State& state) {
  const hq::HexMesh& m = mesh();
  for (auto _ : state) {
    std::vector<std::vector<hq::Index>> vertex_hexes(m.points.size());
    std::map<std::array<hq::Index, 4>, std::vector<hq::Index>> faces;
    std::set<std::array<hq::Index, 2>> edges;
    for (std::size_t h = 0; h < m.hexes.size(); ++h) {
      const hq::Hex& hex = m.hexes[h];
      for (hq::Index v : hex) vertex_hexes[static_cast<std::size_t>(v)].push_back(static_cast<hq::Index>(h));
      for (const auto& f : hq::kHexFaces) {
        std::array<hq::Index, 4> key{hex[f[0]], hex[f[1]], hex[f[2]], hex[f[3]]};
        std::sort(key.begin(), key.end());
        faces[key].push_back(static_cast<hq::Index>(h));
      }
      for (const auto& e : hq::kHexEdges)
        edges.insert({std::min(hex[e[0]], hex[e[1]]), std::max(hex[e[0]], hex[e[1]])});
    }
    std::vector<hq::Index> boundary_vertices;
    for (const auto& [key, hexes] : faces)
      if (hexes.size() == 1) boundary_vertices.insert(boundary_vertices.end(), key.begin(), key.end());
    std::sort(boundary_vertices.begin(), boundary_vertices.end());
    boundary_vertices.erase(std::unique(boundary_vertices.begin(), boundary_vertices.end()), boundary_vertices.end());
    benchmark::DoNotOptimize(boundary_vertices.data());
    benchmark::DoNotOptimize(edges.size());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(m.hexes.size()));
}

// Statistics of 8M values shaped like a refined mesh's corner scaled
// Jacobians (most in [0.6, 1], a few hundred negative, so the order keys
// span both signs), against the definition: copy, one std::sort, sums.
const std::vector<double>& corner_like_values() {
  static const std::vector<double> v = [] {
    std::mt19937_64 rng(16);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> out(8'000'000);
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = i % 20000 == 0 ? -0.9 * unit(rng) : 1.0 - 0.4 * unit(rng) * unit(rng);
    return out;
  }();
  return v;
}

void BM_Statistics_HQView(benchmark::State& state) {
  const auto& v = corner_like_values();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(hq::compute_statistics(v).mean);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(v.size()));
}

void BM_Statistics_BaselineSort(benchmark::State& state) {
  const auto& v = corner_like_values();
  for (auto _ : state) {
    std::vector<double> kept(v);
    std::sort(kept.begin(), kept.end());
    double sum = 0;
    for (double x : kept) sum += x;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(v.size()));
}

BENCHMARK(BM_CornerSJ_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CornerSJ_BaselinePerCorner)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_QualityField_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_QualityField_BaselineScatterMin)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Topology_HQView)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TopologySplitRefined_HQView)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TopologySplitRefined_BaselineHexTopology)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Statistics_HQView)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Statistics_BaselineSort)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Topology_BaselineStdMap)->UseRealTime()->Unit(benchmark::kMicrosecond);


}  // namespace

BENCHMARK_MAIN();
