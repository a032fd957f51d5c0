// Every real mesh of ../shared/data, written by an independent tool
// (Debian's python3-meshio, tests/io/meshio_write.py) as VTU (ASCII, binary,
// binary + zlib), Gmsh 2.2 and 4.1 (ASCII and binary), Abaqus and Exodus II,
// is read back by HQView's readers with:
//   - exactly meshio's own reading of the file (points bit for bit, hexes);
//   - the original hexes, and the original points bit for bit (to 1e-10 of
//     the bounding box for VTU ASCII, which meshio writes with 12 digits);
//   - the same values of all 22 Verdict metrics on every hex (bit for bit
//     when the points are).
// The files are generated in the build tree. Skipped when the data or
// meshio is absent.

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "hqview/io/exodus_reader.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/quality/hex_metrics.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

constexpr const char* kMeshes[] = {
    "gao2016_sweeping/kitten_1.mesh",
    "gao2016_sweeping/bunny_1.mesh",
    "gao2016_sweeping/hand7_1.mesh",
    "gao2016_sweeping/Dolphin_padded.mesh",
    "livesu2016_skeleton/armadillo.mesh",
    "livesu2016_skeleton/warrior.mesh",
    "livesu2015_edgecone/bunny_in.mesh",
    "livesu2015_edgecone/bunny_out.mesh",
    "li2012_srf/fandisk.mesh",
    "dualsheet2019/rockarm.vtk",
    "smf2019/hex_cube_coarse.vtk",
};

std::string shortest(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

void write_dump(const std::filesystem::path& path, const HexMesh& mesh) {
  std::ofstream out(path);
  out << mesh.points.size() << " " << mesh.hexes.size() << "\n";
  for (const Vec3& p : mesh.points) out << shortest(p.x) << " " << shortest(p.y) << " " << shortest(p.z) << "\n";
  for (const Hex& h : mesh.hexes) {
    for (int i = 0; i < 8; ++i) out << (i ? " " : "") << h[i];
    out << "\n";
  }
}

HexMesh read_dump(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::size_t v = 0, h = 0;
  in >> v >> h;
  HexMesh mesh;
  std::string x, y, z;
  for (std::size_t i = 0; i < v; ++i) {
    in >> x >> y >> z;
    const auto parse = [](const std::string& s) {
      double d = 0;
      std::from_chars(s.data(), s.data() + s.size(), d);
      return d;
    };
    mesh.points.push_back({parse(x), parse(y), parse(z)});
  }
  for (std::size_t i = 0; i < h; ++i) {
    Hex hex;
    for (Index& id : hex) in >> id;
    mesh.hexes.push_back(hex);
  }
  return mesh;
}

bool same_bits(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

double mean_volume(const HexMesh& mesh) {
  double sum = 0;
  for (Index h = 0; h < mesh.num_hexes(); ++h) sum += hex_volume(hex_corners(mesh, h));
  return sum / static_cast<double>(mesh.num_hexes());
}

std::filesystem::path out_root() { return std::filesystem::path(HQ_TEST_BINARY_DIR) / "meshio_roundtrip"; }

TEST(MeshioRoundTrip, EveryRealMeshInEveryFormat) {
  if (!test::shared_data_dir()) GTEST_SKIP() << "../shared/data (or $HQVIEW_DATA) not found";
  const std::string python = HQ_SYSTEM_PYTHON;
  if (python.empty()) GTEST_SKIP() << "python3 not found at configure time";
  if (std::system((python + " -c 'import meshio' 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << "python3-meshio is not installed (scripts/setup installs it)";

  int num_files = 0;
  int num_skipped_variants = 0;
  for (const char* relative : kMeshes) {
    SCOPED_TRACE(relative);
    const LoadedMesh original = read_hex_mesh(*test::shared_data_dir() / "meshes" / relative);
    const std::string stem = std::filesystem::path(relative).stem().string();
    const auto dir = out_root() / stem;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    write_dump(dir / "original.txt", original.mesh);
    const std::string command = python + " " + HQ_MESHIO_SCRIPT + " " + (dir / "original.txt").string() + " " +
                                dir.string() + " > " + (dir / "meshio.log").string() + " 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;

    const Vec3 lo = std::accumulate(original.mesh.points.begin(), original.mesh.points.end(), original.mesh.points[0],
                                    [](Vec3 a, const Vec3& b) {
                                      return Vec3{std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
                                    });
    const Vec3 hi = std::accumulate(original.mesh.points.begin(), original.mesh.points.end(), original.mesh.points[0],
                                    [](Vec3 a, const Vec3& b) {
                                      return Vec3{std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
                                    });
    const double diagonal =
        std::sqrt((hi.x - lo.x) * (hi.x - lo.x) + (hi.y - lo.y) * (hi.y - lo.y) + (hi.z - lo.z) * (hi.z - lo.z));
    // The original's metrics, once per mesh (each of its files is compared with them).
    const double volume = mean_volume(original.mesh);
    std::vector<double> original_metrics;
    original_metrics.reserve(static_cast<std::size_t>(original.mesh.num_hexes()) * kNumHexMetrics);
    for (Index h = 0; h < original.mesh.num_hexes(); ++h) {
      const HexCorners q = hex_corners(original.mesh, h);
      for (int m = 0; m < kNumHexMetrics; ++m) original_metrics.push_back(hex_metric(static_cast<HexMetric>(m), q, volume));
    }

    std::ifstream listing(dir / "files.txt");
    std::string line;
    while (std::getline(listing, line)) {
      if (line.starts_with("skip ")) {
        // Only Exodus may be missing (meshio needs python3-netcdf4 for it).
        EXPECT_TRUE(line.starts_with("skip exodus")) << line;
        ++num_skipped_variants;
        continue;
      }
      SCOPED_TRACE(line);
      const std::filesystem::path file = line;
      if (file.extension() == ".e" && !exodus_available()) {
        ++num_skipped_variants;
        continue;
      }
      const LoadedMesh loaded = read_hex_mesh(file);
      const HexMesh expected = read_dump(line + ".expect");
      ++num_files;

      // Exactly what meshio reads from the same file.
      ASSERT_EQ(loaded.mesh.points.size(), expected.points.size());
      ASSERT_EQ(loaded.mesh.hexes, expected.hexes);
      for (std::size_t i = 0; i < expected.points.size(); ++i)
        ASSERT_TRUE(same_bits(loaded.mesh.points[i], expected.points[i])) << "point " << i;

      // The original mesh.
      ASSERT_EQ(loaded.mesh.points.size(), original.mesh.points.size());
      ASSERT_EQ(loaded.mesh.hexes, original.mesh.hexes);
      const bool is_lossy = file.filename() == "vtu_ascii.vtu";
      for (std::size_t i = 0; i < original.mesh.points.size(); ++i) {
        const Vec3& a = loaded.mesh.points[i];
        const Vec3& b = original.mesh.points[i];
        if (is_lossy) {
          ASSERT_LE(std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)}), 1e-10 * diagonal);
        } else {
          ASSERT_TRUE(same_bits(a, b)) << "point " << i;
        }
      }

      // Every Verdict metric on every hex.
      const double loaded_volume = mean_volume(loaded.mesh);
      for (Index h = 0; h < original.mesh.num_hexes(); ++h) {
        const HexCorners p = hex_corners(loaded.mesh, h);
        for (int m = 0; m < kNumHexMetrics; ++m) {
          const double a = hex_metric(static_cast<HexMetric>(m), p, loaded_volume);
          const double b = original_metrics[static_cast<std::size_t>(h) * kNumHexMetrics + m];
          if (is_lossy) {
            ASSERT_NEAR(a, b, 1e-6 * std::max(1.0, std::abs(b))) << "hex " << h << " metric " << m;
          } else {
            ASSERT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << "hex " << h << " metric " << m;
          }
        }
      }
    }
  }
  std::cout << "[ meshio ] " << num_files << " files read back, " << num_skipped_variants
            << " variants skipped (Exodus without netCDF)\n";
  EXPECT_GE(num_files, 11 * 8);
}

}  // namespace
}  // namespace hq
