#include "hqview/quality/hex_metric_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hqview/core/progress.h"

namespace hq {
namespace {

constexpr std::size_t kGrain = 2048;

template <typename Body>
void for_each_hex(std::size_t count, progress::Reporting reporting, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t h = r.begin(); h != r.end(); ++h) body(h);
    progress::add_done(reporting, r.size());
  });
}

}  // namespace

HexMetricField compute_hex_metrics(const HexMesh& mesh, HexMetricSet which, progress::Reporting reporting) {
  insert(which, HexMetric::scaled_jacobian);
  const std::size_t nh = mesh.hexes.size();
  HexMetricField field;
  field.computed = which;
  for (int m = 0; m < kNumHexMetrics; ++m)
    if (which.test(static_cast<std::size_t>(m))) field.values[static_cast<std::size_t>(m)].resize(nh);

  // Pass 1, only when needed: volumes and their mean (the size metrics'
  // reference, so it must be known before pass 2).
  bool wants_size = false;
  progress::set_total(reporting, 2 * nh);  // two passes over the hexes at most
  for (int m = 0; m < kNumHexMetrics; ++m)
    wants_size = wants_size || (which.test(static_cast<std::size_t>(m)) &&
                                hex_metric_info(static_cast<HexMetric>(m)).uses_average_volume);
  HexMetricSet rest = which;
  if (wants_size || contains(which, HexMetric::volume)) {
    std::vector<double> scratch;
    std::vector<double>& volume =
        contains(which, HexMetric::volume) ? field.values[static_cast<std::size_t>(HexMetric::volume)] : scratch;
    volume.resize(nh);
    for_each_hex(nh, reporting, [&](std::size_t h) { volume[h] = hex_volume(hex_corners(mesh, static_cast<Index>(h))); });
    double sum = 0;
    for (double v : volume) sum += v;  // in id order: the same bytes for any thread count
    field.average_volume = nh > 0 ? sum / static_cast<double>(nh) : 0.0;
    rest.reset(static_cast<std::size_t>(HexMetric::volume));
  }

  // Pass 2: everything else, one shared kernel per hex.
  for_each_hex(nh, reporting, [&](std::size_t h) {
    const HexMetricValues v = hex_metrics(hex_corners(mesh, static_cast<Index>(h)), field.average_volume, rest);
    for (int m = 0; m < kNumHexMetrics; ++m)
      if (rest.test(static_cast<std::size_t>(m)))
        field.values[static_cast<std::size_t>(m)][h] = v[static_cast<std::size_t>(m)];
  });
  return field;
}

}  // namespace hq
