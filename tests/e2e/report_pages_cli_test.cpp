// The bundle's pages through the CLI: index.html, boundary.html and
// summary.md are written, byte-identical for any -j, escape a hostile mesh
// name, and -o is refused on a file or a foreign directory unless --force.
// (tests/browser opens the same pages in Chromium.)

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/fixtures.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

namespace fs = std::filesystem;

fs::path example(const std::string& name) { return source_dir() / "examples" / name; }

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> entries;
  for (const auto& e : fs::recursive_directory_iterator(dir)) entries.push_back(fs::relative(e.path(), dir).string());
  std::sort(entries.begin(), entries.end());
  return entries;
}

TEST(ReportPages, SameBytesForOneAndTwoThreadsWithViewsAndReference) {
  // Every view rendered (small), so the pages hold every panel, the chart B
  // links and boundary.html.
  const fs::path dir = fresh_output_dir("pages_threads");
  for (const char* j : {"1", "2"}) {
    const CliResult r =
        run_hqview({"analyze", "--data", "csv,vtu.zlib", example("ball.mesh").string(), "--reference", example("ball.off").string(), "-o",
                    (dir / j).string(), "-j", j, "--size", "320x240"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(listing(dir / "1"), listing(dir / "2"));
  for (const char* f : {"report.json", "data/cells.csv", "data/vertices.csv", "index.html", "boundary.html",
                        "summary.md", "style.css", "views/sorted_quality.svg", "viewer.html", "viewer/data.js"}) {
    EXPECT_TRUE(fs::is_regular_file(dir / "1" / f)) << f;
    EXPECT_EQ(read_text(dir / "1" / f), read_text(dir / "2" / f)) << f;
  }
  // -j1 draws every view on one thread, -j2 on two with two OSMesa
  // contexts: the images are the same bytes.
  std::size_t images = 0;
  for (const std::string& f : listing(dir / "1"))
    if (f.ends_with(".png")) {
      ++images;
      EXPECT_EQ(read_text(dir / "1" / f), read_text(dir / "2" / f)) << f;
    }
  EXPECT_GE(images, 15u);
}

TEST(ReportPages, EveryListedViewIsOnAPageAndSummaryLinksExist) {
  const fs::path out = fresh_output_dir("pages_views") / "bundle";
  const CliResult r = run_hqview({"analyze", "--data", "csv,vtu.zlib", example("ball.mesh").string(), "--reference", example("ball.off").string(),
                                  "-o", out.string(), "--size", "320x240"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(read_text(out / "report.json"));
  const std::string pages = read_text(out / "index.html") + read_text(out / "boundary.html");
  for (const auto& view : report["views"]) {
    if (view["id"] == "thumbnail") continue;  // for the batch index's comparison only (docs/contract.md)
    for (const auto& file : view["files"]) {
      const std::string f = file.get<std::string>();
      // A chart's PNG twin is for Markdown; its SVG is on the page.
      const bool has_svg_twin = f.ends_with(".png") && fs::exists(out / (f.substr(0, f.size() - 4) + ".svg"));
      if (!has_svg_twin) {
        EXPECT_NE(pages.find("src=\"" + f + "\""), std::string::npos) << f;
      }
    }
  }
  // Every relative link of summary.md names a file of the bundle.
  const std::string md = read_text(out / "summary.md");
  int links = 0;
  for (std::size_t p = md.find("]("); p != std::string::npos; p = md.find("](", p + 2)) {
    const std::string target = md.substr(p + 2, md.find(')', p) - p - 2);
    EXPECT_TRUE(fs::is_regular_file(out / target)) << target;
    ++links;
  }
  EXPECT_GE(links, 10);
  EXPECT_NE(md.find("(views/boundary_error_front.png)"), std::string::npos) << md;
  // Without --reference there is no boundary page, and nothing links to one.
  const fs::path plain = fresh_output_dir("pages_views") / "plain";
  ASSERT_EQ(run_hqview({"analyze", "--data", "csv,vtu.zlib", example("ball.mesh").string(), "-o", plain.string(), "--no-render"}).exit_code, 0);
  EXPECT_FALSE(fs::exists(plain / "boundary.html"));
  EXPECT_EQ(read_text(plain / "index.html").find("boundary.html"), std::string::npos);
  EXPECT_EQ(read_text(plain / "summary.md").find("boundary.html"), std::string::npos);
}

TEST(ReportPages, ScriptInTheMeshNameIsShownLiterallyInPagesAndMarkdown) {
  const fs::path dir = fresh_output_dir("pages_escape");
  const std::string name = "<script>window.x=1<img src=q onerror=alert(1)>\"it's\" & co.mesh";
  fs::create_directories(dir / "in");
  fs::copy_file(example("twisted_bar.mesh"), dir / "in" / name);
  const CliResult r = run_hqview({"analyze", "--data", "csv,vtu.zlib", (dir / "in" / name).string(), "--reference", example("ball.off").string(),
                                  "-o", (dir / "bundle").string(), "--no-render"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string escaped =
      "&lt;script&gt;window.x=1&lt;img src=q onerror=alert(1)&gt;&quot;it&apos;s&quot; &amp; co.mesh";
  for (const char* page : {"index.html", "boundary.html"}) {
    const std::string html = read_text(dir / "bundle" / page);
    // The one script is the template's lightbox (issue 45).
    const std::size_t script = html.find("<script");
    EXPECT_EQ(html.compare(script, 25, "<script id=\"hq-lightbox\">"), 0) << page;
    EXPECT_EQ(html.find("<script", script + 1), std::string::npos) << page;
    EXPECT_EQ(html.find("<img src=q"), std::string::npos) << page;
    EXPECT_NE(html.find("<span class=\"file\">" + escaped + "</span>"), std::string::npos) << page;
  }
  // Markdown: no raw < or > anywhere; the name backslash-escaped as
  // CommonMark reads it literally.
  const std::string md = read_text(dir / "bundle" / "summary.md");
  EXPECT_EQ(md.find('<'), std::string::npos) << md;
  EXPECT_EQ(md.find('>'), std::string::npos) << md;
  EXPECT_NE(
      md.find("## HQView: &lt;script&gt;window\\.x\\=1&lt;img src\\=q onerror\\=alert\\(1\\)&gt;\\\"it\\'s\\\" &amp; "
              "co\\.mesh\n"),
      std::string::npos)
      << md;
  // Nothing is written beside the bundle.
  std::vector<std::string> entries;
  for (const auto& e : fs::directory_iterator(dir)) entries.push_back(e.path().filename().string());
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<std::string>{"bundle", "in"}));
}

TEST(ReportPages, OutputOnAFileOrAForeignDirectoryNeedsForce) {
  const fs::path dir = fresh_output_dir("pages_output");
  std::ofstream(dir / "file.txt") << "keep me\n";
  const CliResult file =
      run_hqview({"analyze", "--data", "csv,vtu.zlib", example("ball.mesh").string(), "-o", (dir / "file.txt").string(), "--no-render"});
  EXPECT_EQ(file.exit_code, 2);
  EXPECT_NE(file.err.find("--force"), std::string::npos) << file.err;
  EXPECT_EQ(read_text(dir / "file.txt"), "keep me\n");
  // --force replaces the file with the bundle.
  const CliResult forced = run_hqview(
      {"analyze", "--data", "csv,vtu.zlib", example("ball.mesh").string(), "-o", (dir / "file.txt").string(), "--no-render", "--force"});
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "file.txt" / "report.json"));
  // A non-empty directory that is not a bundle is kept; a bundle is replaced.
  fs::create_directories(dir / "photos");
  std::ofstream(dir / "photos" / "cat.jpg") << "meow\n";
  EXPECT_EQ(
      run_hqview({"analyze", "--data", "csv,vtu.zlib", example("ball.mesh").string(), "-o", (dir / "photos").string(), "--no-render"}).exit_code,
      2);
  EXPECT_EQ(listing(dir / "photos"), std::vector<std::string>{"cat.jpg"});
  EXPECT_EQ(
      run_hqview({"analyze", "--data", "csv,vtu.zlib", example("twisted_bar.mesh").string(), "-o", (dir / "file.txt").string(), "--no-render"})
          .exit_code,
      0);
  // Nothing beside the outputs: no temporaries left.
  std::vector<std::string> entries;
  for (const auto& e : fs::directory_iterator(dir)) entries.push_back(e.path().filename().string());
  std::sort(entries.begin(), entries.end());
  EXPECT_EQ(entries, (std::vector<std::string>{"file.txt", "photos"}));
}


// Issue 45c: the same quantity under the same number everywhere, and each
// ambiguous one named. The twisted bar's 6 inverted hexes have no zero-length
// edge (degenerate hexes 0) but Verdict's condition is undefined (1e30) for
// them (quality.metrics.condition.num_degenerate 6); the per-hex, per-corner
// and per-vertex scaled Jacobian means differ. index.html's cards and metric
// table, summary.md and `hqview diff` must give report.json's values with
// labels that say which quantity each is.
TEST(ReportPages, CardsTablesAndDiffAgreeWithReportJsonAndNameTheirQuantity) {
  const fs::path dir = fresh_output_dir("pages_quantities");
  for (const char* mesh : {"ball.mesh", "twisted_bar.mesh"}) {
    const CliResult r = run_hqview({"analyze", example(mesh).string(), "--views", "histogram", "--no-viewer", "--data",
                                    "none", "-o", (dir / mesh).string(), "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const nlohmann::json report = nlohmann::json::parse(read_text(dir / "twisted_bar.mesh/report.json"));
  const nlohmann::json& q = report["quality"];
  ASSERT_EQ(q["scaled_jacobian"]["num_degenerate"], 0);
  ASSERT_GT(q["metrics"]["condition"]["num_degenerate"].get<int>(), 0);
  ASSERT_NE(q["scaled_jacobian"]["mean"], q["corner_scaled_jacobian"]["mean"]);

  // index.html: a card's value is the text before its label.
  const std::string html = read_text(dir / "twisted_bar.mesh/index.html");
  auto card = [&](const std::string& label) {
    const std::size_t at = html.find("</div><div class=\"label\">" + label + "</div>");
    EXPECT_NE(at, std::string::npos) << "no card " << label;
    if (at == std::string::npos) return std::string();
    const std::size_t from = html.rfind('>', at - 1) + 1;
    return html.substr(from, at - from);
  };
  EXPECT_NEAR(std::stod(card("mean scaled Jacobian (per hex)")), q["scaled_jacobian"]["mean"].get<double>(), 5e-6);
  EXPECT_NEAR(std::stod(card("min scaled Jacobian (per hex)")), q["scaled_jacobian"]["min"].get<double>(), 5e-6);
  EXPECT_EQ(card("degenerate hexes (a zero-length edge or axis)"), "0");
  // The metric table: condition's last cell, under "undefined" (its title: Verdict's 1e30).
  EXPECT_NE(html.find("Verdict returns 1e30 for the metric"), std::string::npos);
  EXPECT_NE(html.find(">undefined</th>"), std::string::npos);
  const std::size_t row = html.find("<th scope=\"row\">condition</th>");
  ASSERT_NE(row, std::string::npos);
  const std::size_t end = html.find("</tr>", row);
  const std::size_t last = html.rfind("<td>", end) + 4;
  EXPECT_EQ(html.substr(last, html.find("</td>", last) - last),
            std::to_string(q["metrics"]["condition"]["num_degenerate"].get<int>()));

  const std::string summary = read_text(dir / "twisted_bar.mesh/summary.md");
  EXPECT_NE(summary.find("| min scaled Jacobian (per hex) | mean scaled Jacobian (per hex) |"), std::string::npos);

  // hqview diff: the changed keys with report.json's values and, for the
  // ambiguous ones, their quantity.
  const CliResult d = run_hqview({"diff", (dir / "ball.mesh").string(), (dir / "twisted_bar.mesh").string()});
  const nlohmann::json base = nlohmann::json::parse(read_text(dir / "ball.mesh/report.json"));
  auto line_of = [&](const std::string& key) {
    const std::size_t at = d.out.find("\n" + key + ": ");
    EXPECT_NE(at, std::string::npos) << key << " not in\n" << d.out;
    return at == std::string::npos ? std::string() : d.out.substr(at + 1, d.out.find('\n', at + 1) - at - 1);
  };
  const std::string condition = line_of("quality.metrics.condition.num_degenerate");
  EXPECT_EQ(condition.substr(0, condition.find(" (")),
            "quality.metrics.condition.num_degenerate: " +
                std::to_string(base["quality"]["metrics"]["condition"]["num_degenerate"].get<int>()) + " -> " +
                std::to_string(q["metrics"]["condition"]["num_degenerate"].get<int>()));
  EXPECT_NE(condition.find("[hexes where Verdict's condition is undefined (1e30"), std::string::npos) << condition;
  EXPECT_NE(line_of("quality.corner_scaled_jacobian.mean").find("[per corner"), std::string::npos);
  EXPECT_NE(line_of("quality.vertex_quality.mean").find("[per vertex"), std::string::npos);
  EXPECT_NE(line_of("quality.scaled_jacobian.mean").find("[per hex"), std::string::npos);
  // The headline table's mean scaled Jacobian is the per-hex one, and says so.
  const std::size_t mean_row = d.out.find("  mean scaled Jacobian ");
  ASSERT_NE(mean_row, std::string::npos);
  std::istringstream cells(d.out.substr(mean_row + 23, d.out.find('\n', mean_row) - mean_row - 23));
  double baseline = 0.0, current = 0.0;
  cells >> baseline >> current;
  EXPECT_NEAR(baseline, base["quality"]["scaled_jacobian"]["mean"].get<double>(), 5e-6);
  EXPECT_NEAR(current, q["scaled_jacobian"]["mean"].get<double>(), 5e-6);
  EXPECT_NE(d.out.find("(scaled Jacobian: per hex"), std::string::npos);
}
}  // namespace
}  // namespace hq::test
