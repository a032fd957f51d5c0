#pragma once
// ReportModel: everything one `analyze` run found, gathered for the writers
// (report.json, CSV, HTML). Plain data; the writers never recompute analysis.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "hqview/boundary/boundary_error.h"
#include "hqview/chart/chart.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/overlap.h"
#include "hqview/quality/hex_metric_field.h"
#include "hqview/quality/quality_field.h"
#include "hqview/quality/statistics.h"
#include "hqview/uv/uv_atlas.h"

namespace hq {

struct InputFile {
  std::string path;    // as given by the user (file name only when absolute)
  std::string format;  // reader's format name
  std::string sha256;  // of the file's bytes, lowercase hex
};

struct MeshSummary {
  Index num_vertices = 0;
  Index num_hexes = 0;
  Index num_unreferenced_vertices = 0;
  Index num_boundary_faces = 0;
  Index num_boundary_vertices = 0;
  Index num_non_manifold_faces = 0;
  Vec3 bbox_min, bbox_max;
  double bbox_diagonal = 0;
  double edge_length_min = 0, edge_length_mean = 0, edge_length_max = 0;
};

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

// One `--gate` rule's outcome (report.json `gates.results`).
struct GateResult {
  std::string rule;
  double value = 0;  // the report value the rule read
  bool passed = true;
};

struct GateSummary {
  bool passed = true;  // every rule passed (true when there are none)
  std::vector<GateResult> results;
};

// What one file of a view shows, for the links between panels in
// index.html (not written to report.json).
struct ViewFileLinks {
  Index cluster = kNoIndex;  // C: its cluster; D, E: the cluster of its vertex (kNoIndex: none)
  Index vertex = kNoIndex;   // D, E: its vertex
  // Chart B: one region per bar, in fractions of the image, key = vertex id.
  std::vector<ChartHotspot> hotspots;
};

struct ViewEntry {
  std::string id;
  std::string title;
  std::vector<std::string> files;    // relative to the bundle root
  std::vector<ViewFileLinks> links;  // one per file, or empty (no links)
};

struct ReportModel {
  std::string tool_version;
  InputFile mesh_input;
  MeshSummary mesh_summary;
  QualitySummary quality;
  std::vector<ViewEntry> views;
  std::vector<std::string> warnings;  // from the readers and the analysis
  GateSummary gates;
  // data/annotated.vtu is part of the bundle (set by whoever writes it):
  // index.html links it only then.
  bool has_annotated_vtu = false;

  // Per-element data the CSV and the views are written from.
  HexMesh mesh;
  Topology topology;
  QualityField field;
  HexMetricField metrics;  // the Verdict metrics per hex (cells.csv columns)

  // With --reference: the reference file, the boundary error and the UV atlas
  // of the reference (as read) for the UV error map.
  std::optional<InputFile> reference_input;
  std::optional<BoundaryError> boundary_error;
  std::optional<UvAtlas> uv_atlas;
  std::optional<TriSurface> reference_surface;  // as read, for the UV error map

  // With --compare MESH2: MESH2 analysed the same way (quality only).
  struct Compared {
    InputFile input;
    MeshSummary mesh_summary;
    QualitySummary quality;
    HexMesh mesh;
    Topology topology;
    QualityField field;
  };
  std::optional<Compared> compare;

  // Vertex glyphs and their clusters (report.json `glyphs`, the glyph_radius
  // and cluster columns of vertices.csv); empty when the stage did not run.
  std::optional<GlyphResult> glyphs;

  // Overlapping vertices and intersecting cells (report.json `overlap`, the
  // coincident_group and intersecting columns); empty with --no-overlap.
  std::optional<OverlapReport> overlap;
};

}  // namespace hq
