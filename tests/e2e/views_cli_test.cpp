// Every view through the CLI: each file report.json lists exists and is not
// blank, --views selects, --focus-vertex adds D/E views, bad values are usage
// errors; every real mesh of ../shared/data gets every view (small --size).

#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/fixtures.h"

namespace hq::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path example(const std::string& name) { return source_dir() / "examples" / name; }

// Checks every listed file; returns the view ids.
std::vector<std::string> check_views(const fs::path& bundle, const std::string& what) {
  const json report = json::parse(read_text(bundle / "report.json"));
  std::vector<std::string> ids;
  for (const auto& view : report["views"]) {
    ids.push_back(view["id"]);
    EXPECT_FALSE(view["files"].empty()) << what << ": " << view["id"];
    for (const auto& file : view["files"]) {
      const fs::path path = bundle / file.get<std::string>();
      EXPECT_TRUE(fs::is_regular_file(path)) << what << ": " << path;
      if (!fs::is_regular_file(path)) continue;
      if (path.extension() == ".svg") {
        EXPECT_NE(read_text(path).find("<svg"), std::string::npos) << path;
        continue;
      }
      OIIO::ImageBuf image(path.string());
      EXPECT_TRUE(image.read()) << image.geterror();
      if (image.has_error()) continue;
      const auto pixels = OIIO::ImageBufAlgo::computePixelStats(image);
      // Not blank: some channel spans a wide range of values.
      double range = 0.0;
      for (int c = 0; c < 3; ++c) range = std::max(range, double(pixels.max[c] - pixels.min[c]));
      EXPECT_GT(range, 0.3) << what << ": " << path << " looks blank";
    }
  }
  return ids;
}

TEST(ViewsCli, EveryViewOfTheBallIsWrittenAndNotBlank) {
  const fs::path out = fresh_output_dir("views/ball") / "bundle";
  const CliResult r = run_hqview({"analyze", example("ball.mesh").string(), "-o", out.string(), "--size", "400x300",
                                  "--focus-vertex", "5", "--top-clusters", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ids = check_views(out, "ball");
  for (const char* id : {"overview", "main", "histogram", "sorted_quality"})
    EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  EXPECT_TRUE(fs::is_regular_file(out / "views/local_v5.png"));
  EXPECT_TRUE(fs::is_regular_file(out / "views/corners_v5.svg"));
  EXPECT_TRUE(fs::is_regular_file(out / "views/main_2.png")) << "two viewpoints";
  // The HTML shows charts as SVG and leaves their PNG twins to Markdown.
  const std::string html = read_text(out / "index.html");
  EXPECT_NE(html.find("views/sorted_quality.svg"), std::string::npos);
  EXPECT_EQ(html.find("views/sorted_quality.png"), std::string::npos);
}

TEST(ViewsCli, ReferenceAddsTheBoundaryChartsAndTheOverlay) {
  const fs::path out = fresh_output_dir("views/reference") / "bundle";
  const CliResult r = run_hqview({"analyze", example("ball.mesh").string(), "--reference", example("ball.off").string(),
                                  "-o", out.string(), "--size", "400x300"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ids = check_views(out, "reference");
  for (const char* id : {"boundary_error", "reference_overlay", "boundary_error_sorted", "boundary_area"})
    EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  for (const char* f : {"views/boundary_error_sorted.png", "views/boundary_area.png", "views/reference_overlay.png"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  // View F on index.html, the boundary views on boundary.html.
  const std::string html = read_text(out / "index.html"), boundary = read_text(out / "boundary.html");
  EXPECT_NE(boundary.find("views/boundary_error_sorted.svg"), std::string::npos);
  EXPECT_NE(boundary.find("views/boundary_area.svg"), std::string::npos);
  EXPECT_NE(html.find("views/reference_overlay.png"), std::string::npos);
}

TEST(ViewsCli, CompareAnalysesTheSecondMeshAndDrawsBothBoundaries) {
  const fs::path out = fresh_output_dir("views/compare") / "bundle";
  const CliResult r = run_hqview({"analyze", example("ball.mesh").string(), "--compare", example("twisted_bar.mesh").string(),
                                  "-o", out.string(), "--size", "480x240", "--views", "compare"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(check_views(out, "compare"), (std::vector<std::string>{"compare"}));
  const json report = json::parse(read_text(out / "report.json"));
  EXPECT_EQ(report["input"]["compare"]["path"], "twisted_bar.mesh");
  const json& c = report["compare"];
  ASSERT_TRUE(c.is_object());
  for (const char* part : {"headline", "mesh", "quality", "differences"}) EXPECT_TRUE(c.contains(part)) << part;
  const json& d = c["differences"];
  EXPECT_EQ(d["headline.num_hexes"].get<double>(),
            c["headline"]["num_hexes"].get<double>() - report["headline"]["num_hexes"].get<double>());
  EXPECT_DOUBLE_EQ(d["quality.scaled_jacobian.min"].get<double>(),
                   c["quality"]["scaled_jacobian"]["min"].get<double>() - report["quality"]["scaled_jacobian"]["min"].get<double>());
  EXPECT_TRUE(d.contains("quality.metrics.skew.mean"));
  // Without --compare: null.
  const fs::path plain = fresh_output_dir("views/compare_none") / "bundle";
  ASSERT_EQ(run_hqview({"analyze", example("ball.mesh").string(), "-o", plain.string(), "--no-render"}).exit_code, 0);
  EXPECT_TRUE(json::parse(read_text(plain / "report.json"))["compare"].is_null());
}

TEST(ViewsCli, ViewsSelectsAndRejectsUnknownIds) {
  const fs::path out = fresh_output_dir("views/select") / "bundle";
  CliResult r = run_hqview({"analyze", example("ball.mesh").string(), "-o", out.string(), "--size", "320x240",
                            "--views", "histogram,main"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(check_views(out, "select"), (std::vector<std::string>{"main", "histogram", "histogram_log"}));
  EXPECT_FALSE(fs::exists(out / "views/overview.png"));
  r = run_hqview({"analyze", example("ball.mesh").string(), "-o", out.string(), "--views", "bogus"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bogus"), std::string::npos) << r.err;
  r = run_hqview({"analyze", example("ball.mesh").string(), "-o", out.string(), "--size", "320x240",
                  "--focus-vertex", "99999"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("99999"), std::string::npos) << r.err;
}

class SharedViews : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedViews, EveryViewWithoutErrorNoneBlank) {
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data absent";
  const fs::path mesh = *data / "meshes" / GetParam();
  const fs::path out = fresh_output_dir("views/shared/" + mesh.stem().string()) / "bundle";
  std::vector<std::string> args = {"analyze", mesh.string(), "-o", out.string(), "--size", "320x240",
                                   "--top-clusters", "3"};
  const CliResult r = run_hqview(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ids = check_views(out, GetParam());
  EXPECT_GE(ids.size(), 5u);
}

INSTANTIATE_TEST_SUITE_P(Meshes, SharedViews,
                         ::testing::Values("gao2016_sweeping/kitten_1.mesh", "gao2016_sweeping/bunny_1.mesh",
                                           "gao2016_sweeping/hand7_1.mesh", "gao2016_sweeping/Dolphin_padded.mesh",
                                           "livesu2016_skeleton/armadillo.mesh", "livesu2016_skeleton/warrior.mesh",
                                           "livesu2015_edgecone/bunny_in.mesh", "livesu2015_edgecone/bunny_out.mesh",
                                           "li2012_srf/fandisk.mesh", "dualsheet2019/rockarm.vtk",
                                           "smf2019/hex_cube_coarse.vtk"),
                         [](const auto& info) {
                           std::string name = fs::path(info.param).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace hq::test
