#include "hqview/quality/cell_metric_field.h"

#include <algorithm>

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

// Metrics computed per pass of summarize_cell_block_metrics: that many
// columns (8 bytes per cell each) alive at once beside the kept ones, and as
// many summaries (each a sorted copy) at most. Two: on 2.18 M tets this
// pass is the run's memory peak (4 took 33 MiB more); the passes' other
// costs (a gather and a size per cell) are small beside the kernels.
constexpr int kMetricsPerPass = 2;
// A kind whose kernel shares its pieces between the metrics of one cell
// (HasMetricList: a quad's edges, size, corner areas and angles) computes
// more per pass: 8 of a quad's 24 (3 passes instead of 12; 8 columns of
// 8 bytes per cell alive at once).
constexpr int kMaxMetricsPerPass = 8;

// The corner values a cell of kind K has (a pyramid: its 4 base corners).
template <CellKind K>
constexpr int kNumCornerValues = static_cast<int>(CellKindTable<K>::corner_frames.size());

// Cells per call of a batch kernel (HasMetricBatch): their corners
// gathered on the stack (96 bytes a tet).
constexpr std::size_t kBatch = 128;

template <typename Body>
void for_each_cell_range(std::size_t count, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

template <typename Body>
void for_each_cell(std::size_t count, const Body& body) {
  for_each_cell_range(count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c != end; ++c) body(c);
  });
}

// The kernels of one kind: its metric table, its Verdict size (the
// reference of its size metrics), every metric at once or one by one (the
// same values: each kind's all-at-once kernel is its one-metric kernel in a
// loop), its corner values and validity (surface kinds against `normal`).
template <CellKind K>
struct BlockKernels;
template <>
struct BlockKernels<CellKind::tet> {
  using Corners = TetCorners;
  static constexpr int num_metrics = kNumTetMetrics;
  static std::string_view name(int m) { return tet_metric_info(TetMetric(m)).name; }
  static double size(const Corners& p) { return tet_volume(p); }
  static auto metrics(const Corners& p, double average) { return tet_metrics(p, average); }
  static double metric(int m, const Corners& p, double average) { return tet_metric(TetMetric(m), p, average); }
  // The block's size reference (the cube root of the size metrics), and
  // metric()'s values of many cells at once (SIMD lanes, the tet's size
  // computed once for all its metrics): out[j][i] for cells[i], bit for bit.
  using Reference = TetSizeReference;
  static Reference reference(double average) { return tet_size_reference(average); }
  static void metric_list_many(std::span<const int> metrics, std::span<const Corners> cells, const Reference& reference,
                               std::span<double* const> out) {
    std::array<TetMetric, kNumTetMetrics> ids;
    for (std::size_t j = 0; j < metrics.size(); ++j) ids[j] = static_cast<TetMetric>(metrics[j]);
    tet_metric_list_many(std::span<const TetMetric>(ids).first(metrics.size()), cells, reference, out);
  }
  // The metric that is size() itself (tet_volume): start_block's sizes.
  static constexpr int size_metric = static_cast<int>(TetMetric::volume);
  // The metric that is the quality field's cell value (tet_scaled_jacobian,
  // the same kernel on the same corners): copied from
  // BlockCornerValues::cell_scaled_jacobian when given.
  static constexpr int field_metric = static_cast<int>(TetMetric::scaled_jacobian);
  // shape_and_size is shape times relative_size_squared (the kernel's very
  // product): read from those columns when they are kept.
  static constexpr std::array<int, 3> product = {static_cast<int>(TetMetric::shape_and_size),
                                                 static_cast<int>(TetMetric::shape),
                                                 static_cast<int>(TetMetric::relative_size_squared)};
  static auto corners(const Corners& p, const std::optional<Vec3>&) { return tet_corner_scaled_jacobians(p); }
  static CellValidity validity(const Corners& p, const std::optional<Vec3>&) { return tet_validity(p); }
};
template <>
struct BlockKernels<CellKind::wedge> {
  using Corners = WedgeCorners;
  static constexpr int num_metrics = kNumWedgeMetrics;
  static std::string_view name(int m) { return wedge_metric_info(WedgeMetric(m)).name; }
  static double size(const Corners& p) { return wedge_metric(WedgeMetric::volume, p); }
  static auto metrics(const Corners& p, double average) { return wedge_metrics(p, average); }
  static double metric(int m, const Corners& p, double average) { return wedge_metric(WedgeMetric(m), p, average); }
  static auto corners(const Corners& p, const std::optional<Vec3>&) { return wedge_corner_scaled_jacobians(p); }
  static CellValidity validity(const Corners& p, const std::optional<Vec3>&) { return wedge_validity(p); }
};
template <>
struct BlockKernels<CellKind::pyramid> {
  using Corners = PyramidCorners;
  static constexpr int num_metrics = kNumPyramidMetrics;
  static std::string_view name(int m) { return pyramid_metric_info(PyramidMetric(m)).name; }
  static double size(const Corners& p) { return pyramid_metric(PyramidMetric::volume, p); }
  static auto metrics(const Corners& p, double average) { return pyramid_metrics(p, average); }
  static double metric(int m, const Corners& p, double average) { return pyramid_metric(PyramidMetric(m), p, average); }
  static auto corners(const Corners& p, const std::optional<Vec3>&) { return pyramid_corner_scaled_jacobians(p); }
  static CellValidity validity(const Corners& p, const std::optional<Vec3>&) { return pyramid_validity(p); }
};
template <>
struct BlockKernels<CellKind::quad> {
  using Corners = QuadCorners;
  static constexpr int num_metrics = kNumQuadMetrics;
  static std::string_view name(int m) { return quad_metric_info(QuadMetric(m)).name; }
  static double size(const Corners& p) { return quad_metric(QuadMetric::area, p, 0.0); }
  static auto metrics(const Corners& p, double average) { return quad_metrics(p, average); }
  static double metric(int m, const Corners& p, double average) { return quad_metric(QuadMetric(m), p, average); }
  // metric()'s values of several metrics of one quad, bit for bit, its
  // shared pieces computed once.
  static constexpr int metrics_per_pass = kMaxMetricsPerPass;
  static void metric_list(std::span<const int> metrics, const Corners& p, double average, std::span<double> out) {
    std::array<QuadMetric, kNumQuadMetrics> ids;
    for (std::size_t j = 0; j < metrics.size(); ++j) ids[j] = static_cast<QuadMetric>(metrics[j]);
    quad_metric_list(std::span<const QuadMetric>(ids).first(metrics.size()), p, average, out);
  }
  // The metric that is size() itself (the area): start_block's sizes.
  static constexpr int size_metric = static_cast<int>(QuadMetric::area);
  static auto corners(const Corners& p, const std::optional<Vec3>& n) { return quad_corner_scaled_jacobians(p, n); }
  static CellValidity validity(const Corners& p, const std::optional<Vec3>& n) { return quad_validity(p, n); }
};
template <>
struct BlockKernels<CellKind::triangle> {
  using Corners = TriangleCorners;
  static constexpr int num_metrics = kNumTriangleMetrics;
  static std::string_view name(int m) { return triangle_metric_info(TriangleMetric(m)).name; }
  static double size(const Corners& p) { return triangle_area(p); }
  static auto metrics(const Corners& p, double average) { return triangle_metrics(p, average); }
  static double metric(int m, const Corners& p, double average) {
    return triangle_metric(TriangleMetric(m), p, average);
  }
  static auto corners(const Corners& p, const std::optional<Vec3>& n) { return triangle_corner_scaled_jacobians(p, n); }
  static CellValidity validity(const Corners& p, const std::optional<Vec3>& n) { return triangle_validity(p, n); }
};

// Metrics of many cells at once by the kind's batch kernel, against its
// block-wide size reference (tets); the other kinds' metrics cell by cell.
template <typename Kernels>
concept HasMetricBatch = requires { typename Kernels::Reference; };

template <typename Kernels>
concept HasMetricList = requires { Kernels::metrics_per_pass; };

// Metrics per pass over a block's cells.
template <typename Kernels>
constexpr int metrics_per_pass() {
  if constexpr (HasMetricList<Kernels>)
    return Kernels::metrics_per_pass;
  else
    return kMetricsPerPass;
}

template <typename Kernels>
concept HasProductMetric = requires { Kernels::product; };

template <typename Kernels>
concept HasSizeMetric = requires { Kernels::size_metric; };

template <typename Kernels>
concept HasFieldMetric = requires { Kernels::field_metric; };

template <CellKind K>
using BlockCells = std::span<const std::array<Index, CellKindTable<K>::num_corners>>;

// Cell c's corner points, written into `p` in place.
template <CellKind K>
void gather_corners(std::span<const Vec3> points, BlockCells<K> cells, std::size_t c, typename BlockKernels<K>::Corners& p) {
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = points[static_cast<std::size_t>(cells[c][i])];
}

template <CellKind K>
typename BlockKernels<K>::Corners corners_of(std::span<const Vec3> points, BlockCells<K> cells, std::size_t c) {
  typename BlockKernels<K>::Corners p;
  gather_corners<K>(points, cells, c, p);
  return p;
}

// The block's count, names and mean size (pass 1: the sizes, summed in id
// order: the same bytes for any thread count; the size metrics need it
// first); values left empty.
template <CellKind K>
CellBlockMetricField start_block(std::span<const Vec3> points, BlockCells<K> cells,
                                 std::vector<double>* sizes_out = nullptr) {
  using Kernels = BlockKernels<K>;
  const std::size_t n = cells.size();
  CellBlockMetricField field;
  field.kind = K;
  field.count = static_cast<std::int64_t>(n);
  for (int m = 0; m < Kernels::num_metrics; ++m) field.names.push_back(Kernels::name(m));
  field.values.resize(Kernels::num_metrics);
  field.corners_per_cell = kNumCornerValues<K>;
  std::vector<double> sizes(n);
  for_each_cell(n, [&](std::size_t c) { sizes[c] = Kernels::size(corners_of<K>(points, cells, c)); });
  double sum = 0;
  for (double s : sizes) sum += s;
  field.average_size = n > 0 ? sum / static_cast<double>(n) : 0.0;
  if (sizes_out) *sizes_out = std::move(sizes);
  return field;
}

template <CellKind K>
CellBlockMetricField compute_block(std::span<const Vec3> points, BlockCells<K> cells,
                                   const std::optional<Vec3>& normal = std::nullopt) {
  using Kernels = BlockKernels<K>;
  constexpr int M = Kernels::num_metrics;
  constexpr int C = kNumCornerValues<K>;
  const std::size_t n = cells.size();
  CellBlockMetricField field = start_block<K>(points, cells);
  for (std::vector<double>& v : field.values) v.resize(n);
  // Pass 2: every metric, the corners and the orientation of each cell.
  field.corner_scaled_jacobian.resize(n * C);
  field.corner_degenerate_mask.resize(n);
  field.validity.resize(n);
  for_each_cell(n, [&](std::size_t c) {
    const auto p = corners_of<K>(points, cells, c);
    const auto v = Kernels::metrics(p, field.average_size);
    for (int m = 0; m < M; ++m) field.values[static_cast<std::size_t>(m)][c] = v[static_cast<std::size_t>(m)];
    const auto k = Kernels::corners(p, normal);
    for (int i = 0; i < C; ++i) field.corner_scaled_jacobian[c * C + static_cast<std::size_t>(i)] = k.value[i];
    field.corner_degenerate_mask[c] = k.degenerate_mask;
    field.validity[c] = Kernels::validity(p, normal);
  });
  for (CellValidity o : field.validity) {
    field.num_inverted += o == CellValidity::inverted;
    field.num_flat += o == CellValidity::flat;
  }
  return field;
}

// The histogram range of a metric's statistics: [-1, 1] for
// scaled_jacobian, [min, max] otherwise.
StatisticsOptions metric_statistics_options(std::string_view name) {
  StatisticsOptions options;
  if (name == "scaled_jacobian") {
    options.histogram_min = -1.0;
    options.histogram_max = 1.0;
  }
  return options;
}

// The statistics of every corner value, degenerate corners left out
// (histogram over [-1, 1]).
CellMetricSummary corner_summary(std::span<const double> values, std::span<const std::uint8_t> masks, int C,
                                 std::vector<double>& sorted) {
  const auto per_cell = static_cast<std::size_t>(C);
  // One flag per corner value, made only when some corner is degenerate
  // (none flagged: the same statistics without the array).
  std::vector<std::uint8_t> degenerate;
  if (std::any_of(masks.begin(), masks.end(), [](std::uint8_t m) { return m != 0; })) {
    degenerate.resize(values.size());
    for (std::size_t c = 0; c < masks.size(); ++c)
      for (std::size_t i = 0; i < per_cell; ++i) degenerate[c * per_cell + i] = (masks[c] >> i) & 1u;
  }
  StatisticsOptions options;
  options.histogram_min = -1.0;
  options.histogram_max = 1.0;
  return {"corner_scaled_jacobian", compute_statistics(values, options, degenerate, sorted)};
}

}  // namespace

const std::vector<double>* CellBlockMetricField::of(std::string_view name) const {
  for (std::size_t m = 0; m < names.size(); ++m)
    if (names[m] == name) return &values[m];
  return nullptr;
}

CellBlockMetricField compute_tet_block_metrics(std::span<const Vec3> points,
                                               std::span<const std::array<Index, 4>> tets) {
  return compute_block<CellKind::tet>(points, tets);
}

CellBlockMetricField compute_wedge_block_metrics(std::span<const Vec3> points,
                                                 std::span<const std::array<Index, 6>> wedges) {
  return compute_block<CellKind::wedge>(points, wedges);
}

CellBlockMetricField compute_pyramid_block_metrics(std::span<const Vec3> points,
                                                   std::span<const std::array<Index, 5>> pyramids) {
  return compute_block<CellKind::pyramid>(points, pyramids);
}

CellBlockMetricField compute_quad_block_metrics(std::span<const Vec3> points,
                                                std::span<const std::array<Index, 4>> quads,
                                                const std::optional<Vec3>& normal) {
  return compute_block<CellKind::quad>(points, quads, normal);
}

CellBlockMetricField compute_triangle_block_metrics(std::span<const Vec3> points,
                                                    std::span<const std::array<Index, 3>> triangles,
                                                    const std::optional<Vec3>& normal) {
  return compute_block<CellKind::triangle>(points, triangles, normal);
}

template <CellKind K>
SummarizedCellBlock summarize_cell_block_metrics(std::span<const Vec3> points,
                                                 std::span<const std::array<Index, CellKindTable<K>::num_corners>> cells,
                                                 const BlockCornerValues& corners,
                                                 const std::function<bool(std::string_view)>& keep) {
  using Kernels = BlockKernels<K>;
  constexpr int M = Kernels::num_metrics;
  const std::size_t n = cells.size();
  SummarizedCellBlock out;
  // The sizes are a metric's very values where the kind has one (a tet's
  // volume): kept for it rather than computed again.
  std::vector<double> sizes;
  out.field = start_block<K>(points, cells, HasSizeMetric<Kernels> ? &sizes : nullptr);
  CellBlockMetricField& field = out.field;
  for (CellValidity o : corners.validity) {
    field.num_inverted += o == CellValidity::inverted;
    field.num_flat += o == CellValidity::flat;
  }
  out.summaries.resize(M + 1);
  // A column summarised (one summary at a time: each sorts a copy of its
  // column, in parallel on a large block; one copy alive, not one per
  // column), then kept or dropped.
  // The sorted copies share one buffer, and a dropped column's memory
  // serves the next pass (fresh pages are zeroed by the kernel: once, not
  // once per column).
  std::vector<double> sorted;
  std::vector<std::vector<double>> spare;
  const auto new_column = [&] {
    if (spare.empty()) return std::vector<double>(n);
    std::vector<double> column = std::move(spare.back());
    spare.pop_back();
    return column;
  };
  const auto summarize = [&](int metric, std::vector<double>& column) {
    const auto m = static_cast<std::size_t>(metric);
    out.summaries[m] = {std::string(field.names[m]),
                        compute_statistics(column, metric_statistics_options(field.names[m]), {}, sorted)};
    if (keep(field.names[m]))
      field.values[m] = std::move(column);
    else
      spare.push_back(std::move(column));
  };
  // The columns whose values are at hand: the size metric (start_block's
  // sizes), the field's metric (the quality field's cell values, when
  // given), a product metric (a tet's shape_and_size) from its kept
  // factors (after them: it is the kind's last metric). Every other metric
  // is computed by its kernel, metrics_per_pass() metrics per pass over the
  // cells (one gather of each cell's corners, one size and one block
  // reference for all of them).
  std::vector<char> at_hand(M, 0);
  if constexpr (HasSizeMetric<Kernels>) at_hand[Kernels::size_metric] = sizes.size() == n;
  if constexpr (HasFieldMetric<Kernels>) at_hand[Kernels::field_metric] = corners.cell_scaled_jacobian.size() == n;
  bool product_at_hand = false;
  if constexpr (HasProductMetric<Kernels>) {
    constexpr auto product = Kernels::product;
    product_at_hand = keep(field.names[product[1]]) && keep(field.names[product[2]]);
    at_hand[product[0]] = product_at_hand;
  }
  std::vector<int> computed;
  for (int m = 0; m < M; ++m)
    if (!at_hand[static_cast<std::size_t>(m)]) computed.push_back(m);
  constexpr std::size_t per_pass = metrics_per_pass<Kernels>();
  static_assert(per_pass <= kMaxMetricsPerPass);
  for (std::size_t first = 0; first < computed.size(); first += per_pass) {
    const std::size_t count = std::min(per_pass, computed.size() - first);
    const std::span<const int> metrics = std::span<const int>(computed).subspan(first, count);
    std::array<std::vector<double>, per_pass> columns;
    for (std::size_t j = 0; j < count; ++j) columns[j] = new_column();
    if constexpr (HasMetricBatch<Kernels>) {
      // Batches of gathered corners through the kind's batch kernel.
      const typename Kernels::Reference reference = Kernels::reference(field.average_size);
      for_each_cell_range(n, [&](std::size_t begin, std::size_t end) {
        std::array<typename Kernels::Corners, kBatch> p;
        for (std::size_t batch = begin; batch < end; batch += kBatch) {
          const std::size_t size = std::min(kBatch, end - batch);
          // In place: a returned array copied into p[c] went through the
          // stack, its 8-byte stores read back as 16-byte loads (a stalled
          // store forwarding on every tet: 4 % of the tets' run).
          for (std::size_t c = 0; c < size; ++c) gather_corners<K>(points, cells, batch + c, p[c]);
          std::array<double*, per_pass> out{};
          for (std::size_t j = 0; j < count; ++j) out[j] = columns[j].data() + batch;
          Kernels::metric_list_many(metrics, std::span(p).first(size), reference, std::span(out).first(count));
        }
      });
    } else if constexpr (HasMetricList<Kernels>) {
      for_each_cell(n, [&](std::size_t c) {
        std::array<double, per_pass> v;
        Kernels::metric_list(metrics, corners_of<K>(points, cells, c), field.average_size, std::span(v).first(count));
        for (std::size_t j = 0; j < count; ++j) columns[j][c] = v[j];
      });
    } else {
      for_each_cell(n, [&](std::size_t c) {
        const auto p = corners_of<K>(points, cells, c);
        for (std::size_t j = 0; j < count; ++j) columns[j][c] = Kernels::metric(metrics[j], p, field.average_size);
      });
    }
    for (std::size_t j = 0; j < count; ++j) summarize(metrics[j], columns[j]);
  }
  if constexpr (HasSizeMetric<Kernels>)
    if (at_hand[Kernels::size_metric]) summarize(Kernels::size_metric, sizes);
  if constexpr (HasFieldMetric<Kernels>) {
    if (at_hand[Kernels::field_metric]) {
      std::vector<double> column = new_column();
      std::copy(corners.cell_scaled_jacobian.begin(), corners.cell_scaled_jacobian.end(), column.begin());
      summarize(Kernels::field_metric, column);
    }
  }
  if constexpr (HasProductMetric<Kernels>) {
    if (product_at_hand) {
      constexpr auto product = Kernels::product;
      const auto& a = field.values[static_cast<std::size_t>(product[1])];
      const auto& b = field.values[static_cast<std::size_t>(product[2])];
      std::vector<double> column = new_column();
      for_each_cell(n, [&](std::size_t c) { column[c] = a[c] * b[c]; });
      summarize(product[0], column);
    }
  }
  spare.clear();
  out.summaries[M] = corner_summary(corners.scaled_jacobian, corners.degenerate_mask, kNumCornerValues<K>, sorted);
  return out;
}

#define HQ_INSTANTIATE_SUMMARIZE(K)                                                                               \
  template SummarizedCellBlock summarize_cell_block_metrics<K>(                                                   \
      std::span<const Vec3>, std::span<const std::array<Index, CellKindTable<K>::num_corners>>,                   \
      const BlockCornerValues&, const std::function<bool(std::string_view)>&);
HQ_INSTANTIATE_SUMMARIZE(CellKind::tet)
HQ_INSTANTIATE_SUMMARIZE(CellKind::wedge)
HQ_INSTANTIATE_SUMMARIZE(CellKind::pyramid)
HQ_INSTANTIATE_SUMMARIZE(CellKind::quad)
HQ_INSTANTIATE_SUMMARIZE(CellKind::triangle)
#undef HQ_INSTANTIATE_SUMMARIZE

std::vector<CellMetricSummary> summarize_cell_block(const CellBlockMetricField& field) {
  std::vector<CellMetricSummary> out;
  for (std::size_t m = 0; m < field.names.size(); ++m)
    out.push_back(
        {std::string(field.names[m]), compute_statistics(field.values[m], metric_statistics_options(field.names[m]))});
  std::vector<double> sorted;
  out.push_back(corner_summary(field.corner_scaled_jacobian, field.corner_degenerate_mask, field.corners_per_cell, sorted));
  return out;
}

}  // namespace hq
