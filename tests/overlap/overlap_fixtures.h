#pragma once
// Defects the overlap tests inject into generated grids and real meshes, and
// small helpers to read an OverlapReport.

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/overlap.h"

namespace hq::test {

// A portable pseudo-random sequence (the standard distributions differ
// between standard libraries): 64-bit LCG, top 53 bits.
class Lcg {
 public:
  explicit Lcg(std::uint64_t seed) : state_(seed * 2862933555777941757ull + 3037000493ull) {}
  double uniform() {  // [0, 1)
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state_ >> 11) * 0x1p-53;
  }
  double symmetric() { return 2.0 * uniform() - 1.0; }  // [-1, 1)

 private:
  std::uint64_t state_;
};

inline Index grid_vertex(int n, int i, int j, int k) { return static_cast<Index>(i + (n + 1) * (j + (n + 1) * k)); }
inline Index grid_cell(int n, int i, int j, int k) { return static_cast<Index>(i + n * (j + n * k)); }

// Every vertex moved by up to `amplitude` (grid spacing 1) on each axis.
inline HexMesh jittered(HexMesh mesh, double amplitude, std::uint64_t seed) {
  Lcg rng(seed);
  for (Vec3& p : mesh.points)
    p = p + Vec3{amplitude * rng.symmetric(), amplitude * rng.symmetric(), amplitude * rng.symmetric()};
  return mesh;
}

// Vertex v gets a twin at the same position, used by the cells of `cells`
// instead of v (a crack along their faces). Returns the twin's id.
inline Index split_vertex(HexMesh& mesh, Index v, const std::vector<Index>& cells) {
  const Index twin = mesh.num_vertices();
  mesh.points.push_back(mesh.points[v]);
  for (Index h : cells)
    for (Index& id : mesh.hexes[h])
      if (id == v) id = twin;
  return twin;
}

// A hex scaled by `s` about cell h's centroid (new vertices), appended.
inline Index add_stray_cell(HexMesh& mesh, Index h, double s) {
  const auto corners = hex_corners(mesh, h);
  Vec3 c{};
  for (const Vec3& p : corners) c = c + p;
  c = c / 8.0;
  Hex hex;
  for (int i = 0; i < 8; ++i) {
    hex[i] = mesh.num_vertices();
    mesh.points.push_back(c + (corners[i] - c) * s);
  }
  mesh.hexes.push_back(hex);
  return mesh.num_hexes() - 1;
}

inline Vec3 centroid(const HexMesh& mesh, Index h) {
  Vec3 c{};
  for (const Vec3& p : hex_corners(mesh, h)) c = c + p;
  return c / 8.0;
}

inline std::vector<std::array<Index, 2>> pair_cells(const OverlapReport& r) {
  std::vector<std::array<Index, 2>> pairs;
  for (const IntersectingPair& p : r.intersecting_pairs) pairs.push_back(p.cells);
  return pairs;
}

inline const IntersectingPair* find_pair(const OverlapReport& r, Index a, Index b) {
  const std::array<Index, 2> key{std::min(a, b), std::max(a, b)};
  for (const IntersectingPair& p : r.intersecting_pairs)
    if (p.cells == key) return &p;
  return nullptr;
}

inline bool contains(const std::vector<Index>& list, Index x) {
  return std::find(list.begin(), list.end(), x) != list.end();
}

// Cells incident to vertex v, ascending.
inline std::vector<Index> cells_of_vertex(const Topology& topo, Index v) {
  return {topo.vertex_hexes.begin() + topo.vertex_hex_offsets[v],
          topo.vertex_hexes.begin() + topo.vertex_hex_offsets[v + 1]};
}

}  // namespace hq::test
