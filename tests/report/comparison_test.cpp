// The model x method comparison from hand-made index rows: columns per
// method and variant, bold by direction, the cell kinds, per-method means
// and medians, the CSV long form and the TeX escaping.
#include "hqview/report/comparison.h"
#include "hqview/report/escape.h"

#include <gtest/gtest.h>

#include "hqview/core/error.h"

namespace hq {
namespace HQ_TEST_UNIT {

std::size_t slot(std::string_view key) {
  for (std::size_t k = 0; k < kNumHeadlineKeys; ++k)
    if (key == kHeadlineKeys[k]) return k;
  return kNumHeadlineKeys;
}

BatchEntry mesh(const std::string& path, const std::string& method, const std::string& model,
                const std::string& variant, std::optional<double> min_sj, std::optional<double> hausdorff = {}) {
  BatchEntry e;
  e.path = path;
  e.label = method;
  e.model = model;
  e.variant = variant;
  e.status = min_sj ? BatchStatus::ok : BatchStatus::failed;
  e.bundle = min_sj ? path : "";
  e.headline[slot("quality.scaled_jacobian.min")] = min_sj;
  e.headline[slot("mesh.num_hexes")] = min_sj ? std::optional<double>(100) : std::nullopt;
  e.headline[slot("boundary_error.hausdorff.relative")] = hausdorff;
  return e;
}

std::vector<BatchEntry> collection() {
  return {mesh("a/bunny_in.mesh", "ec", "bunny", "in", -0.01, 0.02),
          mesh("a/bunny_out.mesh", "ec", "bunny", "out", 0.6, 0.01),
          mesh("a/kitten_out.mesh", "ec", "kitten", "out", std::nullopt),
          mesh("b/bunny.mesh", "pc", "bunny", "", 0.6),
          mesh("b/kitten.mesh", "pc", "kitten", "", 0.3, 0.05),
          mesh("b/rod.mesh", "pc", "rod", "", 0.9)};
}

TEST(Comparison, OneColumnPerMethodAndVariantOneRowPerModel) {
  const std::vector<BatchEntry> entries = collection();
  const Comparison c = build_comparison(entries, parse_comparison_keys(
                                                     "quality.scaled_jacobian.min,mesh.num_hexes,"
                                                     "boundary_error.hausdorff.relative"));
  ASSERT_EQ(c.columns.size(), 3u);
  EXPECT_EQ(column_heading(c.columns[0]), "ec · in");
  EXPECT_EQ(column_heading(c.columns[1]), "ec · out");
  EXPECT_EQ(column_heading(c.columns[2]), "pc");
  ASSERT_EQ(c.rows.size(), 3u);
  EXPECT_EQ(c.rows[0].model, "bunny");

  // min SJ, higher is better: the two 0.6 of bunny tie, both bold.
  auto cells = comparison_cells(c, c.rows[0], 0);
  EXPECT_EQ(cells[0].text, "-0.01");
  EXPECT_FALSE(cells[0].is_best);
  EXPECT_TRUE(cells[1].is_best && cells[2].is_best);
  // kitten: a failed mesh, a missing variant, one value (no bold alone).
  cells = comparison_cells(c, c.rows[1], 0);
  EXPECT_EQ(cells[0].text, "–");
  EXPECT_EQ(cells[1].text, "failed");
  EXPECT_EQ(cells[2].text, "0.3");
  EXPECT_FALSE(cells[2].is_best);
  // #H has no direction: never bold.
  for (const ComparisonCell& cell : comparison_cells(c, c.rows[0], 1)) EXPECT_FALSE(cell.is_best);
  // Hausdorff, lower is better; bunny's pc mesh had no reference.
  cells = comparison_cells(c, c.rows[0], 2);
  EXPECT_TRUE(cells[1].is_best);
  EXPECT_EQ(cells[2].text, "no ref.");

  // Per method: ec meshed 3 (2 models, 1 failed, 1 valid); pc 3 models.
  ASSERT_EQ(c.methods.size(), 2u);
  EXPECT_EQ(c.methods[0].num_meshes, 3);
  EXPECT_EQ(c.methods[0].num_models, 2);
  EXPECT_EQ(c.methods[0].num_failed, 1);
  EXPECT_EQ(c.methods[0].num_valid, 1);
  EXPECT_DOUBLE_EQ(*c.methods[0].mean[0], (-0.01 + 0.6) / 2);
  EXPECT_DOUBLE_EQ(*c.methods[1].mean[0], (0.6 + 0.3 + 0.9) / 3);
  EXPECT_DOUBLE_EQ(*c.methods[1].median[0], 0.6);
  EXPECT_DOUBLE_EQ(*c.methods[1].median[2], 0.05);  // one value with a reference
}

TEST(Comparison, MarkdownAndTexTables) {
  const std::vector<BatchEntry> entries = collection();
  const Comparison c = build_comparison(entries, parse_comparison_keys("quality.scaled_jacobian.min"));
  const std::string md = comparison_markdown({c});
  EXPECT_NE(md.find("| model | ec · in | ec · out | pc |"), std::string::npos) << md;
  EXPECT_NE(md.find("| bunny | -0.01 | **0.6** | **0.6** |"), std::string::npos) << md;
  EXPECT_NE(md.find("| kitten | – | failed | 0.3 |"), std::string::npos) << md;
  const std::string tex = comparison_latex({c});
  EXPECT_NE(tex.find("\\caption{min SJ (quality.scaled\\_jacobian.min; higher is better)}"), std::string::npos) << tex;
  EXPECT_NE(tex.find("bunny & -0.01 & \\textbf{0.6} & \\textbf{0.6} \\\\"), std::string::npos) << tex;
  EXPECT_NE(tex.find("kitten & -- & failed & 0.3 \\\\"), std::string::npos) << tex;
  EXPECT_EQ(latex_escape("a_b & 50% #1 {x} ~ ^ \\ $"),
            "a\\_b \\& 50\\% \\#1 \\{x\\} \\textasciitilde{} \\textasciicircum{} \\textbackslash{} \\$");
  EXPECT_EQ(latex_escape("D\xa6ta"), "D\\textbackslash{}xa6ta");
}

TEST(Comparison, CsvLongFormAndKeys) {
  std::vector<BatchEntry> entries = collection();
  entries[0].model = "bun,ny \"x\"";
  const std::string csv = comparison_csv(entries);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "model,variant,method,mesh,status,mesh.num_vertices,mesh.num_hexes,"
                                           "quality.scaled_jacobian.min,quality.scaled_jacobian.mean,"
                                           "quality.scaled_jacobian.p05,quality.num_inverted,"
                                           "overlap.num_intersecting_cells,boundary_error.hausdorff.relative,"
                                           "structure.num_singular_edges_interior,"
                                           "structure.num_singular_edges_boundary,fem.element.num_invalid,"
                                           "fem.element.num_not_invertible,"
                                           "fem.poisson.mean.l2_error,fem.poisson.mean.h1_error,"
                                           "fem.poisson.scaled_matrix.condition,headline.num_cells,"
                                           "headline.num_cells_by_kind.tet,headline.num_cells_by_kind.wedge,"
                                           "headline.num_cells_by_kind.pyramid,headline.hex_fraction,"
                                           "headline.hex_volume_fraction");
  EXPECT_NE(csv.find("\n\"bun,ny \"\"x\"\"\",in,ec,a/bunny_in.mesh,ok,,100,-0.01,,,,,0.02,,,,,,,,,,,,,\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("\nkitten,out,ec,a/kitten_out.mesh,failed,,,,,,,,,,,,,,,,,,,,,\n"), std::string::npos) << csv;
  // Text from input as message text: no raw byte, no line break from input.
  entries[1].path = "a/kit\xa6\nten.mesh";
  const std::string escaped = comparison_csv(entries);
  EXPECT_NE(escaped.find("\nbunny,out,ec,a/kit\\xa6\\x0aten.mesh,ok,"), std::string::npos) << escaped;
  EXPECT_THROW(parse_comparison_keys("quality.nope"), ValueError);
  EXPECT_THROW(parse_comparison_keys(""), ValueError);
  // Default keys: the singular edges only when some row has them.
  EXPECT_EQ(default_comparison_keys(entries).size(), 6u);
  entries[1].headline[slot("structure.num_singular_edges_interior")] = 12;
  EXPECT_EQ(default_comparison_keys(entries).back().key, "structure.num_singular_edges_interior");
  // The finite-element errors likewise (--simulate), lower is better.
  entries[1].headline[slot("fem.poisson.mean.l2_error")] = 1e-4;
  entries[1].headline[slot("fem.poisson.mean.h1_error")] = 0.02;
  const std::vector<ComparisonKey> keys = default_comparison_keys(entries);
  ASSERT_EQ(keys.size(), 9u);
  EXPECT_EQ(keys[7].key, "fem.poisson.mean.l2_error");
  EXPECT_EQ(keys[8].key, "fem.poisson.mean.h1_error");
  EXPECT_EQ(keys[8].direction, -1);
  EXPECT_EQ(parse_comparison_keys("fem.poisson.scaled_matrix.condition, fem.element.num_invalid").size(), 2u);
}

// A batch of volume and surface meshes (issue 47) compares them apart: a
// group each, volume first, each over its own models with its own default
// keys (a surface's #quads, #triangles when some mesh has one, irregular
// interior vertices when some has them; no #H), its own chart file and
// headings; a failed mesh joins its model's group.
TEST(Comparison, VolumeAndSurfaceMeshesAreComparedApart) {
  std::vector<BatchEntry> entries = collection();
  const auto surface = [](const std::string& path, const std::string& method, const std::string& model,
                          std::optional<double> min_sj, double quads, double triangles, double irregular) {
    BatchEntry e = mesh(path, method, model, "", min_sj);
    e.headline[slot("mesh.num_hexes")] = 0;
    if (min_sj) e.surface = SurfaceCounts{quads, triangles, irregular, 4};
    return e;
  };
  entries.push_back(surface("c/grid_a.obj", "ec", "grid", -0.9, 64, 0, 0));
  entries.push_back(surface("c/grid_b.obj", "pc", "grid", 0.5, 60, 8, 2));
  entries.push_back(surface("c/vase.obj", "pc", "vase", std::nullopt, 0, 0, 0));  // failed: no counts
  entries.push_back(surface("c/vase_ok.obj", "ec", "vase", 0.7, 100, 0, 0));
  const std::vector<Comparison> groups = comparison_groups(entries, nullptr);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].group, "volume meshes");
  EXPECT_EQ(group_heading(groups[1]), "Surface meshes");
  EXPECT_EQ(groups[0].chart_file, "comparison_min_sj.svg");
  EXPECT_EQ(groups[1].chart_file, "comparison_min_sj_surface.svg");
  ASSERT_EQ(groups[0].rows.size(), 3u);  // bunny, kitten, rod
  ASSERT_EQ(groups[1].rows.size(), 2u);  // grid, vase (with its failed mesh)
  EXPECT_EQ(groups[1].rows[1].model, "vase");
  EXPECT_EQ(groups[1].entries.size(), 4u);
  std::vector<std::string_view> keys;
  for (const ComparisonKey& k : groups[1].keys) keys.push_back(k.key);
  EXPECT_EQ(keys, (std::vector<std::string_view>{"mesh.num_vertices", "surface.num_quads", "surface.num_triangles",
                                                 "quality.scaled_jacobian.min", "quality.scaled_jacobian.mean",
                                                 "quality.num_inverted", "boundary_error.hausdorff.relative",
                                                 "surface.num_irregular_vertices_interior"}));
  EXPECT_EQ(groups[0].keys.size(), 6u);  // the volume defaults, #H among them
  EXPECT_EQ(groups[0].keys[1].key, "mesh.num_hexes");
  // grid: ec has 0 irregular vertices, pc 2: lower is better.
  const std::vector<ComparisonCell> irregular = comparison_cells(groups[1], groups[1].rows[0], 7);
  EXPECT_EQ(irregular[0].text, "0");
  EXPECT_TRUE(irregular[0].is_best);
  EXPECT_EQ(irregular[1].text, "2");
  const std::vector<ComparisonCell> vase = comparison_cells(groups[1], groups[1].rows[1], 1);
  EXPECT_EQ(vase[0].text, "100");
  EXPECT_EQ(vase[1].text, "failed");
  // Per method, over the group's meshes only: pc's surface meshes are 2 (one failed).
  EXPECT_EQ(groups[1].methods[1].num_meshes, 2);
  EXPECT_EQ(groups[1].methods[1].num_failed, 1);
  EXPECT_DOUBLE_EQ(*groups[1].methods[0].mean[3], (-0.9 + 0.7) / 2);

  const std::string md = comparison_markdown(groups);
  const std::size_t volume_at = md.find("\n## Volume meshes\n"), surface_at = md.find("\n## Surface meshes\n");
  ASSERT_NE(volume_at, std::string::npos) << md;
  ASSERT_NE(surface_at, std::string::npos) << md;
  EXPECT_LT(volume_at, surface_at);
  EXPECT_NE(md.find("\n### #quads (`surface.num_quads`)\n"), std::string::npos) << md;
  EXPECT_NE(md.find("](comparison_min_sj_surface.svg)"), std::string::npos) << md;
  EXPECT_EQ(md.find("| grid |", 0), md.find("| grid |", surface_at)) << "a surface model in a volume table";
  const std::string tex = comparison_latex(groups);
  EXPECT_NE(tex.find("\\caption{Surface meshes: \\#quads"), std::string::npos) << tex;

  // One dimension: one group without a heading, the old chart name.
  const std::vector<BatchEntry> volumes = collection();
  const std::vector<Comparison> volume_only = comparison_groups(volumes, nullptr);
  ASSERT_EQ(volume_only.size(), 1u);
  EXPECT_TRUE(volume_only[0].group.empty());
  EXPECT_EQ(comparison_markdown(volume_only).find("Volume meshes"), std::string::npos);
  // --compare-keys: the same keys in both groups.
  const std::vector<ComparisonKey> chosen = parse_comparison_keys("quality.scaled_jacobian.min,surface.num_quads");
  for (const Comparison& c : comparison_groups(entries, &chosen)) EXPECT_EQ(c.keys.size(), 2u);
}

}  // namespace
}  // namespace hq
