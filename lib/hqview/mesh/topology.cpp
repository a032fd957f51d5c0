#include "hqview/mesh/topology.h"

#include <algorithm>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "hqview/core/hex_topology.h"

namespace hq {
namespace {

// Counting sort of items by a key in [0, num_keys): returns CSR offsets and
// the item order. Stable, so ties keep their input order.
template <class KeyOf>
void bucket_by_key(std::size_t num_items, std::size_t num_keys, KeyOf key_of, std::vector<Index>& offsets,
                   std::vector<Index>& order) {
  offsets.assign(num_keys + 1, 0);
  for (std::size_t i = 0; i < num_items; ++i) ++offsets[static_cast<std::size_t>(key_of(i)) + 1];
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  order.resize(num_items);
  std::vector<Index> cursor(offsets.begin(), offsets.end() - 1);
  for (std::size_t i = 0; i < num_items; ++i)
    order[static_cast<std::size_t>(cursor[key_of(i)]++)] = static_cast<Index>(i);
}

Quad sorted_quad(Quad q) {
  std::sort(q.begin(), q.end());
  return q;
}

void build_vertex_hexes(const HexMesh& mesh, Topology& topo) {
  const std::size_t nv = mesh.points.size();
  const std::size_t nc = mesh.hexes.size() * 8;
  std::vector<Index> corner_order;
  bucket_by_key(
      nc, nv, [&](std::size_t c) { return mesh.hexes[c / 8][c % 8]; }, topo.vertex_hex_offsets, corner_order);
  // Corners are bucketed in ascending corner order, so hexes come out
  // ascending within each vertex (a hex never repeats a vertex after io/).
  topo.vertex_hexes.resize(nc);
  for (std::size_t i = 0; i < nc; ++i) topo.vertex_hexes[i] = corner_order[i] / 8;
  for (std::size_t v = 0; v < nv; ++v)
    if (topo.vertex_hex_offsets[v] == topo.vertex_hex_offsets[v + 1])
      topo.unreferenced_vertices.push_back(static_cast<Index>(v));
}

// Faces: every hex's 6 faces keyed by their sorted ids, bucketed by the
// smallest id (linear), then sorted within each small bucket, and numbered
// in that order: bucket by bucket (in parallel, each bucket's first face
// from a prefix sum of the buckets' face counts), so any thread count gives
// the same numbers.
void build_faces(const HexMesh& mesh, Topology& topo) {
  const std::size_t nv = mesh.points.size();
  const std::size_t nhf = mesh.hexes.size() * 6;
  UntouchedVector<Quad> keys(nhf);  // filled whole below, in parallel
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nhf), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t hf = r.begin(); hf != r.end(); ++hf) {
      const Hex& hex = mesh.hexes[hf / 6];
      const auto& local = kHexFaces[hf % 6];
      keys[hf] = sorted_quad({hex[local[0]], hex[local[1]], hex[local[2]], hex[local[3]]});
    }
  });
  std::vector<Index> offsets, order;
  bucket_by_key(
      nhf, nv, [&](std::size_t hf) { return keys[hf][0]; }, offsets, order);
  const auto key = [&](Index hf) -> const Quad& { return keys[static_cast<std::size_t>(hf)]; };
  // Within a bucket every key starts with the bucket's vertex.
  const auto less = [&](Index a, Index b) {
    const Quad &x = key(a), &y = key(b);
    return x[1] != y[1] ? x[1] < y[1] : x[2] != y[2] ? x[2] < y[2] : x[3] < y[3];
  };
  // Inline, not std::array's == (a memcmp call per half-face).
  const auto differ = [&](Index a, Index b) {
    const Quad &x = key(a), &y = key(b);
    return x[1] != y[1] || x[2] != y[2] || x[3] != y[3];
  };
  const auto for_each_bucket = [&](auto body) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t v = r.begin(); v != r.end(); ++v)
        body(static_cast<std::size_t>(offsets[v]), static_cast<std::size_t>(offsets[v + 1]), v);
    });
  };
  // Each vertex's bucket (a handful of faces) sorted by insertion: stable,
  // so equal keys stay in ascending hex-face order and the first occurrence
  // belongs to the lowest-numbered hex. Then its distinct keys counted.
  std::vector<Index> first_face(nv + 1, 0);
  for_each_bucket([&](std::size_t begin, std::size_t end, std::size_t v) {
    for (std::size_t i = begin + 1; i < end; ++i) {
      const Index hf = order[i];
      std::size_t j = i;
      for (; j > begin && less(hf, order[j - 1]); --j) order[j] = order[j - 1];
      order[j] = hf;
    }
    Index distinct = 0;
    for (std::size_t i = begin; i < end; ++i) distinct += i == begin || differ(order[i], order[i - 1]);
    first_face[v + 1] = distinct;
  });
  std::partial_sum(first_face.begin(), first_face.end(), first_face.begin());
  const auto nf = static_cast<std::size_t>(first_face[nv]);

  // Every entry is written below, in parallel (where the pages are first touched).
  topo.hex_faces.resize(nhf);
  topo.faces.resize(nf);
  topo.face_hex_offsets.resize(nf + 1);
  topo.face_hexes.resize(nhf);
  for_each_bucket([&](std::size_t begin, std::size_t end, std::size_t v) {
    auto face = static_cast<std::size_t>(first_face[v]);
    for (std::size_t i = begin; i < end; ++i) {
      const Index hf = order[i];
      if (i == begin || differ(hf, order[i - 1])) {
        if (i > begin) ++face;
        // The face's corners in the order of its first hex.
        const Hex& hex = mesh.hexes[static_cast<std::size_t>(hf) / 6];
        const auto& local = kHexFaces[static_cast<std::size_t>(hf) % 6];
        topo.faces[face] = {hex[local[0]], hex[local[1]], hex[local[2]], hex[local[3]]};
        topo.face_hex_offsets[face] = static_cast<Index>(i);
      }
      topo.hex_faces[static_cast<std::size_t>(hf)] = static_cast<Index>(face);
      topo.face_hexes[i] = hf / 6;
    }
  });
  topo.face_hex_offsets[nf] = static_cast<Index>(nhf);
  topo.boundary_faces.clear();
  topo.non_manifold_faces.clear();
  for (std::size_t f = 0; f < nf; ++f) {
    const Index count = topo.face_hex_offsets[f + 1] - topo.face_hex_offsets[f];
    if (count == 1) topo.boundary_faces.push_back(static_cast<Index>(f));
    if (count > 2) topo.non_manifold_faces.push_back(static_cast<Index>(f));
  }

  topo.is_boundary_vertex.assign(nv, 0);
  for (Index f : topo.boundary_faces)
    for (Index v : topo.faces[static_cast<std::size_t>(f)]) topo.is_boundary_vertex[static_cast<std::size_t>(v)] = 1;
  for (std::size_t v = 0; v < nv; ++v)
    if (topo.is_boundary_vertex[v]) topo.boundary_vertices.push_back(static_cast<Index>(v));
}

void build_edges(const HexMesh& mesh, Topology& topo) {
  const std::size_t nv = mesh.points.size();
  const std::size_t nhe = mesh.hexes.size() * 12;
  auto edge_of = [&](std::size_t he) {
    const Hex& hex = mesh.hexes[he / 12];
    const auto& local = kHexEdges[he % 12];
    const Index a = hex[local[0]], b = hex[local[1]];
    return a < b ? Edge{a, b} : Edge{b, a};
  };
  std::vector<Index> offsets, order;
  bucket_by_key(
      nhe, nv, [&](std::size_t he) { return edge_of(he)[0]; }, offsets, order);
  std::vector<Index> others;
  topo.edges.clear();
  for (std::size_t v = 0; v < nv; ++v) {
    others.clear();
    for (Index k = offsets[v]; k < offsets[v + 1]; ++k)
      others.push_back(edge_of(static_cast<std::size_t>(order[static_cast<std::size_t>(k)]))[1]);
    std::sort(others.begin(), others.end());
    others.erase(std::unique(others.begin(), others.end()), others.end());
    for (Index w : others) topo.edges.push_back({static_cast<Index>(v), w});
  }
}

}  // namespace

Topology build_topology(const HexMesh& mesh) {
  Topology topo;
  // Three independent parts, each filling its own members.
  tbb::parallel_invoke([&] { build_vertex_hexes(mesh, topo); }, [&] { build_faces(mesh, topo); },
                       [&] { build_edges(mesh, topo); });
  return topo;
}

std::vector<Edge> boundary_edges(const Topology& topology) {
  std::vector<Edge> edges;
  edges.reserve(4 * topology.boundary_faces.size());
  for (Index face : topology.boundary_faces) {
    const Quad& quad = topology.faces[static_cast<std::size_t>(face)];
    for (int i = 0; i < 4; ++i) {
      const Index a = quad[i], b = quad[(i + 1) % 4];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace hq
