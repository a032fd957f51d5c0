#pragma once
// The side-by-side table of --compare: both meshes' headline numbers and
// their differences (MESH2 - MESH), for index.html and summary.md (the same
// rows as report.json compare.headline and compare.differences, plus a few
// mesh and quality numbers). Display text only: report.json keeps the values.

#include <string>
#include <vector>

#include "hqview/analysis/analysis.h"

namespace hq {

struct CompareTableRow {
  std::string label;       // "min scaled Jacobian"
  std::string mine;        // MESH's value, display text
  std::string theirs;      // MESH2's value
  std::string difference;  // MESH2 - MESH, signed ("+8,496", "-0.178"); "0" when equal, "–" when undefined
  bool is_worse = false;   // MESH2 is worse on a key where lower (or higher) is better
};

struct CompareTable {
  std::string mine_name, theirs_name;  // file names (not escaped)
  std::vector<CompareTableRow> rows;
  std::string alignment;  // how the compare view places MESH2 ("" when as read)
};

// Precondition: analysis.compare holds a value.
CompareTable compare_table(const Analysis& analysis);

}  // namespace hq
