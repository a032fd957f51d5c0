#include "hqview/mesh/surface_topology.h"

#include <algorithm>
#include <deque>

namespace hq {
namespace {

// One side of an edge as a face runs along it.
struct HalfEdge {
  Index lo, hi;  // the edge's ids, lo < hi
  Index face;
  bool is_forward;  // the face runs lo -> hi
};

std::vector<HalfEdge> sorted_half_edges(const Mesh& mesh) {
  std::vector<HalfEdge> half;
  half.reserve(4 * mesh.quads.size() + 3 * mesh.triangles.size());
  Index face = 0;
  for_each_surface_cell(mesh, [&](const std::array<Index, 4>& c, int size) {
    for (int i = 0; i < size; ++i) {
      const Index a = c[static_cast<std::size_t>(i)], b = c[static_cast<std::size_t>((i + 1) % size)];
      if (a != b) half.push_back({std::min(a, b), std::max(a, b), face, a < b});
    }
    ++face;
  });
  std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.face < y.face;
  });
  return half;
}

}  // namespace

SurfaceTopology build_surface_topology(const Mesh& mesh) {
  SurfaceTopology t;
  const auto num_faces = static_cast<std::size_t>(mesh.quads.size() + mesh.triangles.size());
  const std::vector<HalfEdge> half = sorted_half_edges(mesh);
  // Neighbours across manifold edges, as (face, flips) pairs in CSR: flips
  // when the two run the edge the same way (their orientations disagree).
  std::vector<std::array<Index, 3>> links;  // face, other, flips
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    while (j < half.size() && half[j].lo == half[i].lo && half[j].hi == half[i].hi) ++j;
    const auto n = static_cast<Index>(j - i);
    t.edges.push_back({half[i].lo, half[i].hi});
    t.edge_num_faces.push_back(n);
    if (n == 1) ++t.num_boundary_edges;
    if (n > 2) ++t.num_non_manifold_edges;
    if (n == 2 && half[i].face != half[i + 1].face) {
      const Index flips = half[i].is_forward == half[i + 1].is_forward ? 1 : 0;
      links.push_back({half[i].face, half[i + 1].face, flips});
      links.push_back({half[i + 1].face, half[i].face, flips});
    }
    i = j;
  }
  std::sort(links.begin(), links.end());
  std::vector<std::size_t> first(num_faces + 1, 0);
  for (const auto& l : links) ++first[static_cast<std::size_t>(l[0]) + 1];
  for (std::size_t f = 0; f < num_faces; ++f) first[f + 1] += first[f];

  // Breadth-first from the lowest unvisited face: parity 1 = disagrees with it.
  t.is_reversed.assign(num_faces, 0);
  std::vector<signed char> parity(num_faces, -1);
  std::vector<Index> component;
  for (std::size_t seed = 0; seed < num_faces; ++seed) {
    if (parity[seed] >= 0) continue;
    ++t.num_components;
    component.clear();
    std::deque<Index> queue{static_cast<Index>(seed)};
    parity[seed] = 0;
    while (!queue.empty()) {
      const auto f = static_cast<std::size_t>(queue.front());
      queue.pop_front();
      component.push_back(static_cast<Index>(f));
      for (std::size_t k = first[f]; k < first[f + 1]; ++k) {
        const auto g = static_cast<std::size_t>(links[k][1]);
        if (parity[g] >= 0) continue;
        parity[g] = static_cast<signed char>(parity[f] ^ links[k][2]);
        queue.push_back(static_cast<Index>(g));
      }
    }
    std::size_t ones = 0;
    for (Index f : component) ones += static_cast<std::size_t>(parity[static_cast<std::size_t>(f)]);
    const signed char minority = 2 * ones <= component.size() ? 1 : 0;
    for (Index f : component)
      if (parity[static_cast<std::size_t>(f)] == minority) {
        t.is_reversed[static_cast<std::size_t>(f)] = 1;
        ++t.num_reversed;
      }
  }
  return t;
}

}  // namespace hq
