// `batch` without the analysis: manifests, shards, the index (JSON round trip,
// HTML escaping, Markdown) and the exit code.

#include "hqview/pipeline/batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "hqview/analysis/limitations.h"
#include "hqview/core/error.h"
#include "hqview/report/batch_index.h"
#include "io/temp_dir.h"

#include <nlohmann/json.hpp>

namespace hq {
namespace HQ_TEST_UNIT {

BatchEntry entry(const std::string& path, BatchStatus status, const std::string& label = "", double min_sj = 0.5) {
  BatchEntry e;
  e.path = path;
  e.label = label;
  e.model = path;
  e.status = status;
  if (status == BatchStatus::failed) {
    e.error = path + ":3: expected 8 vertex ids, got 7";
  } else {
    e.bundle = path;
    e.sha256 = "abc";
    e.headline[0] = 8;
    e.headline[1] = 1;
    e.headline[2] = min_sj;
    e.headline[3] = 0.75;
  }
  if (status == BatchStatus::gate_failed) e.failed_gates = {"quality.scaled_jacobian.min>=0.9"};
  return e;
}

TEST(Collection, PolygonFilesAreSurfaceMeshesUnlessBesideVolumeMeshes) {
  // quads/: surface meshes only (picked, any case); hex/: a volume mesh and
  // its reference surface (skipped); .stl is no mesh format.
  const test::TempDir dir("collect_polygons");
  std::filesystem::create_directories(dir.path() / "quads" / "deeper");
  std::filesystem::create_directories(dir.path() / "hex");
  for (const char* name : {"quads/grid.obj", "quads/sphere.OFF", "quads/deeper/torus.ply", "quads/part.stl",
                           "hex/bunny_in.mesh", "hex/bunny.off", "hex/bunny.obj"})
    dir.write(name, "x");
  // The reference surfaces are listed with a reason (the index names them), not analysed.
  std::vector<std::string> paths, skipped;
  for (const BatchInput& input : collect_directory(dir.path()))
    (input.skip_reason.empty() ? paths : skipped).push_back(input.path);
  EXPECT_EQ(paths, (std::vector<std::string>{"hex/bunny_in.mesh", "quads/deeper/torus.ply", "quads/grid.obj",
                                             "quads/sphere.OFF"}));
  EXPECT_EQ(skipped, (std::vector<std::string>{"hex/bunny.obj", "hex/bunny.off"}));
}

TEST(Manifest, CsvColumnsByHeaderQuotesAndRelativePaths) {
  const auto rows = parse_manifest(
      "mesh,method,reference,model\n"
      "out/bunny.mesh,\"edge, cone\",bunny.off,bunny\n"
      "# a comment\n"
      "\n"
      "/abs/kitten.vtk,polycube\n",
      "m.csv", "/data", false);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].path, "out/bunny.mesh");
  EXPECT_EQ(rows[0].mesh_file, "/data/out/bunny.mesh");
  EXPECT_EQ(rows[0].reference_file, "/data/bunny.off");
  EXPECT_EQ(rows[0].label, "edge, cone");
  EXPECT_EQ(rows[0].model, "bunny");
  EXPECT_EQ(rows[1].path, "abs/kitten.vtk");
  EXPECT_EQ(rows[1].mesh_file, "/abs/kitten.vtk");
  EXPECT_EQ(rows[1].model, "kitten");  // the stem when not given
  EXPECT_TRUE(rows[1].reference_file.empty());
}

TEST(Manifest, JsonObjectsAndStrings) {
  const auto rows = parse_manifest(R"([{"mesh": "a/x.mesh", "label": "m1"}, "b/y.vtk"])", "m.json", "/d", true);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].label, "m1");
  EXPECT_EQ(rows[1].path, "b/y.vtk");
}

TEST(Manifest, ErrorsNamePathAndLine) {
  try {
    parse_manifest("mesh,colour\nx.mesh,red\n", "m.csv", "/d", false);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), 1);
    EXPECT_NE(std::string(e.what()).find("m.csv:1: unknown column 'colour'"), std::string::npos) << e.what();
  }
  try {
    parse_manifest("mesh\nx.mesh\n./x.mesh\n", "m.csv", "/d", false);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("m.csv:3: mesh 'x.mesh' already listed"), std::string::npos) << e.what();
  }
  try {
    parse_manifest(R"(["a.mesh", {"label": "x"}])", "m.json", "/d", true);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& e) {
    EXPECT_STREQ(e.what(), "m.json: row 2: no mesh in this row");
  }
  EXPECT_THROW(parse_manifest("[1, 2]", "m.json", "/d", true), ParseError);
  EXPECT_THROW(parse_manifest("{", "m.json", "/d", true), ParseError);
}

// The up column (issue 45): an axis per mesh, in canonical form, or auto;
// empty: the run's --up; anything else is refused with the row's line.
TEST(Manifest, UpColumnPerMesh) {
  const auto rows =
      parse_manifest("mesh,up\na.mesh,+y\nb.mesh,\nc.mesh, -X \nd.mesh,z\ne.mesh,Auto\n", "m.csv", "/d", false);
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[4].up, "auto");  // --up auto for this mesh
  EXPECT_EQ(rows[0].up, "+y");
  EXPECT_EQ(rows[1].up, "");
  EXPECT_EQ(rows[2].up, "-x");
  EXPECT_EQ(rows[3].up, "+z");
  const auto json_rows =
      parse_manifest(R"([{"mesh": "a.mesh", "up": "-y"}, {"mesh": "b.mesh"}, "c.mesh"])", "m.json", "/d", true);
  EXPECT_EQ(json_rows[0].up, "-y");
  EXPECT_EQ(json_rows[1].up, "");
  EXPECT_EQ(json_rows[2].up, "");
  try {
    parse_manifest("mesh,up\na.mesh,+y\nb.mesh,sideways\n", "m.csv", "/d", false);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("m.csv:3: up: expected one of +x -x +y -y +z -z auto"), std::string::npos)
        << e.what();
  }
  try {
    parse_manifest(R"([{"mesh": "a.mesh", "up": "+w"}])", "m.json", "/d", true);
    ADD_FAILURE() << "no ParseError";
  } catch (const ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("m.json: row 1: up: expected"), std::string::npos) << e.what();
  }
}

TEST(Shard, StablePartitionCoveringEveryPathOnce) {
  std::vector<BatchInput> inputs;
  for (int i = 0; i < 200; ++i) {
    BatchInput input;
    input.path = "papers/p" + std::to_string(i % 7) + "/m" + std::to_string(i) + ".mesh";
    inputs.push_back(input);
  }
  std::size_t total = 0;
  for (int i = 1; i <= 5; ++i) {
    const auto part = select_shard(inputs, {i, 5});
    EXPECT_GT(part.size(), 10u);  // roughly balanced
    total += part.size();
    for (const BatchInput& in : part) EXPECT_EQ(shard_of(in.path, 5), i);
  }
  EXPECT_EQ(total, inputs.size());
  // The owner of a path depends on the path alone (fixed across machines).
  EXPECT_EQ(shard_of("a/b.mesh", 4), shard_of("a/b.mesh", 4));
  EXPECT_EQ(shard_of("anything", 1), 1);
}

TEST(BatchIndex, JsonRoundTripIsByteIdentical) {
  const std::vector<BatchEntry> entries = {entry("a/x.mesh", BatchStatus::ok, "m1", 0.25),
                                           entry("b/y.mesh", BatchStatus::failed, "m2"),
                                           entry("c/z.mesh", BatchStatus::gate_failed, "m1", 0.125)};
  const std::string text = batch_index_json(entries, "9.9.9");
  const auto parsed = parse_batch_index_json(text, "index.json");
  ASSERT_EQ(parsed.size(), 3u);
  EXPECT_EQ(parsed[1].error, entries[1].error);
  EXPECT_EQ(parsed[2].failed_gates, entries[2].failed_gates);
  EXPECT_EQ(batch_index_json(parsed, "9.9.9"), text);
  EXPECT_EQ(text.find("time"), std::string::npos);
  EXPECT_THROW(parse_batch_index_json("{}", "x.json"), InputError);
}

// index.html's mesh table worst first (issue 45): failed, then gate failed
// (most rules first), then inverted count, then min SJ; ties by path; a
// missing value after the known ones; index.json keeps the path order.
TEST(BatchIndex, MeshTableWorstFirstTiesByPath) {
  auto ok = [](const std::string& path, std::optional<double> min_sj, double inverted) {
    BatchEntry e = entry(path, BatchStatus::ok, "", 0.5);
    e.headline[2] = min_sj;
    e.headline[5] = inverted;
    return e;
  };
  BatchEntry two_gates = entry("e.mesh", BatchStatus::gate_failed, "", 0.9);
  two_gates.failed_gates.push_back("quality.num_inverted==0");
  BatchEntry skipped = entry("h.mesh", BatchStatus::skipped);
  skipped.headline = std::vector<std::optional<double>>(kNumHeadlineKeys);
  skipped.bundle.clear();
  const std::vector<BatchEntry> entries = {
      ok("a.mesh", 0.5, 0),  ok("b.mesh", -0.999, 2357), entry("c.mesh", BatchStatus::failed),
      entry("d.mesh", BatchStatus::gate_failed, "", 0.2), two_gates, ok("f.mesh", 0.5, 0), ok("g.mesh", 0.1, 0),
      skipped, ok("i.mesh", std::nullopt, 0), ok("j.mesh", 0.7, 1)};
  const std::vector<std::string> expected = {"c.mesh", "e.mesh", "d.mesh", "b.mesh", "j.mesh",
                                             "g.mesh", "a.mesh", "f.mesh", "i.mesh", "h.mesh"};
  auto paths = [](const std::vector<BatchEntry>& list) {
    std::vector<std::string> out;
    for (std::size_t i : worst_first_order(list)) out.push_back(list[i].path);
    return out;
  };
  EXPECT_EQ(paths(entries), expected);
  // The same order whatever order the entries come in (a merge's shards).
  std::vector<BatchEntry> reversed(entries.rbegin(), entries.rend());
  EXPECT_EQ(paths(reversed), expected);
  // The page's rows in that order (the skipped input is no row: it is on
  // the "Skipped" line above the table, issue 45); index.json in the given
  // (path) order.
  const std::string html = batch_index_html(entries, "9.9.9");
  const std::size_t table = html.find("id=\"mesh-table\"");
  ASSERT_NE(table, std::string::npos);
  EXPECT_EQ(html.find(">h.mesh<", table), std::string::npos);
  EXPECT_LT(html.find("<code>h.mesh</code>"), table);
  std::size_t last = table;
  for (const std::string& p : expected) {
    if (p == "h.mesh") continue;
    // A name breaks only after '_', '/', '.' or '-' (issue 45, the 45t
    // review: "rockar|m"): a <wbr> after each.
    std::string shown;
    for (char ch : p) shown += std::string(1, ch) + (std::string_view("_/.-").find(ch) != std::string_view::npos ? "<wbr>" : "");
    // In the mesh column: its link's text, or the cell's own text.
    std::size_t at = html.find(">" + shown + "</a>", table);
    if (at == std::string::npos) at = html.find("<td class=\"text path\">" + shown + "<", table);
    ASSERT_NE(at, std::string::npos) << p;
    EXPECT_GT(at, last) << p;
    last = at;
  }
  const auto json_index = nlohmann::json::parse(batch_index_json(entries, "9.9.9"));
  for (std::size_t i = 0; i < entries.size(); ++i) EXPECT_EQ(json_index["meshes"][i]["path"], entries[i].path);
  // Failing rows marked; the inverted count and a negative min SJ in red.
  EXPECT_NE(html.find("<tr class=\"failed\">"), std::string::npos);
  EXPECT_NE(html.find("✗ failed"), std::string::npos);
  EXPECT_NE(html.find("✗ gate failed"), std::string::npos);
  EXPECT_NE(html.find("class=\"alert\">2357<"), std::string::npos);
  EXPECT_NE(html.find("class=\"alert\">-0.999<"), std::string::npos);
}

// No empty columns: labels, variants, a Hausdorff distance or details that
// no row has are left out of the mesh table; thumbnails show when rendered.
TEST(BatchIndex, MeshTableHasNoEmptyColumns) {
  BatchEntry a = entry("a.mesh", BatchStatus::ok);
  BatchEntry b = entry("b.mesh", BatchStatus::ok);
  b.thumbnail = "views/thumbnail.png";
  const std::string html = batch_index_html({a, b}, "9.9.9");
  const std::string table = html.substr(html.find("id=\"mesh-table\""));
  for (const char* absent : {">label<", ">variant<", ">details<", ">Hausdorff (rel.)<", ">#intersecting<"})
    EXPECT_EQ(table.find(absent), std::string::npos) << absent;
  for (const char* present : {">model<", ">min SJ<", ">#V<", ">view<"})
    EXPECT_NE(table.find(present), std::string::npos) << present;
  EXPECT_NE(table.find("<img src=\"b.mesh/views/thumbnail.png\""), std::string::npos);
  // Every row has as many cells as the header.
  const std::size_t body = table.find("<tbody>"), end = table.find("</tbody>");
  const std::string head = table.substr(0, body), rows = table.substr(body, end - body);
  auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count(rows, "</td>"), 2 * count(head, "</th>"));
}

// An "ok" run of a mesh with inverted or intersecting cells or an input
// warning does not read "ok" (issue 45d): the status says what was found,
// the row is tinted, the header counts it; the warning shows with the
// batch's path; the thumbnail opens the overview; index.json keeps both.
TEST(BatchIndex, StatusAgreesWithFindingsAndLightboxOpensTheOverview) {
  auto key = [](std::string_view k) {
    return static_cast<std::size_t>(std::find(std::begin(kHeadlineKeys), std::end(kHeadlineKeys), k) - std::begin(kHeadlineKeys));
  };
  const std::size_t inverted = key("quality.num_inverted"), intersecting = key("overlap.num_intersecting_cells");
  BatchEntry clean = entry("a.mesh", BatchStatus::ok);
  clean.headline[inverted] = 0;
  clean.headline[intersecting] = 0;
  BatchEntry bad = entry("b.mesh", BatchStatus::ok);
  bad.headline[inverted] = 11;
  bad.headline[intersecting] = 22;
  bad.thumbnail = "views/thumbnail.png";
  bad.overview = "views/overview.png";
  BatchEntry warned = entry("m/c.vtk", BatchStatus::ok);
  warned.headline[inverted] = 0;
  warned.warnings = {"/abs/data/m/c.vtk: 68 cells with 8 points but a non-hexahedral type (10) loaded as hexahedra"};
  const std::string html = batch_index_html({clean, bad, warned}, "9.9.9");
  const std::string table = html.substr(html.find("id=\"mesh-table\""));
  EXPECT_NE(table.find("<tr class=\"ok finding\">"), std::string::npos);
  EXPECT_NE(table.find(">⚠ inverted, intersecting<"), std::string::npos);
  EXPECT_NE(table.find(">⚠ input warning<"), std::string::npos);
  EXPECT_NE(table.find("<tr class=\"ok\">"), std::string::npos) << "the clean row";
  EXPECT_NE(table.find("status\">ok<"), std::string::npos);
  EXPECT_NE(table.find("warning: m/c.vtk: 68 cells with 8 points"), std::string::npos);
  EXPECT_EQ(table.find("/abs/data"), std::string::npos);
  EXPECT_NE(html.find("2 with inverted or intersecting cells or input warnings (1 with input warnings)"),
            std::string::npos);
  EXPECT_NE(table.find("data-lightbox=\"b.mesh/views/overview.png\"><img src=\"b.mesh/views/thumbnail.png\""),
            std::string::npos);
  const std::vector<BatchEntry> back = parse_batch_index_json(batch_index_json({clean, bad, warned}, "9.9.9"), "i");
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[1].overview, "views/overview.png");
  // index.json holds the warnings as the page shows them (the mesh's path
  // relative to the batch input), so it does not depend on where the batch ran.
  EXPECT_EQ(back[2].warnings,
            std::vector<std::string>{"m/c.vtk: 68 cells with 8 points but a non-hexahedral type (10) loaded as hexahedra"});
  EXPECT_EQ(batch_index_html(back, "9.9.9"), html) << "merge gives the same page";
  // summary.md says what the page says (issue 45e): no "ok" for the mesh
  // with inverted cells nor for the one read with a warning, whose warning
  // is listed under Problems with the batch's path.
  const std::string md = batch_summary_markdown({clean, bad, warned});
  auto row_of = [&](std::string_view name) {
    const std::size_t at = md.find(std::string("[") + std::string(name));
    return at == std::string::npos ? std::string() : md.substr(at, md.find('\n', at) - at);
  };
  EXPECT_NE(row_of("a\\.mesh").find("| ok |"), std::string::npos) << md;
  EXPECT_NE(row_of("b\\.mesh").find("| ⚠ inverted, intersecting |"), std::string::npos) << md;
  EXPECT_NE(row_of("m\\/c\\.vtk").find("| ⚠ input warning |"), std::string::npos) << md;
  // Issue 45f: the header has the page's counts, every mesh that is not
  // plainly ok is under Problems with why (the warning without its path
  // again), the clean one is not, and the rows are worst first as on the page.
  EXPECT_NE(md.find("3 meshes, 0 failed, 0 with failed gates, 2 with inverted or intersecting cells or input warnings "
                    "(1 with input warnings)\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- b\\.mesh: 11 inverted; 22 intersecting\n"), std::string::npos) << md;
  EXPECT_NE(md.find("- m\\/c\\.vtk: warning: 68 cells with 8 points"), std::string::npos) << md;
  EXPECT_EQ(md.find("- a\\.mesh"), std::string::npos) << md;
  EXPECT_LT(md.find("[b\\.mesh"), md.find("[a\\.mesh")) << "worst first";
  EXPECT_EQ(md.back(), '\n');
}

// Surface meshes in a batch (47c review items 7 and 10): a tool limitation
// is no input warning (a neutral "limited analysis" status, its text once
// under the table), the hex column counts a surface mesh's cells by kind
// (never "0"), the singular columns its irregular vertices, and a skipped
// input is named with its reason at the top; index.json keeps the counts.
TEST(BatchIndex, SurfaceRowsLimitedAnalysisCellCountsAndSkippedInputs) {
  auto key = [](std::string_view k) {
    return static_cast<std::size_t>(std::find(std::begin(kHeadlineKeys), std::end(kHeadlineKeys), k) - std::begin(kHeadlineKeys));
  };
  BatchEntry hex = entry("hex/ball.mesh", BatchStatus::ok);
  hex.headline[key("mesh.num_hexes")] = 1000;
  hex.headline[key("headline.num_cells")] = 1000;
  hex.headline[key("structure.num_singular_edges_interior")] = 12;
  BatchEntry sphere = entry("quads/sphere.obj", BatchStatus::ok);
  sphere.headline[key("mesh.num_hexes")] = 0;
  sphere.surface = SurfaceCounts{600, 0, 8, std::nullopt};
  sphere.warnings = {std::string(kSurfaceBoundaryErrorViewsNotDrawnBefore)};
  BatchEntry holed = entry("quads/holed.obj", BatchStatus::ok);
  holed.headline[key("mesh.num_hexes")] = 0;
  holed.surface = SurfaceCounts{200, 16, 38, 9};
  holed.warnings = {std::string(kSurfaceBoundaryErrorViewsNotDrawnBefore), "/abs/quads/holed.obj: 1 node is no cell's corner"};
  BatchEntry reference = entry("hex/ball.off", BatchStatus::skipped);
  reference.error = "a surface file beside volume meshes: taken for their reference surface";
  // A curved surface with one reversed face (issue 47 part F): its
  // quality.num_inverted counts reversed faces, and the row says so.
  BatchEntry vase = entry("quads/vase.obj", BatchStatus::ok);
  vase.headline[key("mesh.num_hexes")] = 0;
  vase.headline[key("quality.num_inverted")] = 1;
  vase.surface = SurfaceCounts{312, 0, 0, 0};
  vase.surface->planar = false;
  const std::vector<BatchEntry> entries{hex, sphere, holed, reference, vase};
  const std::string html = batch_index_html(entries, "9.9.9");
  const std::string table = html.substr(html.find("id=\"mesh-table\""));
  // The flawless surface mesh: ok, limited, neutral; not an input warning.
  EXPECT_NE(table.find("<tr class=\"ok limited\">"), std::string::npos) << table;
  EXPECT_NE(table.find("status\">ok · limited analysis<"), std::string::npos);
  // The one with a real input warning keeps it (and is limited too).
  EXPECT_NE(table.find("status\">⚠ input warning · limited analysis<"), std::string::npos);
  EXPECT_NE(table.find("warning: quads/holed.obj: 1 node is no cell"), std::string::npos);
  // The limitation's text once, under the table, not under a row's path.
  EXPECT_EQ(table.find("warning: overlap is not checked"), std::string::npos);
  std::size_t once = 0;
  for (std::size_t at = html.find("the boundary-error views of surface meshes"); at != std::string::npos;
       at = html.find("the boundary-error views of surface meshes", at + 1))
    ++once;
  EXPECT_EQ(once, 1u);
  EXPECT_NE(html.find("2 with limited analysis"), std::string::npos);
  EXPECT_NE(html.find("(1 with input warnings)"), std::string::npos);
  // Cells by kind, sorted by their count; never "0" for a mesh with cells.
  EXPECT_NE(table.find("<th>#cells (hex / quad / tri)</th>"), std::string::npos);
  EXPECT_NE(table.find("data-sort=\"600\">600 quad<"), std::string::npos);
  EXPECT_NE(table.find("data-sort=\"216\">200 quad + 16 tri<"), std::string::npos);
  EXPECT_NE(table.find("data-sort=\"1000\">1000 hex<"), std::string::npos);
  EXPECT_NE(table.find(">38 vertices<"), std::string::npos);
  EXPECT_NE(table.find(">8 vertices<"), std::string::npos);
  EXPECT_NE(table.find(">9 vertices<"), std::string::npos);
  EXPECT_EQ(table.find(">0 quad<"), std::string::npos);
  EXPECT_EQ(table.find("data-sort=\"0\">0</td>"), std::string::npos) << "no row reads 0 cells";
  // The skipped input, named with its reason at the top.
  const std::string head = html.substr(0, html.find("<main>"));
  EXPECT_NE(head.find("1 file skipped (listed below)"), std::string::npos) << head;
  EXPECT_NE(head.find("Skipped: 1 file, not analysed (a surface file beside volume meshes"), std::string::npos) << head;
  EXPECT_NE(head.find("<code>hex/ball.off</code>."), std::string::npos) << head;
  EXPECT_EQ(html.find("<tr class=\"skipped"), std::string::npos);
  // Surface wording, not "per hex" alone.
  EXPECT_EQ(table.find("the most inverted hexes"), std::string::npos);
  // index.json round trip: the page is the same after a merge.
  const std::vector<BatchEntry> back = parse_batch_index_json(batch_index_json(entries, "9.9.9"), "i");
  ASSERT_EQ(back.size(), 5u);
  EXPECT_EQ(batch_index_html(back, "9.9.9"), html);
  const auto vase_back = std::find_if(back.begin(), back.end(), [](const BatchEntry& e) { return e.path == "quads/vase.obj"; });
  ASSERT_TRUE(vase_back != back.end() && vase_back->surface);
  EXPECT_FALSE(vase_back->surface->planar);
  EXPECT_NE(table.find("status\">⚠ reversed faces<"), std::string::npos) << table;
  EXPECT_NE(table.find("data-sort=\"1\" class=\"alert\">1 reversed<"), std::string::npos) << table;
  // A batch without surface meshes keeps its page: no limited status, the
  // hex column's title.
  const std::string volume_only = batch_index_html({hex}, "9.9.9");
  EXPECT_NE(volume_only.find("<th>#H</th>"), std::string::npos);
  EXPECT_EQ(volume_only.find("limited"), std::string::npos);
  // summary.md: the limitation is not a warning.
  const std::string md = batch_summary_markdown(entries);
  EXPECT_NE(md.find("- quads\\/holed\\.obj: limited: the boundary\\-error views"), std::string::npos) << md;
  EXPECT_NE(md.find("- quads\\/vase\\.obj: 1 reversed faces\n"), std::string::npos) << md;
  EXPECT_NE(md.find("| ⚠ reversed faces |"), std::string::npos) << md;
}

// Manifest rows with a compare mesh beside surface meshes (issue 47): a
// surface mesh with a surface compare mesh is compared (its report has the
// compare block, no warning); a hex mesh with a surface compare mesh is a
// manifest error (the two are of different dimensions): that row fails
// with the message that says so, the other rows are analysed.
TEST(Batch, SurfaceMeshesAreComparedAndAMixedDimensionRowFails) {
  const test::TempDir dir("batch_surface_compare");
  std::string obj;
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) obj += "v " + std::to_string(i) + " " + std::to_string(j) + " " + std::to_string(i * j) + "\n";
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 1 + i + 3 * j;
      obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 4) + " " + std::to_string(a + 3) + "\n";
    }
  const std::filesystem::path surface = dir.write("quads.obj", obj), other = dir.write("other.obj", obj);
  const std::filesystem::path hex = dir.write("cube.mesh",
                                              "MeshVersionFormatted 2\nDimension 3\nVertices\n8\n0 0 0 0\n1 0 0 0\n1 1 0 0\n"
                                              "0 1 0 0\n0 0 1 0\n1 0 1 0\n1 1 1 0\n0 1 1 0\nHexahedra\n1\n1 2 3 4 5 6 7 8 0\nEnd\n");
  std::vector<BatchInput> inputs(2);
  inputs[0].path = "quads.obj";
  inputs[0].mesh_file = surface;
  inputs[0].compare_file = other;
  inputs[1].path = "cube.mesh";
  inputs[1].mesh_file = hex;
  inputs[1].compare_file = surface;
  BatchOptions options;
  options.output = dir.path() / "out";
  options.analyze.tool_version = "test";
  const std::vector<BatchEntry> entries = run_batch(inputs, options, nullptr);
  ASSERT_EQ(entries.size(), 2u);
  ASSERT_EQ(entries[1].path, "quads.obj");  // sorted by path
  EXPECT_EQ(entries[1].status, BatchStatus::ok) << entries[1].error;
  EXPECT_TRUE(entries[1].warnings.empty());
  const nlohmann::json report =
      nlohmann::json::parse(std::ifstream(options.output / "quads.obj" / "report.json"));
  EXPECT_EQ(report["compare"]["headline"]["num_cells_by_kind"]["quad"], 4);
  EXPECT_EQ(report["compare"]["alignment"]["mode"], "none");  // the same surface, in place
  EXPECT_EQ(entries[0].path, "cube.mesh");
  EXPECT_EQ(entries[0].status, BatchStatus::failed);
  EXPECT_NE(entries[0].error.find("a surface mesh against a volume mesh (compare meshes of one dimension)"),
            std::string::npos)
      << entries[0].error;
}

TEST(BatchIndex, MethodsComparePerLabel) {
  const auto methods =
      summarize_methods({entry("a", BatchStatus::ok, "m1", 0.25), entry("b", BatchStatus::failed, "m1"),
                         entry("c", BatchStatus::ok, "m1", 0.75), entry("d", BatchStatus::ok, "m2", 0.5)});
  ASSERT_EQ(methods.size(), 2u);
  EXPECT_EQ(methods[0].label, "m1");
  EXPECT_EQ(methods[0].num_meshes, 3);
  EXPECT_EQ(methods[0].num_failed, 1);
  EXPECT_DOUBLE_EQ(methods[0].mean_min_scaled_jacobian, 0.5);
  EXPECT_DOUBLE_EQ(methods[0].worst_min_scaled_jacobian, 0.25);
  EXPECT_TRUE(summarize_methods({entry("a", BatchStatus::ok)}).empty());
}

// The Comparison section's tables (one per key, the thumbnails, the methods)
// and the Methods section name their rows: a model or method name in every
// first cell, escaped (the template reads the *_html keys; a row that set
// only the plain key showed an empty cell).
TEST(BatchIndex, ComparisonAndMethodRowsNameTheirModelAndMethod) {
  std::vector<BatchEntry> entries;
  for (const char* label : {"m<1>", "m&2"}) {
    BatchEntry e = entry(std::string(label) + "/kit_ten.mesh", BatchStatus::ok, label);
    e.model = "kit_ten<b>";
    entries.push_back(e);
  }
  const std::string html = batch_index_html(entries, "9.9.9");
  ASSERT_NE(html.find("id=\"comparison\""), std::string::npos) << "two methods on one model: a comparison";
  EXPECT_EQ(html.find("<td class=\"text\"></td>"), std::string::npos) << "no row without its name";
  const std::string model = "<td class=\"text\">kit_<wbr>ten&lt;b&gt;</td>";
  std::size_t models = 0;
  for (std::size_t at = html.find(model); at != std::string::npos; at = html.find(model, at + 1)) ++models;
  EXPECT_GE(models, 1u) << "the comparison tables name the model";
  for (const char* label : {"<td class=\"text\">m&lt;1&gt;</td>", "<td class=\"text\">m&amp;2</td>"}) {
    std::size_t rows = 0;
    for (std::size_t at = html.find(label); at != std::string::npos; at = html.find(label, at + 1)) ++rows;
    EXPECT_GE(rows, 3u) << label << ": the mesh table, the comparison's and the Methods section's method rows";
  }
}

TEST(BatchIndex, HtmlEscapesNamesAndErrorsAndLinksBundles) {
  BatchEntry evil = entry("<script>alert(1)</script>.mesh", BatchStatus::failed, "a&b");
  const std::string html = batch_index_html({entry("ok.mesh", BatchStatus::ok), evil}, "1.0");
  EXPECT_EQ(html.find("<script>alert"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/<wbr>script&gt;.<wbr>mesh"), std::string::npos);
  EXPECT_NE(html.find("a&amp;b"), std::string::npos);
  EXPECT_NE(html.find("href=\"ok.mesh/index.html\""), std::string::npos);
  const std::string odd = batch_index_html({entry("a b/c#1.mesh", BatchStatus::ok)}, "1.0");
  EXPECT_NE(odd.find("href=\"a%20b/c%231.mesh/index.html\""), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos);  // no external resources
  // The one image: the comparison chart beside the page.
  EXPECT_EQ(html.find("src="), html.find("src=\"comparison_min_sj.svg\""));
  EXPECT_EQ(html.find("src=", html.find("src=") + 1), std::string::npos);
}

TEST(BatchIndex, MarkdownTableAndProblems) {
  const std::string md =
      batch_summary_markdown({entry("a|b.mesh", BatchStatus::ok), entry("c.mesh", BatchStatus::failed)});
  EXPECT_NE(md.find("2 meshes, 1 failed"), std::string::npos) << md;
  // One escaper for every Markdown text: the cell's pipe, the name's dot and
  // the error's colons are backslash-escaped.
  EXPECT_NE(md.find("a\\|b\\.mesh"), std::string::npos) << md;
  EXPECT_NE(md.find("- c\\.mesh: c\\.mesh\\:3\\: expected 8 vertex ids"), std::string::npos) << md;
  // Issue 45, the 45t review (24 columns): the quality numbers in one
  // table of 10 columns at most; the other headline numbers in tables of
  // their own, only with columns some mesh has a value in (none here).
  EXPECT_NE(md.find(" status | #V | #H | min SJ | mean SJ | p05 SJ | #inverted | #intersecting |\n"), std::string::npos) << md;
  EXPECT_EQ(md.find("Hausdorff"), std::string::npos) << md;
  EXPECT_EQ(md.find("FEM"), std::string::npos) << md;
  EXPECT_EQ(md.find("### Cell kinds"), std::string::npos) << md;
  for (std::size_t at = 0; at < md.size();) {
    const std::size_t end = md.find('\n', at);
    const std::string line = md.substr(at, end - at);
    std::size_t bars = 0;
    for (std::size_t i = 0; i < line.size(); ++i) bars += line[i] == '|' && (i == 0 || line[i - 1] != '\\');
    EXPECT_LE(bars, 11u) << line;
    at = end == std::string::npos ? md.size() : end + 1;
  }
}

TEST(ModelOfPath, HexMarkersVariantSuffixesAndGenericStems) {
  // The names of HexaLab's published index and of ../shared/data.
  const std::pair<const char*, ModelAndVariant> cases[] = {
      {"gao2016_sweeping/bunny_1.mesh", {"bunny", "1"}},
      {"livesu2015_edgecone/bunny_in.mesh", {"bunny", "in"}},
      {"bunny_out.mesh", {"bunny", "out"}},
      {"hex_mesh/cat/cat_2_padded.mesh", {"cat", "2_padded"}},
      {"Dolphin_padded.mesh", {"dolphin", "padded"}},
      {"armadillo_stresstest_out.mesh", {"armadillo_stresstest", "out"}},
      {"bunny_hex.mesh", {"bunny", ""}},
      {"Kiss_hex_coarse.mesh", {"kiss", "coarse"}},
      {"Armadillo_hex-a.vtk", {"armadillo", "a"}},
      {"kitten-hex.vtk", {"kitten", ""}},
      {"bunny_hex_opt.mesh", {"bunny", "opt"}},
      {"anc101/hex.vtk", {"anc101", ""}},
      {"asm/polycube_in.mesh", {"asm", "polycube_in"}},
      {"asm/model_out.mesh", {"asm", "model_out"}},
      {"double torus/double torus.vtk", {"double torus", ""}},
      {"hexagon.mesh", {"hexagon", ""}},  // "hex" inside a word is no marker
      {"fandisk.mesh", {"fandisk", ""}},
      {"hex.vtk", {"hex", ""}},  // no folder to name it
  };
  for (const auto& [path, expected] : cases) {
    const ModelAndVariant mv = model_of_path(path);
    EXPECT_EQ(mv.model, expected.model) << path;
    EXPECT_EQ(mv.variant, expected.variant) << path;
  }
}

TEST(Manifest, ModelAndVariantColumnsWin) {
  const auto rows = parse_manifest(
      "mesh,method,model,variant\n"
      "a/bunny_in.mesh,ec,,\n"
      "a/bunny_out.mesh,ec,rabbit,\n"
      "a/bunny_3.mesh,ec,,fine\n",
      "m.csv", "/d", false);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].model, "bunny");
  EXPECT_EQ(rows[0].variant, "in");
  EXPECT_EQ(rows[1].model, "rabbit");  // a model alone: its only variant
  EXPECT_EQ(rows[1].variant, "");
  EXPECT_EQ(rows[2].model, "bunny");
  EXPECT_EQ(rows[2].variant, "fine");
}

TEST(HexaLabIndex, TrailingCommaSpacesYearsAndSkippedFiles) {
  // The published file's quirks: a trailing comma inside "paper", a year as
  // a string and one as a number, a path with spaces and non-ASCII, a
  // generic stem, the same file name in two sources, a surface file.
  const std::string text = R"({
    "sources": [
      {"paper": {"title": "Edge-Cone", "year": "2015", "DOI": "10.1145/2766905",},
       "path": "2015 - Édge cone", "label": "edgecone",
       "data": ["bunny_in.mesh", "bunny_out.mesh", "bunny.off"]},
      {"paper": {"title": "ℓ1 polycube", "year": 2014, "DOI": ""},
       "path": "l1", "label": "ℓ1",
       "data": ["bunny/hex.vtk", "bunny_out.mesh"]},
    ]
  })";
  const auto rows = parse_manifest(text, "index.json", "/hl", true);
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0].path, "2015 - Édge cone/bunny_in.mesh");
  EXPECT_EQ(rows[0].mesh_file, "/hl/2015 - Édge cone/bunny_in.mesh");
  EXPECT_EQ(rows[0].label, "edgecone");
  EXPECT_EQ(rows[0].model, "bunny");
  EXPECT_EQ(rows[0].variant, "in");
  EXPECT_EQ(rows[0].paper, (PaperInfo{"Edge-Cone", "2015", "10.1145/2766905"}));
  EXPECT_TRUE(rows[0].skip_reason.empty());
  EXPECT_NE(rows[2].skip_reason.find("not a hex mesh"), std::string::npos);
  EXPECT_EQ(rows[3].model, "bunny");  // l1/bunny/hex.vtk: the folder names it
  EXPECT_EQ(rows[3].paper.year, "2014");
  EXPECT_EQ(rows[4].path, "l1/bunny_out.mesh");  // same name, other source
  // Strict JSON elsewhere: a trailing comma in a plain manifest is an error.
  EXPECT_THROW(parse_manifest(R"([{"mesh": "a.mesh",}])", "m.json", "/d", true), ParseError);
  EXPECT_EQ(strip_trailing_commas(R"({"a": [1, 2, ], "s": ",}", "b": {"c": 1 ,
  }})"),
            R"({"a": [1, 2 ], "s": ",}", "b": {"c": 1 
  }})");
}

}  // namespace
}  // namespace hq
