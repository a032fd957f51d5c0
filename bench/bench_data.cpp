#include "bench_data.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <unordered_map>
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
  fine.points.reserve(coarse.points.size() + 4 * coarse.hexes.size());
  fine.hexes.reserve(8 * coarse.hexes.size());
  // Sorted corner ids (padded with kNoIndex) of an edge or face -> its new
  // point; cell centres are never shared. New points are numbered in the
  // order they are first met, so the result does not depend on the map.
  using Key = std::array<hq::Index, 4>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0x9E3779B97F4A7C15ull;
      for (hq::Index id : k) h = (h ^ static_cast<std::uint32_t>(id)) * 0x100000001B3ull;
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };
  std::unordered_map<Key, hq::Index, KeyHash> made;
  made.reserve(4 * coarse.hexes.size());
  auto point_of = [&](std::vector<hq::Index>& ids) {
    std::sort(ids.begin(), ids.end());
    if (ids.size() == 1) return ids[0];
    Key key;
    key.fill(hq::kNoIndex);
    const bool is_shared = ids.size() <= key.size();
    if (is_shared) {
      std::copy(ids.begin(), ids.end(), key.begin());
      if (const auto it = made.find(key); it != made.end()) return it->second;
    }
    hq::Vec3 sum;
    for (hq::Index id : ids) sum = sum + coarse.points[static_cast<std::size_t>(id)];
    fine.points.push_back(sum / static_cast<double>(ids.size()));
    const auto id = static_cast<hq::Index>(fine.points.size() - 1);
    if (is_shared) made.emplace(key, id);
    return id;
  };
  // Corner of reference bits (r, s, t) in VTK order.
  static constexpr int kCorner[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}};
  std::vector<hq::Index> ids;
  for (const hq::Hex& hex : coarse.hexes) {
    hq::Index local[3][3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) {
          ids.clear();
          for (int r = 0; r < 2; ++r)
            for (int s = 0; s < 2; ++s)
              for (int t = 0; t < 2; ++t)
                if ((i == 1 || i == 2 * r) && (j == 1 || j == 2 * s) && (k == 1 || k == 2 * t))
                  ids.push_back(hex[kCorner[r][s][t]]);
          local[i][j][k] = point_of(ids);
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
