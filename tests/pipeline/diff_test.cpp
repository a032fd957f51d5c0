// `hqview diff`: relative gates, per-key differences, new/vanished meshes.

#include "hqview/pipeline/diff.h"

#include <gtest/gtest.h>

#include "hqview/core/error.h"

#include <algorithm>
#include <string>

namespace hq {
namespace HQ_TEST_UNIT {

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


// Counts the lines of `md` that start with `prefix`.
std::size_t count_lines(const std::string& md, const std::string& prefix) {
  std::size_t n = 0, at = 0;
  while (at < md.size()) {
    const std::size_t end = md.find('\n', at);
    if (md.compare(at, prefix.size(), prefix) == 0) ++n;
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return n;
}

// 300 meshes whose min SJ moved by i/100000 (mesh i; odd: down), mesh 7 dropped by 0.5
// and failed its gate; mesh "a|b`<i>" names test the escaping.
TEST(DiffMarkdown, MarkerAndSizeCapKeepTheWorstRows) {
  DiffResult d;
  d.is_index = true;
  for (int i = 0; i < 300; ++i) {
    const std::string mesh = "m" + std::to_string(i) + ".mesh";
    const double base = 0.5, cur = i == 7 ? 0.0 : 0.5 - (i % 2 ? 1 : -1) * i / 100000.0;
    d.changed.push_back({mesh, "quality.scaled_jacobian.min", base, cur});
    d.gates.push_back({mesh, "quality.scaled_jacobian.min>=baseline-0.01", cur, base, base - 0.01, cur >= base - 0.01});
  }
  d.vanished_meshes = {"a|b`<i>.mesh"};
  d.passed = false;
  const std::string full = diff_markdown(d, 100000000);
  EXPECT_EQ(full.rfind(std::string(kDiffMarkdownMarker) + "\n", 0), 0u);
  EXPECT_EQ(count_lines(full, "| m"), 301u);  // the header and every changed value (gate rows start "| ✅"/"| ❌")
  EXPECT_EQ(full.find("left out"), std::string::npos);
  EXPECT_NE(full.find("- vanished mesh: a\\|b\\`&lt;i&gt;\\.mesh"), std::string::npos);
  EXPECT_EQ(diff_markdown(d), diff_markdown(d, kDiffMarkdownMaxChars));
  EXPECT_LE(full.size(), 60000u);  // this one fits the default cap

  const std::size_t cap = 4000;
  const std::string md = diff_markdown(d, cap);
  EXPECT_LE(md.size(), cap);
  EXPECT_EQ(md.rfind(std::string(kDiffMarkdownMarker) + "\n", 0), 0u);
  // The failed gate, the vanished mesh and the largest drops are kept; passed
  // gates and improvements go first.
  EXPECT_NE(md.find("| ❌ | `quality.scaled_jacobian.min>=baseline-0.01` | m7\\.mesh |"), std::string::npos);
  EXPECT_NE(md.find("vanished mesh"), std::string::npos);
  EXPECT_NE(md.find("| m7\\.mesh | `quality.scaled_jacobian.min` | 0.5 | 0 |"), std::string::npos);
  EXPECT_NE(md.find("| m299\\.mesh |"), std::string::npos);  // the largest drop after mesh 7
  EXPECT_EQ(md.find("| m298\\.mesh |"), std::string::npos);  // an improvement
  EXPECT_EQ(md.find("| m1\\.mesh |"), std::string::npos);    // the smallest drop
  EXPECT_EQ(md.find("| ✅"), std::string::npos);
  const std::size_t kept = count_lines(md, "| m") - 1 + count_lines(md, "| ❌") + count_lines(md, "- vanished");
  const std::string note = "_" + std::to_string(601 - kept) + " of 601 rows left out to stay under 4000 characters";
  EXPECT_NE(md.find(note), std::string::npos) << md.substr(md.size() - 300);
  // Kept drops in their original order, largest to smallest among the odd meshes kept.
  EXPECT_LT(md.find("| m7\\.mesh |"), md.find("| m299\\.mesh |"));
}

// Two report.json with their summaries: the side-by-side table of index.html's
// Comparison (compare_table.h), baseline and current, and MESH2's when both
// runs had --compare; values from the reports, differences by hand.
std::string report_with(const char* mesh, int vertices, double min_sj, int inverted, const char* compare_block) {
  return std::string(R"({"schema_version": 2, "input": {"mesh": {"path": "/d/)") + mesh +
         R"("}, "compare": {"path": "/d/other.mesh"}}, "mesh": {"num_vertices": )" + std::to_string(vertices) +
         R"(, "num_hexes": 10, "num_boundary_faces": 40, "bbox": {"diagonal": 2.5}, "edge_length": {"mean": 0.5}},
  "quality": {"num_inverted": )" + std::to_string(inverted) + R"(, "scaled_jacobian": {"min": )" +
         std::to_string(min_sj) + R"(, "mean": 0.8, "p05": 0.6, "num_inverted": )" + std::to_string(inverted) +
         R"(, "num_degenerate": 0}, "vertex_quality": {"min": null}}, "compare": )" + compare_block + "}";
}

TEST(DiffReports, SideBySideHeadlineOfTwoReports) {
  const char* compared = R"({"mesh": {"num_vertices": 1000, "num_hexes": 729}, "quality": {"scaled_jacobian": {"min": 0.9}}})";
  const std::string a = report_with("a.mesh", 1200, 0.5, 0, "null");
  const std::string b = report_with("b.mesh", 1350, 0.25, 3, compared);
  const DiffResult d = diff_reports(a, b, {}, "", "");
  ASSERT_EQ(d.side_by_side.size(), 1u);  // only b has a compare block
  EXPECT_EQ(d.side_by_side[0].what, "mesh");
  EXPECT_EQ(d.side_by_side[0].baseline_name, "a.mesh");
  EXPECT_EQ(d.side_by_side[0].current_name, "b.mesh");
  const std::vector<CompareTableRow>& rows = d.side_by_side[0].rows;
  ASSERT_EQ(rows.size(), 11u);
  EXPECT_EQ(rows[0].label, "vertices");
  EXPECT_EQ(rows[0].mine, "1,200");
  EXPECT_EQ(rows[0].theirs, "1,350");
  EXPECT_EQ(rows[0].difference, "+150");
  EXPECT_FALSE(rows[0].is_worse);
  EXPECT_EQ(rows[2].label, "min scaled Jacobian");
  EXPECT_EQ(rows[2].difference, "-0.25");
  EXPECT_TRUE(rows[2].is_worse);
  EXPECT_EQ(rows[5].label, "inverted hexes");
  EXPECT_EQ(rows[5].difference, "+3");
  EXPECT_TRUE(rows[5].is_worse);
  EXPECT_EQ(rows[7].mine, "–");  // null in the report: unknown, no difference
  EXPECT_EQ(rows[7].difference, "–");
  EXPECT_EQ(rows[3].difference, "0");

  const std::string text = diff_text(d);
  EXPECT_EQ(text.find("mesh: a.mesh → b.mesh\n"), 0u) << text;
  EXPECT_NE(text.find("  min scaled Jacobian         0.5     0.25       -0.25  worse\n"), std::string::npos) << text;
  const std::string md = diff_markdown(d);
  EXPECT_NE(md.find("### mesh: a\\.mesh → b\\.mesh\n\n| | baseline | current | difference |"), std::string::npos) << md;
  EXPECT_NE(md.find("| min scaled Jacobian | 0.5 | 0.25 | **-0.25** |"), std::string::npos) << md;

  // Both with --compare: the second meshes side by side too.
  const DiffResult both = diff_reports(report_with("a.mesh", 1200, 0.5, 0, compared),
                                       report_with("b.mesh", 1200, 0.5, 0,
                                                   R"({"mesh": {"num_vertices": 900, "num_hexes": 640}, "quality": {"scaled_jacobian": {"min": 0.95}}})"),
                                       {}, "", "");
  ASSERT_EQ(both.side_by_side.size(), 2u);
  EXPECT_EQ(both.side_by_side[1].what, "compared mesh (--compare)");
  EXPECT_EQ(both.side_by_side[1].rows[1].difference, "-89");
  EXPECT_EQ(both.side_by_side[1].rows[2].difference, "+0.05");
  EXPECT_FALSE(both.side_by_side[1].rows[2].is_worse);
  EXPECT_NE(diff_markdown(both).find("### compared mesh (--compare): other\\.mesh → other\\.mesh"), std::string::npos);
  // Excerpts without the summaries (kBase) get no table.
  EXPECT_TRUE(diff_reports(kBase, kWorse, {}, "", "").side_by_side.empty());
}

// An earlier HQView's report or index against a newer one: the keys only
// the newer one writes are added keys, not values changed from null; a key
// under a null parent (`compare: null`) that gets a number is a change.
TEST(DiffReports, KeysOnOneSideOnlyAreAddedOrRemovedNotChanged) {
  const char* old_report = R"({"schema_version": 2, "headline": {"num_vertices": 8, "num_hexes": 1},
    "quality": {"num_inverted": 0}, "compare": null})";
  const char* new_report = R"({"schema_version": 2, "headline": {"num_vertices": 8, "num_hexes": 1, "num_cells": 1,
    "num_cells_by_kind": {"hex": 1, "tet": 0}, "hex_fraction": 1, "hex_volume_fraction": null},
    "quality": {"num_inverted": 0}, "compare": {"mesh": {"num_vertices": 9}}})";
  const DiffResult d = diff_reports(old_report, new_report, {}, "", "");
  std::vector<std::string> added;
  for (const DiffValue& v : d.added) added.push_back(v.key);
  EXPECT_EQ(added, (std::vector<std::string>{"headline.hex_fraction", "headline.num_cells",
                                             "headline.num_cells_by_kind.hex", "headline.num_cells_by_kind.tet"}));
  ASSERT_EQ(d.changed.size(), 1u);  // compare was null
  EXPECT_EQ(d.changed[0].key, "compare.mesh.num_vertices");
  EXPECT_TRUE(d.removed.empty());
  const std::string text = diff_text(d);
  EXPECT_NE(text.find("added key: headline.num_cells = 1\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("headline.num_cells: "), std::string::npos) << text;  // not as a change
  const std::string md = diff_markdown(d);
  EXPECT_NE(md.find("1 values changed, 4 keys added"), std::string::npos) << md;
  EXPECT_NE(md.find("### Keys on one side only"), std::string::npos) << md;
  EXPECT_NE(md.find("- added: `headline.num_cells`\n"), std::string::npos) << md;
  // The other way round: removed.
  const DiffResult back = diff_reports(new_report, old_report, {}, "", "");
  EXPECT_EQ(back.removed.size(), 4u);
  EXPECT_TRUE(back.added.empty());
  EXPECT_NE(diff_text(back).find("removed key: headline.num_cells_by_kind.tet = 0\n"), std::string::npos);

  // Two indexes: the composition keys of every mesh, once per key with the
  // number of meshes; a null composition key (a failed mesh) against a
  // number stays a change.
  const char* old_index = R"({"meshes": [
    {"path": "a.mesh", "status": "ok", "bundle": "a", "headline": {"mesh.num_hexes": 8}},
    {"path": "b.mesh", "status": "ok", "bundle": "b", "headline": {"mesh.num_hexes": 9, "headline.num_cells": null}}]})";
  const char* new_index = R"({"meshes": [
    {"path": "a.mesh", "status": "ok", "bundle": "a", "headline": {"mesh.num_hexes": 8, "headline.num_cells": 8, "headline.hex_fraction": 1}},
    {"path": "b.mesh", "status": "ok", "bundle": "b", "headline": {"mesh.num_hexes": 9, "headline.num_cells": 9, "headline.hex_fraction": 1}}]})";
  const DiffResult i = diff_reports(old_index, new_index, {}, "/none", "/none");
  EXPECT_EQ(i.added.size(), 3u);  // a: two keys, b: hex_fraction
  ASSERT_EQ(i.changed.size(), 1u);
  EXPECT_EQ(i.changed[0].mesh, "b.mesh");
  EXPECT_EQ(i.changed[0].key, "headline.num_cells");
  const std::string itext = diff_text(i);
  EXPECT_NE(itext.find("added key: headline.hex_fraction (2 meshes)\n"), std::string::npos) << itext;
  EXPECT_NE(itext.find("added key: headline.num_cells (1 mesh)\n"), std::string::npos) << itext;
  EXPECT_NE(diff_markdown(i).find("- added: `headline.hex_fraction` (2 meshes)"), std::string::npos);
}

// The side-by-side table of two hybrid reports gains the composition rows
// (from headline), a lower hex fraction is worse; pure-hex reports keep
// their 11 rows (tested above).
TEST(DiffReports, SideBySideOfHybridReportsShowsTheComposition) {
  const auto hybrid = [](int tets, double fraction, double volume_fraction) {
    return std::string(R"({"schema_version": 2, "input": {"mesh": {"path": "/d/h.msh"}},
      "headline": {"num_cells": )") + std::to_string(10 + tets) + R"(, "num_cells_by_kind": {"hex": 10, "tet": )" +
           std::to_string(tets) + R"(, "wedge": 0, "pyramid": 4}, "hex_fraction": )" + std::to_string(fraction) +
           R"(, "hex_volume_fraction": )" + std::to_string(volume_fraction) + R"(},
      "mesh": {"num_vertices": 50, "num_hexes": 10}, "quality": {"scaled_jacobian": {"min": 0.5}}})";
  };
  const DiffResult d = diff_reports(hybrid(20, 0.25, 0.5), hybrid(26, 0.2, 0.5), {}, "", "");
  ASSERT_EQ(d.side_by_side.size(), 1u);
  const std::vector<CompareTableRow>& rows = d.side_by_side[0].rows;
  ASSERT_EQ(rows.size(), 17u);
  EXPECT_EQ(rows[2].label, "cells (every kind)");
  EXPECT_EQ(rows[2].difference, "+6");
  EXPECT_EQ(rows[3].label, "tetrahedra");
  EXPECT_EQ(rows[3].mine, "20");
  EXPECT_EQ(rows[3].theirs, "26");
  EXPECT_EQ(rows[4].label, "wedges");
  EXPECT_EQ(rows[4].difference, "0");
  EXPECT_EQ(rows[5].label, "pyramids");
  EXPECT_EQ(rows[6].label, "hex fraction (by count)");
  EXPECT_EQ(rows[6].difference, "-0.05");
  EXPECT_TRUE(rows[6].is_worse);
  EXPECT_EQ(rows[7].label, "hex fraction (by volume)");
  EXPECT_EQ(rows[7].difference, "0");
  EXPECT_EQ(rows[11].label, "inverted cells");
  EXPECT_NE(diff_markdown(d).find("| hex fraction (by count) | 0.25 | 0.2 | **-0.05** |"), std::string::npos);
}

// Two surface reports (issue 47): no hexahedra or boundary faces rows, the
// quads, triangles and boundary edges instead, and the rows and notes speak
// of faces; a surface against a hex report keeps both sides' rows and says
// cells.
TEST(DiffReports, SideBySideOfSurfaceReportsSpeaksOfFaces) {
  const auto report = [](int quads, int triangles, int hexes, int inverted) {
    const bool surface = quads + triangles > 0;
    return std::string(R"({"schema_version": 2, "input": {"mesh": {"path": "/d/s.obj"}},
      "headline": {"num_cells": )") + std::to_string(quads + triangles + hexes) +
           R"(, "num_cells_by_kind": {"hex": )" + std::to_string(hexes) +
           R"(, "tet": 0, "wedge": 0, "pyramid": 0, "quad": )" + std::to_string(quads) + R"(, "triangle": )" +
           std::to_string(triangles) + R"(}},
      "mesh": {"num_vertices": 81, "num_hexes": )" + std::to_string(hexes) + R"(, "num_boundary_faces": )" +
           (surface ? "0" : "40") + R"(, "num_boundary_edges": )" + (surface ? "32" : "null") + R"(},
      "quality": {"scaled_jacobian": {"min": -0.5, "num_inverted": )" + std::to_string(inverted) + "}}}";
  };
  const DiffResult d = diff_reports(report(64, 0, 0, 2), report(60, 8, 0, 3), {}, "", "");
  ASSERT_EQ(d.side_by_side.size(), 1u);
  EXPECT_EQ(d.side_by_side[0].cells, MeshCells::surface);
  std::vector<std::string> labels;
  for (const CompareTableRow& r : d.side_by_side[0].rows) labels.push_back(r.label);
  const std::vector<std::string> expected = {"vertices", "quadrilaterals", "triangles", "min scaled Jacobian",
                                             "mean scaled Jacobian", "p05 scaled Jacobian", "inverted faces",
                                             "degenerate faces", "min vertex quality", "boundary edges",
                                             "bounding box diagonal", "mean edge length"};
  EXPECT_EQ(labels, expected);
  EXPECT_EQ(d.side_by_side[0].rows[1].difference, "-4");
  EXPECT_EQ(d.side_by_side[0].rows[2].difference, "+8");
  EXPECT_TRUE(d.side_by_side[0].rows[6].is_worse);  // 2 -> 3 inverted faces
  const std::string text = diff_text(d);
  EXPECT_EQ(text.find("hexahedra"), std::string::npos) << text;
  EXPECT_EQ(text.find("per hex"), std::string::npos) << text;
  EXPECT_NE(text.find("(scaled Jacobian: per face: its lowest signed corner"), std::string::npos) << text;
  EXPECT_NE(text.find("degenerate faces: faces whose scaled Jacobian"), std::string::npos) << text;

  // A quad surface without triangles has no triangles row.
  const DiffResult q = diff_reports(report(64, 0, 0, 2), report(64, 0, 0, 2), {}, "", "");
  EXPECT_EQ(q.side_by_side[0].rows.size(), expected.size() - 1);

  // A hex report against a surface report: both kinds of rows, "cells".
  const DiffResult m = diff_reports(report(0, 0, 27, 0), report(64, 0, 0, 2), {}, "", "");
  EXPECT_EQ(m.side_by_side[0].cells, MeshCells::volume);
  labels.clear();
  for (const CompareTableRow& r : m.side_by_side[0].rows) labels.push_back(r.label);
  for (const char* label : {"hexahedra", "quadrilaterals", "inverted cells", "boundary faces", "boundary edges"})
    EXPECT_NE(std::find(labels.begin(), labels.end(), label), labels.end()) << label;
  EXPECT_NE(diff_text(m).find("per cell: Verdict's scaled Jacobian of its kind"), std::string::npos);
}

}  // namespace
}  // namespace hq
