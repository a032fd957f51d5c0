// The finite-element check end to end: --simulate and --metrics fem_element,
// the skipped check on the example with inverted hexes (exit 0, or a gate's
// 1), gates and diff on fem keys, batch passing --simulate through, and the
// same bytes for -j1 and -j2.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/fixtures.h"

namespace hq::test {
namespace {

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

}  // namespace
}  // namespace hq::test
