#include "hqview/uv/uv_cut.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>
#include <utility>

#include "hqview/core/vec3.h"

namespace hq {
namespace {

// One edge of the chart: its key, its two chart vertices, and for an edge
// the chart glues, its two triangles (chart order).
struct ChartEdge {
  std::uint64_t key;
  std::uint32_t u, v;
  std::uint32_t t0, t1;
  bool glued;
  double length;
};

std::uint32_t find(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

std::vector<std::uint64_t> disk_cut(const TriSurface& surface, std::span<const Index> chart,
                                    std::span<const std::uint64_t> seams) {
  const std::size_t nt = chart.size();
  if (nt < 2) return {};
  // Chart vertices are the surface vertices the chart touches.
  std::vector<Index> ids;
  ids.reserve(3 * nt);
  for (Index t : chart) ids.insert(ids.end(), surface.triangles[t].begin(), surface.triangles[t].end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  auto local = [&](Index v) {
    return static_cast<std::uint32_t>(std::lower_bound(ids.begin(), ids.end(), v) - ids.begin());
  };
  // Edges: glued when exactly two chart triangles share them and they are
  // no seam (as lscm_chart_layout glues); every other edge is already cut.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> sides;  // key, chart triangle
  sides.reserve(3 * nt);
  for (std::size_t i = 0; i < nt; ++i) {
    const auto& tri = surface.triangles[chart[i]];
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint32_t>(tri[k]), b = static_cast<std::uint32_t>(tri[(k + 1) % 3]);
      sides.emplace_back(static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b),
                         static_cast<std::uint32_t>(i));
    }
  }
  std::sort(sides.begin(), sides.end());
  std::vector<ChartEdge> edges;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].first == sides[i].first) ++j;
    const std::uint64_t key = sides[i].first;
    const auto a = static_cast<Index>(key >> 32), b = static_cast<Index>(key & 0xffffffffu);
    const bool glued = j - i == 2 && !std::binary_search(seams.begin(), seams.end(), key);
    edges.push_back({key, local(a), local(b), sides[i].second, glued ? sides[i + 1].second : sides[i].second, glued,
                     norm(surface.points[a] - surface.points[b])});
    i = j;
  }
  const std::size_t nv = ids.size(), ne = edges.size();

  // Primal shortest-path forest along glued edges, grown from every vertex
  // on a cut edge (or from the first vertex of a closed chart).
  std::vector<std::uint32_t> first(nv + 1, 0), incident;
  for (const ChartEdge& e : edges)
    if (e.glued) ++first[e.u + 1], ++first[e.v + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  incident.resize(first[nv]);
  {
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (std::uint32_t e = 0; e < ne; ++e)
      if (edges[e].glued) incident[fill[edges[e].u]++] = e, incident[fill[edges[e].v]++] = e;
  }
  constexpr double kFar = std::numeric_limits<double>::infinity();
  std::vector<double> dist(nv, kFar);
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (const ChartEdge& e : edges)
    if (!e.glued)
      for (std::uint32_t v : {e.u, e.v})
        if (dist[v] != 0.0) dist[v] = 0.0, queue.emplace(0.0, v);
  if (queue.empty()) dist[0] = 0.0, queue.emplace(0.0, 0u);
  std::vector<std::uint8_t> in_tree(ne, 0);
  std::vector<std::uint32_t> via(nv, std::numeric_limits<std::uint32_t>::max());
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    for (std::uint32_t i = first[v]; i < first[v + 1]; ++i) {
      const ChartEdge& e = edges[incident[i]];
      const std::uint32_t w = e.u == v ? e.v : e.u;
      if (d + e.length < dist[w]) {
        dist[w] = d + e.length;
        via[w] = incident[i];
        queue.emplace(dist[w], w);
      }
    }
  }
  for (std::uint32_t v = 0; v < nv; ++v)
    if (via[v] != std::numeric_limits<std::uint32_t>::max()) in_tree[via[v]] = 1;

  // Dual spanning tree of the other glued edges, the edge closing the
  // longest loop first, so that the edges left over close the shortest.
  std::vector<std::uint32_t> rest;
  for (std::uint32_t e = 0; e < ne; ++e)
    if (edges[e].glued && !in_tree[e]) rest.push_back(e);
  auto loop = [&](std::uint32_t e) { return dist[edges[e].u] + dist[edges[e].v] + edges[e].length; };
  std::sort(rest.begin(), rest.end(), [&](std::uint32_t x, std::uint32_t y) {
    const double lx = loop(x), ly = loop(y);
    return lx != ly ? lx > ly : edges[x].key < edges[y].key;
  });
  std::vector<std::uint32_t> parent(nt);
  std::iota(parent.begin(), parent.end(), 0u);
  std::size_t joined = 0;
  std::vector<std::uint8_t> cut(ne, 1);  // cut graph: every edge but the dual tree's
  bool leftover = false;
  for (std::uint32_t e : rest) {
    const std::uint32_t a = find(parent, edges[e].t0), b = find(parent, edges[e].t1);
    if (a == b) {
      leftover = true;
      continue;
    }
    parent[std::max(a, b)] = std::min(a, b);
    cut[e] = 0;
    ++joined;
  }
  if (joined + 1 != nt || !leftover) return {};

  // Glue dangling branches back: a glued edge of the cut graph with an end
  // that no other cut edge reaches only slits the disk.
  std::vector<std::uint32_t> degree(nv, 0);
  for (std::uint32_t e = 0; e < ne; ++e)
    if (cut[e]) ++degree[edges[e].u], ++degree[edges[e].v];
  std::vector<std::uint32_t> dangling;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (degree[v] == 1) dangling.push_back(v);
  while (!dangling.empty()) {
    const std::uint32_t v = dangling.back();
    dangling.pop_back();
    if (degree[v] != 1) continue;
    for (std::uint32_t i = first[v]; i < first[v + 1]; ++i) {
      const std::uint32_t e = incident[i];
      if (!cut[e]) continue;
      cut[e] = 0;
      degree[v] = 0;
      const std::uint32_t w = edges[e].u == v ? edges[e].v : edges[e].u;
      if (--degree[w] == 1) dangling.push_back(w);
      break;
    }
  }
  std::vector<std::uint64_t> extra;
  for (std::uint32_t e = 0; e < ne; ++e)
    if (cut[e] && edges[e].glued) extra.push_back(edges[e].key);
  return extra;  // ascending: edges are in key order
}

}  // namespace hq
