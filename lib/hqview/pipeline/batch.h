#pragma once
// `hqview batch`: analyse a collection of meshes (a directory tree or a
// manifest) into one bundle per mesh plus an index (batch_index.h). One mesh
// is one independent job: meshes run in parallel within a memory budget, a
// failing mesh is recorded with its error and the others go on. `--shard I/N`
// takes a stable, path-based part of the collection (ARCHITECTURE.md,
// "Scaling out"); `--resume` keeps a bundle whose input hash and HQView
// version are unchanged. The library never prints: progress goes to a
// BatchProgress sink that main() implements.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/pipeline/analyze.h"

namespace hq {

// One row of the collection.
struct BatchInput {
  std::string path;                      // index key and bundle directory: relative, '/'-separated
  std::filesystem::path mesh_file;       // the file to open
  std::filesystem::path reference_file;  // --reference for this mesh; empty: none
  std::filesystem::path compare_file;    // --compare for this mesh (MESH2); empty: none
  std::string label;                     // method / algorithm, for the per-method comparison
  std::string model;                     // model name (rows of the method comparison); default: file stem
};

// True for the hex mesh extensions read_hex_mesh() knows (.mesh .vtk .vtu
// .msh .ovm .inp .e .exo; any case).
bool is_hex_mesh_extension(const std::filesystem::path& path);

// Every hex mesh file under `dir` (recursive), sorted by relative path;
// hidden entries and HQView outputs (directories with report.json or
// index.json) are skipped.
// Throws InputError when `dir` cannot be listed.
std::vector<BatchInput> collect_directory(const std::filesystem::path& dir);

// A manifest: CSV with a header row naming the columns (mesh, reference,
// compare, label or method, model; only mesh is required), or JSON (an array
// of objects with those keys, or of strings). Relative file names are
// relative to the manifest's directory; rows keep the manifest's order until
// the index sorts them. Throws ParseError (`path:line: what`) on a malformed
// row or a duplicate mesh.
std::vector<BatchInput> read_manifest(const std::filesystem::path& file);
std::vector<BatchInput> parse_manifest(std::string_view text, const std::string& name,
                                       const std::filesystem::path& base_dir, bool is_json);

// A directory or a manifest file (.csv, .json).
std::vector<BatchInput> collect_batch_inputs(const std::filesystem::path& dir_or_manifest);

// "I/N" with 1 <= I <= N; throws UsageError otherwise.
struct Shard {
  int index = 1;
  int count = 1;
};
Shard parse_shard(std::string_view text);

// The shard (1-based) that owns `path`: a hash of the path alone, so the
// partition does not change when other meshes are added or removed.
int shard_of(std::string_view path, int count);
std::vector<BatchInput> select_shard(const std::vector<BatchInput>& inputs, const Shard& shard);

enum class BatchStatus { ok, gate_failed, failed };
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
};
inline constexpr std::size_t kNumHeadlineKeys = std::size(kHeadlineKeys);

// One row of the index.
struct BatchEntry {
  std::string path;
  std::string label;
  std::string model;
  BatchStatus status = BatchStatus::failed;
  std::string error;   // why it failed (status failed)
  std::string bundle;  // bundle directory relative to the batch output; empty when failed
  std::string sha256;  // of the mesh file; empty when unreadable
  std::vector<std::optional<double>> headline = std::vector<std::optional<double>>(kNumHeadlineKeys);
  std::vector<std::string> failed_gates;  // rules
};

// Fills the report-derived fields of `entry` (status ok/gate_failed,
// sha256, headline, failed_gates) from a report.json text.
void fill_entry_from_report(BatchEntry& entry, std::string_view report_json_text);

struct BatchOptions {
  AnalyzeOptions analyze;  // template: mesh_path and reference_path are set per mesh
  std::filesystem::path output;
  int jobs = 1;                     // meshes analysed at once
  std::uint64_t memory_budget = 0;  // bytes for the meshes in flight (estimated); 0: no limit
  bool resume = false;
  bool force = false;  // passed to each bundle (replace a non-bundle directory)
};

// Progress sink (main draws a bar or prints lines). Called from worker
// threads, one call at a time.
class BatchProgress {
 public:
  virtual ~BatchProgress() = default;
  virtual void mesh_started(const BatchInput& /*input*/) {}
  virtual void mesh_finished(const BatchEntry& /*entry*/, bool /*is_resumed*/, double /*seconds*/, int /*done*/,
                             int /*total*/) {}
};

// Estimated peak memory (bytes) of analysing a mesh file of `file_bytes`
// bytes, with or without the rendered views.
std::uint64_t estimate_mesh_memory(std::uint64_t file_bytes, bool is_rendering);

// Analyses every input into options.output / input.path (bundle_path()).
// Never throws for a mesh's failure (it is recorded in its entry); throws
// UsageError when options.output is unusable. Entries sorted by path.
std::vector<BatchEntry> run_batch(const std::vector<BatchInput>& inputs, const BatchOptions& options,
                                  BatchProgress* progress);

// One mesh: analyze + gates + bundle writing, or the kept bundle with
// --resume. `is_resumed` tells which.
BatchEntry run_batch_mesh(const BatchInput& input, const BatchOptions& options, bool& is_resumed);

// 3 if any entry failed, else 1 if any gate failed, else 0 (CONTRACT.md).
int batch_exit_code(const std::vector<BatchEntry>& entries);

}  // namespace hq
