#include "hqview/pipeline/gates.h"

#include <limits>

#include <algorithm>
#include <charconv>
#include <cmath>
#include "hqview/core/error.h"
#include "hqview/core/text.h"
#include "hqview/report/json_path.h"

namespace hq {
namespace {

bool is_key_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

[[noreturn]] void bad_rule(std::string_view rule, const std::string& what) {
  throw ValueError("--gate '" + std::string(rule) + "': " + what +
                   " (expected PATH OP NUMBER, e.g. quality.scaled_jacobian.min>=0.2; OP is one of <= >= == != < >)");
}

std::vector<std::string> parse_path(std::string_view rule, std::string_view path) {
  if (path.empty()) bad_rule(rule, "no report.json key before the operator");
  std::vector<std::string> keys;
  std::size_t start = 0;
  while (true) {
    const auto dot = path.find('.', start);
    const std::string_view key =
        path.substr(start, dot == std::string_view::npos ? std::string_view::npos : dot - start);
    if (key.empty()) bad_rule(rule, "empty key in '" + std::string(path) + "'");
    for (char c : key)
      if (!is_key_char(c))
        bad_rule(rule, "unexpected character '" + std::string(1, c) + "' in '" + std::string(path) + "'");
    keys.emplace_back(key);
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  return keys;
}

// The right-hand side. Only numbers for now; `diff` will add baseline-relative
// operands here.
double parse_operand(std::string_view rule, std::string_view operand) {
  if (operand.rfind("baseline", 0) == 0)
    throw ValueError("--gate '" + std::string(rule) + "': comparisons with a baseline belong to `hqview diff`; " +
                     "`analyze` compares with numbers");
  std::string_view digits = operand;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value))
    bad_rule(rule, "'" + std::string(operand) + "' is not a number");
  return value;
}

std::string joined(const std::vector<std::string>& keys, std::size_t count) {
  std::string s;
  for (std::size_t i = 0; i < count; ++i) s += (i ? "." : "") + keys[i];
  return s;
}

// The keys available under `node`, sorted, for the error message.
std::string available_keys(const ReportDocument& node) {
  if (node.is_array())
    return "an array of " + std::to_string(node.size()) + ", index it with 0.." + std::to_string(node.size() - 1);
  if (!node.is_object()) return "a value with no keys";
  std::vector<std::string> keys;
  for (const auto& item : node.items()) keys.push_back(item.key());
  std::sort(keys.begin(), keys.end());
  std::string list;
  int shown = 0;
  for (const std::string& key : keys) {
    if (shown++ == 24) {
      list += ", ...";
      break;
    }
    list += (list.empty() ? "" : ", ") + key;
  }
  return "keys: " + list;
}

// A null under quality.by_kind.<kind> of a kind with no cell: the note a
// passing rule carries, else empty.
std::string absent_kind_note(const GateRule& rule, const ReportDocument& report) {
  if (rule.path.size() < 3 || rule.path[0] != "quality" || rule.path[1] != "by_kind") return {};
  const std::vector<std::string> count_path = {"quality", "by_kind", rule.path[2], "count"};
  const ReportDocument* count = find_json_path(report, std::span<const std::string>(count_path));
  if (count == nullptr || !count->is_number() || count->get<double>() != 0) return {};
  return "no " + rule.path[2] + " in the mesh";
}

// The value a rule reads; NaN with `note` set for a null of an absent kind.
double lookup(const GateRule& rule, const ReportDocument& report, std::string& note) {
  std::size_t depth = 0;
  const ReportDocument* node = find_json_path(report, std::span<const std::string>(rule.path), &depth);
  if (node == nullptr) {
    const std::vector<std::string> found(rule.path.begin(), rule.path.begin() + static_cast<std::ptrdiff_t>(depth));
    const ReportDocument* parent = find_json_path(report, std::span<const std::string>(found));
    // Under a null of an absent kind (quality.by_kind.pyramid.metrics.shape is
    // null, so its .min is not there): no value, with the note.
    if (parent != nullptr && parent->is_null()) {
      note = absent_kind_note(rule, report);
      if (!note.empty()) return std::numeric_limits<double>::quiet_NaN();
    }
    const std::string where = depth == 0 ? "report.json" : "'" + joined(rule.path, depth) + "'";
    const bool metric = depth == 2 && rule.path[0] == "quality" && rule.path[1] == "metrics";
    throw ValueError("--gate '" + rule.text + "': report.json has no '" + rule.path[depth] + "' under " + where + " (" +
                     available_keys(*parent) + ")" + (metric ? "; was it left out by --metrics?" : ""));
  }
  if (node->is_number()) return node->get<double>();
  if (node->is_null()) {
    note = absent_kind_note(rule, report);
    if (!note.empty()) return std::numeric_limits<double>::quiet_NaN();
  }
  const std::string type = node->type_name();
  const std::string what =
      node->is_null() ? "null (not computed for this input)" : (type[0] == 'a' || type[0] == 'o' ? "an " : "a ") + type;
  throw ValueError("--gate '" + rule.text + "': '" + joined(rule.path, rule.path.size()) + "' is " + what +
                   ", not a number");
}

}  // namespace

GateRule parse_gate_rule(std::string_view text) {
  const std::string_view rule = trim(text, " \t");
  const auto op_at = rule.find_first_of("<>=!");
  if (op_at == std::string_view::npos) bad_rule(rule, "no comparison operator");
  GateRule g;
  g.text = std::string(rule);
  g.path = parse_path(rule, trim(rule.substr(0, op_at), " \t"));
  std::size_t op_end = op_at;
  while (op_end < rule.size() && std::string_view("<>=!").find(rule[op_end]) != std::string_view::npos) ++op_end;
  const std::string_view op = rule.substr(op_at, op_end - op_at);
  if (op == "<=")
    g.op = GateOp::less_equal;
  else if (op == ">=")
    g.op = GateOp::greater_equal;
  else if (op == "==")
    g.op = GateOp::equal;
  else if (op == "!=")
    g.op = GateOp::not_equal;
  else if (op == "<")
    g.op = GateOp::less;
  else if (op == ">")
    g.op = GateOp::greater;
  else
    bad_rule(rule, "'" + std::string(op) + "' is not an operator");
  g.threshold = parse_operand(rule, trim(rule.substr(op_end), " \t"));
  return g;
}

bool gate_holds(double value, GateOp op, double threshold) {
  switch (op) {
    case GateOp::less_equal:
      return value <= threshold;
    case GateOp::greater_equal:
      return value >= threshold;
    case GateOp::equal:
      return value == threshold;
    case GateOp::not_equal:
      return value != threshold;
    case GateOp::less:
      return value < threshold;
    case GateOp::greater:
      return value > threshold;
  }
  return false;
}

GateSummary evaluate_gates(const std::vector<GateRule>& rules, const ReportDocument& report) {
  GateSummary summary;
  for (const GateRule& rule : rules) {
    std::string note;
    const double value = lookup(rule, report, note);
    // A rule on a kind the mesh has none of holds vacuously (every one of
    // its cells satisfies it): it passes, with a note.
    const bool passed = note.empty() ? gate_holds(value, rule.op, rule.threshold) : true;
    summary.results.push_back({rule.text, value, passed, std::move(note)});
    summary.passed = summary.passed && passed;
  }
  return summary;
}

}  // namespace hq
