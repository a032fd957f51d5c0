// The glyph stage through the CLI: report.json `glyphs` against
// data/vertices.csv (every number recomputed from the CSV), the options
// --rmax, --glyph-threshold, --top-clusters and their errors, the HTML table,
// and the real meshes of ../shared/data.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "hqview/image/colormap.h"
#include "cli_runner.h"
#include "support/fixtures.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

fs::path example(const std::string& name) { return source_dir() / "examples" / name; }

struct GlyphBundle {
  ordered_json report;
  fs::path dir;
};

GlyphBundle analyze(const fs::path& mesh, const std::string& name, std::vector<std::string> extra = {}) {
  const fs::path out = fresh_output_dir("glyphs/" + name) / "bundle";
  std::vector<std::string> args = {"analyze", "--data", "csv,vtu.zlib", mesh.string(), "-o", out.string(), "--no-render"};
  args.insert(args.end(), extra.begin(), extra.end());
  const CliResult r = run_hqview(args);
  EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
  if (r.exit_code != 0) return {};
  return {ordered_json::parse(read_text(out / "report.json")), out};
}

double bonus(std::int64_t size) { return static_cast<double>(std::min<std::int64_t>(size / 10, 10)) / 10.0; }

// Every glyph number of report.json, recomputed from vertices.csv.
void expect_glyphs_match_vertices_csv(const GlyphBundle& b) {
  const ordered_json& g = b.report["glyphs"];
  ASSERT_TRUE(g.is_object());
  std::vector<std::string> keys;
  for (const auto& item : g.items()) keys.push_back(item.key());
  EXPECT_EQ(keys,
            (std::vector<std::string>{"rmax", "threshold", "num_glyphs", "num_clusters", "rmax_mode", "rmax_factor",
                                      "top_clusters", "size_rule", "num_clusters_omitted", "tie_tolerance",
                                      "clusters"}));
  const bool is_paper = g["size_rule"] == "paper";
  EXPECT_TRUE(is_paper || g["size_rule"] == "severity");
  const double rmax = g["rmax"], threshold = g["threshold"];
  const auto rows = read_csv(b.dir / "data/vertices.csv");
  ASSERT_GT(rows.size(), 1u);
  EXPECT_EQ(rows[0][5], "glyph_radius");
  EXPECT_EQ(rows[0][6], "cluster");
  std::map<long, std::vector<long>> members;  // cluster -> vertices
  std::map<long, double> min_quality;
  long glyphs = 0;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const auto& row = rows[r];
    const long vertex = std::stol(row[0]);
    const long cluster = std::stol(row[6]);
    if (row[4].empty()) {  // a vertex no hex uses
      EXPECT_EQ(row[5], "") << "vertex " << vertex;
      EXPECT_EQ(cluster, -1) << "vertex " << vertex;
      continue;
    }
    const double q = std::stod(row[4]);
    const double radius = std::stod(row[5]);
    if (1.0 - q > threshold) {
      ++glyphs;
      EXPECT_EQ(radius, (1.0 - q) * rmax) << "vertex " << vertex;
      ASSERT_GE(cluster, 0) << "vertex " << vertex;
      members[cluster].push_back(vertex);
      min_quality[cluster] = min_quality.count(cluster) ? std::min(min_quality[cluster], q) : q;
    } else {
      EXPECT_EQ(radius, 0.0) << "vertex " << vertex;
      EXPECT_EQ(cluster, -1) << "vertex " << vertex;
    }
  }
  EXPECT_EQ(g["num_glyphs"].get<long>(), glyphs);
  EXPECT_EQ(g["num_clusters"].get<std::size_t>(), members.size());
  const auto& clusters = g["clusters"];
  // Tie classes (issue 44 part T), recomputed from the listed min qualities:
  // a class starts where the min quality leaves its first one's tolerance
  // or crosses 0; classes are coloured while at most 6 and (after the
  // first) their members add up to at most 12.
  const double tolerance = g["tie_tolerance"];
  EXPECT_EQ(tolerance, 0.001);
  std::vector<long> tie(clusters.size(), 0), class_size;
  double first = 0.0;  // the current class's first min quality
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    const double q = clusters[i]["min_quality"];
    const bool ties = i > 0 && q - first <= tolerance && (q < 0.0) == (first < 0.0);
    tie[i] = i == 0 ? 0 : tie[i - 1] + (ties ? 0 : 1);
    if (!ties) {
      first = q;
      class_size.push_back(0);
    }
    ++class_size.back();
    EXPECT_EQ(clusters[i]["tie_class"].get<long>(), tie[i]) << i;
  }
  long coloured = 0, coloured_glyphs = 0;
  const long palette = labelled_cluster_count(g["top_clusters"].get<std::int64_t>());
  for (long size : class_size) {
    if (coloured >= palette || (coloured > 0 && coloured_glyphs + size > 12)) break;
    coloured_glyphs += size;
    ++coloured;
  }
  EXPECT_EQ(clusters.size() + g["num_clusters_omitted"].get<std::size_t>(), members.size());
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    const auto& c = clusters[i];
    const long id = c["id"];
    EXPECT_EQ(id, static_cast<long>(i));
    const auto& m = members[id];
    EXPECT_EQ(c["size"].get<std::size_t>(), m.size()) << "cluster " << id;
    const long rep = c["representative_vertex"];
    EXPECT_TRUE(std::find(m.begin(), m.end(), rep) != m.end()) << "cluster " << id;
    const auto& row = rows[static_cast<std::size_t>(rep) + 1];
    EXPECT_EQ(c["position"], (ordered_json{std::stod(row[1]), std::stod(row[2]), std::stod(row[3])}));
    EXPECT_EQ(c["min_quality"].get<double>(), min_quality[id]) << "cluster " << id;
    // Size is severity; the paper's rule adds the size bonus.
    const double ratio = (1.0 - min_quality[id]) + (is_paper ? bonus(static_cast<std::int64_t>(m.size())) : 0.0);
    EXPECT_EQ(c["ratio"].get<double>(), ratio) << "cluster " << id;
    EXPECT_EQ(c["radius"].get<double>(), ratio * rmax) << "cluster " << id;
    const std::string color = c["color"];
    EXPECT_EQ(color.size(), 7u);
    EXPECT_EQ(color[0], '#');
    // The coloured tie classes wear distinct colours, one per class; every
    // other cluster the one neutral tone, which no coloured class wears.
    for (std::size_t j = 0; j < i; ++j) {
      const bool same = tie[i] == tie[j] || (tie[i] >= coloured && tie[j] >= coloured);
      EXPECT_EQ(color == clusters[j]["color"].get<std::string>(), same) << i << " " << j;
    }
    if (i > 0) {  // ranked by min quality, then larger first
      const auto& prev = clusters[i - 1];
      EXPECT_LE(prev["min_quality"].get<double>(), c["min_quality"].get<double>());
      if (prev["min_quality"] == c["min_quality"]) {
        EXPECT_GE(prev["size"].get<long>(), c["size"].get<long>());
      }
    }
  }
}

TEST(Glyphs, BallDefaultsMatchVerticesCsv) {
  const GlyphBundle b = analyze(example("ball.mesh"), "ball");
  ASSERT_TRUE(b.report.is_object());
  const auto& g = b.report["glyphs"];
  EXPECT_EQ(g["rmax"].get<double>(), b.report["mesh"]["edge_length"]["mean"].get<double>());
  EXPECT_EQ(g["threshold"].get<double>(), 0.5);
  EXPECT_EQ(g["rmax_mode"], "mean_edge_length");
  EXPECT_EQ(g["rmax_factor"].get<double>(), 1.0);
  EXPECT_EQ(g["top_clusters"], 8);
  EXPECT_GT(g["num_glyphs"].get<int>(), 0);
  EXPECT_EQ(g["size_rule"], "severity");
  // The worst cluster holds the worst vertex.
  EXPECT_EQ(g["clusters"][0]["min_quality"], b.report["quality"]["vertex_quality"]["min"]);
  expect_glyphs_match_vertices_csv(b);
}

TEST(Glyphs, PaperSizeRuleAddsTheBonusOnHqviewersClusters) {
  const GlyphBundle severity = analyze(example("ball.mesh"), "ball-severity", {"--rmax", "2x"});
  const GlyphBundle paper = analyze(example("ball.mesh"), "ball-paper", {"--rmax", "2x", "--glyph-size", "paper"});
  ASSERT_TRUE(severity.report.is_object() && paper.report.is_object());
  EXPECT_EQ(paper.report["glyphs"]["size_rule"], "paper");
  expect_glyphs_match_vertices_csv(severity);
  expect_glyphs_match_vertices_csv(paper);
  // The same glyphs; paper keeps HQViewer's clusters (the overlap
  // components), which severity splits into bounded ones (issue 44's fifth
  // round): at least as many, the worst the same.
  const auto& a = severity.report["glyphs"]["clusters"];
  const auto& b = paper.report["glyphs"]["clusters"];
  EXPECT_EQ(severity.report["glyphs"]["num_glyphs"], paper.report["glyphs"]["num_glyphs"]);
  EXPECT_GE(severity.report["glyphs"]["num_clusters"].get<long>(), paper.report["glyphs"]["num_clusters"].get<long>());
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(a[0]["min_quality"], b[0]["min_quality"]);
  bool has_bonus = false;
  for (std::size_t i = 0; i < b.size(); ++i) has_bonus = has_bonus || b[i]["size"].get<long>() >= 10;
  EXPECT_TRUE(has_bonus);  // some cluster of 10 or more members: the rules differ there
  // vertices.csv: the same rows up to the cluster column.
  const auto rows_a = read_csv(severity.dir / "data/vertices.csv"), rows_b = read_csv(paper.dir / "data/vertices.csv");
  ASSERT_EQ(rows_a.size(), rows_b.size());
  for (std::size_t r = 0; r < rows_a.size(); ++r)
    for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(rows_a[r][k], rows_b[r][k]) << r << " " << k;
}

TEST(Glyphs, SmallerRmaxSplitsClusters) {
  const GlyphBundle b = analyze(example("ball.mesh"), "ball-small-rmax", {"--rmax", "0.3x", "--top-clusters", "3"});
  ASSERT_TRUE(b.report.is_object());
  const auto& g = b.report["glyphs"];
  EXPECT_GT(g["num_clusters"].get<int>(), 10);
  EXPECT_EQ(g["top_clusters"], 3);
  EXPECT_DOUBLE_EQ(g["rmax"].get<double>(), 0.3 * b.report["mesh"]["edge_length"]["mean"].get<double>());
  expect_glyphs_match_vertices_csv(b);
  const std::string html = read_text(b.dir / "index.html");
  EXPECT_NE(html.find("id=\"clusters\""), std::string::npos);
  EXPECT_NE(html.find("class=\"swatch\" style=\"background: " + g["clusters"][0]["color"].get<std::string>()),
            std::string::npos);
  std::size_t top_rows = 0;
  // Rows are <tr id="cluster-row-K" class="top">.
  for (std::size_t at = html.find(" class=\"top\">"); at != std::string::npos; at = html.find(" class=\"top\">", at + 1))
    ++top_rows;
  EXPECT_EQ(top_rows, 3u);
}

TEST(Glyphs, RmaxInModelUnitsAndThreshold) {
  const GlyphBundle b =
      analyze(example("twisted_bar.mesh"), "bar-model", {"--rmax", "0.05", "--glyph-threshold", "0.25"});
  ASSERT_TRUE(b.report.is_object());
  const auto& g = b.report["glyphs"];
  EXPECT_EQ(g["rmax"].get<double>(), 0.05);
  EXPECT_EQ(g["rmax_mode"], "model_units");
  EXPECT_TRUE(g["rmax_factor"].is_null());
  EXPECT_EQ(g["threshold"].get<double>(), 0.25);
  expect_glyphs_match_vertices_csv(b);

  const GlyphBundle none = analyze(example("twisted_bar.mesh"), "bar-none", {"--glyph-threshold", "2"});
  ASSERT_TRUE(none.report.is_object());
  EXPECT_EQ(none.report["glyphs"]["num_glyphs"], 0);
  EXPECT_EQ(none.report["glyphs"]["clusters"], ordered_json::array());
  expect_glyphs_match_vertices_csv(none);
  EXPECT_EQ(read_text(none.dir / "index.html").find("class=\"swatch\""), std::string::npos);
}

TEST(Glyphs, ReportListsTheThousandWorstClusters) {
  // Tiny glyphs on every vertex: 1,330 clusters of one (one ball vertex has quality 1).
  const GlyphBundle b = analyze(example("ball.mesh"), "ball-many", {"--glyph-threshold", "0", "--rmax", "0.01x"});
  ASSERT_TRUE(b.report.is_object());
  const auto& g = b.report["glyphs"];
  EXPECT_EQ(g["num_clusters"], 1330);
  EXPECT_EQ(g["clusters"].size(), 1000u);
  EXPECT_EQ(g["num_clusters_omitted"], 330);
  expect_glyphs_match_vertices_csv(b);
  const std::string html = read_text(b.dir / "index.html");
  EXPECT_NE(html.find("… and 1,310 more clusters"), std::string::npos);
}

TEST(Glyphs, BadOptionValuesAreUsageErrors) {
  const std::vector<std::vector<std::string>> bad = {
      {"--rmax", "0"},
      {"--rmax", "-1"},
      {"--rmax", "abc"},
      {"--rmax", "1.5y"},
      {"--rmax", "x"},
      {"--rmax", "nan"},
      {"--rmax", "inf"},
      {"--rmax", "1e400"},
      {"--rmax", "0x"},
      {"--rmax", " 1"},
      {"--glyph-size", "big"},
      {"--glyph-size", "Paper"},
      {"--glyph-threshold", "-0.1"},
      {"--glyph-threshold", "2.5"},
      {"--glyph-threshold", "nan"},
      {"--glyph-threshold", "half"},
      {"--top-clusters", "-1"},
      {"--top-clusters", "two"},
      {"--top-clusters", "1.5"},
  };
  for (const auto& option : bad) {
    const fs::path out = fresh_output_dir("glyphs/bad") / "bundle";
    std::vector<std::string> args = {"analyze", "--data", "csv,vtu.zlib", example("ball.mesh").string(), "-o", out.string(), "--no-render"};
    args.insert(args.end(), option.begin(), option.end());
    const CliResult r = run_hqview(args);
    EXPECT_EQ(r.exit_code, 2) << option[0] << " " << option[1] << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << option[0] << " " << option[1];
    EXPECT_NE(r.err.find(option[0]), std::string::npos) << "the message names the option: " << r.err;
  }
}

TEST(Glyphs, SharedMeshes) {
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data absent";
  const fs::path meshes = *data / "meshes";
  // rockarm: 11 inverted hexes, several clusters; the worst holds the worst vertex.
  const GlyphBundle rockarm = analyze(meshes / "dualsheet2019/rockarm.vtk", "rockarm");
  ASSERT_TRUE(rockarm.report.is_object());
  EXPECT_GT(rockarm.report["glyphs"]["num_clusters"].get<int>(), 10);
  EXPECT_LT(rockarm.report["glyphs"]["clusters"][0]["min_quality"].get<double>(), 0.0);
  expect_glyphs_match_vertices_csv(rockarm);
  // bunny_in: its barely inverted hex is in the worst cluster; bunny_out, optimized, has no glyph at all.
  const GlyphBundle in = analyze(meshes / "livesu2015_edgecone/bunny_in.mesh", "bunny_in");
  ASSERT_TRUE(in.report.is_object());
  EXPECT_EQ(in.report["glyphs"]["clusters"][0]["min_quality"], in.report["quality"]["vertex_quality"]["min"]);
  expect_glyphs_match_vertices_csv(in);
  const GlyphBundle out = analyze(meshes / "livesu2015_edgecone/bunny_out.mesh", "bunny_out");
  ASSERT_TRUE(out.report.is_object());
  EXPECT_EQ(out.report["glyphs"]["num_glyphs"], 0);
  EXPECT_EQ(out.report["glyphs"]["num_clusters"], 0);
}

}  // namespace
}  // namespace hq::test
