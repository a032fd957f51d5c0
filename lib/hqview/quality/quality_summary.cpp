#include "hqview/quality/quality_summary.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "hqview/quality/corner_jacobian.h"
#include "hqview/quality/pyramid_metrics.h"
#include "hqview/quality/quad_metrics.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/triangle_metrics.h"
#include "hqview/quality/wedge_metrics.h"

namespace hq {
namespace {

StatisticsOptions jacobian_histogram() {
  StatisticsOptions o;
  o.histogram_min = -1.0;
  o.histogram_max = 1.0;
  o.histogram_bins = 20;
  return o;
}

}  // namespace

QualitySummary summarize_quality(const HexMesh& mesh, const QualityField& field, int worst_count,
                                 const KnownQualityStatistics& known) {
  QualitySummary q;
  const auto options = jacobian_histogram();
  // A corner with a zero-length edge is degenerate: counted, kept out of the
  // distribution (its value 0 still reaches vertex quality).
  std::vector<std::uint8_t> corner_flags(known.corner_scaled_jacobian ? 0 : field.corner_scaled_jacobian.size());
  if (!known.corner_scaled_jacobian) {
    for (std::size_t h = 0; h < field.num_hexes; ++h)
      for (int i = 0; i < 8; ++i)
        corner_flags[8 * h + static_cast<std::size_t>(i)] = (field.corner_degenerate_mask[h] >> i) & 1u;
    std::size_t first_cell = field.num_hexes;
    for_each_cell_kind([&](auto kind) {
      if constexpr (kind() != CellKind::hex) {
        constexpr std::size_t C = kCornerValuesPerCell<kind()>;
        const std::size_t n = cell_block<kind()>(mesh).size();
        const std::size_t corner0 = field.corner_begin[static_cast<std::size_t>(kind())];
        for (std::size_t c = 0; c < n; ++c)
          for (std::size_t i = 0; i < C; ++i)
            corner_flags[corner0 + C * c + i] = (field.corner_degenerate_mask[first_cell + c] >> i) & 1u;
        first_cell += n;
      }
    });
  }
  // Three independent sorts (the corners': 8 values per hex) run at once;
  // those `known` gives are copied.
  tbb::parallel_invoke(
      [&] {
        q.scaled_jacobian = known.scaled_jacobian ? *known.scaled_jacobian
                                                  : compute_statistics(field.cell_scaled_jacobian, options);
      },
      [&] {
        q.corner_scaled_jacobian = known.corner_scaled_jacobian
                                       ? *known.corner_scaled_jacobian
                                       : compute_statistics(field.corner_scaled_jacobian, options, corner_flags);
      },
      [&] { q.vertex_quality = compute_statistics(field.vertex_quality, options); });

  // The headline's cell counts (Verdict metrics: summarize_hex_metrics).
  // Hexes by their scaled Jacobian (<= 0, not Verdict's sentinel), every
  // other kind by its own rule (a pyramid's Verdict value is never < 0).
  q.num_degenerate = q.scaled_jacobian.num_degenerate;
  for (std::size_t h = 0; h < field.num_hexes; ++h) {
    const double v = field.cell_scaled_jacobian[h];
    q.num_inverted += v <= 0.0 && !is_verdict_sentinel(v);
  }
  for (CellValidity o : field.non_hex_validity) q.num_inverted += is_inverted(o);

  // Worst vertices: lowest quality first, ties by id; unreferenced ones skipped.
  std::vector<Index> vertices;
  for (std::size_t v = 0; v < field.vertex_quality.size(); ++v)
    if (!std::isnan(field.vertex_quality[v])) vertices.push_back(static_cast<Index>(v));
  const std::size_t nv = std::min<std::size_t>(static_cast<std::size_t>(worst_count), vertices.size());
  std::partial_sort(vertices.begin(), vertices.begin() + static_cast<std::ptrdiff_t>(nv), vertices.end(),
                    [&](Index a, Index b) {
                      const double qa = field.vertex_quality[a], qb = field.vertex_quality[b];
                      return qa != qb ? qa < qb : a < b;
                    });
  for (std::size_t i = 0; i < nv; ++i)
    q.worst_vertices.push_back({vertices[i], field.vertex_quality[vertices[i]], mesh.points[vertices[i]]});

  // Worst cells: degenerate (1e30) cells first, they are the worst of all,
  // then ascending scaled Jacobian, ties by id. An inverted cell of another
  // kind whose Verdict value is not negative (a pyramid's is 0 when
  // inverted) ranks by its lowest corner.
  std::vector<Index> cells(field.cell_scaled_jacobian.size());
  std::iota(cells.begin(), cells.end(), 0);
  auto rank = [&](Index c) -> double {
    const double v = field.cell_scaled_jacobian[c];
    if (v >= kVerdictDegenerate) return -INFINITY;
    const auto cell = static_cast<std::size_t>(c);
    if (cell >= field.num_hexes && is_inverted(field.non_hex_validity[cell - field.num_hexes]) && v >= 0) {
      const CellRef ref = any_cell(mesh, c);
      double lowest = v;
      for_each_cell_kind([&](auto kind) {
        if constexpr (kind() != CellKind::hex) {
          if (kind() != ref.kind) return;
          constexpr std::size_t C = kCornerValuesPerCell<kind()>;
          const double* k = field.corner_scaled_jacobian.data() + field.corner_begin[static_cast<std::size_t>(kind())] +
                            C * ref.index;
          lowest = std::min(lowest, *std::min_element(k, k + C));
        }
      });
      return lowest;
    }
    return v;
  };
  const std::size_t nc = std::min<std::size_t>(static_cast<std::size_t>(worst_count), cells.size());
  std::partial_sort(cells.begin(), cells.begin() + static_cast<std::ptrdiff_t>(nc), cells.end(), [&](Index a, Index b) {
    const double ra = rank(a), rb = rank(b);
    return ra != rb ? ra < rb : a < b;
  });
  for (std::size_t i = 0; i < nc; ++i) {
    const CellRef ref = any_cell(mesh, static_cast<Index>(cells[i]));
    q.worst_cells.push_back({cells[i], field.cell_scaled_jacobian[cells[i]], ref.kind,
                             cell_source_index(mesh, ref.kind, ref.index)});
  }
  return q;
}

KnownQualityStatistics single_kind_statistics(const Mesh& mesh, const QualityField& field,
                                              const std::vector<KindQualitySummary>& by_kind) {
  KnownQualityStatistics known;
  int kinds_with_cells = 0;
  CellKind only = CellKind::hex;
  std::size_t corner_values = 0;
  for_each_cell_kind([&](auto kind) {
    const std::size_t n = cell_block<kind()>(mesh).size();
    if (n == 0) return;
    ++kinds_with_cells;
    only = kind();
    corner_values = kCornerValuesPerCell<kind()> * n;
  });
  if (kinds_with_cells != 1) return known;
  // The kind's corners must be the whole corner array, its cells every cell.
  if (field.corner_begin[static_cast<std::size_t>(only)] != 0 || corner_values != field.corner_scaled_jacobian.size())
    return known;
  const auto summary = std::find_if(by_kind.begin(), by_kind.end(),
                                    [&](const KindQualitySummary& k) { return k.kind == only && k.count > 0; });
  if (summary == by_kind.end()) return known;
  for (const MetricSummary& m : summary->metrics) {
    if (m.name == "corner_scaled_jacobian") known.corner_scaled_jacobian = &m.stats;
    if (m.name == "scaled_jacobian" && only == CellKind::tet &&
        static_cast<std::int64_t>(field.cell_scaled_jacobian.size()) == summary->count)
      known.scaled_jacobian = &m.stats;
  }
  return known;
}

std::vector<MetricSummary> summarize_hex_metrics(const HexMetricField& field) {
  std::vector<HexMetric> computed;
  for (int i = 0; i < kNumHexMetrics; ++i)
    if (contains(field.computed, static_cast<HexMetric>(i))) computed.push_back(static_cast<HexMetric>(i));
  // One task per metric, each summarised sequentially (statistics sort their
  // values): the same numbers for any thread count.
  std::vector<MetricSummary> out(computed.size());
  tbb::parallel_for(std::size_t{0}, computed.size(), [&](std::size_t k) {
    const HexMetric m = computed[k];
    const HexMetricInfo& info = hex_metric_info(m);
    StatisticsOptions options;
    if (m == HexMetric::scaled_jacobian) {
      options.histogram_min = -1.0;
      options.histogram_max = 1.0;
    }
    MetricSummary& s = out[k];
    s.name = std::string(info.name);
    s.stats = compute_statistics(field.of(m), options);
    s.acceptable_min = info.acceptable_min;
    s.acceptable_max = info.acceptable_max;
    std::int64_t inside = 0;
    for (double v : field.of(m))
      if (!is_verdict_sentinel(v) && v >= info.acceptable_min && v <= info.acceptable_max) ++inside;
    s.fraction_acceptable = s.stats.count > 0 ? static_cast<double>(inside) / static_cast<double>(s.stats.count) : 0.0;
  });
  return out;
}

}  // namespace hq

namespace hq {

std::vector<std::string_view> volume_kind_metric_names(CellKind kind) {
  std::vector<std::string_view> names;
  switch (kind) {
    case CellKind::hex:
      for (int m = 0; m < kNumHexMetrics; ++m) names.push_back(hex_metric_info(static_cast<HexMetric>(m)).name);
      break;
    case CellKind::tet:
      for (int m = 0; m < kNumTetMetrics; ++m) names.push_back(tet_metric_info(static_cast<TetMetric>(m)).name);
      break;
    case CellKind::wedge:
      for (int m = 0; m < kNumWedgeMetrics; ++m) names.push_back(wedge_metric_info(static_cast<WedgeMetric>(m)).name);
      break;
    case CellKind::pyramid:
      for (int m = 0; m < kNumPyramidMetrics; ++m)
        names.push_back(pyramid_metric_info(static_cast<PyramidMetric>(m)).name);
      break;
    case CellKind::quad:
      for (int m = 0; m < kNumQuadMetrics; ++m) names.push_back(quad_metric_info(static_cast<QuadMetric>(m)).name);
      break;
    case CellKind::triangle:
      for (int m = 0; m < kNumTriangleMetrics; ++m)
        names.push_back(triangle_metric_info(static_cast<TriangleMetric>(m)).name);
      break;
  }
  names.push_back("corner_scaled_jacobian");
  return names;
}

std::vector<SummarizedCellBlock> summarize_non_hex_blocks(const Mesh& mesh, const QualityField& field,
                                                          const std::function<bool(std::string_view)>& keep) {
  std::vector<SummarizedCellBlock> out;
  std::size_t first_cell = field.num_hexes;
  // The volume kinds of a volume mesh, the surface kinds of a surface mesh
  // (the analysis holds one or the other).
  const bool surface = is_surface_mesh(mesh);
  for_each_block(mesh, [&](auto kind, const auto& cells) {
    if constexpr (kind() != CellKind::hex) {
      if ((CellKindTable<kind()>::dimension == 2) != surface) return;
      const std::size_t n = cells.size();
      if (n > 0) {
        constexpr std::size_t C = kCornerValuesPerCell<kind()>;
        const BlockCornerValues corners{
            std::span<const double>(field.corner_scaled_jacobian).subspan(field.corner_begin[static_cast<std::size_t>(kind())], C * n),
            std::span<const std::uint8_t>(field.corner_degenerate_mask).subspan(first_cell, n),
            std::span<const CellValidity>(field.non_hex_validity).subspan(first_cell - field.num_hexes, n),
            std::span<const double>(field.cell_scaled_jacobian).subspan(first_cell, n)};
        out.push_back(summarize_cell_block_metrics<kind()>(mesh.points, cells, corners, keep));
      }
      first_cell += n;
    }
  });
  return out;
}

std::vector<KindQualitySummary> summarize_by_kind(const Mesh& mesh, const QualityField& field,
                                                  const std::vector<MetricSummary>& hex_metrics,
                                                  const std::vector<SummarizedCellBlock>& blocks) {
  // A volume mesh lists the volume kinds, a surface mesh (no volume cell,
  // some quad or triangle) the surface kinds.
  const bool is_surface = is_surface_mesh(mesh);
  std::vector<KindQualitySummary> out;
  for_each_cell_kind([&](auto kind) {
    if ((CellKindTable<kind()>::dimension == 2) == is_surface) {
      KindQualitySummary& k = out.emplace_back();
      k.kind = kind();
      k.count = static_cast<std::int64_t>(cell_block<kind()>(mesh).size());
      if (k.count == 0) return;
      if constexpr (kind() == CellKind::hex) {
        k.metrics = hex_metrics;
        const std::size_t nh = field.num_hexes;
        std::vector<std::uint8_t> flags(8 * nh);
        for (std::size_t h = 0; h < nh; ++h) {
          for (std::size_t i = 0; i < 8; ++i) flags[8 * h + i] = (field.corner_degenerate_mask[h] >> i) & 1u;
          const double v = field.cell_scaled_jacobian[h];
          k.num_inverted += v <= 0.0 && !is_verdict_sentinel(v);
        }
        StatisticsOptions options;
        options.histogram_min = -1.0;
        options.histogram_max = 1.0;
        MetricSummary& corners = k.metrics.emplace_back();
        corners.name = "corner_scaled_jacobian";
        corners.stats = compute_statistics(std::span<const double>(field.corner_scaled_jacobian).first(8 * nh), options, flags);
      } else {
        const auto block = std::find_if(blocks.begin(), blocks.end(),
                                        [&](const SummarizedCellBlock& b) { return b.field.kind == kind(); });
        if (block == blocks.end()) return;
        k.num_inverted = block->field.num_inverted;
        k.num_flat = block->field.num_flat;
        for (const CellMetricSummary& m : block->summaries) {
          MetricSummary& s = k.metrics.emplace_back();
          s.name = m.name;
          s.stats = m.stats;
        }
      }
    }
  });
  return out;
}

}  // namespace hq
