// The model x method comparison from hand-made index rows: columns per
// method and variant, bold by direction, the cell kinds, per-method means
// and medians, the CSV long form and the TeX escaping.
#include "hqview/report/comparison.h"
#include "hqview/report/escape.h"

#include <gtest/gtest.h>

#include "hqview/core/error.h"

namespace hq {
namespace {

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
  const std::string md = comparison_markdown(c);
  EXPECT_NE(md.find("| model | ec · in | ec · out | pc |"), std::string::npos) << md;
  EXPECT_NE(md.find("| bunny | -0.01 | **0.6** | **0.6** |"), std::string::npos) << md;
  EXPECT_NE(md.find("| kitten | – | failed | 0.3 |"), std::string::npos) << md;
  const std::string tex = comparison_latex(c);
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

}  // namespace
}  // namespace hq
