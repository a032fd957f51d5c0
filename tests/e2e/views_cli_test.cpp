// Every view through the CLI: each file report.json lists exists and is not
// blank, --views selects, --focus-vertex adds D/E views, bad values are usage
// errors; every real mesh of ../shared/data gets every view (small --size).

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <algorithm>
#include <array>
#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "hqview/image/colormap.h"
#include "support/fixtures.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

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
                                  "-o", out.string(), "--size", "480x240", "--views", "main,structure,local,compare"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // --compare keeps every view asked for (46r review M2), and the page says
  // which mesh its panels show.
  EXPECT_EQ(check_views(out, "compare"), (std::vector<std::string>{"main", "local", "compare", "structure"}));
  const std::string html = read_text(out / "index.html");
  for (const char* nav : {">A main</a>", ">S structure</a>", ">D local</a>", ">F reference</a>", ">Comparison</a>"})
    EXPECT_NE(html.find(nav), std::string::npos) << nav;
  EXPECT_NE(html.find("Panels A main, S structure and D local show ball.mesh only. twisted_bar.mesh is shown by its "
                      "boundary beside it in the compare view (panel F)"),
            std::string::npos);
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

// A copy of a MEDIT mesh with every vertex p -> f p + offset.
fs::path scaled_copy(const fs::path& mesh, double f, Vec3 offset, const fs::path& out) {
  std::istringstream in(read_text(mesh));
  std::ofstream o(out);
  std::string line;
  while (std::getline(in, line)) {
    o << line << "\n";
    if (line != "Vertices") continue;
    std::getline(in, line);
    o << line << "\n";
    const long n = std::stol(line);
    for (long i = 0; i < n; ++i) {
      double x, y, z;
      long ref;
      in >> x >> y >> z >> ref;
      o << std::setprecision(17) << f * x + offset.x << " " << f * y + offset.y << " " << f * z + offset.z << " "
        << ref << "\n";
    }
    std::getline(in, line);  // the rest of the last vertex line
  }
  return out;
}

// Model pixels (not the background) of the two halves of compare.png's view
// (the view is the left 0.76 of an 800-wide figure; the colour bar right of it).
std::array<long, 2> compare_half_pixels(const fs::path& png) {
  OIIO::ImageBuf image(png.string());
  EXPECT_TRUE(image.read()) << image.geterror();
  const int w = image.spec().width, h = image.spec().height;
  std::array<long, 2> count{0, 0};
  float bg[4], px[4];
  image.getpixel(w - 1, h - 1, bg, 3);
  for (int y = h / 8; y < h; ++y)
    for (int x = 0; x < static_cast<int>(0.76 * w); ++x) {
      image.getpixel(x, y, px, 3);
      if (std::abs(px[0] - bg[0]) + std::abs(px[1] - bg[1]) + std::abs(px[2] - bg[2]) > 0.05)
        ++count[x < static_cast<int>(0.38 * w) ? 0 : 1];
    }
  return count;
}

TEST(ViewsCli, CompareAlignsAMeshInAnotherFrameByBoundingBox) {
  const fs::path dir = fresh_output_dir("views/compare_align");
  // 50x larger and moved away: auto aligns, both halves show the ball alike.
  const fs::path big = scaled_copy(example("ball.mesh"), 50.0, {300, -100, 40}, dir / "ball50.mesh");
  const fs::path out = dir / "bundle";
  CliResult r = run_hqview({"analyze", example("ball.mesh").string(), "--compare", big.string(), "-o", out.string(),
                            "--size", "800x400", "--views", "compare"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  json a = json::parse(read_text(out / "report.json"))["compare"]["alignment"];
  EXPECT_EQ(a["mode"], "bbox");
  EXPECT_EQ(a["requested"], "auto");
  EXPECT_NEAR(a["scale"].get<double>(), 1.0 / 50.0, 1e-9);
  EXPECT_FALSE(a["boxes_overlap"].get<bool>());
  auto pixels = compare_half_pixels(out / "views/compare.png");
  ASSERT_GT(pixels[0], 1000);
  EXPECT_LT(std::max(pixels[0], pixels[1]), 1.5 * std::min(pixels[0], pixels[1])) << pixels[0] << " " << pixels[1];
  // Numbers stay in each mesh's own units: the copy's edges are 50 times as long.
  const json report = json::parse(read_text(out / "report.json"));
  EXPECT_NEAR(report["compare"]["mesh"]["edge_length"]["mean"].get<double>(),
              50.0 * report["mesh"]["edge_length"]["mean"].get<double>(),
              1e-9 * report["compare"]["mesh"]["edge_length"]["mean"].get<double>());
  // --compare-align none: the ball is a dot next to the big one.
  const fs::path raw = dir / "raw";
  r = run_hqview({"analyze", example("ball.mesh").string(), "--compare", big.string(), "-o", raw.string(), "--size",
                  "800x400", "--views", "compare", "--compare-align", "none"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(read_text(raw / "report.json"))["compare"]["alignment"]["mode"], "none");
  pixels = compare_half_pixels(raw / "views/compare.png");
  EXPECT_GT(pixels[1], 20 * pixels[0]) << pixels[0] << " " << pixels[1];

  // The same frame, 1.5x: not aligned, the right ball has about 2.25x the pixels.
  const fs::path larger = scaled_copy(example("ball.mesh"), 1.5, {0, 0, 0}, dir / "ball15.mesh");
  const fs::path same = dir / "same";
  r = run_hqview({"analyze", example("ball.mesh").string(), "--compare", larger.string(), "-o", same.string(),
                  "--size", "800x400", "--views", "compare"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  a = json::parse(read_text(same / "report.json"))["compare"]["alignment"];
  EXPECT_EQ(a["mode"], "none");
  EXPECT_DOUBLE_EQ(a["scale"].get<double>(), 1.0);
  EXPECT_NEAR(a["diagonal_ratio"].get<double>(), 1.5, 1e-9);
  pixels = compare_half_pixels(same / "views/compare.png");
  const double ratio = static_cast<double>(pixels[1]) / static_cast<double>(pixels[0]);
  EXPECT_NEAR(ratio, 2.25, 0.3) << pixels[0] << " " << pixels[1];
}

// A copy of a MEDIT mesh with every vertex p -> m p (m a 3x3 matrix, rows).
fs::path turned_copy(const fs::path& mesh, const std::array<std::array<double, 3>, 3>& m, const fs::path& out) {
  std::istringstream in(read_text(mesh));
  std::ofstream o(out);
  std::string line;
  while (std::getline(in, line)) {
    o << line << "\n";
    // "Vertices" then the count, or both on one line (kitten_1.mesh).
    if (!line.starts_with("Vertices")) continue;
    std::string count = line.substr(8);
    if (count.find_first_not_of(" \t\r") == std::string::npos) {
      std::getline(in, count);
      o << count << "\n";
    }
    const long n = std::stol(count);
    for (long i = 0; i < n; ++i) {
      double p[3];
      long ref;
      in >> p[0] >> p[1] >> p[2] >> ref;
      o << std::setprecision(17);
      for (int r = 0; r < 3; ++r) o << m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] << " ";
      o << ref << "\n";
    }
    std::getline(in, line);  // the rest of the last vertex line
  }
  return out;
}

// --compare-align auto (the default): a copy of a shared mesh turned 90
// degrees about x, and one turned 180 degrees about up (+z), is turned back;
// both halves of compare.png show the model alike; a mirrored copy is said.
TEST(ViewsCli, CompareTurnsACopyInAnotherAxisConventionBack) {
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data is absent";
  const fs::path dir = fresh_output_dir("views/compare_turn");
  const fs::path kitten = *data / "meshes/gao2016_sweeping/kitten_1.mesh";
  struct Case {
    const char* name;
    std::array<std::array<double, 3>, 3> m;
    const char* found;  // the rotation taking the copy back
  };
  for (const Case& c : {Case{"x90", {{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}}, "90 deg about -x"},
                        Case{"z180", {{{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}}}, "180 deg about +z"}}) {
    SCOPED_TRACE(c.name);
    const fs::path copy = turned_copy(kitten, c.m, dir / (std::string("kitten_") + c.name + ".mesh"));
    const fs::path out = dir / c.name;
    const CliResult r = run_hqview({"analyze", kitten.string(), "--compare", copy.string(), "-o", out.string(),
                                    "--size", "800x400", "--views", "compare"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json a = json::parse(read_text(out / "report.json"))["compare"]["alignment"];
    EXPECT_EQ(a["mode"], "rotation");
    EXPECT_EQ(a["axis_rotation"], c.found);
    EXPECT_LT(a["mean_distance"].get<double>(), 1e-3);
    EXPECT_GT(a["mean_distance_identity"].get<double>(), 0.02);
    EXPECT_FALSE(a["mirrored"].get<bool>());
    EXPECT_NE(a["description"].get<std::string>().find(std::string("turned ") + c.found), std::string::npos);
    const auto pixels = compare_half_pixels(out / "views/compare.png");
    ASSERT_GT(pixels[0], 1000);
    EXPECT_LT(std::max(pixels[0], pixels[1]), 1.3 * std::min(pixels[0], pixels[1])) << pixels[0] << " " << pixels[1];
  }
  // Mirrored across x: no rotation fits; said in report.json and the title.
  const fs::path mirrored = turned_copy(kitten, {{{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}, dir / "kitten_mirror.mesh");
  const fs::path out = dir / "mirror";
  const CliResult r = run_hqview({"analyze", kitten.string(), "--compare", mirrored.string(), "-o", out.string(),
                                  "--no-render"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json a = json::parse(read_text(out / "report.json"))["compare"]["alignment"];
  EXPECT_TRUE(a["mirrored"].get<bool>());
  EXPECT_LT(a["mean_distance_mirror"].get<double>(), 1e-3);
  EXPECT_NE(a["description"].get<std::string>().find("mirror image"), std::string::npos);
}

// index.html and summary.md of --compare hold both meshes' numbers side by
// side and their differences.
TEST(ViewsCli, ComparePagesHoldBothMeshesNumbers) {
  const fs::path out = fresh_output_dir("views/compare_pages") / "bundle";
  const CliResult r = run_hqview({"analyze", example("ball.mesh").string(), "--compare",
                                  example("twisted_bar.mesh").string(), "-o", out.string(), "--no-render"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = json::parse(read_text(out / "report.json"));
  const auto count = [](long long v) {  // thousands separators, as the pages show counts
    std::string d = std::to_string(v), o;
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (i > 0 && (d.size() - i) % 3 == 0) o += ',';
      o += d[i];
    }
    return o;
  };
  const long long h1 = report["headline"]["num_hexes"], h2 = report["compare"]["headline"]["num_hexes"];
  const std::string diff = (h2 - h1 > 0 ? "+" : "") + (h2 - h1 < 0 ? "-" + count(h1 - h2) : count(h2 - h1));
  const std::string html = read_text(out / "index.html"), md = read_text(out / "summary.md");
  const std::string row = "<tr><th scope=\"row\">hexahedra</th><td>" + count(h1) + "</td><td>" + count(h2) +
                          "</td><td>" + diff + "</td></tr>";
  EXPECT_NE(html.find(row), std::string::npos) << row;
  EXPECT_NE(html.find("<section id=\"compare\">"), std::string::npos);
  EXPECT_NE(md.find("| hexahedra | " + count(h1) + " | " + count(h2) + " | " + diff + " |"), std::string::npos) << md;
  EXPECT_NE(md.find("### Compared with twisted"), std::string::npos) << md;
  char sj[2][40];
  std::snprintf(sj[0], sizeof sj[0], "%.6g", report["quality"]["scaled_jacobian"]["min"].get<double>());
  std::snprintf(sj[1], sizeof sj[1], "%.6g", report["compare"]["quality"]["scaled_jacobian"]["min"].get<double>());
  const std::string sj_row = std::string("| min scaled Jacobian | ") + sj[0] + " | " + sj[1] + " | ";
  EXPECT_NE(md.find(sj_row), std::string::npos) << sj_row << "\n" << md;
  EXPECT_NE(html.find(std::string("<td>") + sj[0] + "</td><td>" + sj[1] + "</td>"), std::string::npos);
}

// A tall box of 2 x 2 x 12 unit hexes whose long side lies along `axis`
// (0: x, 1: y, 2: z), the edge vertex at mid-height pulled outwards so
// that glyphs exist.
fs::path tall_box(int axis, const fs::path& out) {
  const int n[3] = {axis == 0 ? 12 : 2, axis == 1 ? 12 : 2, axis == 2 ? 12 : 2};
  auto id = [&](int i, int j, int k) { return 1 + i + (n[0] + 1) * (j + (n[1] + 1) * k); };
  std::ofstream o(out);
  o << "MeshVersionFormatted 1\nDimension 3\nVertices\n" << (n[0] + 1) * (n[1] + 1) * (n[2] + 1) << "\n";
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) {
        const int c[3] = {i, j, k};
        bool pulled = true;
        for (int d = 0; d < 3; ++d) pulled = pulled && c[d] == (d == axis ? n[d] / 2 : n[d]);
        for (int d = 0; d < 3; ++d) o << c[d] + (pulled && d != axis ? 0.7 : 0.0) << (d < 2 ? " " : " 0\n");
      }
  o << "Hexahedra\n" << n[0] * n[1] * n[2] << "\n";
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        o << id(i, j, k) << " " << id(i + 1, j, k) << " " << id(i + 1, j + 1, k) << " " << id(i, j + 1, k) << " "
          << id(i, j, k + 1) << " " << id(i + 1, j, k + 1) << " " << id(i + 1, j + 1, k + 1) << " " << id(i, j + 1, k + 1)
          << " 0\n";
  o << "End\n";
  return out;
}

// The extent (width, height) in pixels of what is not background in the
// left `fraction` of a figure, below its title band.
std::array<int, 2> model_extent(const fs::path& png, double fraction) {
  OIIO::ImageBuf image(png.string());
  EXPECT_TRUE(image.read()) << image.geterror();
  const int w = image.spec().width, h = image.spec().height;
  float bg[4], px[4];
  image.getpixel(w - 1, h - 1, bg, 3);
  int x0 = w, x1 = -1, y0 = h, y1 = -1;
  for (int y = h / 10; y < h; ++y)
    for (int x = 0; x < static_cast<int>(fraction * w); ++x) {
      image.getpixel(x, y, px, 3);
      if (std::abs(px[0] - bg[0]) + std::abs(px[1] - bg[1]) + std::abs(px[2] - bg[2]) <= 0.05) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  return {x1 - x0 + 1, y1 - y0 + 1};
}

TEST(ViewsCli, UpKeepsATallBoxUprightInEveryView) {
  const fs::path dir = fresh_output_dir("views/upright");
  const char* names[3] = {"+x", "+y", "+z"};
  for (int axis : {0, 2}) {
    const fs::path box = tall_box(axis, dir / ("box" + std::to_string(axis) + ".mesh"));
    const fs::path out = dir / ("bundle" + std::to_string(axis));
    CliResult r = run_hqview({"analyze", box.string(), "-o", out.string(), "--size", "480x480", "--up",
                              names[axis], "--views", "overview,main,clusters,local", "--glyph-threshold", "0.1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json report = json::parse(read_text(out / "report.json"));
    Vec3 up{0, 0, 0};
    up[axis] = 1.0;
    int cameras = 0;
    for (const json& view : report["views"]) {
      ASSERT_EQ(view["cameras"].size(), view["files"].size());
      for (std::size_t i = 0; i < view["files"].size(); ++i) {
        const json& c = view["cameras"][i];
        if (c.is_null()) continue;
        ++cameras;
        const std::string file = view["files"][i];
        const auto e = c["eye"].get<std::vector<double>>(), t = c["target"].get<std::vector<double>>();
        const Vec3 back = normalized(Vec3{e[0] - t[0], e[1] - t[1], e[2] - t[2]});
        // The eye 15-35 degrees above the horizon, read from the camera itself.
        const double elevation = std::asin(dot(back, up)) * 180.0 / 3.14159265358979323846;
        EXPECT_GE(elevation, 15.0 - 1e-6) << file;
        EXPECT_LE(elevation, 35.0 + 1e-6) << file;
        EXPECT_NEAR(c["elevation_degrees"].get<double>(), elevation, 1e-9) << file;
        // The image's up direction leans towards the axis and the axis has no
        // sideways component: the box's long side is vertical in the image.
        const auto u = c["up"].get<std::vector<double>>();
        const Vec3 image_up{u[0], u[1], u[2]};
        EXPECT_GT(dot(image_up, up), 0.8) << file;
        EXPECT_NEAR(dot(normalized(cross(back, image_up)), up), 0.0, 1e-9) << file;
      }
    }
    EXPECT_GE(cameras, 5);  // overview, two main views, a cluster and a local view
    // Seen upright, the box is a tall shape in the overview and in view A
    // (their 3D areas: the left 60 % and 70 % of the figure).
    for (const char* file : {"views/overview.png", "views/main_1.png", "views/main_2.png"}) {
      const auto extent = model_extent(out / file, file[6] == 'o' ? 0.6 : 0.7);
      EXPECT_GT(extent[1], 2 * extent[0]) << file << ": " << extent[0] << " x " << extent[1];
    }
  }
}

// --up auto, the default: the armadillo (y-up, lying on its back with +z)
// is drawn with +y up and its report says so; with an axis given there is
// no up_auto key.
TEST(ViewsCli, UpAutoByDefaultStandsTheArmadilloOnItsFeet) {
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "no shared data";
  const fs::path mesh = *data / "meshes/livesu2016_skeleton/armadillo.mesh";
  const fs::path dir = fresh_output_dir("views/up_auto");
  CliResult r = run_hqview({"analyze", mesh.string(), "-o", (dir / "auto").string(), "--size", "320x240", "--views",
                            "overview", "--no-overlap", "--data", "none", "--no-viewer"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = json::parse(read_text(dir / "auto" / "report.json"));
  EXPECT_EQ(report["up_auto"]["axis"], "+y");
  EXPECT_TRUE(report["up_auto"]["from_data"].get<bool>());
  ASSERT_EQ(report["up_auto"]["candidates"].size(), 6u);
  EXPECT_EQ(report["up_auto"]["candidates"][1]["up"], "+y");
  EXPECT_TRUE(report["up_auto"]["candidates"][1]["rests"].get<bool>());
  const json& camera = report["views"][0]["cameras"][0];
  EXPECT_GT(camera["up"][1].get<double>(), 0.8);
  // The page's Inputs say which axis and why.
  const std::string html = read_text(dir / "auto" / "index.html");
  EXPECT_NE(html.find("up axis of the views</th><td class=\"text\">+y (--up auto: the pose it would rest in)"),
            std::string::npos);
  r = run_hqview(
      {"analyze", mesh.string(), "-o", (dir / "z").string(), "--up", "+z", "--no-render", "--no-overlap", "--data", "none"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(json::parse(read_text(dir / "z" / "report.json")).contains("up_auto"));
}

// A copy of an OFF surface with every vertex p -> f p + offset.
fs::path scaled_off_copy(const fs::path& off, double f, Vec3 offset, const fs::path& out) {
  return transformed_off_copy(
      off, [&](double x, double y, double z) { return std::array<double, 3>{f * x + offset.x, f * y + offset.y, f * z + offset.z}; },
      out);
}

TEST(ViewsCli, ReferenceAlignMovesAReferenceInAnotherFrame) {
  const fs::path dir = fresh_output_dir("views/reference_align");
  const fs::path far = scaled_off_copy(example("ball.off"), 50.0, {300, -100, 40}, dir / "ball50.off");
  // Default none: today's refusal, which now names the flag.
  CliResult r = run_hqview({"analyze", example("ball.mesh").string(), "--reference", far.string(), "-o",
                            (dir / "refused").string(), "--no-render"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("--reference-align bbox"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "refused" / "report.json"));
  // bbox: the reference is moved onto the mesh; the error matches the run
  // with the reference in place.
  r = run_hqview({"analyze", example("ball.mesh").string(), "--reference", far.string(), "--reference-align", "bbox",
                  "-o", (dir / "aligned").string(), "--no-render"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json aligned = json::parse(read_text(dir / "aligned" / "report.json"))["boundary_error"];
  EXPECT_EQ(aligned["reference_alignment"]["mode"], "bbox");
  EXPECT_EQ(aligned["reference_alignment"]["requested"], "bbox");
  const double scale = aligned["reference_alignment"]["scale"].get<double>();
  r = run_hqview({"analyze", example("ball.mesh").string(), "--reference", example("ball.off").string(), "-o",
                  (dir / "in_place").string(), "--no-render"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json in_place = json::parse(read_text(dir / "in_place" / "report.json"))["boundary_error"];
  EXPECT_EQ(in_place["reference_alignment"]["mode"], "none");
  // The ball's hex boundary and ball.off have nearly the same box: the
  // scale is 1/50 up to the boxes' difference.
  EXPECT_NEAR(scale * 50.0, 1.0, 0.02);
  EXPECT_NEAR(aligned["hausdorff"]["relative"].get<double>(), in_place["hausdorff"]["relative"].get<double>(),
              0.02 * in_place["hausdorff"]["relative"].get<double>() + 1e-3);
}

// Pixels of a figure's 3D area (the left 70 %, below the title) for which
// is_match(rgb in [0, 1]) holds.
template <class Match>
long count_pixels(const fs::path& png, Match is_match) {
  OIIO::ImageBuf image(png.string());
  EXPECT_TRUE(image.read()) << image.geterror();
  const int w = image.spec().width, h = image.spec().height;
  float px[4];
  long n = 0;
  for (int y = h / 10; y < h; ++y)
    for (int x = 0; x < static_cast<int>(0.7 * w); ++x) {
      image.getpixel(x, y, px, 3);
      n += is_match(px);
    }
  return n;
}

// Pixels within 10 of a colour in every channel (view A's cluster edges are
// drawn unlit in their colour).
long pixels_near(const fs::path& png, const Color& c) {
  return count_pixels(png, [&c](const float* px) {
    return std::abs(px[0] - c.r) <= 10 / 255.0 && std::abs(px[1] - c.g) <= 10 / 255.0 &&
           std::abs(px[2] - c.b) <= 10 / 255.0;
  });
}

// The 3D area's model pixels (not the white background) and, of those, the
// rows of the top `top` fraction of the model's height.
struct ModelPixels {
  long model = 0, coloured = 0;          // coloured: chroma (max - min channel) above 0.12
  long top_model = 0, top_inside = 0;    // top rows: model pixels, and "inside" blue ones (b > r + 0.2)
  long outside = 0;                      // red ones (r > b + 0.2)
  long top_marker = 0;                   // top rows: pixels of the max |error| ring (kWorstMarkerColor, 20 grey)
};
ModelPixels model_pixels(const fs::path& png, double top) {
  OIIO::ImageBuf image(png.string());
  EXPECT_TRUE(image.read()) << image.geterror();
  const int w = image.spec().width, h = image.spec().height;
  float px[4];
  auto is_model = [](const float* p) { return (1.0f - p[0]) + (1.0f - p[1]) + (1.0f - p[2]) > 0.03f; };
  int first = h, last = -1;
  for (int y = h / 10; y < h; ++y)
    for (int x = 0; x < static_cast<int>(0.7 * w); ++x) {
      image.getpixel(x, y, px, 3);
      if (is_model(px)) first = std::min(first, y), last = std::max(last, y);
    }
  ModelPixels m;
  const int top_end = first + static_cast<int>(top * (last - first));
  for (int y = h / 10; y < h; ++y)
    for (int x = 0; x < static_cast<int>(0.7 * w); ++x) {
      image.getpixel(x, y, px, 3);
      if (!is_model(px)) continue;
      ++m.model;
      m.coloured += std::max({px[0], px[1], px[2]}) - std::min({px[0], px[1], px[2]}) > 0.12f;
      m.outside += px[0] > px[2] + 0.2f;
      const float chroma = std::max({px[0], px[1], px[2]}) - std::min({px[0], px[1], px[2]});
      if (y <= top_end) {
        m.top_marker += std::abs(px[0] - 20.0f / 255) < 0.002f && chroma < 0.002f;
        // Dark neutral pixels are the marker's ring and label, not the
        // model: the diverging map's dark ends are saturated.
        if (chroma < 0.04f && std::max({px[0], px[1], px[2]}) < 0.5f) continue;
        ++m.top_model;
        m.top_inside += px[2] > px[0] + 0.2f;
      }
    }
  return m;
}

// kitten_1 against kitten.off (issue 43): its boundary vertices lie on the
// reference (0.27 % of the diagonal), its flat quads do not (5 %): the
// boundary view coloured per sample shows error colours over most of the
// model, where per-vertex colours were white; the reference view shows the
// ear tips the mesh cuts off in the "inside" blue.
// A surface mesh against a reference (issue 47): a cube-sphere of quads,
// radius 0.97, inside the unit icosphere of examples/ball.off, gets every
// boundary view (they were not drawn for surface meshes: a warning said so),
// worded for a surface mesh, its front view mostly coloured and nowhere
// "outside" (it lies inside its reference).
TEST(ViewsCli, SurfaceMeshAgainstAReferenceGetsTheBoundaryViews) {
  const fs::path dir = fresh_output_dir("views/surface_reference");
  const int n = 8;
  std::ostringstream obj;
  obj.precision(17);
  // Six n x n grids on the cube's faces, projected to the sphere; the
  // vertices of shared edges are written once per face and merged by
  // position below (an index map).
  std::vector<std::array<double, 3>> points;
  std::map<std::array<long, 3>, int> id_of;
  auto vertex = [&](std::array<double, 3> c) {
    const std::array<long, 3> key = {std::lround(c[0] * n), std::lround(c[1] * n), std::lround(c[2] * n)};
    if (const auto it = id_of.find(key); it != id_of.end()) return it->second;
    const double r = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    points.push_back({0.97 * c[0] / r, 0.97 * c[1] / r, 0.97 * c[2] / r});
    return id_of[key] = static_cast<int>(points.size());
  };
  std::vector<std::array<int, 4>> quads;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1})
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          std::array<int, 4> q;
          const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            std::array<double, 3> c;
            c[axis] = side;
            c[(axis + 1) % 3] = -1.0 + 2.0 * (i + di[k]) / n;
            c[(axis + 2) % 3] = -1.0 + 2.0 * (j + dj[k]) / n;
            q[side > 0 ? k : 3 - k] = vertex(c);  // outward
          }
          quads.push_back(q);
        }
  for (const auto& p : points) obj << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  for (const auto& q : quads) obj << "f " << q[0] << ' ' << q[1] << ' ' << q[2] << ' ' << q[3] << '\n';
  const fs::path mesh = dir / "cube_sphere.obj";
  std::ofstream(mesh) << obj.str();
  const fs::path out = dir / "bundle";
  const CliResult r = run_hqview({"analyze", mesh.string(), "--reference", example("ball.off").string(), "-o",
                                  out.string(), "--size", "640x480", "--no-viewer"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ids = check_views(out, "surface reference");
  for (const char* id : {"boundary_error", "reference_error", "uv_error", "uv_key", "reference_overlay",
                         "boundary_error_sorted", "boundary_area"})
    EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  const json report = json::parse(read_text(out / "report.json"));
  EXPECT_EQ(report["headline"]["num_cells_by_kind"]["quad"], 6 * n * n);
  for (const auto& w : report["warnings"]) EXPECT_EQ(w.get<std::string>().find("not drawn yet"), std::string::npos) << w;
  const std::string boundary = read_text(out / "boundary.html");
  EXPECT_NE(boundary.find("The signed distance of the surface mesh to the reference"), std::string::npos);
  EXPECT_EQ(boundary.find("hex boundary"), std::string::npos);
  EXPECT_NE(boundary.find("views/boundary_error_front.png"), std::string::npos);
  for (const auto& view : report["views"])
    EXPECT_EQ(view["title"].get<std::string>().find("hex boundary"), std::string::npos) << view["title"];
  const ModelPixels front = model_pixels(out / "views/boundary_error_front.png", 0.1);
  ASSERT_GT(front.model, 20000);
  EXPECT_GT(front.coloured, 0.4 * front.model) << front.coloured << " of " << front.model;
  EXPECT_LT(front.outside, 0.02 * front.model) << "the cube-sphere lies inside its reference";
}

TEST(ViewsCli, KittenBoundaryViewsShowTheErrorBetweenTheVertices) {
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data absent";
  const fs::path dir = fresh_output_dir("views/kitten_error");
  const fs::path kitten = *data / "meshes/gao2016_sweeping";
  const CliResult r = run_hqview({"analyze", (kitten / "kitten_1.mesh").string(), "--reference",
                                  (kitten / "kitten.off").string(), "-o", (dir / "out").string(), "--size", "640x480",
                                  "--views", "boundary_error,reference_error", "--no-viewer", "--no-overlap", "-j", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ModelPixels front = model_pixels(dir / "out/views/boundary_error_front.png", 0.1);
  ASSERT_GT(front.model, 20000);
  // Pixels far from the map's neutral: at least 40 % of the model's in the
  // front view, 15 % in the back (measured: 60 % and 24 %; per-vertex
  // colours gave 3 % and 0 %).
  EXPECT_GT(front.coloured, 0.4 * front.model) << front.coloured << " of " << front.model;
  const ModelPixels back = model_pixels(dir / "out/views/boundary_error_back.png", 0.1);
  EXPECT_GT(back.coloured, 0.15 * back.model) << back.coloured << " of " << back.model;
  // The reference: its top tenth (the ears, with the z axis up) mostly blue.
  const ModelPixels reference = model_pixels(dir / "out/views/reference_error_front.png", 0.1);
  ASSERT_GT(reference.top_model, 1000);
  EXPECT_GT(reference.top_inside, 0.6 * reference.top_model) << reference.top_inside << " of " << reference.top_model;
  // The marker of the largest |error| (reference -> mesh, 10.2 % of the
  // diagonal: a cut-off ear tip) is drawn on the ears.
  EXPECT_GT(reference.top_marker, 30) << "the max |error| ring on the ears";
  EXPECT_LT(reference.outside, 0.05 * reference.model) << "the kitten mesh lies mostly inside its reference";
  for (const char* f : {"views/reference_error_back.png", "views/boundary_error_back.png"})
    EXPECT_TRUE(fs::is_regular_file(dir / "out" / f)) << f;
}

TEST(ViewsCli, OnlyTheTopClustersWearTheirColoursInViewA) {
  // armadillo.mesh has 67 clusters; with K = 4 the first 4 palette colours
  // are on screen and the other 6 nowhere; with K = 0 no palette colour is
  // (every cluster neutral), so no unlabelled cluster ever wears one.
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data absent";
  const fs::path mesh = *data / "meshes/livesu2016_skeleton/armadillo.mesh";
  const fs::path dir = fresh_output_dir("views/cluster_pixels");
  for (int k : {4, 0}) {
    const fs::path out = dir / ("k" + std::to_string(k));
    CliResult r = run_hqview({"analyze", mesh.string(), "-o", out.string(), "--size", "800x600", "--views", "main",
                              "--top-clusters", std::to_string(k), "--no-overlap", "--up", "+y"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json glyphs = json::parse(read_text(out / "report.json"))["glyphs"];
    ASSERT_GT(glyphs["num_clusters"].get<long>(), 20);
    for (int i = 0; i < kLabelledClusterPaletteSize; ++i) {
      const long n = pixels_near(out / "views/main_1.png", labelled_cluster_color(i)) +
                     pixels_near(out / "views/main_2.png", labelled_cluster_color(i));
      // With labels on screen, the two dark palette entries (L* < 35) are
      // also reached by antialiased label text and by the shadowed side of
      // a lit labelled sphere; K = 0 checks them (no labels, no palette).
      const bool is_dark = cie_lightness(labelled_cluster_color(i)) < 35.0;
      if (i < k) {
        EXPECT_GT(n, 20) << "K=" << k << ": colour " << i << " missing";
      } else if (k == 0 || !is_dark) {
        EXPECT_EQ(n, 0) << "K=" << k << ": colour " << i << " drawn by an unlabelled cluster";
      }
    }
    EXPECT_GT(pixels_near(out / "views/main_1.png", neutral_cluster_color()), 20) << "K=" << k;
  }
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

// The colour of a singular edge after one or two layers of the translucent
// boundary veil (structure_views.cpp: grey 176,182,194 at alpha 56).
bool near_veiled(const float* px, Rgba8 line) {
  const double a = 56.0 / 255.0, veil[3] = {176, 182, 194};
  const double c[3] = {static_cast<double>(line.r), static_cast<double>(line.g), static_cast<double>(line.b)};
  for (int layers = 1; layers <= 2; ++layers) {
    bool close = true;
    for (int k = 0; k < 3; ++k) {
      double v = c[k];
      for (int l = 0; l < layers; ++l) v = v * (1 - a) + veil[k] * a;
      close = close && std::abs(px[k] * 255.0 - v) <= 12.0;
    }
    if (close) return true;
  }
  return false;
}

long veiled_pixels(const fs::path& png, Rgba8 line) {
  return count_pixels(png, [line](const float* px) { return near_veiled(px, line); });
}

TEST(ViewsCli, TheStructurePanelDrawsEachSingularClassInItsColour) {
  // fandisk.mesh (counted by the numpy oracle): interior valence 3 (1 edge)
  // and 5 (12), boundary valence 1 (169) and 3+ (38); no interior valence
  // 6+ or 1-2. Each present class shows its colour, the absent ones none.
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data absent";
  const fs::path out = fresh_output_dir("views/structure") / "bundle";
  const CliResult r = run_hqview({"analyze", (*data / "meshes/li2012_srf/fandisk.mesh").string(), "-o", out.string(),
                                  "--size", "800x600", "--views", "main,structure,size_gradation", "--no-overlap"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(check_views(out, "structure"), (std::vector<std::string>{"main", "structure", "size_gradation"}));
  const json report = json::parse(read_text(out / "report.json"));
  const json& by = report["structure"]["singular_edges_by_valence"];
  EXPECT_EQ(by["interior"], json::parse(R"({"3": 1, "5": 12})"));
  struct Class {
    Rgba8 color;
    bool present;
  };
  const Class classes[] = {{{0, 114, 178, 255}, true},    {{213, 94, 0, 255}, true},
                           {{204, 121, 167, 255}, false}, {{86, 180, 233, 255}, false},
                           {{0, 158, 115, 255}, true},    {{230, 159, 0, 255}, true}};
  for (std::size_t i = 0; i < std::size(classes); ++i) {
    const long n = veiled_pixels(out / "views/structure_1.png", classes[i].color) +
                   veiled_pixels(out / "views/structure_2.png", classes[i].color);
    if (classes[i].present) {
      EXPECT_GT(n, 10) << "class " << i;
    } else {
      EXPECT_EQ(n, 0) << "class " << i;
    }
  }
  // Two upright viewpoints at least 90 degrees of azimuth apart.
  const json& cameras = report["views"][1]["cameras"];
  ASSERT_EQ(report["views"][1]["id"], "structure");
  ASSERT_EQ(cameras.size(), 2u);
  for (const json& c : cameras) {
    EXPECT_GE(c["elevation_degrees"].get<double>(), 15.0 - 1e-9);
    EXPECT_LE(c["elevation_degrees"].get<double>(), 35.0 + 1e-9);
  }
  double gap = std::abs(cameras[0]["azimuth_degrees"].get<double>() - cameras[1]["azimuth_degrees"].get<double>());
  gap = gap > 180 ? 360 - gap : gap;
  EXPECT_GE(gap, 90.0 - 1e-9);
  // The size gradation from an upright three-quarter pose in perspective,
  // as the overview (46r review M4: a head-on orthographic view read flat).
  ASSERT_EQ(report["views"][2]["id"], "size_gradation");
  const json& g = report["views"][2]["cameras"][0];
  EXPECT_EQ(g["projection"], "perspective");
  EXPECT_NEAR(g["elevation_degrees"].get<double>(), 25.0, 1e-9);
  EXPECT_NEAR(std::fmod(g["azimuth_degrees"].get<double>() + 360.0, 90.0), 30.0, 1e-9);
  // Flat faces (46t review: lit side faces took colours the bar has not):
  // nearly every drawn pixel of the view is a colour of its bar (the
  // quality map), the rest the faint edges' blend.
  // (Every colour within 3 in RGB, L1, of a bar colour, as a set.)
  std::set<int> bar;
  for (int i = 0; i <= 2048; ++i) {
    const Rgba8 c = to_rgba8(sample_quality_map(i / 2048.0));
    for (int dr = -3; dr <= 3; ++dr)
      for (int dg = -3 + std::abs(dr); dg <= 3 - std::abs(dr); ++dg)
        for (int db = -3 + std::abs(dr) + std::abs(dg); db <= 3 - std::abs(dr) - std::abs(dg); ++db)
          if (std::min({c.r + dr, c.g + dg, c.b + db}) >= 0)
            bar.insert(((c.r + dr) << 20) | ((c.g + dg) << 10) | (c.b + db));
  }
  long drawn = 0, on_bar = 0;
  count_pixels(out / "views/size_gradation.png", [&](const float* px) {
    const int r = static_cast<int>(std::lround(255 * px[0])), gr = static_cast<int>(std::lround(255 * px[1])),
              b = static_cast<int>(std::lround(255 * px[2]));
    if (r == 255 && gr == 255 && b == 255) return false;
    ++drawn;
    on_bar += bar.count((r << 20) | (gr << 10) | b) ? 1 : 0;
    return false;
  });
  EXPECT_GT(drawn, 50000);
  EXPECT_GT(on_bar, 0.8 * drawn) << on_bar << " of " << drawn;
  // The max cell outlined and its label framed in magenta (204, 0, 204),
  // a colour of no gradation (46t2 review: the title's max was unmarked).
  long magenta = 0;
  count_pixels(out / "views/size_gradation.png", [&](const float* px) {
    magenta += std::lround(255 * px[0]) == 204 && std::lround(255 * px[1]) == 0 && std::lround(255 * px[2]) == 204;
    return false;
  });
  EXPECT_GT(magenta, 200);
  // On index.html, panel S after panel A.
  const std::string html = read_text(out / "index.html");
  const auto s = html.find("id=\"panel-s\"");
  ASSERT_NE(s, std::string::npos);
  EXPECT_LT(html.find("id=\"panel-a\""), s);
  EXPECT_LT(s, html.find("id=\"panel-b\""));
  EXPECT_NE(html.find("views/structure_1.png", s), std::string::npos);
  EXPECT_NE(html.find("views/size_gradation.png", s), std::string::npos);
  // The Structure table: report.json's counts, by valence.
  EXPECT_NE(html.find("<td class=\"text\">13 — valence 3: 1, valence 5: 12</td><td><code>structure.num_singular_edges_interior</code>"),
            std::string::npos);
  EXPECT_NE(html.find("<td class=\"text\">207 — valence 1: 169, valence 3: 38</td>"), std::string::npos);
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
