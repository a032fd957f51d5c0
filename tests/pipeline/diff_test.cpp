// `hqview diff`: relative gates, per-key differences, new/vanished meshes.

#include "hqview/pipeline/diff.h"

#include <gtest/gtest.h>

#include "hqview/core/error.h"

namespace hq {
namespace {

const char* kBase =
    R"({"schema_version": 1, "quality": {"scaled_jacobian": {"min": 0.5, "mean": 0.8}, "num_inverted": 0}, "boundary_error": null})";
const char* kWorse =
    R"({"schema_version": 1, "quality": {"scaled_jacobian": {"min": 0.45, "mean": 0.8}, "num_inverted": 2}, "boundary_error": null})";

TEST(DiffGate, RelativeAndAbsolute) {
  DiffGate g = parse_diff_gate("quality.scaled_jacobian.min >= baseline-0.01");
  EXPECT_TRUE(g.is_relative);
  EXPECT_EQ(g.rule.op, GateOp::greater_equal);
  EXPECT_DOUBLE_EQ(g.rule.threshold, -0.01);
  EXPECT_EQ(g.rule.text, "quality.scaled_jacobian.min >= baseline-0.01");
  EXPECT_TRUE(parse_diff_gate("quality.num_inverted<=baseline").is_relative);
  EXPECT_FALSE(parse_diff_gate("quality.num_inverted==0").is_relative);
  EXPECT_THROW(parse_diff_gate("quality.num_inverted<=baseline*2"), ValueError);
  EXPECT_THROW(parse_diff_gate("quality.num_inverted<=baseline-x"), ValueError);
}

TEST(DiffReports, RegressionFailsRelativeGate) {
  const std::vector<DiffGate> gates = {parse_diff_gate("quality.scaled_jacobian.min>=baseline-0.01"),
                                       parse_diff_gate("quality.num_inverted<=baseline")};
  const DiffResult same = diff_reports(kBase, kBase, gates, "", "");
  EXPECT_TRUE(same.passed);
  EXPECT_TRUE(same.changed.empty());
  const DiffResult worse = diff_reports(kBase, kWorse, gates, "", "");
  EXPECT_FALSE(worse.passed);
  ASSERT_EQ(worse.gates.size(), 2u);
  EXPECT_DOUBLE_EQ(worse.gates[0].threshold, 0.49);
  ASSERT_EQ(worse.changed.size(), 2u);
  EXPECT_EQ(worse.changed[0].key, "quality.num_inverted");
  EXPECT_NE(diff_markdown(worse).find("❌"), std::string::npos);
  EXPECT_THROW(diff_reports(kBase, kWorse, {parse_diff_gate("quality.nothing>=baseline")}, "", ""), ValueError);
  EXPECT_THROW(diff_reports(kBase, "[]", {}, "", ""), InputError);
}

TEST(DiffReports, IndexNewVanishedAndFailedMeshes) {
  const char* base = R"({"meshes": [
    {"path": "a.mesh", "status": "ok", "bundle": "a.mesh", "headline": {"quality.scaled_jacobian.min": 0.5}},
    {"path": "b.mesh", "status": "ok", "bundle": "b.mesh", "headline": {"quality.scaled_jacobian.min": 0.4}},
    {"path": "gone.mesh", "status": "ok", "bundle": "gone.mesh", "headline": {"quality.scaled_jacobian.min": 0.4}}]})";
  const char* cur = R"({"meshes": [
    {"path": "a.mesh", "status": "ok", "bundle": "a.mesh", "headline": {"quality.scaled_jacobian.min": 0.6}},
    {"path": "b.mesh", "status": "failed", "bundle": null, "headline": {"quality.scaled_jacobian.min": null}},
    {"path": "new.mesh", "status": "ok", "bundle": "new.mesh", "headline": {"quality.scaled_jacobian.min": 0.1}}]})";
  const DiffResult d =
      diff_reports(base, cur, {parse_diff_gate("quality.scaled_jacobian.min>=baseline-0.01")}, "/none", "/none");
  EXPECT_TRUE(d.is_index);
  EXPECT_EQ(d.new_meshes, std::vector<std::string>{"new.mesh"});
  EXPECT_EQ(d.vanished_meshes, std::vector<std::string>{"gone.mesh"});
  ASSERT_EQ(d.status_changes.size(), 1u);
  EXPECT_EQ(d.status_changes[0].current, "failed");
  ASSERT_EQ(d.gates.size(), 2u);
  EXPECT_TRUE(d.gates[0].passed);   // a.mesh improved
  EXPECT_FALSE(d.gates[1].passed);  // b.mesh failed to analyse: a regression
  EXPECT_FALSE(d.passed);
  EXPECT_THROW(diff_reports(base, kBase, {}, "", ""), InputError);  // index vs report
}

}  // namespace
}  // namespace hq
