#pragma once
// The `analyze` pipeline: read -> [read compare mesh] -> topology -> [read reference, the UV atlas
// started on its own thread] -> quality -> overlap (and beside it the
// structure) -> metrics -> summaries -> [fem elements -> fem poisson] -> glyphs -> boundary error -> compare mesh ->
// views (the UV error map waits for the atlas) -> report document -> gates. The one place that knows the order of the
// stages. Touches no output file: the caller hands the result to write_bundle(). When a stage fails while the atlas is
// being built, the error is reported once the atlas thread has ended (it
// stops at once on a signal or a --mesh-timeout, else runs to its end).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hqview/analysis/analysis.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/io/read_limits.h"
#include "hqview/overlap/overlap.h"
#include "hqview/pipeline/gates.h"
#include "hqview/report/data_files.h"
#include "hqview/quality/hex_metrics.h"
#include "hqview/render/renderer.h"
#include "hqview/report/bundle_writer.h"
#include "hqview/report/report_json.h"
#include "hqview/report/report_model.h"
#include "hqview/views/views.h"

namespace hq {

struct AnalyzeOptions {
  std::filesystem::path mesh_path;
  std::string mesh_format;               // a name of mesh_format_names(); empty: by extension and content
  std::filesystem::path reference_path;  // empty: no boundary error
  std::filesystem::path compare_path;    // empty: no comparison
  CompareAlign compare_align = CompareAlign::auto_;  // --compare-align
  CompareAlign reference_align = CompareAlign::none; // --reference-align (none, bbox or auto)
  BoundaryOptions boundary;                          // --boundary-tolerance (sampling_tolerance)
  std::string tool_version;
  ViewOptions views;                         // size, views to draw, focus vertices, up axis
  bool up_auto = false;                      // --up auto: views.up is chosen per mesh (choose_resting_up)
  DataFormats data;                          // --data: the per-cell and per-vertex data files
  bool viewer = true;                        // viewer.html when views are drawn (--no-viewer: false)
  double viewer_max_mb = 25;                 // --viewer-max-mb
  int worst_count = 20;                      // entries in worst_vertices / worst_cells
  HexMetricSet metrics = all_hex_metrics();  // Verdict metrics to compute (scaled_jacobian always)
  bool fem_elements = false;                 // the Q1 element conditioning (fem_element in --metrics; --simulate)
  bool simulate = false;                     // --simulate: the Poisson check (implies fem_elements)
  std::vector<GateRule> gates;               // evaluated on the finished report document
  GlyphOptions glyphs;
  std::optional<OverlapOptions> overlap = OverlapOptions{};  // nullopt: no overlap stage
  ReadLimits read_limits;  // checked against each mesh file's size and declared counts
  StageSink on_stage;      // called as each stage ends (--verbose); may be empty
};

struct AnalyzeResult {
  ReportModel model;
  ReportDocument document;  // report.json, gates included
  std::vector<BundleImage> images;
};

// Every stage but the views: what `analyze` computes before it draws.
// Throws InputError/ParseError for unreadable or malformed input,
// InvalidMeshError for a mesh that cannot be analysed.
Analysis analyze_mesh(const AnalyzeOptions& options);

// analyze_mesh(), then every view drawn with `renderer` (nullptr: no views),
// the report document and the gates. Throws as analyze_mesh(), RenderError
// when drawing fails, ValueError for a focus vertex that does not exist or a
// gate rule whose key the report lacks.
AnalyzeResult analyze(const AnalyzeOptions& options, Renderer* renderer);

}  // namespace hq
