// MEDIT .mesh parse throughput (MB/s): HQView's reader against a baseline
// iostream reader (the way most research codes read MEDIT files), both on
// the same bytes already in memory.

#include <benchmark/benchmark.h>

#include <sstream>

#include "bench_data.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/mesh_reader.h"

namespace {

const std::string& mesh_bytes() {
  static const std::string bytes = hq::read_file_bytes(hq::bench::largest_mesh());
  return bytes;
}

// Baseline: operator>> on a stringstream, keywords then counts then records.
hq::HexMesh baseline_iostream_medit(const std::string& text) {
  std::istringstream in(text);
  hq::HexMesh mesh;
  std::string word;
  while (in >> word) {
    if (word == "Vertices") {
      std::size_t n = 0;
      in >> n;
      mesh.points.resize(n);
      int ref = 0;
      for (auto& p : mesh.points) in >> p.x >> p.y >> p.z >> ref;
    } else if (word == "Hexahedra") {
      std::size_t n = 0;
      in >> n;
      mesh.hexes.resize(n);
      int ref = 0;
      for (auto& h : mesh.hexes) {
        for (auto& v : h) {
          in >> v;
          --v;
        }
        in >> ref;
      }
    }
  }
  return mesh;
}

void BM_ParseMedit_HQView(benchmark::State& state) {
  const std::string& bytes = mesh_bytes();
  for (auto _ : state) {
    auto loaded = hq::read_medit(bytes, "bench.mesh");
    benchmark::DoNotOptimize(loaded.mesh.hexes.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes.size()));
}

void BM_ParseMedit_BaselineIostream(benchmark::State& state) {
  const std::string& bytes = mesh_bytes();
  for (auto _ : state) {
    auto mesh = baseline_iostream_medit(bytes);
    benchmark::DoNotOptimize(mesh.hexes.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(bytes.size()));
}

BENCHMARK(BM_ParseMedit_HQView)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ParseMedit_BaselineIostream)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
