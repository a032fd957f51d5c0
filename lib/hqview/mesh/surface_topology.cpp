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

// Ascending (lo, hi, face) without a comparison sort: each face's sides
// counted into the bucket of their smaller id, then placed there in face
// order (two passes over the faces, no array but the result), each bucket
// (a vertex's edges up: a handful) ordered by hi by insertion, which keeps
// the face order among equal edges (the order of the sort by (lo, hi, face)
// it replaces; the sort took 2.5 % of the 1M-quad run).
std::vector<HalfEdge> sorted_half_edges(const Mesh& mesh) {
  const auto for_each_side = [&](auto body) {
    Index face = 0;
    for_each_surface_cell(mesh, [&](const std::array<Index, 4>& c, int size) {
      for (int i = 0; i < size; ++i) {
        const Index a = c[static_cast<std::size_t>(i)], b = c[static_cast<std::size_t>((i + 1) % size)];
        if (a != b) body(HalfEdge{std::min(a, b), std::max(a, b), face, a < b});
      }
      ++face;
    });
  };
  std::vector<std::size_t> next(mesh.points.size() + 1, 0);
  for_each_side([&](const HalfEdge& h) { ++next[static_cast<std::size_t>(h.lo) + 1]; });
  for (std::size_t v = 1; v < next.size(); ++v) next[v] += next[v - 1];
  std::vector<HalfEdge> half(next.back());
  for_each_side([&](const HalfEdge& h) { half[next[static_cast<std::size_t>(h.lo)]++] = h; });
  // next[v] is now the end of v's bucket; a large one (the apex of a fan)
  // by a stable sort.
  const auto by_hi = [](const HalfEdge& x, const HalfEdge& y) { return x.hi < y.hi; };
  for (std::size_t v = 0, begin = 0; v + 1 < next.size(); begin = next[v++]) {
    if (next[v] - begin > 32) {
      std::stable_sort(half.begin() + static_cast<std::ptrdiff_t>(begin),
                       half.begin() + static_cast<std::ptrdiff_t>(next[v]), by_hi);
      continue;
    }
    for (std::size_t i = begin + 1; i < next[v]; ++i) {
      const HalfEdge h = half[i];
      std::size_t j = i;
      for (; j > begin && by_hi(h, half[j - 1]); --j) half[j] = half[j - 1];
      half[j] = h;
    }
  }
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
  // Ascending by face, then other face and flips: a counting sort by face
  // (its links a handful: ordered by insertion).
  std::vector<std::size_t> first(num_faces + 1, 0);
  for (const auto& l : links) ++first[static_cast<std::size_t>(l[0]) + 1];
  for (std::size_t f = 0; f < num_faces; ++f) first[f + 1] += first[f];
  {
    std::vector<std::array<Index, 3>> by_face(links.size());
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (const auto& l : links) by_face[next[static_cast<std::size_t>(l[0])]++] = l;
    links = std::move(by_face);
  }
  for (std::size_t f = 0; f < num_faces; ++f)
    for (std::size_t i = first[f] + 1; i < first[f + 1]; ++i) {
      const std::array<Index, 3> l = links[i];
      std::size_t j = i;
      for (; j > first[f] && links[j - 1] > l; --j) links[j] = links[j - 1];
      links[j] = l;
    }

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
