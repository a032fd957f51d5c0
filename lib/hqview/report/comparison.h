#pragma once
// Methods compared over a dataset: the model x method table a paper prints.
// Built from the batch index's rows (BatchEntry) alone, so a sharded run
// merged by `hqview merge` gives the same files byte for byte.
//
//   OUT/comparison.csv  long form: one row per mesh (model, variant, method,
//                       mesh, status, every headline key);
//   OUT/comparison.md   and OUT/comparison.tex: one table per chosen key,
//                       models as rows, methods as columns (one column per
//                       method and variant: bunny_in and bunny_out of an
//                       optimiser are two cells, never merged), the best
//                       value of a row in bold, then per method the mean and
//                       median of each key and its counts;
//   index.html          the same tables (batch_index.cpp), each cell a link
//                       to its mesh's bundle.
//
// A cell is "–" when the method has no mesh for the row, "failed" when its
// mesh failed, "no ref." when the key needs a reference the mesh was
// analysed without, else the value. Best follows the key's direction; keys
// without one (counts such as #H) have no bold.

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/report/batch_index.h"

namespace hq {

struct ComparisonKey {
  std::string_view key;    // a kHeadlineKeys entry (report.json path), or an index.json surface.* count
  std::string_view title;  // column / table title
  int direction = 0;       // +1: higher is better, -1: lower is better, 0: neither
};

// Every key a comparison can show (the headline keys), with its direction.
const std::vector<ComparisonKey>& comparison_keys();
// The default: #V, #H, min SJ, mean SJ, #inverted, Hausdorff, and the
// singular interior edges when some mesh has them; for surface meshes
// (issue 47) #V, #quads, #triangles (when some mesh has one), min SJ, mean
// SJ, #inverted, Hausdorff and the irregular interior vertices.
std::vector<ComparisonKey> default_comparison_keys(const std::vector<BatchEntry>& entries);
// The value a comparison shows for `key` (comparison_keys()): a headline
// key's, or an index.json surface count; nullopt when the mesh has none.
std::optional<double> comparison_value(const BatchEntry& entry, std::string_view key);
// `--compare-keys a,b,...`: report.json paths of headline keys. Throws
// ValueError naming an unknown key and listing the known ones.
std::vector<ComparisonKey> parse_comparison_keys(std::string_view list);

// A column: one method and variant.
struct ComparisonColumn {
  std::string label, variant;
  std::string year;  // of the method's paper, for the heading
  auto operator<=>(const ComparisonColumn&) const = default;
};

struct ComparisonRow {
  std::string model;
  std::map<std::pair<std::string, std::string>, const BatchEntry*> cells;  // by (label, variant)
};

struct MethodColumn {
  std::string label;
  PaperInfo paper;
  int num_meshes = 0, num_models = 0, num_valid = 0, num_failed = 0;  // valid: min SJ > 0
  // Per chosen key, over the method's analysed meshes: mean and median
  // (nullopt: no value).
  std::vector<std::optional<double>> mean, median;
};

struct Comparison {
  // "" when the batch holds meshes of one dimension; else "volume meshes"
  // or "surface meshes" (comparison_groups).
  std::string group;
  // OUT/comparison_min_sj.svg, or OUT/comparison_min_sj_surface.svg for the
  // surface meshes of a batch that also holds volume meshes.
  std::string chart_file;
  std::vector<const BatchEntry*> entries;  // the group's meshes, in path order (not owned)
  std::vector<ComparisonKey> keys;
  std::vector<MethodColumn> methods;     // sorted by label
  std::vector<ComparisonColumn> columns;  // sorted by label, then variant
  std::vector<ComparisonRow> rows;       // sorted by model
};
// "label (year) · variant".
std::string column_heading(const ComparisonColumn& c);

// True when some analysed or failed row has a method label.
bool has_comparison(const std::vector<BatchEntry>& entries);
Comparison build_comparison(const std::vector<BatchEntry>& entries, std::vector<ComparisonKey> keys);

// Volume and surface meshes are compared apart (issue 47): one Comparison
// per dimension present, volume first, each over its own meshes with
// `keys` (nullptr: each group's default keys). A failed mesh, whose
// dimension is unknown, joins the group of its model's other meshes
// (volume when none has one). The entries must outlive the comparisons.
std::vector<Comparison> comparison_groups(const std::vector<BatchEntry>& entries,
                                          const std::vector<ComparisonKey>* keys);

// What a cell shows, and whether it is the best of its row for keys[k].
struct ComparisonCell {
  std::string text;
  std::optional<double> value;
  bool is_best = false;
  const BatchEntry* entry = nullptr;
};
std::vector<ComparisonCell> comparison_cells(const Comparison& c, const ComparisonRow& row, std::size_t k);

std::string comparison_csv(const std::vector<BatchEntry>& entries);
// OUT/comparison_min_sj.svg: the min scaled Jacobian of every analysed mesh,
// one column per method (method_distribution_chart).
// "Volume meshes", "Surface meshes", or "" (a batch of one dimension).
std::string group_heading(const Comparison& c);

// A group's chart (Comparison::chart_file): its meshes' min SJ by method.
std::string comparison_chart_svg(const Comparison& c);
inline constexpr const char* kComparisonChartFile = "comparison_min_sj.svg";
inline constexpr const char* kComparisonSurfaceChartFile = "comparison_min_sj_surface.svg";
// Every group's tables in one file: under a heading per group when there
// are two.
std::string comparison_markdown(const std::vector<Comparison>& groups);
std::string comparison_latex(const std::vector<Comparison>& groups);

}  // namespace hq
