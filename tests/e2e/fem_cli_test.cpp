// The finite-element check end to end: --simulate and --metrics fem_element,
// the skipped check on the example with inverted hexes (exit 0, or a gate's
// 1), gates and diff on fem keys, batch passing --simulate through, and the
// same bytes for -j1 and -j2.

#include <gtest/gtest.h>

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

// An n x n x n box of side n as MEDIT; vertex (2, 2, 2) moved by `shift` along x.
fs::path write_box(const fs::path& path, int n, double shift) {
  std::ofstream f(path);
  const int m = n + 1;
  f << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << m * m * m << "\n";
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) f << i + (i == 2 && j == 2 && k == 2 ? shift : 0.0) << " " << j << " " << k << " 0\n";
  f << "Hexahedra\n" << n * n * n << "\n";
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int c = 1 + i + m * j + m * m * k;
        f << c << " " << c + 1 << " " << c + 1 + m << " " << c + m << " " << c + m * m << " " << c + 1 + m * m << " "
          << c + 1 + m + m * m << " " << c + m + m * m << " 0\n";
      }
  f << "End\n";
  return path;
}

TEST(FemCli, SimulateSolvesAndGates) {
  const fs::path dir = fresh_output_dir("fem_simulate");
  const std::string box = write_box(dir / "box.mesh", 6, 0.3).string();
  CliResult r =
      run_hqview({"analyze", box, "-o", (dir / "a").string(), "--no-render", "--simulate", "--data", "csv", "--quiet",
                  "--gate", "fem.poisson.mean.h1_error<=0.1", "--gate", "fem.element.num_invalid==0"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = read_report(dir / "a");
  const json& p = report["fem"]["poisson"];
  EXPECT_TRUE(p["skipped"].is_null());
  EXPECT_EQ(p["num_free_vertices"], 125);
  for (const char* s : {"exp_x", "exp_y", "exp_z"}) {
    EXPECT_TRUE(p["solutions"][s]["converged"].get<bool>()) << s;
    EXPECT_GT(p["solutions"][s]["l2_error"].get<double>(), 0) << s;
  }
  EXPECT_LE(p["stiffness"]["lambda_max"].get<double>(), p["stiffness"]["fried_bound"].get<double>());
  EXPECT_EQ(report["fem"]["element"]["kappa"]["count"], 216);
  EXPECT_TRUE(p["correlation"].contains("scaled_jacobian"));
  // The moved vertex's hexes are the worst: the densest cell uses it.
  const auto cells = read_csv(dir / "a" / "data/cells.csv");
  const auto& header = cells.at(0);
  const auto column =
      static_cast<std::size_t>(std::find(header.begin(), header.end(), "fem_error_density") - header.begin());
  ASSERT_LT(column, header.size());
  double share_sum = 0;
  const auto share =
      static_cast<std::size_t>(std::find(header.begin(), header.end(), "fem_h1_error_share") - header.begin());
  for (std::size_t i = 1; i < cells.size(); ++i) share_sum += std::stod(cells[i][share]);
  EXPECT_NEAR(share_sum, 1.0, 1e-9);
  // A failing rule on a fem key: exit 1.
  r = run_hqview({"analyze", box, "-o", (dir / "b").string(), "--no-render", "--simulate", "--quiet", "--gate",
                  "fem.poisson.mean.l2_error<=1e-9"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  // diff reads fem keys: the unperturbed box is better.
  const std::string regular = write_box(dir / "regular.mesh", 6, 0.0).string();
  ASSERT_EQ(
      run_hqview({"analyze", regular, "-o", (dir / "c").string(), "--no-render", "--simulate", "--quiet"}).exit_code,
      0);
  r = run_hqview({"diff", (dir / "a").string(), (dir / "c").string(), "--gate", "fem.poisson.mean.h1_error<=baseline"});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("fem.poisson.mean.h1_error"), std::string::npos) << r.out;
}

TEST(FemCli, InvalidElementsSkipTheSolveWithExitZero) {
  // The ball example holds inverted hexes: 7 of them have a Gauss-point det J <= 0.
  const fs::path dir = fresh_output_dir("fem_skipped");
  CliResult r = run_hqview({"analyze", kBall, "-o", (dir / "a").string(), "--no-render", "--simulate", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = read_report(dir / "a");
  EXPECT_EQ(report["fem"]["element"]["num_invalid"], 7);
  EXPECT_EQ(report["fem"]["poisson"]["skipped"],
            "7 hexes are not a valid trilinear element (a Gauss-point det J <= 0)");
  EXPECT_TRUE(report["fem"]["poisson"]["mean"]["h1_error"].is_null());
  r = run_hqview({"analyze", kBall, "-o", (dir / "b").string(), "--no-render", "--simulate", "--quiet", "--gate",
                  "fem.element.num_invalid==0"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
}

TEST(FemCli, ErrorDensityReferenceNeedsSimulate) {
  const fs::path dir = fresh_output_dir("fem_reference_alone");
  const CliResult r = run_hqview({"analyze", kBall, "-o", (dir / "a").string(), "--no-render", "--error-density-reference", "0.1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--error-density-reference: needs --simulate"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "a")) << "nothing written";
}

TEST(FemCli, MetricsFemElementAloneAndTheDefaultLeavesFemOut) {
  const fs::path dir = fresh_output_dir("fem_metrics");
  ASSERT_EQ(run_hqview({"analyze", kBall, "-o", (dir / "a").string(), "--no-render", "--metrics", "fem_element",
                        "--quiet", "--data", "csv"})
                .exit_code,
            0);
  const json report = read_report(dir / "a");
  EXPECT_EQ(report["quality"]["metrics"].size(), 1u);  // scaled_jacobian, always
  EXPECT_EQ(report["fem"]["element"]["kappa"]["count"], 993);
  EXPECT_TRUE(report["fem"]["poisson"].is_null());
  ASSERT_EQ(run_hqview({"analyze", kBall, "-o", (dir / "b").string(), "--no-render", "--quiet"}).exit_code, 0);
  EXPECT_FALSE(read_report(dir / "b").contains("fem"));
  const CliResult bad = run_hqview({"analyze", kBall, "-o", (dir / "c").string(), "--metrics", "fem_elements"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("choose from: all, "), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("fem_element"), std::string::npos) << bad.err;
}

TEST(FemCli, SameBytesForOneAndTwoThreadsAndBatchPassesSimulate) {
  const fs::path dir = fresh_output_dir("fem_threads");
  const std::string box = write_box(dir / "box.mesh", 9, 0.25).string();
  for (const char* j : {"1", "2"})
    ASSERT_EQ(run_hqview({"analyze", box, "-o", (dir / (std::string("j") + j)).string(), "--no-render", "--simulate",
                          "-j", j, "--quiet", "--data", "csv,vtu.zlib"})
                  .exit_code,
              0);
  for (const char* file : {"report.json", "data/cells.csv", "data/annotated.vtu"})
    EXPECT_EQ(read_text(dir / "j1" / file), read_text(dir / "j2" / file)) << file;
  std::ofstream(dir / "manifest.csv") << "mesh,label\n" << box << ",box\n";
  ASSERT_EQ(run_hqview({"batch", (dir / "manifest.csv").string(), "-o", (dir / "batch").string(), "--no-render",
                        "--simulate", "--quiet"})
                .exit_code,
            0);
  const json index = json::parse(read_text(dir / "batch" / "index.json"));
  const std::string bundle = index["meshes"][0]["bundle"].get<std::string>();
  EXPECT_EQ(read_report(dir / "batch" / bundle)["fem"], read_report(dir / "j1")["fem"]);
}

// --simulate draws panel P's two charts (views fem_correlation and
// fem_error_scatter: report.json views, the files, index.html's panel);
// without it they are left out.
TEST(FemCli, SimulateDrawsPanelP) {
  const fs::path dir = fresh_output_dir("fem_views");
  const std::string box = write_box(dir / "box.mesh", 6, 0.3).string();
  ASSERT_EQ(run_hqview({"analyze", box, "-o", (dir / "a").string(), "--simulate", "--views",
                        "fem_correlation,fem_error_scatter,fem_error_density,histogram", "--quiet", "-j1"})
                .exit_code,
            0);
  const json report = read_report(dir / "a");
  std::vector<std::string> ids;
  for (const json& v : report["views"]) ids.push_back(v["id"].get<std::string>());
  EXPECT_EQ(ids, (std::vector<std::string>{"histogram", "histogram_log", "fem_correlation", "fem_error_scatter",
                                           "fem_error_density"}));
  // The 3D error density view: two figures with their cameras, the same
  // bytes for -j1 and -j2, and a field of the viewer.
  EXPECT_EQ(report["views"][4]["files"],
            json::array({"views/fem_error_density.png", "views/fem_error_density_cells.png"}));
  EXPECT_FALSE(report["views"][4]["cameras"][0].is_null());
  ASSERT_EQ(run_hqview({"analyze", box, "-o", (dir / "a2").string(), "--simulate", "--views", "fem_error_density",
                        "--quiet", "-j2"})
                .exit_code,
            0);
  for (const char* f : {"views/fem_error_density.png", "views/fem_error_density_cells.png", "viewer/data.js"})
    EXPECT_EQ(read_text(dir / "a" / f), read_text(dir / "a2" / f)) << f << " differs between -j1 and -j2";
  EXPECT_NE(read_text(dir / "a/viewer/data.js").find("\"id\":\"fem_error_density\""), std::string::npos);
  for (const char* f : {"views/fem_correlation.svg", "views/fem_correlation.png", "views/fem_error_scatter.svg",
                        "views/fem_error_scatter.png"})
    EXPECT_TRUE(fs::exists(dir / "a" / f)) << f;
  // The chart names the metrics the report correlates.
  const std::string svg = read_text(dir / "a/views/fem_correlation.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  const std::string html = read_text(dir / "a/index.html");
  EXPECT_NE(html.find("id=\"panel-p\""), std::string::npos);
  EXPECT_NE(html.find("views/fem_error_scatter.svg"), std::string::npos);
  ASSERT_EQ(run_hqview({"analyze", box, "-o", (dir / "b").string(), "--views", "fem_correlation,histogram", "--quiet"})
                .exit_code,
            0);
  const json plain = read_report(dir / "b");
  ASSERT_EQ(plain["views"].size(), 2u);  // histogram, histogram_log
  EXPECT_EQ(plain["views"][0]["id"], "histogram");
  EXPECT_EQ(read_text(dir / "b/index.html").find("panel-p"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "b/views/fem_error_density.png"));
  EXPECT_EQ(read_text(dir / "b/viewer/data.js").find("fem_error_density"), std::string::npos);
}

// Spearman's rho written here (average ranks, Pearson of the ranks), not the library's.
double test_spearman(const std::vector<double>& x, const std::vector<double>& y) {
  const auto ranks = [](const std::vector<double>& v) {
    std::vector<double> r(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
      double below = 0, equal = 0;
      for (double w : v) below += w < v[i], equal += w == v[i];
      r[i] = below + (equal + 1) / 2;
    }
    return r;
  };
  const std::vector<double> a = ranks(x), b = ranks(y);
  const double mean = (static_cast<double>(x.size()) + 1) / 2;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - mean) * (b[i] - mean);
    saa += (a[i] - mean) * (a[i] - mean);
    sbb += (b[i] - mean) * (b[i] - mean);
  }
  return sab / std::sqrt(saa * sbb);
}

// Batch with --simulate: the fem headline keys in index.json, index.html,
// comparison.csv and --compare-keys; each mesh's metric min/mean and the
// collection's Spearman correlations (checked against the bundles' own
// values and a rank correlation written here); a method with fewer than 5
// meshes gets nulls; diff gates on fem keys of two indexes; a batch without
// --simulate has none of it.
TEST(FemCli, BatchCorrelatesErrorsWithMetricsAcrossMeshes) {
  const fs::path dir = fresh_output_dir("fem_collection");
  const double shifts[] = {0.0, 0.1, 0.2, 0.3, 0.35, 0.4};
  std::ofstream manifest(dir / "manifest.csv");
  manifest << "mesh,label,model\n";
  for (int i = 0; i < 6; ++i) {
    const fs::path mesh = write_box(dir / ("box" + std::to_string(i) + ".mesh"), 6, shifts[i]);
    manifest << mesh.string() << "," << (i < 3 ? "a" : "b") << ",m" << i % 3 << "\n";
  }
  manifest.close();
  CliResult r = run_hqview({"batch", (dir / "manifest.csv").string(), "-o", (dir / "sim").string(), "--no-render",
                            "--simulate", "--quiet", "--compare-keys",
                            "quality.scaled_jacobian.min,fem.poisson.mean.h1_error,fem.poisson.scaled_matrix.condition"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json index = json::parse(read_text(dir / "sim" / "index.json"));
  ASSERT_EQ(index["meshes"].size(), 6u);
  std::vector<double> l2, h1, sj_min, sj_mean, er_max, hexes;
  for (const json& m : index["meshes"]) {
    const json report = read_report(dir / "sim" / m["bundle"].get<std::string>());
    EXPECT_EQ(m["headline"]["fem.poisson.mean.h1_error"], report["fem"]["poisson"]["mean"]["h1_error"]);
    EXPECT_EQ(m["headline"]["fem.poisson.mean.l2_error"], report["fem"]["poisson"]["mean"]["l2_error"]);
    EXPECT_EQ(m["headline"]["fem.poisson.scaled_matrix.condition"], report["fem"]["poisson"]["scaled_matrix"]["condition"]);
    EXPECT_EQ(m["headline"]["fem.element.num_invalid"], 0);
    EXPECT_EQ(m["metrics"]["scaled_jacobian"]["min"], report["quality"]["metrics"]["scaled_jacobian"]["min"]);
    EXPECT_EQ(m["metrics"]["fem_kappa"]["mean"], report["fem"]["element"]["kappa"]["mean"]);
    EXPECT_NEAR(m["metrics"]["h_over_l"]["mean"].get<double>(),
                std::cbrt(report["quality"]["metrics"]["volume"]["mean"].get<double>()) /
                    report["fem"]["poisson"]["mesh_length"].get<double>(),
                1e-15);
    // L: the diagonal of the box with the mesh's second moments. A moved
    // interior vertex leaves the domain, the 6^3 box, as it is: 6 sqrt 3 (to
    // the 2x2x2 Gauss rule's error on the distorted hexes).
    EXPECT_NEAR(report["fem"]["poisson"]["mesh_length"].get<double>(), std::sqrt(3.0) * 6, 1e-3);
    // Each hex's rho has its 95 % interval around it.
    const json& sj_rho = report["fem"]["poisson"]["correlation"]["scaled_jacobian"];
    const json& sj_interval = report["fem"]["poisson"]["correlation_interval"]["scaled_jacobian"];
    const json& sj_adjusted = report["fem"]["poisson"]["correlation_interval_adjusted"]["scaled_jacobian"];
    if (sj_rho.is_number()) {
      EXPECT_LT(sj_interval[0].get<double>(), sj_rho.get<double>());
      EXPECT_GT(sj_interval[1].get<double>(), sj_rho.get<double>());
      // Simultaneous over the verdict family: wider.
      EXPECT_GT(report["fem"]["poisson"]["correlation_verdict_family"].get<int>(), 1);
      EXPECT_LT(sj_adjusted[0].get<double>(), sj_interval[0].get<double>());
      EXPECT_GT(sj_adjusted[1].get<double>(), sj_interval[1].get<double>());
    }
    l2.push_back(report["fem"]["poisson"]["mean"]["l2_error"].get<double>());
    h1.push_back(report["fem"]["poisson"]["mean"]["h1_error"].get<double>());
    sj_min.push_back(report["quality"]["metrics"]["scaled_jacobian"]["min"].get<double>());
    sj_mean.push_back(report["quality"]["metrics"]["scaled_jacobian"]["mean"].get<double>());
    er_max.push_back(report["quality"]["metrics"]["edge_ratio"]["max"].get<double>());
    EXPECT_EQ(m["metrics"]["edge_ratio"]["max"], report["quality"]["metrics"]["edge_ratio"]["max"]);
    hexes.push_back(report["mesh"]["num_hexes"].get<double>());
  }
  // The more the vertex moves, the larger the error and the lower the min SJ.
  EXPECT_LT(h1.front(), h1.back());
  const json& c = index["fem_correlation"];
  EXPECT_EQ(c["num_meshes"], 6);
  EXPECT_EQ(c["min_meshes"], 5);
  // Six distinct boxes: no duplicate; the smallest p 2/6!, the critical |rho| 31/35.
  EXPECT_TRUE(c["duplicates"].empty());
  EXPECT_NEAR(c["min_p"].get<double>(), 2.0 / 720.0, 1e-15);
  EXPECT_NEAR(c["critical_rho"].get<double>(), 31.0 / 35.0, 1e-12);
  bool seen_min = false, seen_mean = false, seen_edge_ratio = false, seen_baseline = false;
  for (const json& row : c["metrics"]) {
    // The worst of a lower-is-better metric is its max (the first version
    // took every metric's min: the best hex of edge_ratio).
    if (row["metric"] == "edge_ratio" && row["stat"] == "worst") {
      seen_edge_ratio = true;
      EXPECT_EQ(row["direction"], "lower is better");
      EXPECT_NEAR(row["rho_h1_error"].get<double>(), test_spearman(er_max, h1), 1e-12);
    }
    if (row["metric"] == "num_hexes") {
      seen_baseline = true;
      EXPECT_EQ(row["stat"], "count");
      EXPECT_TRUE(row["rho_h1_error"].is_null());  // every box has 216 hexes: constant
    }
    if (row["metric"] != "scaled_jacobian") continue;
    EXPECT_EQ(row["direction"], "higher is better");
    // Exact permutation p of 6 meshes: a multiple of 1/720, at least 2/720.
    if (row["p_h1_error"].is_number()) {
      const double p = row["p_h1_error"].get<double>() * 720;
      EXPECT_NEAR(p, std::round(p), 1e-9);
      EXPECT_GE(p, 2 - 1e-9);
    }
    const bool is_min = row["stat"] == "worst";
    (is_min ? seen_min : seen_mean) = true;
    EXPECT_EQ(row["num_meshes"], 6);
    EXPECT_NEAR(row["rho_l2_error"].get<double>(), test_spearman(is_min ? sj_min : sj_mean, l2), 1e-12);
    EXPECT_NEAR(row["rho_h1_error"].get<double>(), test_spearman(is_min ? sj_min : sj_mean, h1), 1e-12);
  }
  EXPECT_TRUE(seen_min && seen_mean && seen_edge_ratio && seen_baseline);
  // q: Benjamini-Hochberg over the family's p (recomputed here from the p's):
  // the rows that are their own hypothesis; a restating row (mean volume /
  // L^3 restates h_over_l) carries the restated row's q.
  std::vector<std::pair<double, double>> pq;  // (p, q) of the H1 column
  for (const json& row : c["metrics"]) {
    if (!row["restates"].is_null()) {
      for (const json& other : c["metrics"]) {
        if (other["metric"] == row["restates"]) {
          EXPECT_EQ(row["q_h1_error"], other["q_h1_error"]);
        }
      }
      continue;
    }
    if (row["p_h1_error"].is_number()) pq.push_back({row["p_h1_error"].get<double>(), row["q_h1_error"].get<double>()});
    else EXPECT_TRUE(row["q_h1_error"].is_null());
  }
  EXPECT_EQ(c["num_hypotheses_h1_error"].get<std::size_t>(), pq.size());
  std::sort(pq.begin(), pq.end());
  for (std::size_t i = 0; i < pq.size(); ++i) {
    double expected = 1.0;
    for (std::size_t j = i; j < pq.size(); ++j)
      expected = std::min(expected, pq[j].first * static_cast<double>(pq.size()) / static_cast<double>(j + 1));
    EXPECT_NEAR(pq[i].second, expected, 1e-12) << i;
  }
  EXPECT_LT(test_spearman(sj_min, h1), -0.5);  // the min SJ mostly ranks these meshes by their error
  // A method of 3 meshes: too few, every rho null.
  for (const json& m : index["methods"]) {
    EXPECT_EQ(m["fem_correlation"]["num_meshes"], 3);
    for (const json& row : m["fem_correlation"]["metrics"]) EXPECT_TRUE(row["rho_h1_error"].is_null()) << row;
  }
  const std::string html = read_text(dir / "sim" / "index.html");
  EXPECT_NE(html.find("Which metrics rank these meshes by their simulation error"), std::string::npos);
  // Said plainly, by hand from index.json: m rows at best p_min each give the
  // k-th of them q = p_min m / k (Benjamini-Hochberg), so q < 0.05 needs
  // k > 20 m p_min rows together (m: the family, the restated row out).
  {
    const json& fc = index["fem_correlation"];
    const double spread = fc["num_hypotheses_h1_error"].get<double>() * fc["min_p"].get<double>();
    ASSERT_GT(spread, 0.05);
    const int needed = static_cast<int>(std::floor(spread / 0.05)) + 1;
    EXPECT_NE(html.find("The Benjamini\u2013Hochberg family: the " +
                        std::to_string(fc["num_hypotheses_h1_error"].get<int>()) + " rows that are their own hypothesis"),
              std::string::npos);
    EXPECT_NE(html.find("A row reaches q &lt; 0.05 only when at least " + std::to_string(needed) + " rows reach p = "),
              std::string::npos)
        << needed;
  }
  EXPECT_NE(html.find("<table class=\"sortable\" id=\"fem-meshes\">"), std::string::npos);
  EXPECT_NE(html.find("<th>FEM H1 error (rel., semi-norm)</th>"), std::string::npos);
  EXPECT_NE(html.find("FEM cond. (Jacobi)"), std::string::npos);  // a --compare-keys table
  EXPECT_NE(read_text(dir / "sim" / "comparison.csv").find(",fem.poisson.mean.h1_error,"), std::string::npos);
  // diff of two indexes gates on fem keys.
  r = run_hqview({"diff", (dir / "sim" / "index.json").string(), (dir / "sim" / "index.json").string(), "--gate",
                  "fem.poisson.mean.h1_error<=baseline", "--gate", "fem.poisson.mean.l2_error<=1e-12"});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;  // every mesh passes the first and fails the second
  EXPECT_NE(r.out.find("fem.poisson.mean.l2_error<=1e-12"), std::string::npos) << r.out;
  // Shards merged: the same index.json bytes (the rows' metrics read back).
  for (const char* shard : {"1/2", "2/2"})
    ASSERT_EQ(run_hqview({"batch", (dir / "manifest.csv").string(), "-o", (dir / (std::string("s") + shard[0])).string(),
                          "--no-render", "--simulate", "--quiet", "--shard", shard})
                  .exit_code,
              0);
  ASSERT_EQ(run_hqview({"merge", (dir / "s1").string(), (dir / "s2").string(), "-o", (dir / "merged").string()}).exit_code,
            0);
  EXPECT_EQ(read_text(dir / "merged" / "index.json"), read_text(dir / "sim" / "index.json"));
  // Without --simulate: no metrics per row, no correlation, no fem columns.
  ASSERT_EQ(run_hqview({"batch", (dir / "manifest.csv").string(), "-o", (dir / "plain").string(), "--no-render",
                        "--quiet"})
                .exit_code,
            0);
  const json plain = json::parse(read_text(dir / "plain" / "index.json"));
  EXPECT_FALSE(plain.contains("fem_correlation"));
  EXPECT_FALSE(plain["meshes"][0].contains("metrics"));
  EXPECT_TRUE(plain["meshes"][0]["headline"]["fem.poisson.mean.h1_error"].is_null());
  EXPECT_EQ(read_text(dir / "plain" / "index.html").find("FEM H1 error"), std::string::npos);
}

}  // namespace
}  // namespace hq::test
