#pragma once
// The batch index: OUT/index.json (every mesh, sorted by path, no timestamps:
// a sharded-then-merged run gives the same bytes as one run), OUT/index.html
// (a table sortable in the browser and readable without scripts, plus the
// per-method comparison) and OUT/summary.md. Also `hqview merge`.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/pipeline/batch.h"

namespace hq {

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
std::string batch_index_html(const std::vector<BatchEntry>& entries, const std::string& tool_version);
std::string batch_summary_markdown(const std::vector<BatchEntry>& entries);

// Writes index.json, index.html and summary.md into `dir`, each through a
// temporary sibling renamed into place. Throws Error on an I/O failure.
void write_batch_index(const std::vector<BatchEntry>& entries, const std::string& tool_version,
                       const std::filesystem::path& dir);

// Throws UsageError when `dir` exists and is neither empty nor a batch
// output (index.json) and !force.
void check_batch_output_dir(const std::filesystem::path& dir, bool force);

// `hqview merge`: copies every shard's bundles into `out` and returns the
// union of their index entries, sorted by path. Throws InputError for a
// shard without index.json or a mesh present in two shards.
std::vector<BatchEntry> merge_shards(const std::vector<std::filesystem::path>& shard_dirs,
                                     const std::filesystem::path& out);

}  // namespace hq
