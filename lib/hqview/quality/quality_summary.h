#pragma once
// report.json `quality`: statistics of the scaled Jacobian (per hex, per
// corner), of vertex quality and of every computed Verdict metric, with the
// worst vertices and cells.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/quality/cell_metric_field.h"
#include "hqview/quality/hex_metric_field.h"
#include "hqview/quality/quality_field.h"
#include "hqview/quality/statistics.h"

namespace hq {

struct WorstVertex {
  Index vertex = 0;
  double quality = 0;
  Vec3 position;
};

struct WorstCell {
  Index cell = 0;  // cell id over every volume kind (hexes first)
  double scaled_jacobian = 0;  // Verdict's, of its kind
  CellKind kind = CellKind::hex;
  std::int64_t source_index = 0;  // where it is in its file (mesh.h)
};

// A Verdict metric's statistics with its acceptable range.
struct MetricSummary {
  std::string name;
  Statistics stats;
  double acceptable_min = 0, acceptable_max = 0;
  double fraction_acceptable = 0;  // of the non-degenerate cells
};

// report.json quality.by_kind.<kind>: one volume kind's cells.
struct KindQualitySummary {
  CellKind kind = CellKind::hex;
  std::int64_t count = 0;
  std::int64_t num_inverted = 0;  // by the kind's rule (QualitySummary::num_inverted)
  std::int64_t num_flat = 0;      // non-hex kinds: no corner determinant < 0, one = 0
  // Every Verdict metric of the kind, in its table's order (hex:
  // HexMetric order, those computed), then "corner_scaled_jacobian".
  std::vector<MetricSummary> metrics;
};

struct QualitySummary {
  // Over every volume cell: hexes with scaled Jacobian <= 0 (not degenerate),
  // other kinds inverted by their kind's rule (cell_corner_jacobian.h).
  std::int64_t num_inverted = 0;
  std::int64_t num_degenerate = 0;    // cells with Verdict's 1e30 scaled Jacobian
  Statistics scaled_jacobian;         // per cell, Verdict's of its kind
  Statistics corner_scaled_jacobian;  // every corner value (8 per hex, 4 per tet, 6 per wedge, 4 per pyramid)
  Statistics vertex_quality;          // per referenced vertex
  std::vector<MetricSummary> metrics;  // the hexes' Verdict metrics
  // hex, tet, wedge, pyramid in CellKind order (summarize_by_kind); empty
  // until filled.
  std::vector<KindQualitySummary> by_kind;
  std::vector<WorstVertex> worst_vertices;
  std::vector<WorstCell> worst_cells;
};

// Whole-mesh statistics already computed over the very same values, options
// and degenerate flags (single_kind_statistics): summarize_quality copies
// them instead of sorting those values again. Null: computed.
struct KnownQualityStatistics {
  const Statistics* scaled_jacobian = nullptr;
  const Statistics* corner_scaled_jacobian = nullptr;
};

// The scaled Jacobian, corner and vertex quality statistics (histograms of
// 20 bins over [-1, 1]) and the worst_count worst vertices (lowest quality
// first, ties by id, unreferenced ones skipped) and cells (degenerate first,
// then ascending scaled Jacobian, ties by id). `metrics` is left empty:
// summarize_hex_metrics() fills it. `known`: statistics taken as given.
QualitySummary summarize_quality(const HexMesh& mesh, const QualityField& field, int worst_count,
                                 const KnownQualityStatistics& known = {});

// What a mesh whose cells are all of one kind shares between `by_kind`
// (summarize_by_kind) and summarize_quality: that kind's
// corner_scaled_jacobian statistics (the same corner values, flags and
// [-1, 1] histogram: the kind's corners are all of the field's), and its
// scaled_jacobian statistics when its column is the quality field's own
// (tets: summarize_cell_block_metrics copies it). Null pointers for a mesh of
// several kinds. Points into `by_kind`.
KnownQualityStatistics single_kind_statistics(const Mesh& mesh, const QualityField& field,
                                              const std::vector<KindQualitySummary>& by_kind);

// One MetricSummary per computed metric, in HexMetric order. Verdict's
// sentinels (|v| >= 1e30) are counted in num_degenerate and kept out of
// every other number, fraction_acceptable included (its denominator is the
// non-degenerate count). Histograms: 20 bins over [-1, 1] for
// scaled_jacobian, over [min, max] otherwise.
std::vector<MetricSummary> summarize_hex_metrics(const HexMetricField& field);

// The names of every Verdict metric of a volume kind in its table's order,
// then "corner_scaled_jacobian" (the keys of quality.by_kind.<kind>.metrics).
std::vector<std::string_view> volume_kind_metric_names(CellKind kind);

// The Verdict metrics of every non-hex block present of the mesh's
// dimension (a volume mesh's tets, wedges, pyramids; a surface mesh's quads
// and triangles; in CellKind order), computed and summarised one metric at
// a time (summarize_cell_block_metrics), the corner summaries and inverted
// counts from `field`'s slice of each block (a surface cell's: against the
// plane of a planar mesh, else by orientation against its neighbours);
// each block keeps the values of the metrics `keep` accepts.
std::vector<SummarizedCellBlock> summarize_non_hex_blocks(const Mesh& mesh, const QualityField& field,
                                                          const std::function<bool(std::string_view)>& keep);

// by_kind: the hexes from `hex_metrics` (summarize_hex_metrics) and the
// corner values of `field`, every other kind from its block's summaries
// (summarize_non_hex_blocks); a volume mesh lists the volume kinds, a surface
// mesh the surface kinds; a kind without cells has count 0 and no metrics.
std::vector<KindQualitySummary> summarize_by_kind(const Mesh& mesh, const QualityField& field,
                                                  const std::vector<MetricSummary>& hex_metrics,
                                                  const std::vector<SummarizedCellBlock>& blocks);

}  // namespace hq
