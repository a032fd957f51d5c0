#pragma once
// `hqview diff BASELINE CURRENT`: two report.json or two batch index.json.
// Per-key numeric differences, new and vanished meshes, and gates that may
// compare to the baseline (`quality.scaled_jacobian.min>=baseline-0.01`),
// for nightly regression checks and pull-request comments.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/report/compare_table.h"
#include "hqview/report/junit.h"

#include "hqview/pipeline/gates.h"

namespace hq {

// A gate of `diff`: PATH OP NUMBER, or PATH OP baseline[(+|-)NUMBER].
struct DiffGate {
  GateRule rule;             // path and op; threshold is the offset when is_relative
  bool is_relative = false;  // the threshold is the baseline's value + rule.threshold
};
// Throws ValueError naming the rule.
DiffGate parse_diff_gate(std::string_view text);

struct DiffValue {
  std::string mesh;  // empty for two report.json
  std::string key;   // dotted report.json path
  std::optional<double> baseline;
  std::optional<double> current;
};

struct DiffGateResult {
  std::string mesh;
  std::string rule;
  std::optional<double> value;     // current; nullopt: the mesh failed in CURRENT
  std::optional<double> baseline;  // for relative rules
  double threshold = 0;
  bool passed = false;
};

struct DiffStatusChange {
  std::string mesh;
  std::string baseline;
  std::string current;
};

// Two index.json with methods: a cell of the model x method comparison
// (comparison.h) whose value moved, better or worse by the key's direction.
struct DiffCellChange {
  std::string model, method, variant, key;
  double baseline = 0, current = 0;
  bool is_better = false;
};

// Two report.json: a mesh's headline numbers side by side, baseline and
// current, as index.html's Comparison table shows --compare (compare_table.h;
// difference = current - baseline, is_worse: current is worse).
struct DiffSideBySide {
  std::string what;                          // "mesh", or "compared mesh (--compare)"
  std::string baseline_name, current_name;  // the meshes' file names (not escaped)
  std::vector<CompareTableRow> rows;
  MeshCells cells = MeshCells::hex;  // the cells the rows' numbers run over (their words)
};

struct DiffResult {
  bool is_index = false;
  // Two report.json: MESH's numbers; when both carry a compare block, also
  // MESH2's (the second mesh of each run). Empty for two index.json.
  std::vector<DiffSideBySide> side_by_side;
  std::vector<DiffCellChange> cells;  // index.json with methods: comparison cells that got better or worse
  std::vector<DiffValue> changed;  // keys whose value differs (a number against null counts)
  // Keys that exist on one side only (an earlier or a later HQView wrote the
  // other report): the numbers of `current` whose key BASELINE lacks
  // altogether (baseline nullopt), and the numbers of BASELINE whose key
  // CURRENT lacks (current nullopt); a key present but null is in `changed`.
  std::vector<DiffValue> added;
  std::vector<DiffValue> removed;
  std::vector<std::string> new_meshes;
  std::vector<std::string> vanished_meshes;
  std::vector<DiffStatusChange> status_changes;
  std::vector<DiffGateResult> gates;
  bool passed = true;  // every gate held
};

// Gates on two index.json may also name a method's numbers, checked per
// method of CURRENT: `method.num_meshes`, `method.num_models`,
// `method.num_valid` (min SJ > 0), `method.num_failed`, `method.mean.KEY`,
// `method.median.KEY` (KEY a headline key), e.g. `method.num_valid>=baseline`.
// `baseline_text`/`current_text` are both report.json or both index.json
// (told apart by content); the directories are where each file lives, used
// to read a mesh's report.json for a gate key that is not in the index's
// headline. Throws InputError for unreadable/mismatched files, ValueError for
// a gate whose key no compared report has.
DiffResult diff_reports(std::string_view baseline_text, std::string_view current_text,
                        const std::vector<DiffGate>& gates, const std::filesystem::path& baseline_dir,
                        const std::filesystem::path& current_dir);

// `diff --markdown FILE`: a pull-request comment or job summary. Its first
// line is kDiffMarkdownMarker (an HTML comment: hidden when rendered, found
// by a bot that updates its comment). At most max_chars bytes (so at most
// that many characters; GitHub takes 65,536 in a comment or a step summary):
// over it, whole table rows are left out, passed gates first, then
// improvements, then the smallest changes (|current - baseline| relative to
// the larger magnitude); failed gates, meshes that failed or vanished and the
// largest regressions stay; a last line says how many rows were left out.
// The kept rows keep their order. max_chars must be at least
// kDiffMarkdownMinChars (the header and the note).
inline constexpr std::string_view kDiffMarkdownMarker = "<!-- hqview diff -->";
inline constexpr std::size_t kDiffMarkdownMaxChars = 60000;
inline constexpr std::size_t kDiffMarkdownMinChars = 1000;
std::string diff_markdown(const DiffResult& diff, std::size_t max_chars = kDiffMarkdownMaxChars);
std::string diff_text(const DiffResult& diff);

// `diff --junit FILE`: one test case per gate (per mesh of two indexes):
// "RULE" or "MESH: RULE", a failure with the value, the threshold and the
// baseline value.
std::vector<JunitCase> diff_junit_cases(const DiffResult& diff);

}  // namespace hq
