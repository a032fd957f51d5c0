// Prints the UV atlas statistics of each surface given (the numbers of docs/analysis.md, "UV atlas"):
//   build/bench/uv_atlas_stats ../shared/data/meshes/*/*.off
// LSCM=1 lays charts out by LSCM where better and merges them (as hqview does; NOMERGE=1: without the
// merging); PROJ=1 uses the first, projected charting. Each line ends with a hash of the UVs and charts.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include "hqview/io/mesh_reader.h"
#include "hqview/uv/uv_atlas.h"
using namespace hq;
// FNV-1a of the UVs' bytes and the charts: two atlases with the same hash are the same (to check a speed-up).
static unsigned long long uv_hash(const UvAtlas& a) {
  unsigned long long h = 1469598103934665603ULL;
  const auto add = [&](const void* data, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<const unsigned char*>(data)[i]) * 1099511628211ULL;
  };
  add(a.uvs.data(), a.uvs.size() * sizeof(a.uvs[0]));
  add(a.triangle_chart.data(), a.triangle_chart.size() * sizeof(a.triangle_chart[0]));
  return h;
}
int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    TriSurface s = read_surface(argv[i]);
    UvOptions o; o.improve_with_lscm = getenv("LSCM") != nullptr;
    if (getenv("PROJ")) o.charts = UvCharts::projected;
    if (getenv("UPY")) o.up = {0,1,0};
    if (getenv("NOMERGE")) o.merge_by_layout = false;
    if (getenv("NOARAP")) o.merge_with_arap = false;
    if (getenv("RES")) o.pack_resolution = atoi(getenv("RES"));
    if (getenv("WITHIN")) o.merge_min_area_within_2 = atof(getenv("WITHIN"));
    if (getenv("PACKSPLITS")) o.pack_max_splits = atoi(getenv("PACKSPLITS"));
    auto t0 = std::chrono::steady_clock::now();
    UvAtlas a = build_uv_atlas(s, o);
    double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-14s tris %7zu charts %5d lscm %3d splits %4d top1 %.3f top4 %.3f top8 %.3f pack %.3f ratio p5 %.2f p50 %.2f p95 %.2f within %.3f conf p50 %.2f p95 %.2f flip %d ov %d  %.2fs uvs %016llx\n",
      argv[i] + std::string(argv[i]).rfind('/') + 1, s.triangles.size(), a.num_charts, a.num_lscm_charts, a.num_splits,
      a.area_fraction_largest_chart, a.area_fraction_top_4_charts, a.area_fraction_top_8_charts, a.packing_efficiency,
      a.area_ratio.p5, a.area_ratio.p50, a.area_ratio.p95, a.area_fraction_area_ratio_within_2,
      a.conformal_distortion.p50, a.conformal_distortion.p95, a.num_flipped, a.num_overlaps, sec, uv_hash(a));
  }
}
