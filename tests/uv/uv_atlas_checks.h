#pragma once
// Checks of a UV atlas shared by the atlas tests.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <tuple>
#include <vector>

#include "hqview/uv/uv_atlas.h"

namespace hq::test {

// Every triangle in exactly one chart, 0 flipped, 0 overlapping (exact), all
// UVs in [0,1]^2, and the atlas's own counts agree.
inline void expect_valid_atlas(const TriSurface& s, const UvAtlas& atlas, const std::string& name) {
  const std::size_t nt = s.triangles.size();
  ASSERT_EQ(atlas.uvs.size(), 3 * nt) << name;
  ASSERT_EQ(atlas.triangle_chart.size(), nt) << name;
  std::vector<int> chart_size(static_cast<std::size_t>(atlas.num_charts), 0);
  for (Index c : atlas.triangle_chart) {
    ASSERT_GE(c, 0) << name;
    ASSERT_LT(c, atlas.num_charts) << name;
    ++chart_size[c];
  }
  for (int n : chart_size) EXPECT_GT(n, 0) << name << ": empty chart";
  for (const Uv& p : atlas.uvs) {
    ASSERT_TRUE(p[0] >= 0.0 && p[0] <= 1.0 && p[1] >= 0.0 && p[1] <= 1.0) << name << ": " << p[0] << " " << p[1];
  }
  const auto flipped = uv_flipped_triangles(atlas.uvs);
  EXPECT_EQ(std::count(flipped.begin(), flipped.end(), 1), 0) << name;
  EXPECT_TRUE(uv_overlapping_pairs(atlas.uvs).empty()) << name;
  EXPECT_EQ(atlas.num_flipped, 0) << name;
  EXPECT_EQ(atlas.num_overlaps, 0) << name;
  EXPECT_GT(atlas.packing_efficiency, 0.0) << name;
  EXPECT_LE(atlas.packing_efficiency, 1.0) << name;
}

// V - E + F of each chart over its own vertices and edges (1: a disk). A
// vertex of a chart is a surface vertex at one UV position: where a chart is
// cut open along a seam, the two sides are two vertices.
inline std::vector<long> chart_euler_characteristics(const TriSurface& s, const UvAtlas& atlas) {
  using Vertex = std::tuple<Index, double, double>;
  std::vector<std::vector<Vertex>> vertices(static_cast<std::size_t>(atlas.num_charts));
  std::vector<std::vector<std::pair<Vertex, Vertex>>> edges(vertices.size());
  std::vector<long> faces(vertices.size(), 0);
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const auto c = static_cast<std::size_t>(atlas.triangle_chart[t]);
    ++faces[c];
    for (int k = 0; k < 3; ++k) {
      const Uv &p = atlas.uvs[3 * t + k], &q = atlas.uvs[3 * t + (k + 1) % 3];
      const Vertex a{s.triangles[t][k], p[0], p[1]}, b{s.triangles[t][(k + 1) % 3], q[0], q[1]};
      vertices[c].push_back(a);
      edges[c].emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::vector<long> out;
  for (std::size_t c = 0; c < vertices.size(); ++c) {
    std::sort(vertices[c].begin(), vertices[c].end());
    std::sort(edges[c].begin(), edges[c].end());
    const long v = std::unique(vertices[c].begin(), vertices[c].end()) - vertices[c].begin();
    const long e = std::unique(edges[c].begin(), edges[c].end()) - edges[c].begin();
    out.push_back(v - e + faces[c]);
  }
  return out;
}

inline void expect_disks(const TriSurface& s, const UvAtlas& atlas, const std::string& name) {
  const auto euler = chart_euler_characteristics(s, atlas);
  EXPECT_EQ(std::count(euler.begin(), euler.end(), 1L), static_cast<long>(euler.size())) << name;
}

}  // namespace hq::test
