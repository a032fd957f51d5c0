#pragma once
// report.json `quality`: statistics of the scaled Jacobian (per hex, per
// corner), of vertex quality and of every computed Verdict metric, with the
// worst vertices and cells.

#include <cstdint>
#include <string>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"
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
  Index cell = 0;
  double scaled_jacobian = 0;
};

// A Verdict metric's statistics with its acceptable range.
struct MetricSummary {
  std::string name;
  Statistics stats;
  double acceptable_min = 0, acceptable_max = 0;
  double fraction_acceptable = 0;  // of the non-degenerate cells
};

struct QualitySummary {
  std::int64_t num_inverted = 0;      // cells with scaled Jacobian <= 0
  std::int64_t num_degenerate = 0;    // cells with Verdict's 1e30 scaled Jacobian
  Statistics scaled_jacobian;         // per hex, Verdict
  Statistics corner_scaled_jacobian;  // 8 per hex
  Statistics vertex_quality;          // per referenced vertex
  std::vector<MetricSummary> metrics;
  std::vector<WorstVertex> worst_vertices;
  std::vector<WorstCell> worst_cells;
};

// The scaled Jacobian, corner and vertex quality statistics (histograms of
// 20 bins over [-1, 1]) and the worst_count worst vertices (lowest quality
// first, ties by id, unreferenced ones skipped) and cells (degenerate first,
// then ascending scaled Jacobian, ties by id). `metrics` is left empty:
// summarize_hex_metrics() fills it.
QualitySummary summarize_quality(const HexMesh& mesh, const QualityField& field, int worst_count);

// One MetricSummary per computed metric, in HexMetric order. Verdict's
// sentinels (|v| >= 1e30) are counted in num_degenerate and kept out of
// every other number, fraction_acceptable included (its denominator is the
// non-degenerate count). Histograms: 20 bins over [-1, 1] for
// scaled_jacobian, over [min, max] otherwise.
std::vector<MetricSummary> summarize_hex_metrics(const HexMetricField& field);

}  // namespace hq
