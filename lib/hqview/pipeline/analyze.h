#pragma once
// The `analyze` pipeline: read -> topology -> quality -> views -> ReportModel.
// The one place that knows the order of the stages. Touches no output file:
// main() hands the result to write_bundle().

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hqview/glyph/glyphs.h"
#include "hqview/io/read_limits.h"
#include "hqview/overlap/overlap.h"
#include "hqview/pipeline/gates.h"
#include "hqview/quality/hex_metrics.h"
#include "hqview/report/bundle_writer.h"
#include "hqview/report/report_model.h"

namespace hq {

struct AnalyzeOptions {
  std::filesystem::path mesh_path;
  std::string mesh_format;  // --format: a name of mesh_format_names(); empty: by extension and content
  std::filesystem::path reference_path;  // --reference SURFACE; empty: no boundary error
  std::filesystem::path compare_path;    // --compare MESH2; empty: no comparison
  std::string tool_version;
  bool render = true;
  int image_width = 1600;
  int image_height = 1200;
  std::vector<std::string> views;  // --views: ids to render (parse_view_list); empty: all
  std::vector<Index> focus_vertices;  // --focus-vertex: more D/E views
  int worst_count = 20;  // entries in worst_vertices / worst_cells
  HexMetricSet metrics = all_hex_metrics();  // Verdict metrics to compute (scaled_jacobian always)
  std::vector<GateRule> gates;  // evaluated on the finished report (throws UsageError for a missing key)
  GlyphOptions glyphs;          // --rmax, --glyph-threshold, --top-clusters
  std::optional<OverlapOptions> overlap = OverlapOptions{};  // --overlap, --coincident-eps; nullopt: --no-overlap
  ReadLimits read_limits;  // --max-memory: checked against each mesh file's size and declared counts
};

struct Analysis {
  ReportModel model;
  std::vector<BundleImage> images;
};

// Throws InputError/ParseError for unreadable or malformed input,
// InvalidMeshError for a mesh that cannot be analysed, RenderError when the
// offscreen context fails.
Analysis analyze(const AnalyzeOptions& options);

// The summary parts, exposed for tests.
MeshSummary summarize_mesh(const HexMesh& mesh, const Topology& topo);
QualitySummary summarize_quality(const HexMesh& mesh, const QualityField& field, int worst_count);

}  // namespace hq
