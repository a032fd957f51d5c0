// `hqview batch`, `merge` and `diff` end to end, on ../shared/data/meshes
// (linked, never copied into the repository; skipped when absent) and on
// small copies made in the build tree.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/fixtures.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kNumSharedMeshes = 11;  // ../shared/data/README.md

// A collection directory under `dir` mirroring ../shared/data/meshes with
// symbolic links, plus a malformed mesh when `with_broken`.
fs::path link_collection(const fs::path& shared_meshes, const fs::path& dir, bool with_broken) {
  const fs::path collection = dir / "collection";
  for (const auto& entry : fs::recursive_directory_iterator(shared_meshes)) {
    if (!entry.is_regular_file()) continue;
    const fs::path link = collection / entry.path().lexically_relative(shared_meshes);
    fs::create_directories(link.parent_path());
    fs::create_symlink(entry.path(), link);
  }
  if (with_broken) {
    fs::create_directories(collection / "broken");
    std::ofstream(collection / "broken" / "truncated.mesh")
        << "MeshVersionFormatted 1\nDimension 3\nVertices\n3\n0 0 0 0\n";
  }
  return collection;
}

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

json read_json(const fs::path& path) { return json::parse(read_text(path)); }

#define REQUIRE_SHARED_DATA(data)      \
  const auto data = shared_data_dir(); \
  if (!data) GTEST_SKIP() << "../shared/data absent (set HQVIEW_DATA to run these)"

TEST(Batch, SharedCollectionWithABrokenFile) {
  REQUIRE_SHARED_DATA(data);
  const fs::path dir = fresh_output_dir("batch/shared");
  const fs::path collection = link_collection(*data / "meshes", dir, true);
  const fs::path out = dir / "out";
  const CliResult r = run_hqview({"batch", collection.string(), "-o", out.string(), "-j", "2", "--no-render"});
  EXPECT_EQ(r.exit_code, 3) << r.err;  // an input failed; the others went on
  const json index = read_json(out / "index.json");
  // The reference surfaces beside the meshes (.off .obj .ply) are listed as
  // skipped rows, not analysed (issue 47, part D: the page names them).
  std::size_t references = 0;
  for (const auto& e : fs::recursive_directory_iterator(collection)) {
    const std::string ext = e.path().extension().string();
    references += ext == ".off" || ext == ".obj" || ext == ".ply";
  }
  ASSERT_GT(references, 0u);
  ASSERT_EQ(index["meshes"].size(), kNumSharedMeshes + 1u + references);
  EXPECT_EQ(index["counts"]["ok"], kNumSharedMeshes);
  EXPECT_EQ(index["counts"]["failed"], 1);
  EXPECT_EQ(index["counts"]["skipped"], references);
  EXPECT_EQ(index["counts"]["meshes"], kNumSharedMeshes + 1u);
  std::string previous;
  for (const json& m : index["meshes"]) {
    const std::string path = m["path"];
    EXPECT_LT(previous, path);  // sorted by path
    previous = path;
    if (m["status"] == "skipped") {
      EXPECT_NE(m["error"].get<std::string>().find("reference surface"), std::string::npos) << m["error"];
      EXPECT_TRUE(m["bundle"].is_null());
      continue;
    }
    if (path == "broken/truncated.mesh") {
      EXPECT_EQ(m["status"], "failed");
      EXPECT_NE(m["error"].get<std::string>().find("truncated.mesh:"), std::string::npos) << m["error"];
      EXPECT_TRUE(m["bundle"].is_null());
      EXPECT_FALSE(fs::exists(out / path));
      EXPECT_NE(r.err.find("failed broken/truncated.mesh"), std::string::npos) << r.err;
      continue;
    }
    EXPECT_EQ(m["status"], "ok") << path;
    EXPECT_EQ(m["bundle"], path);  // bundles mirror the input paths
    const json report = read_json(out / path / "report.json");
    EXPECT_EQ(report["mesh"]["num_hexes"], m["headline"]["mesh.num_hexes"]);
    EXPECT_EQ(report["quality"]["scaled_jacobian"]["min"], m["headline"]["quality.scaled_jacobian.min"]);
  }
  const std::string html = read_text(out / "index.html");
  EXPECT_NE(html.find("href=\"livesu2015_edgecone/bunny_out.mesh/index.html\""), std::string::npos);
  EXPECT_NE(read_text(out / "summary.md").find("12 meshes, 1 failed"), std::string::npos);
  // No reference surfaces or temporary siblings are taken for meshes: a
  // reference is named on the "Skipped" line, never linked to a bundle, and
  // is no row of the mesh table (issue 45: they were rows of dashes).
  EXPECT_EQ(html.find("bunny.off/index.html"), std::string::npos);
  EXPECT_NE(html.find("<p class=\"note skipped\">Skipped: "), std::string::npos);
  EXPECT_NE(html.find("<code>gao2016_sweeping/bunny.off</code>"), std::string::npos);
  EXPECT_EQ(html.find("<tr class=\"skipped"), std::string::npos);
  const std::string md = read_text(out / "summary.md");
  EXPECT_NE(md.find("\nSkipped: "), std::string::npos) << md;
  EXPECT_NE(md.find(" files, not analysed ("), std::string::npos) << md;
  EXPECT_EQ(md.find("| skipped |"), std::string::npos) << md;
}

TEST(Batch, ExitCodesAndRenderedBundlesInParallel) {
  REQUIRE_SHARED_DATA(data);
  const fs::path dir = fresh_output_dir("batch/exit");
  const fs::path meshes = *data / "meshes";
  // A manifest with labels: the per-method comparison.
  write_file(dir / "manifest.csv", "mesh,label\n" + (meshes / "gao2016_sweeping/kitten_1.mesh").string() +
                                       ",sweeping\n" + (meshes / "smf2019/hex_cube_coarse.vtk").string() + ",smf\n" +
                                       (meshes / "li2012_srf/fandisk.mesh").string() + ",srf\n");
  const CliResult ok = run_hqview({"batch", (dir / "manifest.csv").string(), "-o", (dir / "ok").string(), "-j", "2"});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  const json index = read_json(dir / "ok" / "index.json");
  ASSERT_EQ(index["meshes"].size(), 3u);
  ASSERT_EQ(index["methods"].size(), 3u);
  EXPECT_EQ(index["methods"][0]["label"], "smf");
  for (const json& m : index["meshes"]) EXPECT_TRUE(fs::exists(dir / "ok" / m["bundle"].get<std::string>() / "views"));
  EXPECT_NE(read_text(dir / "ok" / "index.html").find("Methods"), std::string::npos);

  const CliResult gate = run_hqview({"batch", (dir / "manifest.csv").string(), "-o", (dir / "gate").string(),
                                     "--no-render", "--gate", "quality.scaled_jacobian.min>=0.5"});
  EXPECT_EQ(gate.exit_code, 1) << gate.err;  // kitten's min is 0.357
  const json gated = read_json(dir / "gate" / "index.json");
  EXPECT_EQ(gated["counts"]["gate_failed"], 1);

  EXPECT_EQ(
      run_hqview({"batch", (dir / "manifest.csv").string(), "-o", (dir / "x").string(), "--shard", "3/2"}).exit_code,
      2);
  EXPECT_EQ(run_hqview({"batch", (dir / "nothing").string(), "-o", (dir / "x").string()}).exit_code, 3);
  write_file(dir / "bad.csv", "mesh,colour\nx.mesh,red\n");
  const CliResult bad = run_hqview({"batch", (dir / "bad.csv").string(), "-o", (dir / "x").string()});
  EXPECT_EQ(bad.exit_code, 3);
  EXPECT_NE(bad.err.find("bad.csv:1: unknown column 'colour'"), std::string::npos) << bad.err;
}

TEST(Batch, ShardsMergedEqualTheUnshardedRun) {
  REQUIRE_SHARED_DATA(data);
  const fs::path dir = fresh_output_dir("batch/shards");
  const fs::path collection = link_collection(*data / "meshes", dir, true);
  const CliResult whole =
      run_hqview({"batch", collection.string(), "-o", (dir / "whole").string(), "--no-render", "-j", "2"});
  EXPECT_EQ(whole.exit_code, 3);
  std::vector<std::string> merge = {"merge"};
  std::size_t rows = 0;
  for (int i = 1; i <= 3; ++i) {
    const fs::path shard = dir / ("shard" + std::to_string(i));
    run_hqview(
        {"batch", collection.string(), "-o", shard.string(), "--no-render", "--shard", std::to_string(i) + "/3"});
    rows += read_json(shard / "index.json")["meshes"].size();
    merge.push_back(shard.string());
  }
  EXPECT_EQ(rows, read_json(dir / "whole" / "index.json")["meshes"].size());  // a partition
  merge.push_back("-o");
  merge.push_back((dir / "merged").string());
  const CliResult merged = run_hqview(merge);
  EXPECT_EQ(merged.exit_code, 3) << merged.err;  // the broken mesh is still there
  EXPECT_EQ(read_text(dir / "merged" / "index.json"), read_text(dir / "whole" / "index.json"));
  EXPECT_EQ(read_text(dir / "merged" / "index.html"), read_text(dir / "whole" / "index.html"));
  EXPECT_TRUE(fs::exists(dir / "merged" / "livesu2016_skeleton/warrior.mesh/report.json"));
  // A mesh in two shards is an input error.
  EXPECT_EQ(run_hqview({"merge", (dir / "shard1").string(), (dir / "shard1").string(), "-o", (dir / "twice").string()})
                .exit_code,
            3);
}

TEST(Batch, ResumeRedoesOnlyTheChangedMesh) {
  REQUIRE_SHARED_DATA(data);
  const fs::path dir = fresh_output_dir("batch/resume");
  const fs::path meshes = *data / "meshes";
  fs::create_directories(dir / "collection");
  fs::copy_file(meshes / "gao2016_sweeping/kitten_1.mesh", dir / "collection/kitten.mesh");
  fs::copy_file(meshes / "smf2019/hex_cube_coarse.vtk", dir / "collection/cube.vtk");
  const std::vector<std::string> args = {
      "batch", (dir / "collection").string(), "-o", (dir / "out").string(), "--no-render", "--resume"};
  ASSERT_EQ(run_hqview(args).exit_code, 0);
  // An output inside the collection is not taken for input next time.
  ASSERT_EQ(
      run_hqview({"batch", (dir / "collection").string(), "-o", (dir / "collection/report").string(), "--no-render"})
          .exit_code,
      0);
  const auto cube_time = fs::last_write_time(dir / "out/cube.vtk/report.json");
  const std::string before = read_text(dir / "out/index.json");
  // Same files: everything is kept.
  const CliResult same = run_hqview(args);
  EXPECT_EQ(same.exit_code, 0);
  EXPECT_NE(same.err.find("kept cube.vtk"), std::string::npos) << same.err;
  EXPECT_NE(same.err.find("kept kitten.mesh"), std::string::npos) << same.err;
  EXPECT_EQ(read_text(dir / "out/index.json"), before);
  // kitten.mesh changes (now the bunny): only it is analysed again.
  fs::copy_file(meshes / "gao2016_sweeping/bunny_1.mesh", dir / "collection/kitten.mesh",
                fs::copy_options::overwrite_existing);
  const CliResult changed = run_hqview(args);
  EXPECT_EQ(changed.exit_code, 0) << changed.err;
  EXPECT_NE(changed.err.find("kept cube.vtk"), std::string::npos) << changed.err;
  EXPECT_NE(changed.err.find("ok kitten.mesh"), std::string::npos) << changed.err;
  EXPECT_EQ(fs::last_write_time(dir / "out/cube.vtk/report.json"), cube_time);
  EXPECT_EQ(read_json(dir / "out/kitten.mesh/report.json")["mesh"]["num_hexes"], 264);
  EXPECT_EQ(read_json(dir / "out/index.json")["meshes"][1]["headline"]["mesh.num_hexes"], 264);
  EXPECT_EQ(read_json(dir / "out/index.json")["meshes"].size(), 2u);
}

// A manifest row's `compare` mesh is analysed as with `analyze --compare`
// (report.json input.compare and compare, the compare view); a row without
// one has none; --resume redoes the row whose compare mesh changed.
TEST(Batch, ManifestRowsWithACompareMesh) {
  REQUIRE_SHARED_DATA(data);
  const fs::path dir = fresh_output_dir("batch/compare");
  const fs::path meshes = *data / "meshes" / "gao2016_sweeping";
  fs::create_directories(dir / "in");
  fs::copy_file(meshes / "kitten_1.mesh", dir / "in/kitten.mesh");
  fs::copy_file(meshes / "bunny_1.mesh", dir / "in/bunny.mesh");
  write_file(dir / "in/manifest.csv", "mesh,compare,label\nkitten.mesh,bunny.mesh,before\nbunny.mesh,,after\n");
  const std::vector<std::string> args = {"batch",    (dir / "in/manifest.csv").string(),
                                         "-o",       (dir / "out").string(),
                                         "--views",  "compare",
                                         "--size",   "320x240",
                                         "--resume", "-j",
                                         "2"};
  const CliResult run = run_hqview(args);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json kitten = read_json(dir / "out/kitten.mesh/report.json");
  ASSERT_TRUE(kitten["compare"].is_object());
  EXPECT_EQ(kitten["input"]["compare"]["path"], "bunny.mesh");
  // ../shared/data/README.md: kitten_1 has 300 hexes, bunny_1 264.
  EXPECT_EQ(kitten["mesh"]["num_hexes"], 300);
  EXPECT_EQ(kitten["compare"]["headline"]["num_hexes"], 264);
  EXPECT_EQ(kitten["compare"]["differences"]["headline.num_hexes"], 264 - 300);
  EXPECT_TRUE(fs::is_regular_file(dir / "out/kitten.mesh/views/compare.png"));
  const json bunny = read_json(dir / "out/bunny.mesh/report.json");
  EXPECT_TRUE(bunny["compare"].is_null());
  EXPECT_FALSE(fs::exists(dir / "out/bunny.mesh/views/compare.png"));
  // The compare mesh changes (now the kitten itself): its row is redone.
  fs::copy_file(meshes / "kitten_1.mesh", dir / "in/bunny.mesh", fs::copy_options::overwrite_existing);
  const CliResult again = run_hqview(args);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("ok kitten.mesh"), std::string::npos) << again.err;
  EXPECT_EQ(read_json(dir / "out/kitten.mesh/report.json")["compare"]["differences"]["headline.num_hexes"], 0);
}

TEST(Diff, BunnyInToOutImprovesAndAnInjectedRegressionFails) {
  REQUIRE_SHARED_DATA(data);
  const fs::path dir = fresh_output_dir("batch/diff");
  const fs::path meshes = *data / "meshes/livesu2015_edgecone";
  // Reports of the input and the optimised output of the same model.
  ASSERT_EQ(run_hqview({"analyze", (meshes / "bunny_in.mesh").string(), "-o", (dir / "in").string(), "--no-render"})
                .exit_code,
            0);
  ASSERT_EQ(run_hqview({"analyze", (meshes / "bunny_out.mesh").string(), "-o", (dir / "out").string(), "--no-render"})
                .exit_code,
            0);
  const std::string gate = "quality.scaled_jacobian.min>=baseline-0.01";
  const CliResult better = run_hqview({"diff", (dir / "in/report.json").string(), (dir / "out/report.json").string(),
                                       "--gate", gate, "--markdown", (dir / "better.md").string()});
  EXPECT_EQ(better.exit_code, 0) << better.err;
  EXPECT_NE(better.out.find("quality.scaled_jacobian.min: -0.0027514737706080556 -> 0.6061486641020569"),
            std::string::npos)
      << better.out;
  EXPECT_NE(better.out.find("quality.num_inverted: 1 -> 0"), std::string::npos) << better.out;
  EXPECT_NE(read_text(dir / "better.md").find("✅"), std::string::npos);
  // The regression: the output as baseline, the input as current.
  const CliResult worse = run_hqview({"diff", (dir / "out").string(), (dir / "in").string(), "--gate", gate,
                                      "--markdown", (dir / "worse.md").string()});
  EXPECT_EQ(worse.exit_code, 1) << worse.err;
  EXPECT_NE(worse.err.find("gate failed: " + gate), std::string::npos) << worse.err;
  EXPECT_NE(read_text(dir / "worse.md").find("❌"), std::string::npos);
  EXPECT_EQ(
      run_hqview({"diff", (dir / "in").string(), (dir / "out").string(), "--gate", "quality.nope>=baseline"}).exit_code,
      2);
}

TEST(Diff, IndexOfTwoNightlyRuns) {
  REQUIRE_SHARED_DATA(data);
  const fs::path dir = fresh_output_dir("batch/diff_index");
  const fs::path meshes = *data / "meshes";
  // Last night: bunny is the optimised mesh. Tonight: a regression brings
  // back the input mesh, kitten vanished and the cube is new.
  fs::create_directories(dir / "night1");
  fs::create_directories(dir / "night2");
  fs::create_symlink(meshes / "livesu2015_edgecone/bunny_out.mesh", dir / "night1/bunny.mesh");
  fs::create_symlink(meshes / "gao2016_sweeping/kitten_1.mesh", dir / "night1/kitten.mesh");
  fs::create_symlink(meshes / "livesu2015_edgecone/bunny_in.mesh", dir / "night2/bunny.mesh");
  fs::create_symlink(meshes / "smf2019/hex_cube_coarse.vtk", dir / "night2/cube.vtk");
  for (const char* night : {"night1", "night2"})
    ASSERT_EQ(
        run_hqview({"batch", (dir / night).string(), "-o", (dir / night).string() + "-out", "--no-render"}).exit_code,
        0);
  const CliResult d = run_hqview({"diff", (dir / "night1-out/index.json").string(), (dir / "night2-out").string(),
                                  "--gate", "quality.scaled_jacobian.min>=baseline-0.01", "--gate",
                                  "quality.scaled_jacobian.max<=baseline", "--markdown", (dir / "pr.md").string()});
  EXPECT_EQ(d.exit_code, 1) << d.err;
  EXPECT_NE(d.out.find("new mesh: cube.vtk"), std::string::npos) << d.out;
  EXPECT_NE(d.out.find("vanished mesh: kitten.mesh"), std::string::npos) << d.out;
  EXPECT_NE(d.err.find("gate failed: quality.scaled_jacobian.min>=baseline-0.01 [bunny.mesh]"), std::string::npos)
      << d.err;
  const std::string md = read_text(dir / "pr.md");
  EXPECT_NE(md.find("1 new, 1 vanished"), std::string::npos) << md;
}

}  // namespace
}  // namespace hq::test
