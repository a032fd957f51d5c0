#pragma once
// A hand-built mesh of every volume kind for tests: an n x n x n grid of unit
// cubes, cube i (x fastest) kept as a hex, split into 6 tets (Kuhn: around
// its 0-6 diagonal), into 2 wedges, or into 6 pyramids to an added centre,
// by i % 4 (so quads meet quads and triangles meet quads: conforming and
// non-conforming interfaces); then the first tet repeated (its faces used 3
// times, non-manifold; a duplicate cell) and a lone wedge on the top (a
// wedge's boundary quads). Grid points moved by `jitter` times a fixed
// pseudo-random offset in [-1, 1]^3 (0: the unit grid), so that cell sizes
// differ.

#include <array>
#include <cstdint>

#include "hqview/core/hex_topology.h"
#include "hqview/mesh/mesh.h"

namespace hq::test {

inline Mesh mixed_grid(int n = 3, double jitter = 0.0) {
  Mesh mesh;
  const auto id = [&](int x, int y, int z) { return static_cast<Index>(x + (n + 1) * (y + (n + 1) * z)); };
  const auto add = [&](Vec3 p) {
    mesh.points.push_back(p);
    return static_cast<Index>(mesh.points.size() - 1);
  };
  std::uint32_t state = 12345;
  const auto next = [&] {  // a linear congruential sequence in [-1, 1]
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 23) - 1.0;
  };
  for (int z = 0; z <= n; ++z)
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x) {
        const double dx = jitter * next(), dy = jitter * next(), dz = jitter * next();
        add({x + dx, y + dy, z + dz});
      }
  int i = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x, ++i) {
        const Hex h = {id(x, y, z),     id(x + 1, y, z),     id(x + 1, y + 1, z),     id(x, y + 1, z),
                       id(x, y, z + 1), id(x + 1, y, z + 1), id(x + 1, y + 1, z + 1), id(x, y + 1, z + 1)};
        const auto c = [&](int k) { return h[static_cast<std::size_t>(k)]; };
        if (i % 4 == 0) {
          mesh.hexes.push_back(h);
        } else if (i % 4 == 1) {
          for (const auto& t : {std::array{0, 1, 2, 6}, std::array{0, 5, 1, 6}, std::array{0, 4, 5, 6},
                                std::array{0, 7, 4, 6}, std::array{0, 3, 7, 6}, std::array{0, 2, 3, 6}})
            mesh.tets.push_back({c(t[0]), c(t[1]), c(t[2]), c(t[3])});
        } else if (i % 4 == 2) {
          mesh.wedges.push_back({c(0), c(1), c(2), c(4), c(5), c(6)});
          mesh.wedges.push_back({c(0), c(2), c(3), c(4), c(6), c(7)});
        } else {
          const Index centre = add({x + 0.5, y + 0.5, z + 0.5});
          for (const auto& f : kHexFaces) mesh.pyramids.push_back({c(f[0]), c(f[1]), c(f[2]), c(f[3]), centre});
        }
      }
  mesh.tets.push_back(mesh.tets.front());
  const Index a = add({0, 0, n + 1.0}), b = add({1, 0, n + 1.0}), d = add({0, 1, n + 1.0});
  mesh.wedges.push_back({id(0, 0, n), id(1, 0, n), id(0, 1, n), a, b, d});
  return mesh;
}

}  // namespace hq::test
