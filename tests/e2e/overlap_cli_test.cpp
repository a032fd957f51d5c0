// The overlap stages through the CLI: report.json `overlap`, the
// coincident_group and intersecting CSV columns, the HTML section, the
// --overlap / --coincident-eps / --no-overlap options and their errors.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/fixtures.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;  // keeps report.json's key order

fs::path example(const std::string& name) { return source_dir() / "examples" / name; }

json analyze_json(const std::string& mesh, std::vector<std::string> extra, const fs::path& out) {
  std::vector<std::string> args = {"analyze", "--data", "csv,vtu.zlib", example(mesh).string(), "-o", out.string(), "--no-render", "-q", "--json",
                                   "-"};
  args.insert(args.end(), extra.begin(), extra.end());
  const CliResult r = run_hqview(args);
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
  return json::parse(r.out);
}

// The column `name` of a CSV, header dropped.
std::vector<std::string> column(const fs::path& csv, const std::string& name) {
  const auto rows = read_csv(csv);
  const auto it = std::find(rows[0].begin(), rows[0].end(), name);
  EXPECT_NE(it, rows[0].end()) << name;
  const auto k = static_cast<std::size_t>(it - rows[0].begin());
  std::vector<std::string> values;
  for (std::size_t i = 1; i < rows.size(); ++i) values.push_back(k < rows[i].size() ? rows[i][k] : "");
  return values;
}

TEST(OverlapCli, DuplicatedVertexIsOneCoincidentGroup) {
  const fs::path out = fresh_output_dir("overlap_dup") / "bundle";
  const json o = analyze_json("duplicated_vertex.mesh", {}, out)["overlap"];
  ASSERT_TRUE(o.is_object());
  EXPECT_EQ(o["num_coincident_vertices"], 2);
  ASSERT_EQ(o["coincident_groups"].size(), 1u);
  EXPECT_EQ(o["coincident_groups"][0]["vertices"], json::array({62, 125}));
  EXPECT_EQ(o["coincident_groups"][0]["position"], json::array({2.0, 2.0, 2.0}));
  EXPECT_EQ(o["num_intersecting_cells"], 0);
  EXPECT_EQ(o["intersecting_pairs"], json::array());
  EXPECT_EQ(o["markers"], json::parse(R"([{"kind": "coincident", "position": [2.0, 2.0, 2.0], "count": 2}])"));
  EXPECT_EQ(o["mode"], "certificate");
  EXPECT_FALSE(o["certified_clean"].get<bool>());
  // Contract keys first, in the contract's order.
  std::vector<std::string> keys;
  for (const auto& [key, value] : o.items()) keys.push_back(key);
  const std::vector<std::string> contract = {
      "num_coincident_vertices", "coincident_groups",      "num_zero_length_edges",
      "num_inverted_cells",      "num_non_manifold_faces", "num_duplicate_cells",
      "num_intersecting_cells",  "intersecting_pairs",     "markers"};
  ASSERT_GE(keys.size(), contract.size());
  EXPECT_EQ(std::vector<std::string>(keys.begin(), keys.begin() + 9), contract);

  const auto groups = column(out / "data/vertices.csv", "coincident_group");
  for (std::size_t v = 0; v < groups.size(); ++v) EXPECT_EQ(groups[v], v == 62 || v == 125 ? "0" : "-1") << v;
  for (const std::string& x : column(out / "data/cells.csv", "intersecting")) EXPECT_EQ(x, "0");
}

TEST(OverlapCli, BallFoldIsReportedInJsonCsvAndHtml) {
  const fs::path out = fresh_output_dir("overlap_ball") / "bundle";
  const json o = analyze_json("ball.mesh", {}, out)["overlap"];
  const int cells = o["num_intersecting_cells"];
  EXPECT_GT(cells, 0);
  EXPECT_EQ(o["intersecting_pairs"].size(), o["num_intersecting_pairs"].get<std::size_t>());
  ASSERT_EQ(o["intersecting_pairs_detail"].size(), o["intersecting_pairs"].size());
  for (std::size_t i = 0; i < o["intersecting_pairs"].size(); ++i) {
    const json& pair = o["intersecting_pairs"][i];
    EXPECT_LT(pair[0].get<int>(), pair[1].get<int>());
    EXPECT_EQ(o["intersecting_pairs_detail"][i]["cells"], pair);
    EXPECT_TRUE(o["intersecting_pairs_detail"][i]["inside_vertex"].is_number());
  }
  int marked = 0;
  for (const json& m : o["markers"]) {
    EXPECT_EQ(m["kind"], "intersection");
    marked += m["count"].get<int>();
  }
  EXPECT_EQ(marked, o["num_intersecting_pairs"].get<int>());
  int flagged = 0;
  for (const std::string& x : column(out / "data/cells.csv", "intersecting")) flagged += x == "1";
  EXPECT_EQ(flagged, cells);
  const std::string html = read_text(out / "index.html");
  EXPECT_NE(html.find("<h2>Overlap check</h2>"), std::string::npos);
  EXPECT_NE(html.find("intersecting hexes"), std::string::npos);
  // The 45t review: the nav said "Overlaps" beside the cards' "intersecting
  // hexes". The check is the "overlap check".
  EXPECT_NE(html.find("<a href=\"#overlap\">Overlap check</a>"), std::string::npos);
  EXPECT_EQ(html.find(">Overlaps<"), std::string::npos);
  // One term for one count (issue 45): the card, the overlap table and
  // summary.md name num_intersecting_cells "intersecting hexes", with the
  // same number; "overlapping" names none of them (the card said
  // "overlapping hexes" beside the overview's "intersecting hexes: N").
  const std::string count = std::to_string(cells);
  EXPECT_NE(html.find("<div class=\"value\">" + count + "</div><div class=\"label\">intersecting hexes</div>"),
            std::string::npos);
  EXPECT_NE(html.find("<th scope=\"row\">intersecting hexes</th><td class=\"alert\">" + count + "</td>"), std::string::npos);
  EXPECT_EQ(html.find("overlapping hexes"), std::string::npos);
  const std::string md = read_text(out / "summary.md");
  EXPECT_NE(md.find("| #inverted | intersecting hexes |"), std::string::npos) << md;
  EXPECT_EQ(md.find("overlapping"), std::string::npos) << md;
  // Exhaustive mode finds the same pairs.
  const json exhaustive =
      analyze_json("ball.mesh", {"--overlap=exhaustive"}, fresh_output_dir("overlap_ball_ex") / "bundle")["overlap"];
  EXPECT_EQ(exhaustive["mode"], "exhaustive");
  EXPECT_EQ(exhaustive["intersecting_pairs"], o["intersecting_pairs"]);
}

// The 45t review: panel A's heading and view A's title said "clusters and
// overlaps" beside the cards' "intersecting hexes": one term, the cards'.
TEST(OverlapCli, ViewATitlesNameIntersectingHexesAsTheCards) {
  const fs::path out = fresh_output_dir("overlap_view_a_titles") / "bundle";
  const CliResult r = run_hqview({"analyze", example("ball.mesh").string(), "-o", out.string(), "--views", "main",
                                  "--no-viewer", "--data", "none", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = read_text(out / "index.html");
  EXPECT_EQ(html.find("overlaps"), std::string::npos);
  EXPECT_NE(html.find("A · Main view: glyphs, clusters and intersecting hexes"), std::string::npos);
  EXPECT_NE(html.find("<div class=\"label\">intersecting hexes</div>"), std::string::npos);
  int main_titles = 0;
  const json report = json::parse(read_text(out / "report.json"));
  for (const json& v : report["views"])
    if (v["id"] == "main") {
      EXPECT_EQ(v["title"], "A: glyphs, clusters and intersecting hexes");
      ++main_titles;
    }
  EXPECT_EQ(main_titles, 1);
}

TEST(OverlapCli, GateOnIntersectingCells) {
  const fs::path out = fresh_output_dir("overlap_gate") / "bundle";
  const CliResult r = run_hqview({"analyze", "--data", "csv,vtu.zlib", example("ball.mesh").string(), "-o", out.string(), "--no-render", "-q",
                                  "--gate", "overlap.num_intersecting_cells==0"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
}

TEST(OverlapCli, CoincidentEpsilonMergesNearVertices) {
  // The duplicated vertex is exactly coincident: any tolerance keeps it, and
  // the grid's other vertices (1/4 of the diagonal 6.9 apart) stay apart.
  const json o = analyze_json("duplicated_vertex.mesh", {"--coincident-eps", "1e-3"},
                              fresh_output_dir("overlap_eps") / "bundle")["overlap"];
  EXPECT_EQ(o["num_coincident_vertices"], 2);
  EXPECT_NEAR(o["coincident_tolerance"].get<double>(), 1e-3 * std::sqrt(48.0), 1e-12);
}

TEST(OverlapCli, NoOverlapLeavesItNull) {
  const fs::path out = fresh_output_dir("overlap_none") / "bundle";
  const json report = analyze_json("duplicated_vertex.mesh", {"--no-overlap"}, out);
  EXPECT_TRUE(report["overlap"].is_null());
  for (const std::string& x : column(out / "data/vertices.csv", "coincident_group")) EXPECT_EQ(x, "");
  for (const std::string& x : column(out / "data/cells.csv", "intersecting")) EXPECT_EQ(x, "");
  EXPECT_EQ(read_text(out / "index.html").find("<h2>Overlap check</h2>"), std::string::npos);
}

TEST(OverlapCli, BadValuesAreUsageErrors) {
  const fs::path out = fresh_output_dir("overlap_bad") / "bundle";
  for (const std::vector<std::string>& extra :
       std::vector<std::vector<std::string>>{{"--overlap", "fast"},
                                             {"--overlap="},
                                             {"--coincident-eps", "-1"},
                                             {"--coincident-eps", "nan"},
                                             {"--coincident-eps", "inf"},
                                             {"--coincident-eps", "2"},
                                             {"--coincident-eps", "0.1x"},
                                             {"--no-overlap", "--overlap", "exhaustive"}}) {
    std::vector<std::string> args = {"analyze", "--data", "csv,vtu.zlib", example("duplicated_vertex.mesh").string(), "-o", out.string(),
                                     "--no-render"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = run_hqview(args);
    EXPECT_EQ(r.exit_code, 2) << extra[0] << " " << (extra.size() > 1 ? extra[1] : "") << ": " << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
}  // namespace hq::test
