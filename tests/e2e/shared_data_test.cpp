// The CLI on every real mesh in ../shared/data (skipped when absent):
// counts from ../shared/data/README.md and the known defects of the papers'
// meshes.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/fixtures.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

namespace fs = std::filesystem;
using nlohmann::json;

struct SharedMesh {
  const char* path;
  int vertices;
  int hexes;
};

// ../shared/data/README.md's table.
const SharedMesh kSharedMeshes[] = {
    {"gao2016_sweeping/kitten_1.mesh", 425, 300},       {"gao2016_sweeping/bunny_1.mesh", 404, 264},
    {"gao2016_sweeping/hand7_1.mesh", 1362, 956},       {"gao2016_sweeping/Dolphin_padded.mesh", 48794, 45440},
    {"livesu2016_skeleton/armadillo.mesh", 5137, 3856}, {"livesu2016_skeleton/warrior.mesh", 24699, 19392},
    {"livesu2015_edgecone/bunny_in.mesh", 41749, 37734}, {"livesu2015_edgecone/bunny_out.mesh", 41749, 37734},
    {"li2012_srf/fandisk.mesh", 614, 357},              {"dualsheet2019/rockarm.vtk", 2651, 1858},
    {"smf2019/hex_cube_coarse.vtk", 136, 68},
};

void PrintTo(const SharedMesh& m, std::ostream* os) { *os << m.path; }

struct Bundle {
  json report;
  fs::path dir;
};

Bundle analyze_shared(const std::string& relative, bool render) {
  const auto data = shared_data_dir();
  const fs::path out = fresh_output_dir("shared/" + fs::path(relative).stem().string()) / "bundle";
  std::vector<std::string> args = {"analyze", "--data", "csv,vtu.zlib", (*data / "meshes" / relative).string(), "-o", out.string()};
  if (!render) args.push_back("--no-render");
  const CliResult r = run_hqview(args);
  EXPECT_EQ(r.exit_code, 0) << relative << ": " << r.err;
  if (r.exit_code != 0) return {};
  return {json::parse(read_text(out / "report.json")), out};
}

// Hexes with at least one negative corner scaled Jacobian, and the minimum
// corner value among them, from data/cells.csv.
std::pair<int, double> negative_corner_hexes(const fs::path& bundle) {
  const auto rows = read_csv(bundle / "data/cells.csv");
  int count = 0;
  double min_value = 1.0;
  const auto& header = rows.at(0);
  const auto first = std::find(header.begin(), header.end(), "corner_sj_0") - header.begin();
  for (std::size_t r = 1; r < rows.size(); ++r) {
    bool negative = false;
    for (int i = 0; i < 8; ++i) {
      const double v = std::stod(rows[r].at(static_cast<std::size_t>(first + i)));
      min_value = std::min(min_value, v);
      negative |= v < 0;
    }
    count += negative;
  }
  return {count, min_value};
}

class SharedData : public ::testing::TestWithParam<SharedMesh> {};

TEST_P(SharedData, CountsMatchTheDataReadme) {
  if (!shared_data_dir()) GTEST_SKIP() << "../shared/data absent (set HQVIEW_DATA to run these)";
  const SharedMesh& m = GetParam();
  // Render the smaller meshes too: the whole road, end to end.
  const Bundle b = analyze_shared(m.path, m.hexes < 5000);
  ASSERT_FALSE(b.report.is_null());
  EXPECT_EQ(b.report["mesh"]["num_vertices"], m.vertices);
  EXPECT_EQ(b.report["mesh"]["num_hexes"], m.hexes);
  EXPECT_EQ(b.report["quality"]["corner_scaled_jacobian"]["count"].get<int>() +
                b.report["quality"]["corner_scaled_jacobian"]["num_degenerate"].get<int>(),
            8 * m.hexes);
}

INSTANTIATE_TEST_SUITE_P(Meshes, SharedData, ::testing::ValuesIn(kSharedMeshes),
                         [](const auto& info) {
                           std::string name = fs::path(info.param.path).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(SharedDefects, RockarmHasElevenHexesWithANegativeCorner) {
  if (!shared_data_dir()) GTEST_SKIP() << "../shared/data absent";
  const Bundle b = analyze_shared("dualsheet2019/rockarm.vtk", false);
  ASSERT_FALSE(b.report.is_null());
  EXPECT_EQ(negative_corner_hexes(b.dir).first, 11);
}

TEST(SharedDefects, BunnyInHasOneBarelyInvertedHexAndBunnyOutNone) {
  if (!shared_data_dir()) GTEST_SKIP() << "../shared/data absent";
  const Bundle in = analyze_shared("livesu2015_edgecone/bunny_in.mesh", false);
  ASSERT_FALSE(in.report.is_null());
  const auto [count_in, min_in] = negative_corner_hexes(in.dir);
  EXPECT_EQ(count_in, 1);
  EXPECT_NEAR(min_in, -0.0028, 1e-4);
  EXPECT_NEAR(in.report["quality"]["corner_scaled_jacobian"]["min"].get<double>(), -0.0028, 1e-4);
  EXPECT_NEAR(in.report["quality"]["vertex_quality"]["min"].get<double>(), -0.0028, 1e-4);

  const Bundle out = analyze_shared("livesu2015_edgecone/bunny_out.mesh", false);
  ASSERT_FALSE(out.report.is_null());
  EXPECT_EQ(negative_corner_hexes(out.dir).first, 0);
  EXPECT_GT(out.report["quality"]["corner_scaled_jacobian"]["min"].get<double>(), 0.0);
}

TEST(SharedDefects, MislabelledVtkCellsLoadWithAWarning) {
  if (!shared_data_dir()) GTEST_SKIP() << "../shared/data absent";
  const Bundle b = analyze_shared("smf2019/hex_cube_coarse.vtk", false);
  ASSERT_FALSE(b.report.is_null());
  ASSERT_FALSE(b.report["warnings"].empty());
  EXPECT_NE(b.report["warnings"][0].get<std::string>().find("68"), std::string::npos) << b.report["warnings"][0];
}

}  // namespace
}  // namespace hq::test
