#pragma once
// The batch index: one row per mesh (BatchEntry, filled from its report
// document), OUT/index.json (every mesh, sorted by path, no timestamps: a
// sharded-then-merged run gives the same bytes as one run), OUT/index.html
// (a table worst first, sortable in the browser and readable without
// scripts, plus the per-method comparison) and OUT/summary.md.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <optional>

#include "hqview/report/report_json.h"

namespace hq {

// skipped: listed by the collection but not a hex mesh (HexaLab's index
// lists other files too); its error says why. Skipped rows never fail a run.
enum class BatchStatus { ok, gate_failed, failed, skipped };
std::string_view to_string(BatchStatus status);

// The headline values of a bundle's report.json, named by their dotted
// report.json paths (so `diff` gates use the same names on both). nullopt
// where the report has null (e.g. no reference: no boundary error).
inline constexpr const char* kHeadlineKeys[] = {
    "mesh.num_vertices",
    "mesh.num_hexes",
    "quality.scaled_jacobian.min",
    "quality.scaled_jacobian.mean",
    "quality.scaled_jacobian.p05",
    "quality.num_inverted",
    "overlap.num_intersecting_cells",
    "boundary_error.hausdorff.relative",
    "structure.num_singular_edges_interior",
    "structure.num_singular_edges_boundary",
    // The finite-element check (--simulate; null without it).
    "fem.element.num_invalid",
    "fem.element.num_not_invertible",
    "fem.poisson.mean.l2_error",
    "fem.poisson.mean.h1_error",
    "fem.poisson.scaled_matrix.condition",
    // What the mesh is made of (issue 46; null in a report of an earlier HQView).
    "headline.num_cells",
    "headline.num_cells_by_kind.tet",
    "headline.num_cells_by_kind.wedge",
    "headline.num_cells_by_kind.pyramid",
    "headline.hex_fraction",
    "headline.hex_volume_fraction",
};
inline constexpr std::size_t kNumHeadlineKeys = std::size(kHeadlineKeys);
// The index of `key` in kHeadlineKeys; throws Error for a key not there
// (callers name fixed keys).
std::size_t headline_slot(std::string_view key);

// The paper a method comes from (HexaLab's index.json `paper`); empty when
// unknown.
struct PaperInfo {
  std::string title, year, doi;
  bool empty() const { return title.empty() && year.empty() && doi.empty(); }
  bool operator==(const PaperInfo&) const = default;
};

// A mesh's min and mean of one metric (collection_correlation.h); NaN: null.
struct MeshMetricRange {
  std::string metric;
  double min = 0, mean = 0, max = 0;
  bool operator==(const MeshMetricRange&) const = default;
};

// A surface mesh's counts (report.json mesh.dimension "surface"): its
// cells by kind and its irregular vertices (structure), which the batch
// page shows in the cell and singular columns; index.json `surface`.
struct SurfaceCounts {
  double quads = 0, triangles = 0;
  std::optional<double> irregular_interior, irregular_boundary;  // null: not counted
  // report.json mesh.planar: a curved surface's quality.num_inverted counts
  // its reversed faces (orientation flipped against their neighbours), which
  // the status, the #inverted cell and summary.md call so (issue 47 part F).
  bool planar = true;
  bool operator==(const SurfaceCounts&) const = default;
};

// One row of the index.
struct BatchEntry {
  std::string path;
  std::string label;
  std::string model;
  std::string variant;  // several meshes of one model and method (bunny_1, _in/_out): one row each
  PaperInfo paper;
  BatchStatus status = BatchStatus::failed;
  std::string error;   // why it failed (status failed)
  std::string bundle;  // bundle directory relative to the batch output; empty when failed
  std::string sha256;  // of the mesh file; empty when unreadable
  std::vector<std::optional<double>> headline = std::vector<std::optional<double>>(kNumHeadlineKeys);
  std::vector<std::string> failed_gates;  // rules
  std::string thumbnail;  // the bundle's thumbnail view, relative to the bundle; empty: not rendered
  std::string overview;   // the bundle's overview view (the batch lightbox shows it); empty: not rendered
  std::vector<std::string> warnings;  // report.json warnings (input integrity: cells read as another kind ...)
  std::optional<SurfaceCounts> surface;  // a surface mesh's; absent for a volume mesh
  // With a solved finite-element check only (else empty, and absent from
  // index.json): every computed metric's min and mean, for the correlation
  // across the collection (collection_correlation.h).
  std::vector<MeshMetricRange> metrics;
  // Of this run only (not in index.json, so not after merge): every gate's
  // rule, value and outcome (OUT/junit.xml), and whether the failure was
  // the machine's (disk full, permission: batch exit code 5).
  std::vector<GateResult> gates;
  bool environment_failure = false;
};

// Fills the report-derived fields of `entry` (status ok/gate_failed,
// sha256, headline, failed_gates) from a report document.
void fill_entry_from_report(BatchEntry& entry, const ReportDocument& report);

// Per label (method): the paper's "compare mesh generation and optimization
// algorithms" table. Means are over the meshes analysed (not failed).
struct MethodSummary {
  std::string label;
  int num_meshes = 0;
  int num_failed = 0;
  int num_gate_failed = 0;
  int num_with_inverted = 0;  // meshes with at least one inverted hex
  double mean_min_scaled_jacobian = 0;
  double mean_mean_scaled_jacobian = 0;
  double worst_min_scaled_jacobian = 0;
};

// Empty when no entry has a label.
std::vector<MethodSummary> summarize_methods(const std::vector<BatchEntry>& entries);

std::string batch_index_json(const std::vector<BatchEntry>& entries, const std::string& tool_version);
// Throws InputError naming `name` when the text is not an HQView index.json.
std::vector<BatchEntry> parse_batch_index_json(std::string_view text, const std::string& name);
struct ComparisonKey;  // comparison.h
// keys: the comparison's keys (nullptr: default_comparison_keys).
// The order of index.html's mesh table, as indices into `entries`: worst
// first. Key: failed, then gate failed, then ok, then skipped; within a
// status, more failed gates first, then more inverted hexes, then the lower
// min scaled Jacobian (a missing value after every known one); ties by path.
// A total order of the entries' own fields, so a merge of shards gives the
// same page as one run. index.json keeps the path order.
std::vector<std::size_t> worst_first_order(const std::vector<BatchEntry>& entries);
std::string batch_index_html(const std::vector<BatchEntry>& entries, const std::string& tool_version,
                             const std::vector<ComparisonKey>* keys = nullptr);
// What a row shows beyond its run's status (issue 45): "inverted",
// "intersecting", "input warning", comma-separated; empty: none. A warning
// that names a tool limitation (analysis/limitations.h: overlap not checked
// on a surface mesh ...) is no input warning.
std::string batch_findings(const BatchEntry& entry);
// Whether the row's warnings hold a tool limitation (is_limitation_warning).
bool has_limited_analysis(const BatchEntry& entry);
// A row's status in words, the same on index.html and summary.md: "✗ failed",
// "✗ gate failed", "skipped", "ok", or "⚠ " + batch_findings (an "ok" run of a
// broken mesh, or of a mesh read with warnings, is not "ok"); " · limited
// analysis" follows when has_limited_analysis.
std::string batch_status_text(const BatchEntry& entry);
// summary.md: the status column is batch_status_text; every input warning is
// listed under "Problems" with the mesh's path.
std::string batch_summary_markdown(const std::vector<BatchEntry>& entries);

// Writes index.json, index.html and summary.md into `dir`, and with method
// labels comparison.csv, .md and .tex (comparison.h), each through a
// temporary sibling renamed into place. Throws Error on an I/O failure.
void write_batch_index(const std::vector<BatchEntry>& entries, const std::string& tool_version,
                       const std::filesystem::path& dir, const std::vector<ComparisonKey>* keys = nullptr, const std::string& link_base = "");

// OUT/report.html (--single-file), after write_batch_index: OUT/index.html
// with its thumbnails and chart as data URIs (single_file.h); each mesh's
// link goes to its bundle's report.html where that exists, else stays.
void write_batch_single_file(const std::filesystem::path& dir, const std::string& link_base = "");

// Throws ValueError when `dir` exists and is neither empty nor a batch
// output (index.json, or the marker of a batch that has not written its
// index yet: a run killed or stopped midway) and !force.
void check_batch_output_dir(const std::filesystem::path& dir, bool force);

// Creates `dir` and its marker `.hqview-batch` (before any bundle is
// written), so that a run killed before its index can be resumed there.
inline constexpr const char* kBatchMarkerFile = ".hqview-batch";
void mark_batch_output_dir(const std::filesystem::path& dir);

}  // namespace hq
