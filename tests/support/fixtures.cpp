#include "support/fixtures.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace hq::test {

std::array<Vec3, 8> cube_corners() {
  return {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
}

HexMesh unit_cube() {
  HexMesh mesh;
  const auto corners = cube_corners();
  mesh.points.assign(corners.begin(), corners.end());
  mesh.hexes.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  return mesh;
}

HexMesh box_grid(int nx, int ny, int nz) {
  HexMesh mesh;
  auto id = [&](int i, int j, int k) { return static_cast<Index>(i + (nx + 1) * (j + (ny + 1) * k)); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) mesh.points.push_back({double(i), double(j), double(k)});
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                              id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
  return mesh;
}

HexMesh grid(int n) { return box_grid(n, n, n); }

std::array<Vec3, 8> twisted_hex(double theta) {
  auto p = cube_corners();
  const double c = std::cos(theta), s = std::sin(theta);
  for (int i = 4; i < 8; ++i) {
    const double x = p[i].x - 0.5, y = p[i].y - 0.5;
    p[i].x = 0.5 + c * x - s * y;
    p[i].y = 0.5 + s * x + c * y;
  }
  return p;
}

std::array<Vec3, 8> inverted_hex() {
  auto p = cube_corners();
  for (int i = 0; i < 4; ++i) std::swap(p[i], p[i + 4]);
  return p;
}

std::filesystem::path source_dir() { return HQVIEW_SOURCE_DIR; }

std::optional<std::filesystem::path> shared_data_dir() {
  if (const char* env = std::getenv("HQVIEW_DATA"); env && *env) {
    if (std::filesystem::is_directory(env)) return std::filesystem::path(env);
    return std::nullopt;
  }
  const auto dir = source_dir() / ".." / "shared" / "data";
  if (std::filesystem::is_directory(dir)) return std::filesystem::weakly_canonical(dir);
  return std::nullopt;
}

std::vector<std::filesystem::path> shared_hex_meshes(const std::filesystem::path& data) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(data / "meshes")) {
    const auto ext = entry.path().extension();
    if (entry.is_regular_file() && (ext == ".mesh" || ext == ".vtk")) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

double mean_edge_length(const HexMesh& mesh, const Topology& topology) {
  double sum = 0;
  for (const Edge& e : topology.edges)
    sum += norm(mesh.points[static_cast<std::size_t>(e[1])] - mesh.points[static_cast<std::size_t>(e[0])]);
  return topology.edges.empty() ? 0.0 : sum / static_cast<double>(topology.edges.size());
}

Vec3 turned(const Vec3& p, const Vec3& axis, double angle, const Vec3& shift) {
  const double c = std::cos(angle), s = std::sin(angle);
  return c * p + s * cross(axis, p) + ((1.0 - c) * dot(axis, p)) * axis + shift;
}

}  // namespace hq::test
