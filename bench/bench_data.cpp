#include "bench_data.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <vector>

namespace hq::bench {

std::filesystem::path largest_mesh() {
  namespace fs = std::filesystem;
  fs::path data = fs::path(HQVIEW_SOURCE_DIR) / ".." / "shared" / "data";
  if (const char* env = std::getenv("HQVIEW_DATA"); env && *env) data = env;
  const fs::path dolphin = data / "meshes" / "gao2016_sweeping" / "Dolphin_padded.mesh";
  if (fs::exists(dolphin)) return dolphin;
  return fs::path(HQVIEW_SOURCE_DIR) / "examples" / "ball.mesh";
}

hq::HexMesh refine_1_to_8(const hq::HexMesh& coarse) {
  hq::HexMesh fine;
  fine.points = coarse.points;
  std::map<std::vector<hq::Index>, hq::Index> made;  // sorted corner ids -> new point
  auto point_of = [&](std::vector<hq::Index> ids) {
    std::sort(ids.begin(), ids.end());
    if (ids.size() == 1) return ids[0];
    if (const auto it = made.find(ids); it != made.end()) return it->second;
    hq::Vec3 sum;
    for (hq::Index id : ids) sum = sum + coarse.points[static_cast<std::size_t>(id)];
    fine.points.push_back(sum / static_cast<double>(ids.size()));
    const auto id = static_cast<hq::Index>(fine.points.size() - 1);
    made.emplace(std::move(ids), id);
    return id;
  };
  // Corner of reference bits (r, s, t) in VTK order.
  static constexpr int kCorner[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}};
  for (const hq::Hex& hex : coarse.hexes) {
    hq::Index local[3][3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) {
          std::vector<hq::Index> ids;
          for (int r = 0; r < 2; ++r)
            for (int s = 0; s < 2; ++s)
              for (int t = 0; t < 2; ++t)
                if ((i == 1 || i == 2 * r) && (j == 1 || j == 2 * s) && (k == 1 || k == 2 * t))
                  ids.push_back(hex[kCorner[r][s][t]]);
          local[i][j][k] = point_of(std::move(ids));
        }
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int c = 0; c < 2; ++c)
          fine.hexes.push_back({local[a][b][c], local[a + 1][b][c], local[a + 1][b + 1][c], local[a][b + 1][c],
                                local[a][b][c + 1], local[a + 1][b][c + 1], local[a + 1][b + 1][c + 1],
                                local[a][b + 1][c + 1]});
  }
  return fine;
}

}  // namespace hq::bench
