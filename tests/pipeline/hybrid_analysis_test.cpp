// The analyze pipeline on meshes with tetrahedra, wedges and pyramids beside
// the hexahedra: a hand-built mesh with a tangled tet and an inverted wedge
// (every number from a hand computation or the kernels), and two real
// hybrid meshes Debian's Gmsh makes in the test (counts from the .msh file,
// volumes by hand). One analyze run per mesh, with a recording renderer so
// that every view is drawn on the mixed mesh too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "hqview/pipeline/analyze.h"
#include "hqview/quality/cell_corner_jacobian.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/wedge_metrics.h"
#include "hqview/report/report_csv.h"
#include "io/gmsh_run.h"
#include "io/temp_dir.h"

namespace hq {
namespace HQ_TEST_UNIT {

using Json = nlohmann::ordered_json;

class BlankRenderer final : public Renderer {
 public:
  Image render(const Scene&, const Camera&, int width, int height) override {
    ++frames;
    return {width, height, std::vector<std::uint8_t>(4 * static_cast<std::size_t>(width) * height, 200)};
  }
  int frames = 0;
};

AnalyzeResult run(const std::filesystem::path& mesh, std::vector<std::string> gates = {}) {
  AnalyzeOptions options;
  options.mesh_path = mesh;
  options.tool_version = "test";
  options.views.width = 160;
  options.views.height = 120;
  for (const std::string& g : gates) options.gates.push_back(parse_gate_rule(g));
  BlankRenderer renderer;
  AnalyzeResult result = analyze(options, &renderer);
  EXPECT_GT(renderer.frames, 0);
  return result;
}

Json report_of(const AnalyzeResult& r) { return Json::parse(r.document.dump()); }

// Unit cube hex 0-7; above its top a valid tet (4,5,6,8) and a tangled one
// (4,7,6,8: (P7-P4) x (P6-P4) . (P8-P4) = -1); beside it at x in [1,2] a
// wedge on the hex's x = 1 face, listed with its triangles' normals towards
// each other (inverted in VTK order). File order: wedge, tangled tet, hex,
// valid tet (VTK cell ids 0-3, the source indices).
const std::vector<Vec3> kPoints = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1},
                                   {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, 2}, {2, 0, 0}, {2, 1, 0}};
constexpr const char* kHandMesh =
    "# vtk DataFile Version 4.2\nhand\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 11 double\n"
    "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1 0.5 0.5 2 2 0 0 2 1 0\n"
    "CELLS 4 26\n6 1 5 9 2 6 10\n4 4 7 6 8\n8 0 1 2 3 4 5 6 7\n4 4 5 6 8\n"
    "CELL_TYPES 4\n13\n10\n12\n10\n";

template <std::size_t N>
std::array<Vec3, N> corners(const std::array<int, N>& ids) {
  std::array<Vec3, N> p;
  for (std::size_t i = 0; i < N; ++i) p[i] = kPoints[static_cast<std::size_t>(ids[i])];
  return p;
}

TEST(HybridAnalysis, HandBuiltTangledTetAndInvertedWedgeAreFoundAndListed) {
  const test::TempDir dir("hybrid_hand");
  const AnalyzeResult result =
      run(dir.write("hand.vtk", kHandMesh), {"quality.by_kind.pyramid.metrics.scaled_jacobian.min>=0.2",
                                            "quality.by_kind.tet.metrics.scaled_jacobian.min>=0"});
  const Json r = report_of(result);
  const Json& q = r["quality"];
  // Hand: the tangled tet and the wedge are inverted, the hex and the valid tet not.
  EXPECT_EQ(q["num_inverted"], 2);
  EXPECT_EQ(r["headline"]["num_inverted"], 2);
  EXPECT_EQ(q["by_kind"]["hex"]["count"], 1);
  EXPECT_EQ(q["by_kind"]["hex"]["num_inverted"], 0);
  EXPECT_EQ(q["by_kind"]["tet"]["count"], 2);
  EXPECT_EQ(q["by_kind"]["tet"]["num_inverted"], 1);
  EXPECT_EQ(q["by_kind"]["wedge"]["count"], 1);
  EXPECT_EQ(q["by_kind"]["wedge"]["num_inverted"], 1);
  // No pyramid: count 0 and every pyramid metric null.
  EXPECT_EQ(q["by_kind"]["pyramid"]["count"], 0);
  ASSERT_EQ(q["by_kind"]["pyramid"]["metrics"].size(), 6u);  // Verdict's 5 and corner_scaled_jacobian
  for (const auto& [name, stats] : q["by_kind"]["pyramid"]["metrics"].items()) EXPECT_TRUE(stats.is_null()) << name;

  // The kernels: Verdict's scaled Jacobian of each cell.
  const double tangled = tet_scaled_jacobian(corners<4>({4, 7, 6, 8}));
  const double valid = tet_scaled_jacobian(corners<4>({4, 5, 6, 8}));
  const double wedge = wedge_metric(WedgeMetric::scaled_jacobian, corners<6>({1, 5, 9, 2, 6, 10}));
  ASSERT_LT(tangled, 0);
  ASSERT_LT(wedge, 0);
  EXPECT_EQ(q["by_kind"]["tet"]["metrics"]["scaled_jacobian"]["min"], std::min(tangled, valid));
  EXPECT_EQ(q["by_kind"]["wedge"]["metrics"]["scaled_jacobian"]["min"], wedge);
  EXPECT_EQ(q["scaled_jacobian"]["min"], std::min(tangled, wedge));
  EXPECT_EQ(q["scaled_jacobian"]["count"], 4);
  EXPECT_EQ(q["corner_scaled_jacobian"]["count"], 8 + 4 + 4 + 6);
  // Worst cells: the two inverted ones first, with kind and source index
  // (cell ids: hex 0, tets 1-2 in file order, wedge 3).
  const Json& worst = q["worst_cells"];
  const bool tet_first = tangled < wedge;
  EXPECT_EQ(worst[tet_first ? 0 : 1]["kind"], "tet");
  EXPECT_EQ(worst[tet_first ? 0 : 1]["cell"], 1);
  EXPECT_EQ(worst[tet_first ? 0 : 1]["source_index"], 1);
  EXPECT_EQ(worst[tet_first ? 1 : 0]["kind"], "wedge");
  EXPECT_EQ(worst[tet_first ? 1 : 0]["cell"], 3);
  EXPECT_EQ(worst[tet_first ? 1 : 0]["source_index"], 0);

  // Vertex 8 (tets only) and 9 (the wedge only) have a quality: the min of
  // their corners by the kernels (corner 3 of both tets; wedge corner 2).
  const Analysis& a = result.model.analysis;
  EXPECT_EQ(r["mesh"]["num_unreferenced_vertices"], 0);
  EXPECT_EQ(a.field.vertex_quality[8], std::min(tet_corner_scaled_jacobians(corners<4>({4, 7, 6, 8})).value[3],
                                                tet_corner_scaled_jacobians(corners<4>({4, 5, 6, 8})).value[3]));
  EXPECT_EQ(a.field.vertex_quality[9], wedge_corner_scaled_jacobians(corners<6>({1, 5, 9, 2, 6, 10})).value[2]);
  EXPECT_LT(a.field.vertex_quality[9], 0);

  // Headline: 4 cells, 1 hex; volumes by hand 1, 1/6, 1/6, 1/2.
  EXPECT_EQ(r["headline"]["num_cells"], 4);
  EXPECT_EQ(r["headline"]["num_cells_by_kind"]["tet"], 2);
  EXPECT_EQ(r["headline"]["hex_fraction"], 0.25);
  EXPECT_NEAR(r["headline"]["hex_volume_fraction"].get<double>(), 6.0 / 11.0, 1e-15);

  // Gates: no pyramid passes with a note; the tangled tet fails its gate.
  const Json& gates = r["gates"]["results"];
  EXPECT_TRUE(gates[0]["passed"].get<bool>());
  EXPECT_TRUE(gates[0]["value"].is_null());
  EXPECT_EQ(gates[0]["note"], "no pyramid in the mesh");
  EXPECT_FALSE(gates[1]["passed"].get<bool>());
  EXPECT_FALSE(gates[1].contains("note"));

  // cells.csv: a row per cell, with its kind and source index last.
  std::ostringstream csv;
  write_cells_csv(result.model, csv);
  std::istringstream lines(csv.str());
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(lines, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_TRUE(rows[0].ends_with(",cell_type,source_index"));
  EXPECT_TRUE(rows[1].ends_with(",hex,2"));
  EXPECT_TRUE(rows[2].ends_with(",tet,1"));  // the tangled one: first of the tets in the file
  EXPECT_TRUE(rows[3].ends_with(",tet,3"));
  EXPECT_TRUE(rows[4].ends_with(",wedge,0"));
  // The inverted column: hex, tangled tet, valid tet, wedge.
  const auto field = [](const std::string& row, int k) {
    std::size_t at = 0;
    for (int i = 0; i < k; ++i) at = row.find(',', at) + 1;
    return row.substr(at, row.find(',', at) - at);
  };
  int inverted = 0;
  while (field(rows[0], inverted) != "inverted") ++inverted;
  EXPECT_EQ(field(rows[1], inverted) + field(rows[2], inverted) + field(rows[3], inverted) + field(rows[4], inverted),
            "0101");
}

// Two boxes sharing the face x = 1: [0,1]^3 transfinite and recombined
// (125 hexes), [1,2] x [0,1]^2 tetrahedral; Gmsh puts a pyramid on each of
// the 25 interface quads.
using test::kTwoSquares;  // x = 1 between them
const std::string kBoxes = std::string("lc = 0.25;\n") + kTwoSquares + R"(
Transfinite Curve{1,2,3,4}=6; Transfinite Surface{1}; Recombine Surface{1};
a[] = Extrude{0,0,1}{Surface{1}; Layers{5}; Recombine;};
b[] = Extrude{0,0,1}{Surface{2};};
Coherence;
Physical Volume(1) = {a[1], b[1]};
)";
// A recombined square beside a triangulated one, extruded 0.6 in 3
// recombined layers: hexes under the square, wedges under the triangles.
const std::string kExtruded = std::string("lc = 0.3;\n") + kTwoSquares + R"(
Transfinite Curve{1,2,3,4}=5; Transfinite Surface{1}; Recombine Surface{1};
e[] = Extrude{0,0,0.6}{Surface{1,2}; Layers{3}; Recombine;};
Physical Volume(1) = {Volume{:}};
)";

struct GmshRun {
  std::map<int, int> counts;  // by Gmsh element type, from the file
  Json report;
};

std::optional<GmshRun> gmsh_run(const test::TempDir& dir, const std::string& geo) {
#ifdef HQ_GMSH_PATH
  if (!test::run_gmsh(HQ_GMSH_PATH, dir, geo, {"m22.msh"})) return std::nullopt;
  std::ifstream in(dir.path() / "m22.msh");
  std::stringstream text;
  text << in.rdbuf();
  GmshRun out{test::msh22_type_counts(text.str()), report_of(run(dir.path() / "m22.msh"))};
  return out;
#else
  (void)dir;
  (void)geo;
  return std::nullopt;
#endif
}

int count_of(const GmshRun& g, int type) { return g.counts.count(type) ? g.counts.at(type) : 0; }

TEST(HybridAnalysis, GmshHexPyramidTetBoxesAreAnalysedWhole) {
  const test::TempDir dir("hybrid_boxes");
  const auto g = gmsh_run(dir, kBoxes);
  if (!g) GTEST_SKIP() << "gmsh not found";
  const Json& r = g->report;
  const Json& k = r["quality"]["by_kind"];
  EXPECT_EQ(k["hex"]["count"], count_of(*g, 5));
  EXPECT_EQ(k["hex"]["count"], 125);
  EXPECT_EQ(k["tet"]["count"], count_of(*g, 4));
  EXPECT_EQ(k["pyramid"]["count"], count_of(*g, 7));
  EXPECT_EQ(k["pyramid"]["count"], 25);
  EXPECT_EQ(k["wedge"]["count"], 0);
  EXPECT_EQ(r["headline"]["num_cells"], 125 + count_of(*g, 4) + 25);
  // Every vertex is some cell's corner: quality everywhere, none unused.
  EXPECT_EQ(r["mesh"]["num_unreferenced_vertices"], 0);
  EXPECT_EQ(r["quality"]["vertex_quality"]["count"], r["mesh"]["num_vertices"]);
  EXPECT_EQ(r["quality"]["num_inverted"], 0);
  // Volumes by hand: the hex box 1 of 2; tets and pyramids fill the other.
  EXPECT_NEAR(r["headline"]["hex_volume_fraction"].get<double>(), 0.5, 1e-12);
  const auto total = [&](const char* kind) {
    const Json& v = k[kind]["metrics"]["volume"];
    return v["mean"].get<double>() * v["count"].get<double>();
  };
  EXPECT_NEAR(total("tet") + total("pyramid"), 1.0, 1e-12);
  EXPECT_TRUE(r["warnings"].empty()) << r["warnings"].dump();
}

TEST(HybridAnalysis, GmshExtrudedMixedSurfaceHexesAndWedges) {
  const test::TempDir dir("hybrid_extruded");
  const auto g = gmsh_run(dir, kExtruded);
  if (!g) GTEST_SKIP() << "gmsh not found";
  const Json& r = g->report;
  const Json& k = r["quality"]["by_kind"];
  EXPECT_EQ(k["hex"]["count"], 48);
  EXPECT_EQ(k["wedge"]["count"], count_of(*g, 6));
  EXPECT_GT(count_of(*g, 6), 0);
  EXPECT_EQ(k["tet"]["count"], 0);
  EXPECT_TRUE(k["tet"]["metrics"]["scaled_jacobian"].is_null());
  EXPECT_EQ(r["quality"]["num_inverted"], 0);
  EXPECT_EQ(r["quality"]["vertex_quality"]["count"], r["mesh"]["num_vertices"]);
  // Hand: the hexes fill [0,1]^2 x 0.6 of [0,2] x [0,1] x 0.6.
  EXPECT_NEAR(r["headline"]["hex_volume_fraction"].get<double>(), 0.5, 1e-12);
  const Json& v = k["wedge"]["metrics"]["volume"];
  EXPECT_NEAR(v["mean"].get<double>() * v["count"].get<double>(), 0.6, 1e-12);
  // Wedges of a straight extrusion of a valid triangle are valid: every
  // corner positive (Verdict's wedge scaled Jacobian > 0).
  EXPECT_GT(k["wedge"]["metrics"]["scaled_jacobian"]["min"].get<double>(), 0);
  EXPECT_EQ(k["wedge"]["metrics"]["corner_scaled_jacobian"]["count"].get<int>(), 6 * count_of(*g, 6));
}

}  // namespace
}  // namespace hq
