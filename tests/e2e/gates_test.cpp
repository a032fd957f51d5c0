// `--gate` and `--metrics` end to end, the headline, the metric columns of
// data/cells.csv, and on the real meshes of ../shared/data the report's
// statistics recomputed independently from cells.csv.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/fixtures.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kBall = (source_dir() / "examples" / "ball.mesh").string();

std::vector<std::string> lines_with(const std::string& text, const std::string& part) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start < text.size()) {
    const auto end = std::min(text.find('\n', start), text.size());
    const std::string line = text.substr(start, end - start);
    if (line.find(part) != std::string::npos) out.push_back(line);
    start = end + 1;
  }
  return out;
}

TEST(Gates, PassingRulesExitZeroAndAreReported) {
  const fs::path out = fresh_output_dir("gates_pass") / "bundle";
  const CliResult r = run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", out.string(), "--no-render", "--gate",
                                  "quality.num_degenerate==0", "--gate", "quality.metrics.skew.p95 <= 0.5"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json gates = read_report(out)["gates"];
  EXPECT_EQ(gates["passed"], true);
  ASSERT_EQ(gates["results"].size(), 2u);
  EXPECT_EQ(gates["results"][0]["rule"], "quality.num_degenerate==0");
  EXPECT_EQ(gates["results"][0]["value"], 0);
  EXPECT_EQ(gates["results"][1]["passed"], true);
  EXPECT_TRUE(lines_with(r.err, "gate failed").empty()) << r.err;
}

TEST(Gates, AFailingRuleExitsOneWritesTheBundleAndSaysWhichOnStderr) {
  const fs::path out = fresh_output_dir("gates_fail") / "bundle";
  // The ball has folded corners: 14 inverted hexes, min scaled Jacobian < 0.
  const CliResult r = run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", out.string(), "--no-render", "--quiet", "--gate",
                                  "quality.scaled_jacobian.min>=0.2", "--gate", "quality.num_inverted==0", "--gate",
                                  "quality.worst_cells.0.scaled_jacobian>-1", "--gate", "headline.num_hexes==1000"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json report = read_report(out);
  EXPECT_EQ(report["gates"]["passed"], false);
  const auto& results = report["gates"]["results"];
  ASSERT_EQ(results.size(), 4u);
  EXPECT_EQ(results[0]["value"], report["quality"]["scaled_jacobian"]["min"]);
  EXPECT_EQ(results[1]["value"].get<double>(), report["quality"]["num_inverted"].get<double>());
  EXPECT_EQ(results[2]["passed"], true);
  EXPECT_EQ(results[3]["passed"], true);
  // One line per failing rule, even with --quiet.
  const auto failed = lines_with(r.err, "gate failed");
  ASSERT_EQ(failed.size(), 2u) << r.err;
  EXPECT_NE(failed[0].find("quality.scaled_jacobian.min>=0.2"), std::string::npos);
  EXPECT_NE(failed[1].find("quality.num_inverted==0 (value 14)"), std::string::npos) << failed[1];
  const std::string html = read_text(out / "index.html");
  EXPECT_NE(html.find("Quality gates: failed"), std::string::npos);
  EXPECT_NE(html.find("quality.num_inverted==0"), std::string::npos);
}

TEST(Gates, BadRulesAndMissingKeysExitTwoWithoutABundle) {
  const fs::path dir = fresh_output_dir("gates_usage");
  const CliResult syntax =
      run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", (dir / "a").string(), "--no-render", "--gate", "quality.num_inverted=0"});
  EXPECT_EQ(syntax.exit_code, 2);
  EXPECT_NE(syntax.err.find("'=' is not an operator"), std::string::npos) << syntax.err;
  const CliResult missing = run_hqview(
      {"analyze", "--data", "csv,vtu.zlib", kBall, "-o", (dir / "b").string(), "--no-render", "--gate", "quality.scaled_jacobian.mn>=0.2"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("no 'mn' under 'quality.scaled_jacobian'"), std::string::npos) << missing.err;
  const CliResult null_value = run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", (dir / "c").string(), "--no-render", "--gate",
                                           "quality.metrics.volume.acceptable.1<=1"});
  EXPECT_EQ(null_value.exit_code, 2);
  EXPECT_NE(null_value.err.find("null"), std::string::npos) << null_value.err;
  const CliResult baseline = run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", (dir / "d").string(), "--no-render", "--gate",
                                         "quality.scaled_jacobian.min>=baseline-0.01"});
  EXPECT_EQ(baseline.exit_code, 2);
  for (const char* d : {"a", "b", "c", "d"}) EXPECT_FALSE(fs::exists(dir / d)) << d;
}

TEST(Metrics, SubsetKeepsTheCsvHeaderAndLeavesColumnsEmpty) {
  const fs::path dir = fresh_output_dir("metrics_subset");
  ASSERT_EQ(run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", (dir / "all").string(), "--no-render"}).exit_code, 0);
  const CliResult r =
      run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", (dir / "some").string(), "--no-render", "--metrics", "taper, skew"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = read_report(dir / "some");
  std::vector<std::string> names;  // in the file's order
  const auto ordered = nlohmann::ordered_json::parse(read_text(dir / "some" / "report.json"));
  for (const auto& [name, value] : ordered["quality"]["metrics"].items()) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"skew", "taper", "scaled_jacobian"}));
  const json full = read_report(dir / "all");
  EXPECT_EQ(report["quality"]["metrics"]["skew"], full["quality"]["metrics"]["skew"]);
  const auto all_rows = read_csv(dir / "all" / "data/cells.csv");
  const auto rows = read_csv(dir / "some" / "data/cells.csv");
  ASSERT_EQ(rows.size(), all_rows.size());
  EXPECT_EQ(rows[0], all_rows[0]);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i][column("skew")], all_rows[i][column("skew")]);
    EXPECT_EQ(rows[i][column("oddy")], "");
    EXPECT_NE(all_rows[i][column("oddy")], "");
  }
  EXPECT_EQ(run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", (dir / "bad").string(), "--metrics", "skew,aspect"}).exit_code, 2);
}

TEST(Metrics, HeadlineComesFirstAndCellsCsvHasEveryVerdictColumn) {
  const fs::path out = fresh_output_dir("headline") / "bundle";
  ASSERT_EQ(run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", out.string(), "--no-render"}).exit_code, 0);
  const std::string text = read_text(out / "report.json");
  const json report = json::parse(text);
  // (nlohmann::json sorts keys when parsing: the order is read from the text.)
  EXPECT_LT(text.find("\"tool\""), text.find("\"headline\""));
  EXPECT_LT(text.find("\"headline\""), text.find("\"input\""));
  const json& h = report["headline"];
  EXPECT_EQ(h["num_vertices"], report["mesh"]["num_vertices"]);
  EXPECT_EQ(h["num_hexes"], report["mesh"]["num_hexes"]);
  EXPECT_EQ(h["min_scaled_jacobian"], report["quality"]["scaled_jacobian"]["min"]);
  EXPECT_EQ(h["mean_scaled_jacobian"], report["quality"]["scaled_jacobian"]["mean"]);
  EXPECT_EQ(h["num_inverted"], report["quality"]["num_inverted"]);
  EXPECT_EQ(report["quality"]["num_inverted"], report["quality"]["scaled_jacobian"]["num_inverted"]);
  EXPECT_EQ(report["quality"]["num_degenerate"], report["quality"]["scaled_jacobian"]["num_degenerate"]);
  EXPECT_EQ(report["quality"]["metrics"].size(), 22u);

  // Verdict's order; scaled_jacobian is the second column, not repeated.
  std::vector<std::string> expected = {"cell", "scaled_jacobian"};
  for (int i = 0; i < 8; ++i) expected.push_back("corner_sj_" + std::to_string(i));
  for (const char* name : {"edge_ratio",
                           "max_edge_ratio",
                           "max_aspect_frobenius",
                           "med_aspect_frobenius",
                           "skew",
                           "taper",
                           "volume",
                           "stretch",
                           "diagonal",
                           "dimension",
                           "oddy",
                           "condition",
                           "jacobian",
                           "shear",
                           "shape",
                           "relative_size_squared",
                           "shape_and_size",
                           "shear_and_size",
                           "distortion",
                           "nodal_jacobian_ratio",
                           "equiangle_skew",
                           "inverted",
                           "degenerate",
                           "intersecting",
                           "size_gradation",
                           // The finite-element check's, empty without --simulate.
                           "fem_kappa",
                           "fem_lambda_max",
                           "fem_det_j_min",
                           "fem_det_j_max",
                           "fem_l2_error_share",
                           "fem_h1_error_share",
                           "fem_error_density",
                           // Where the cell is (issue 46): its kind and its number in the file.
                           "cell_type",
                           "source_index"})
    expected.push_back(name);
  EXPECT_EQ(read_csv(out / "data/cells.csv").at(0), expected);
  EXPECT_FALSE(report.contains("fem"));
  EXPECT_LT(text.find("\"edge_ratio\": {"), text.find("\"equiangle_skew\": {"));
}

// ---------------------------------------------------------------------------
// The report's statistics against an independent computation from cells.csv.

struct Recomputed {
  std::int64_t count = 0, degenerate = 0;
  double min = 0, max = 0, mean = 0, std = 0, p05 = 0, p50 = 0, p95 = 0, largest_magnitude = 0;
};

// numpy.percentile's default (linear between closest ranks).
double percentile(const std::vector<double>& sorted, double q) {
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(pos);
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (pos - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

Recomputed recompute(const std::vector<std::vector<std::string>>& rows, std::size_t column) {
  Recomputed r;
  std::vector<double> kept;
  long double sum = 0;  // in file order, in extended precision: independent of the report's summation
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double v = std::stod(rows[i].at(column));
    if (std::abs(v) >= 1e30) {
      ++r.degenerate;
      continue;
    }
    kept.push_back(v);
    sum += v;
    r.largest_magnitude = std::max(r.largest_magnitude, std::abs(v));
  }
  r.count = static_cast<std::int64_t>(kept.size());
  if (kept.empty()) return r;
  r.mean = static_cast<double>(sum / static_cast<long double>(kept.size()));
  long double squares = 0;
  for (double v : kept) squares += (v - r.mean) * (v - r.mean);
  r.std = std::sqrt(static_cast<double>(squares / static_cast<long double>(kept.size())));
  std::sort(kept.begin(), kept.end());
  r.min = kept.front();
  r.max = kept.back();
  r.p05 = percentile(kept, 0.05);
  r.p50 = percentile(kept, 0.50);
  r.p95 = percentile(kept, 0.95);
  return r;
}

class RealMeshStatistics : public ::testing::TestWithParam<const char*> {};

TEST_P(RealMeshStatistics, ReportMatchesCellsCsv) {
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data absent (set HQVIEW_DATA to run these)";
  const std::string relative = GetParam();
  const fs::path out = fresh_output_dir("stats/" + fs::path(relative).stem().string()) / "bundle";
  const CliResult r =
      run_hqview({"analyze", "--data", "csv,vtu.zlib", (*data / "meshes" / relative).string(), "-o", out.string(), "--no-render"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = read_report(out);
  const auto rows = read_csv(out / "data/cells.csv");
  ASSERT_EQ(rows.size(), report["mesh"]["num_hexes"].get<std::size_t>() + 1);
  const auto& header = rows[0];
  int checked = 0;
  for (const auto& [name, stats] : report["quality"]["metrics"].items()) {
    const auto column = static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
    ASSERT_LT(column, header.size()) << name;
    const Recomputed expected = recompute(rows, column);
    EXPECT_EQ(stats["count"], expected.count) << name;
    EXPECT_EQ(stats["num_degenerate"], expected.degenerate) << name;
    if (expected.count == 0) continue;
    const double tolerance = 1e-12 * expected.largest_magnitude;
    EXPECT_EQ(stats["min"].get<double>(), expected.min) << name;
    EXPECT_EQ(stats["max"].get<double>(), expected.max) << name;
    EXPECT_NEAR(stats["mean"].get<double>(), expected.mean, tolerance) << name;
    EXPECT_NEAR(stats["std"].get<double>(), expected.std, tolerance) << name;
    EXPECT_NEAR(stats["p05"].get<double>(), expected.p05, tolerance) << name;
    EXPECT_NEAR(stats["p50"].get<double>(), expected.p50, tolerance) << name;
    EXPECT_NEAR(stats["p95"].get<double>(), expected.p95, tolerance) << name;
    // The fraction inside Verdict's acceptable range (null = unbounded).
    const auto& range = stats["acceptable"];
    const double lo = range[0].is_null() ? -INFINITY : range[0].get<double>();
    const double hi = range[1].is_null() ? INFINITY : range[1].get<double>();
    std::int64_t inside = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const double v = std::stod(rows[i][column]);
      inside += std::abs(v) < 1e30 && v >= lo && v <= hi;
    }
    EXPECT_DOUBLE_EQ(stats["fraction_acceptable"].get<double>(),
                     static_cast<double>(inside) / static_cast<double>(expected.count))
        << name;
    ++checked;
  }
  EXPECT_EQ(checked, 22);
  // The headline's inverted count is the CSV's `inverted` column.
  const auto inverted = static_cast<std::size_t>(std::find(header.begin(), header.end(), "inverted") - header.begin());
  std::int64_t inverted_rows = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) inverted_rows += rows[i][inverted] == "1";
  EXPECT_EQ(report["headline"]["num_inverted"], inverted_rows);
}

INSTANTIATE_TEST_SUITE_P(Meshes, RealMeshStatistics,
                         ::testing::Values("dualsheet2019/rockarm.vtk", "livesu2015_edgecone/bunny_in.mesh",
                                           "gao2016_sweeping/Dolphin_padded.mesh", "smf2019/hex_cube_coarse.vtk"),
                         [](const auto& info) {
                           std::string name = fs::path(info.param).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(RealMeshGates, ExitCodesOnTheDefectsThePapersKnow) {
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data absent (set HQVIEW_DATA to run these)";
  const fs::path dir = fresh_output_dir("real_gates");
  // rockarm: 11 hexes with a negative corner, so at least 11 inverted cells.
  const CliResult rockarm =
      run_hqview({"analyze", "--data", "csv,vtu.zlib", (*data / "meshes/dualsheet2019/rockarm.vtk").string(), "-o", (dir / "rockarm").string(),
                  "--no-render", "--gate", "quality.num_inverted==0"});
  EXPECT_EQ(rockarm.exit_code, 1) << rockarm.err;
  EXPECT_GE(read_report(dir / "rockarm")["quality"]["num_inverted"].get<int>(), 11);
  // bunny_out: no inverted hex, every scaled Jacobian positive.
  const CliResult bunny = run_hqview({"analyze", "--data", "csv,vtu.zlib", (*data / "meshes/livesu2015_edgecone/bunny_out.mesh").string(), "-o",
                                      (dir / "bunny").string(), "--no-render", "--gate", "quality.num_inverted==0",
                                      "--gate", "quality.scaled_jacobian.min>0", "--metrics", "scaled_jacobian"});
  EXPECT_EQ(bunny.exit_code, 0) << bunny.err;
}

}  // namespace
}  // namespace hq::test

namespace hq::test {
namespace HQ_TEST_UNIT {

TEST(StructureGates, SingularityCountsGateLikeAnyNumber) {
  // The ball is a 10x10x10 grid warped into a sphere: its 12 box edges (120
  // edges of valence 1) lie on a smooth surface, where valence 2 is
  // expected, so all 120 are irregular. A rule that wants none fails with
  // exit 1, one that allows the count passes; a size-gradation rule reads
  // the statistics.
  const fs::path out = fresh_output_dir("gates_structure") / "bundle";
  CliResult r = run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", out.string(), "--no-render", "--quiet", "--gate",
                            "structure.num_irregular_edges_boundary==0"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json report = read_report(out);
  const auto count = report["structure"]["num_irregular_edges_boundary"].get<long>();
  EXPECT_EQ(count, 120);
  EXPECT_EQ(report["structure"]["num_singular_edges_interior"].get<long>(), 0);
  EXPECT_EQ(report["structure"]["num_singular_curves"].get<long>(), 12);
  EXPECT_EQ(report["gates"]["results"][0]["value"].get<long>(), count);
  r = run_hqview({"analyze", "--data", "csv,vtu.zlib", kBall, "-o", out.string(), "--no-render", "--quiet", "--gate",
                  "structure.num_irregular_edges_boundary<=" + std::to_string(count), "--gate",
                  "structure.size_gradation.max>=1"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(StructureGates, BatchAndDiffReadTheStructureKeys) {
  // Two examples: the ball (120 singular boundary edges) and the twisted bar
  // (88, counted by the numpy oracle structure.oracle). A batch gate on a
  // structure key fails the mesh over it (exit 1); diff prints the change.
  const fs::path dir = fresh_output_dir("gates_structure_batch");
  const std::string bar = (source_dir() / "examples" / "twisted_bar.mesh").string();
  std::ofstream(dir / "manifest.csv") << "mesh,label\n" << kBall << ",ball\n" << bar << ",bar\n";
  CliResult r = run_hqview({"batch", (dir / "manifest.csv").string(), "-o", (dir / "batch").string(), "--no-render",
                            "--quiet", "--gate", "structure.num_singular_edges_boundary<=100"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json index = json::parse(read_text(dir / "batch" / "index.json"));
  EXPECT_EQ(index["counts"]["gate_failed"], 1);
  for (const json& m : index["meshes"])
    EXPECT_EQ(m["status"], m["label"] == "ball" ? "gate_failed" : "ok") << m["label"];
  for (const auto& [name, path] : {std::pair{"ball", kBall}, std::pair{"bar", bar}})
    ASSERT_EQ(run_hqview({"analyze", "--data", "csv,vtu.zlib", path, "-o", (dir / name).string(), "--no-render", "--quiet"}).exit_code, 0);
  r = run_hqview({"diff", (dir / "ball").string(), (dir / "bar").string(), "--gate",
                  "structure.num_singular_edges_boundary<=baseline"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("structure.num_singular_edges_boundary: 120 -> 88"), std::string::npos) << r.out;
  r = run_hqview({"diff", (dir / "bar").string(), (dir / "ball").string(), "--gate",
                  "structure.num_singular_edges_boundary<=baseline"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
}

}  // namespace
}  // namespace hq::test
