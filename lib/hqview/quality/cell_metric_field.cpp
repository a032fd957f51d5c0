#include "hqview/quality/cell_metric_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hqview/quality/pyramid_metrics.h"
#include "hqview/quality/quad_metrics.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/triangle_metrics.h"
#include "hqview/quality/wedge_metrics.h"

namespace hq {
namespace {

constexpr std::size_t kGrain = 1024;

template <typename Body>
void for_each_cell(std::size_t count, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) body(c);
  });
}

// What the block loop needs of a kind: its metric table and kernels.
template <std::size_t N, int M, class Info, class Size, class Metrics, class Corners, class Orient>
CellBlockMetricField compute_block(CellKind kind, std::span<const Vec3> points,
                                   std::span<const std::array<Index, N>> cells, const Info& info, const Size& size,
                                   const Metrics& metrics, const Corners& corners, const Orient& orient) {
  const std::size_t n = cells.size();
  CellBlockMetricField field;
  field.kind = kind;
  field.count = static_cast<std::int64_t>(n);
  for (int m = 0; m < M; ++m) field.names.push_back(info(m));
  field.values.assign(M, std::vector<double>(n));
  auto corners_of = [&](std::size_t c) {
    std::array<Vec3, N> p;
    for (std::size_t i = 0; i < N; ++i) p[i] = points[static_cast<std::size_t>(cells[c][i])];
    return p;
  };

  // Pass 1: the sizes and their mean (the size metrics need it first).
  std::vector<double> sizes(n);
  for_each_cell(n, [&](std::size_t c) { sizes[c] = size(corners_of(c)); });
  double sum = 0;
  for (double s : sizes) sum += s;  // in id order: the same bytes for any thread count
  field.average_size = n > 0 ? sum / static_cast<double>(n) : 0.0;

  // Pass 2: every metric, the corners and the orientation of each cell.
  using CornerValues = decltype(corners(std::array<Vec3, N>{}));
  constexpr int C = static_cast<int>(std::tuple_size_v<decltype(CornerValues::value)>);
  field.corners_per_cell = C;
  field.corner_scaled_jacobian.resize(n * C);
  field.corner_degenerate_mask.resize(n);
  field.validity.resize(n);
  for_each_cell(n, [&](std::size_t c) {
    const auto p = corners_of(c);
    const auto v = metrics(p, field.average_size);
    for (int m = 0; m < M; ++m) field.values[static_cast<std::size_t>(m)][c] = v[static_cast<std::size_t>(m)];
    const auto k = corners(p);
    for (int i = 0; i < C; ++i) field.corner_scaled_jacobian[c * C + static_cast<std::size_t>(i)] = k.value[i];
    field.corner_degenerate_mask[c] = k.degenerate_mask;
    field.validity[c] = orient(p);
  });
  for (CellValidity o : field.validity) {
    field.num_inverted += o == CellValidity::inverted;
    field.num_flat += o == CellValidity::flat;
  }
  return field;
}

}  // namespace

const std::vector<double>* CellBlockMetricField::of(std::string_view name) const {
  for (std::size_t m = 0; m < names.size(); ++m)
    if (names[m] == name) return &values[m];
  return nullptr;
}

CellBlockMetricField compute_tet_block_metrics(std::span<const Vec3> points,
                                               std::span<const std::array<Index, 4>> tets) {
  return compute_block<4, kNumTetMetrics>(
      CellKind::tet, points, tets, [](int m) { return tet_metric_info(TetMetric(m)).name; },
      [](const TetCorners& p) { return tet_volume(p); },
      [](const TetCorners& p, double average) { return tet_metrics(p, average); },
      [](const TetCorners& p) { return tet_corner_scaled_jacobians(p); },
      [](const TetCorners& p) { return tet_validity(p); });
}

CellBlockMetricField compute_wedge_block_metrics(std::span<const Vec3> points,
                                                 std::span<const std::array<Index, 6>> wedges) {
  return compute_block<6, kNumWedgeMetrics>(
      CellKind::wedge, points, wedges, [](int m) { return wedge_metric_info(WedgeMetric(m)).name; },
      [](const WedgeCorners& p) { return wedge_metric(WedgeMetric::volume, p); },
      [](const WedgeCorners& p, double average) { return wedge_metrics(p, average); },
      [](const WedgeCorners& p) { return wedge_corner_scaled_jacobians(p); },
      [](const WedgeCorners& p) { return wedge_validity(p); });
}

CellBlockMetricField compute_pyramid_block_metrics(std::span<const Vec3> points,
                                                   std::span<const std::array<Index, 5>> pyramids) {
  return compute_block<5, kNumPyramidMetrics>(
      CellKind::pyramid, points, pyramids, [](int m) { return pyramid_metric_info(PyramidMetric(m)).name; },
      [](const PyramidCorners& p) { return pyramid_metric(PyramidMetric::volume, p); },
      [](const PyramidCorners& p, double average) { return pyramid_metrics(p, average); },
      [](const PyramidCorners& p) { return pyramid_corner_scaled_jacobians(p); },
      [](const PyramidCorners& p) { return pyramid_validity(p); });
}

CellBlockMetricField compute_quad_block_metrics(std::span<const Vec3> points,
                                                std::span<const std::array<Index, 4>> quads,
                                                const std::optional<Vec3>& normal) {
  return compute_block<4, kNumQuadMetrics>(
      CellKind::quad, points, quads, [](int m) { return quad_metric_info(QuadMetric(m)).name; },
      [](const QuadCorners& p) { return quad_metric(QuadMetric::area, p, 0.0); },
      [](const QuadCorners& p, double average) { return quad_metrics(p, average); },
      [&](const QuadCorners& p) { return quad_corner_scaled_jacobians(p, normal); },
      [&](const QuadCorners& p) { return quad_validity(p, normal); });
}

CellBlockMetricField compute_triangle_block_metrics(std::span<const Vec3> points,
                                                    std::span<const std::array<Index, 3>> triangles,
                                                    const std::optional<Vec3>& normal) {
  return compute_block<3, kNumTriangleMetrics>(
      CellKind::triangle, points, triangles, [](int m) { return triangle_metric_info(TriangleMetric(m)).name; },
      [](const TriangleCorners& p) { return triangle_area(p); },
      [](const TriangleCorners& p, double average) { return triangle_metrics(p, average); },
      [&](const TriangleCorners& p) { return triangle_corner_scaled_jacobians(p, normal); },
      [&](const TriangleCorners& p) { return triangle_validity(p, normal); });
}

std::vector<CellMetricSummary> summarize_cell_block(const CellBlockMetricField& field) {
  std::vector<CellMetricSummary> out;
  for (std::size_t m = 0; m < field.names.size(); ++m) {
    StatisticsOptions options;
    if (field.names[m] == "scaled_jacobian") {
      options.histogram_min = -1.0;
      options.histogram_max = 1.0;
    }
    out.push_back({std::string(field.names[m]), compute_statistics(field.values[m], options)});
  }
  // Every corner value, degenerate corners left out.
  const std::size_t C = static_cast<std::size_t>(field.corners_per_cell);
  std::vector<std::uint8_t> degenerate(field.corner_scaled_jacobian.size());
  for (std::size_t c = 0; c < field.corner_degenerate_mask.size(); ++c)
    for (std::size_t i = 0; i < C; ++i) degenerate[c * C + i] = (field.corner_degenerate_mask[c] >> i) & 1u;
  StatisticsOptions corner_options;
  corner_options.histogram_min = -1.0;
  corner_options.histogram_max = 1.0;
  out.push_back(
      {"corner_scaled_jacobian", compute_statistics(field.corner_scaled_jacobian, corner_options, degenerate)});
  return out;
}

}  // namespace hq
