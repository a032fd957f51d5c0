#pragma once
// Quality gates (`--gate RULE`, CONTRACT.md): pass/fail rules on any numeric
// value of report.json, named by its dotted path, for nightly regression and
// pull-request checks.
//
// Grammar:  RULE := PATH OP NUMBER
//           PATH := KEY ("." KEY)*     KEY: [A-Za-z0-9_]+; a number indexes an array
//           OP   := "<=" | ">=" | "==" | "!=" | "<" | ">"
// e.g. `quality.scaled_jacobian.min>=0.2`, `quality.num_inverted==0`,
// `quality.metrics.skew.p95<=0.5`, `quality.worst_cells.0.scaled_jacobian>0`.
// Spaces around the operator are allowed. `hqview diff` will add operands
// relative to a baseline (`>=baseline-0.01`); `analyze` rejects them.

#include <string>
#include <string_view>
#include <vector>

#include "hqview/report/report_json.h"

namespace hq {

enum class GateOp { less_equal, greater_equal, equal, not_equal, less, greater };

struct GateRule {
  std::string text;               // as the user wrote it, trimmed
  std::vector<std::string> path;  // the dotted path's keys
  GateOp op = GateOp::less_equal;
  double threshold = 0;
};

// Parses one rule. Throws ValueError naming the rule and what is wrong.
GateRule parse_gate_rule(std::string_view text);

// Evaluates `rules` in order against a report document. Throws ValueError
// when a rule's path names no key of the report, or a value that is not a
// number (null, text, object): such a rule can never pass, it is a mistake.
GateSummary evaluate_gates(const std::vector<GateRule>& rules, const ReportDocument& report);

// True when `value OP threshold` holds.
bool gate_holds(double value, GateOp op, double threshold);

}  // namespace hq
