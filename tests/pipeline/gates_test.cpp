// `--gate` rules: the grammar, its error messages, and evaluation against a
// report.json text.

#include "hqview/pipeline/gates.h"

#include <gtest/gtest.h>

#include "hqview/core/error.h"

namespace hq {
namespace HQ_TEST_UNIT {

// Expects a ValueError whose text contains `part`.
#define EXPECT_VALUE_ERROR(statement, part)                                     \
  try {                                                                         \
    statement;                                                                  \
    ADD_FAILURE() << "no ValueError from " #statement;                          \
  } catch (const ValueError& e) {                                               \
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what(); \
  }

TEST(GateRule, ParsesPathOperatorAndNumber) {
  const GateRule r = parse_gate_rule("quality.scaled_jacobian.min>=0.2");
  EXPECT_EQ(r.text, "quality.scaled_jacobian.min>=0.2");
  EXPECT_EQ(r.path, (std::vector<std::string>{"quality", "scaled_jacobian", "min"}));
  EXPECT_EQ(r.op, GateOp::greater_equal);
  EXPECT_EQ(r.threshold, 0.2);
}

TEST(GateRule, EveryOperatorSpacesSignsAndExponents) {
  struct Case {
    const char* text;
    GateOp op;
    double threshold;
  };
  for (const Case& c : {Case{"a<=1", GateOp::less_equal, 1}, Case{"a >= -2.5", GateOp::greater_equal, -2.5},
                        Case{"a==0", GateOp::equal, 0}, Case{"a != +3", GateOp::not_equal, 3},
                        Case{" a<1e-3 ", GateOp::less, 1e-3}, Case{"a>4E2", GateOp::greater, 400}}) {
    const GateRule r = parse_gate_rule(c.text);
    EXPECT_EQ(r.path, std::vector<std::string>{"a"}) << c.text;
    EXPECT_EQ(r.op, c.op) << c.text;
    EXPECT_EQ(r.threshold, c.threshold) << c.text;
  }
  EXPECT_EQ(parse_gate_rule("quality.worst_cells.0.scaled_jacobian>0").path[2], "0");
}

TEST(GateRule, MalformedRulesAreValueErrors) {
  EXPECT_VALUE_ERROR(parse_gate_rule("quality.num_inverted"), "no comparison operator");
  EXPECT_VALUE_ERROR(parse_gate_rule(">=1"), "no report.json key");
  EXPECT_VALUE_ERROR(parse_gate_rule("a=1"), "'=' is not an operator");
  EXPECT_VALUE_ERROR(parse_gate_rule("a=>1"), "'=>' is not an operator");
  EXPECT_VALUE_ERROR(parse_gate_rule("a<>1"), "'<>' is not an operator");
  EXPECT_VALUE_ERROR(parse_gate_rule("a>=abc"), "'abc' is not a number");
  EXPECT_VALUE_ERROR(parse_gate_rule("a>="), "'' is not a number");
  EXPECT_VALUE_ERROR(parse_gate_rule("a>=1.5x"), "is not a number");
  EXPECT_VALUE_ERROR(parse_gate_rule("a>=inf"), "is not a number");
  EXPECT_VALUE_ERROR(parse_gate_rule("a..b>=1"), "empty key");
  EXPECT_VALUE_ERROR(parse_gate_rule("a-b>=1"), "unexpected character '-'");
  EXPECT_VALUE_ERROR(parse_gate_rule("quality.scaled_jacobian.min>=baseline-0.01"), "hqview diff");
}

TEST(GateRule, Comparisons) {
  EXPECT_TRUE(gate_holds(0.2, GateOp::greater_equal, 0.2));
  EXPECT_FALSE(gate_holds(0.2, GateOp::greater, 0.2));
  EXPECT_TRUE(gate_holds(0.1, GateOp::less, 0.2));
  EXPECT_TRUE(gate_holds(0.2, GateOp::less_equal, 0.2));
  EXPECT_TRUE(gate_holds(0, GateOp::equal, 0));
  EXPECT_TRUE(gate_holds(1, GateOp::not_equal, 0));
}

const char* kReport = R"({
  "schema_version": 1,
  "quality": {
    "num_inverted": 3,
    "scaled_jacobian": {"min": -0.25, "mean": 0.8},
    "metrics": {"skew": {"p95": 0.4}},
    "worst_cells": [{"cell": 7, "scaled_jacobian": -0.25}, {"cell": 2, "scaled_jacobian": 0.1}]
  },
  "glyphs": null,
  "tool": {"name": "hqview"}
})";

const ReportDocument& report() {
  static const ReportDocument document = ReportDocument::parse(kReport);
  return document;
}

TEST(Gates, EvaluatesEveryRuleInOrder) {
  const std::vector<GateRule> rules = {
      parse_gate_rule("quality.scaled_jacobian.min>=0.2"), parse_gate_rule("quality.metrics.skew.p95<=0.5"),
      parse_gate_rule("quality.num_inverted==0"), parse_gate_rule("quality.worst_cells.1.scaled_jacobian>0")};
  const GateSummary s = evaluate_gates(rules, report());
  EXPECT_FALSE(s.passed);
  ASSERT_EQ(s.results.size(), 4u);
  EXPECT_EQ(s.results[0].rule, "quality.scaled_jacobian.min>=0.2");
  EXPECT_EQ(s.results[0].value, -0.25);
  EXPECT_FALSE(s.results[0].passed);
  EXPECT_TRUE(s.results[1].passed);
  EXPECT_EQ(s.results[2].value, 3);
  EXPECT_FALSE(s.results[2].passed);
  EXPECT_EQ(s.results[3].value, 0.1);
  EXPECT_TRUE(s.results[3].passed);
}

TEST(Gates, AllPassingAndNoRules) {
  EXPECT_TRUE(evaluate_gates({parse_gate_rule("quality.scaled_jacobian.mean>0.5")}, report()).passed);
  const GateSummary none = evaluate_gates({}, ReportDocument());
  EXPECT_TRUE(none.passed);
  EXPECT_TRUE(none.results.empty());
}

TEST(Gates, MissingOrNonNumericKeysAreValueErrors) {
  EXPECT_VALUE_ERROR(evaluate_gates({parse_gate_rule("quality.scaled_jacobian.mn>=0.2")}, report()),
                     "no 'mn' under 'quality.scaled_jacobian' (keys: mean, min)");
  EXPECT_VALUE_ERROR(evaluate_gates({parse_gate_rule("qualty.num_inverted==0")}, report()),
                     "no 'qualty' under report.json");
  EXPECT_VALUE_ERROR(evaluate_gates({parse_gate_rule("quality.metrics.oddy.max<1")}, report()), "--metrics");
  EXPECT_VALUE_ERROR(evaluate_gates({parse_gate_rule("quality.worst_cells.2.cell==0")}, report()),
                     "index it with 0..1");
  EXPECT_VALUE_ERROR(evaluate_gates({parse_gate_rule("quality.worst_cells.x.cell==0")}, report()), "no 'x'");
  EXPECT_VALUE_ERROR(evaluate_gates({parse_gate_rule("glyphs.num_glyphs==0")}, report()),
                     "no 'num_glyphs' under 'glyphs'");
  EXPECT_VALUE_ERROR(evaluate_gates({parse_gate_rule("tool.name==1")}, report()), "is a string, not a number");
  EXPECT_VALUE_ERROR(evaluate_gates({parse_gate_rule("quality.scaled_jacobian>0")}, report()),
                     "is an object, not a number");
}

}  // namespace
}  // namespace hq
