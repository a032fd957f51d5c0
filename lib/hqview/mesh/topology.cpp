#include "hqview/mesh/topology.h"

#include <algorithm>
#include <iterator>
#include <limits>
#include <numeric>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "hqview/core/cell_kinds.h"
#include "hqview/core/hex_topology.h"

namespace hq {
namespace {

// The non-hex volume blocks of a mesh, corner ids in VTK order
// (core/cell_kinds.h). Cell ids run over the blocks in CellKind order: hexes
// [0, H), tets [H, H+T), wedges [H+T, H+T+W), pyramids after them.
struct NonHexBlocks {
  std::span<const std::array<Index, 4>> tets;
  std::span<const std::array<Index, 6>> wedges;
  std::span<const std::array<Index, 5>> pyramids;

  bool empty() const { return tets.empty() && wedges.empty() && pyramids.empty(); }
};

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

// ---- Across kinds ----

Tri sorted_tri(Tri t) {
  if (t[0] > t[1]) std::swap(t[0], t[1]);
  if (t[1] > t[2]) std::swap(t[1], t[2]);
  if (t[0] > t[1]) std::swap(t[0], t[1]);
  return t;
}
// Equal sorted ids, compared inline (std::array's == calls memcmp).
template <std::size_t N>
bool same_face(const std::array<Index, N>& x, const std::array<Index, N>& y) {
  for (std::size_t i = 0; i < N; ++i)
    if (x[i] != y[i]) return false;
  return true;
}
Quad sorted_face(const Quad& q) { return sorted_quad(q); }
Tri sorted_face(const Tri& t) { return sorted_tri(t); }

// The faces with N corners of one non-hex block, as a run of half-faces:
// half-face `begin + per_cell * c + i` is local face faces[i] of the
// block's cell c (cell id first_cell + c).
struct FaceRun {
  CellKind kind;
  std::size_t begin;
  Index first_cell;
  int per_cell;
  std::array<int, 5> faces;
};

// Every N-cornered face of the non-hex cells (half-faces), grouped by their
// sorted vertex ids: compact (a key per half-face; corners and cells are
// decoded from the runs), linear (bucketed by the smallest id, as the hex
// faces, then each small bucket sorted in parallel), deterministic (ties in
// half-face order: cell, then local face).
template <int N>
struct HalfFaces {
  using Face = std::array<Index, N>;
  const NonHexBlocks* blocks = nullptr;
  UntouchedVector<Face> keys;      // sorted ids, by half-face (filled whole by add, in parallel)
  std::vector<FaceRun> runs;
  std::vector<Index> order;        // half-faces by key, then half-face
  std::vector<std::size_t> groups; // starts of equal keys in `order`, then order.size()

  template <CellKind K, class Cells>
  void add(const Cells& cells, Index first_cell) {
    FaceRun run{K, keys.size(), first_cell, 0, {}};
    const auto& faces = CellKindTable<K>::faces;
    for (int f = 0; f < static_cast<int>(faces.size()); ++f)
      if (faces[static_cast<std::size_t>(f)].size == N) run.faces[static_cast<std::size_t>(run.per_cell++)] = f;
    if (run.per_cell == 0 || cells.empty()) return;
    runs.push_back(run);
    const auto per_cell = static_cast<std::size_t>(run.per_cell);
    keys.resize(run.begin + cells.size() * per_cell);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size()), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t c = r.begin(); c != r.end(); ++c)
        for (std::size_t i = 0; i < per_cell; ++i) {
          const CellFace& face = faces[static_cast<std::size_t>(run.faces[i])];
          Face key;
          for (int j = 0; j < N; ++j)
            key[static_cast<std::size_t>(j)] = cells[c][static_cast<std::size_t>(face.v[static_cast<std::size_t>(j)])];
          keys[run.begin + c * per_cell + i] = sorted_face(key);
        }
    });
  }

  void group(std::size_t num_vertices) {
    std::vector<Index> offsets;
    bucket_by_key(
        keys.size(), num_vertices, [&](std::size_t h) { return keys[h][0]; }, offsets, order);
    // Within a bucket every key starts with the bucket's vertex. Compared
    // inline, component by component (std::array's operators call memcmp).
    const auto less = [&](Index a, Index b) {
      const Face &x = keys[static_cast<std::size_t>(a)], &y = keys[static_cast<std::size_t>(b)];
      for (std::size_t i = 1; i < N; ++i)
        if (x[i] != y[i]) return x[i] < y[i];
      return a < b;
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_vertices), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t v = r.begin(); v != r.end(); ++v)
        if (offsets[v + 1] - offsets[v] > 1) std::sort(order.begin() + offsets[v], order.begin() + offsets[v + 1], less);
    });
    for (std::size_t i = 0; i < order.size(); ++i)
      if (i == 0 || !same_face(key(order[i]), key(order[i - 1]))) groups.push_back(i);
    groups.push_back(order.size());
  }

  const Face& key(Index h) const { return keys[static_cast<std::size_t>(h)]; }
  std::size_t num_groups() const { return groups.empty() ? 0 : groups.size() - 1; }
  std::size_t group_size(std::size_t g) const { return groups[g + 1] - groups[g]; }
  Index first_of(std::size_t g) const { return order[groups[g]]; }

  const FaceRun& run_of(Index h) const {
    std::size_t r = 0;
    while (r + 1 < runs.size() && runs[r + 1].begin <= static_cast<std::size_t>(h)) ++r;
    return runs[r];
  }
  // The cell id, kind and outward corners of half-face h.
  Index cell(Index h) const {
    const FaceRun& run = run_of(h);
    return run.first_cell + static_cast<Index>((static_cast<std::size_t>(h) - run.begin) / static_cast<std::size_t>(run.per_cell));
  }
  CellKind kind(Index h) const { return run_of(h).kind; }
  // Half-face h as a half-face id over every volume cell (half_face_id).
  Index global_id(Index h, const std::array<Index, 5>& first) const {
    const FaceRun& run = run_of(h);
    const std::size_t local = static_cast<std::size_t>(h) - run.begin;
    const auto per_cell = static_cast<std::size_t>(run.per_cell);
    return half_face_id(first, run.kind, static_cast<Index>(local / per_cell), run.faces[local % per_cell]);
  }
  Face corners(Index h) const {
    const FaceRun& run = run_of(h);
    const std::size_t local = static_cast<std::size_t>(h) - run.begin;
    const std::size_t c = local / static_cast<std::size_t>(run.per_cell);
    const int f = run.faces[local % static_cast<std::size_t>(run.per_cell)];
    Face out{};
    const auto fill = [&](const auto& corners, const CellFace& face) {
      for (int j = 0; j < N; ++j) out[static_cast<std::size_t>(j)] = corners[static_cast<std::size_t>(face.v[static_cast<std::size_t>(j)])];
    };
    if (run.kind == CellKind::tet)
      fill(blocks->tets[c], CellKindTable<CellKind::tet>::faces[static_cast<std::size_t>(f)]);
    else if (run.kind == CellKind::wedge)
      fill(blocks->wedges[c], CellKindTable<CellKind::wedge>::faces[static_cast<std::size_t>(f)]);
    else
      fill(blocks->pyramids[c], CellKindTable<CellKind::pyramid>::faces[static_cast<std::size_t>(f)]);
    return out;
  }
};

// Calls f(a, b) for every edge of every cell of a block of kind K.
template <CellKind K, class Cells, class F>
void for_each_cell_edge(const Cells& cells, F&& f) {
  for (const auto& cell : cells)
    for (const auto& e : CellKindTable<K>::edges) f(cell[e[0]], cell[e[1]]);
}

// The unique edges (a < b) of every tet, wedge and pyramid, ascending:
// each cell edge counted into the bucket of its smaller vertex and its other
// vertex scattered there (linear, in cell order), then each small bucket
// sorted and deduplicated and the buckets' runs placed by a prefix sum of
// their distinct counts (both in parallel; the result does not depend on
// the thread count). Memory: one vertex id per cell edge, not a sorted
// array of whole edges.
std::vector<Edge> unique_non_hex_edges(const NonHexBlocks& others, std::size_t num_vertices) {
  const auto for_each_edge = [&](auto&& f) {
    for_each_cell_edge<CellKind::tet>(others.tets, f);
    for_each_cell_edge<CellKind::wedge>(others.wedges, f);
    for_each_cell_edge<CellKind::pyramid>(others.pyramids, f);
  };
  std::vector<Index> offsets(num_vertices + 1, 0);
  for_each_edge([&](Index a, Index b) { ++offsets[static_cast<std::size_t>(std::min(a, b)) + 1]; });
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<Index> other(static_cast<std::size_t>(offsets[num_vertices]));
  {
    std::vector<Index> cursor(offsets.begin(), offsets.end() - 1);
    for_each_edge([&](Index a, Index b) {
      if (b < a) std::swap(a, b);
      other[static_cast<std::size_t>(cursor[static_cast<std::size_t>(a)]++)] = b;
    });
  }
  std::vector<Index> first_edge(num_vertices + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_vertices), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      const auto begin = other.begin() + offsets[v], end = other.begin() + offsets[v + 1];
      std::sort(begin, end);
      first_edge[v + 1] = static_cast<Index>(std::unique(begin, end) - begin);
    }
  });
  std::partial_sum(first_edge.begin(), first_edge.end(), first_edge.begin());
  std::vector<Edge> edges(static_cast<std::size_t>(first_edge[num_vertices]));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_vertices), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v)
      for (Index k = 0; k < first_edge[v + 1] - first_edge[v]; ++k)
        edges[static_cast<std::size_t>(first_edge[v] + k)] = {static_cast<Index>(v),
                                                              other[static_cast<std::size_t>(offsets[v] + k)]};
  });
  return edges;
}

// The hex face whose sorted ids are `key`, or kNoIndex (topo.faces is
// ordered by sorted ids).
Index find_hex_face(const Topology& topo, const Quad& key) {
  std::size_t lo = 0, hi = topo.faces.size();
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (sorted_quad(topo.faces[mid]) < key) lo = mid + 1;
    else hi = mid;
  }
  return lo < topo.faces.size() && sorted_quad(topo.faces[lo]) == key ? static_cast<Index>(lo) : kNoIndex;
}

// Topology::cell_face_offsets / cell_face_uses from the grouped half-faces:
// the triangle groups (non-hex cells only), then the hex faces and the
// non-hex quad groups merged by their sorted ids (a face of both: the hex
// uses first, their cell ids being lower). tris.order becomes the uses, in
// place; tris.keys is released first.
void build_cell_faces(const HexMesh& mesh, const NonHexBlocks& others, HalfFaces<3>& tris, const HalfFaces<4>& quads,
                      Topology& topo) {
  std::array<Index, 5> first{};
  first[1] = static_cast<Index>(mesh.hexes.size());
  first[2] = first[1] + static_cast<Index>(others.tets.size());
  first[3] = first[2] + static_cast<Index>(others.wedges.size());
  first[4] = first[3] + static_cast<Index>(others.pyramids.size());
  std::int64_t num_half_faces = 0;
  for (std::size_t k = 0; k < 4; ++k)
    num_half_faces += static_cast<std::int64_t>(first[k + 1] - first[k]) * kFacesPerVolumeKind[k];
  if (num_half_faces > std::int64_t{std::numeric_limits<Index>::max()}) return;
  tris.keys.clear();
  tris.keys.shrink_to_fit();
  std::vector<Index>& uses = tris.order;
  std::vector<Index>& offsets = topo.cell_face_offsets;
  offsets.reserve(tris.num_groups() + topo.faces.size() + quads.num_groups() + 1);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, uses.size()), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) uses[i] = tris.global_id(uses[i], first);
  });
  for (std::size_t g = 0; g < tris.num_groups(); ++g) offsets.push_back(static_cast<Index>(tris.groups[g]));
  uses.reserve(static_cast<std::size_t>(num_half_faces));  // every half-face is a use
  const std::size_t nf = topo.faces.size(), ng = quads.num_groups();
  std::size_t f = 0, g = 0;
  while (f < nf || g < ng) {
    const Quad hex_key = f < nf ? sorted_quad(topo.faces[f]) : Quad{};
    const int order = f == nf ? 1 : g == ng ? -1 : hex_key < quads.key(quads.first_of(g)) ? -1
                                                  : same_face(hex_key, quads.key(quads.first_of(g))) ? 0 : 1;
    offsets.push_back(static_cast<Index>(uses.size()));
    if (order <= 0) {
      // The hexes of face f, ascending; a hex using it twice, its local
      // faces in ascending order.
      Index last_hex = kNoIndex;
      int last_local = -1;
      for (Index i = topo.face_hex_offsets[f]; i < topo.face_hex_offsets[f + 1]; ++i) {
        const Index h = topo.face_hexes[static_cast<std::size_t>(i)];
        int k = h == last_hex ? last_local + 1 : 0;
        while (k < 6 && topo.hex_faces[6 * static_cast<std::size_t>(h) + static_cast<std::size_t>(k)] != static_cast<Index>(f)) ++k;
        uses.push_back(half_face_id(first, CellKind::hex, h, k));
        last_hex = h;
        last_local = k;
      }
      ++f;
    }
    if (order >= 0) {
      for (std::size_t i = quads.groups[g]; i < quads.groups[g + 1]; ++i) uses.push_back(quads.global_id(quads.order[i], first));
      ++g;
    }
  }
  offsets.push_back(static_cast<Index>(uses.size()));
  topo.cell_face_uses = std::move(uses);
}

// Matches the faces of the non-hex cells against each other and against the
// hex faces; finds the non-conforming interfaces; rebuilds the boundary
// (hex part filtered, non-hex faces added), boundary vertices, unreferenced
// vertices and the edges' touches_non_hex flags.
void match_across_kinds(const HexMesh& mesh, const NonHexBlocks& others, Topology& topo) {
  topo.across_kinds = true;
  const std::size_t nv = mesh.points.size();
  const auto num_hexes = static_cast<Index>(mesh.hexes.size());
  const Index first_tet = num_hexes;
  const Index first_wedge = first_tet + static_cast<Index>(others.tets.size());
  const Index first_pyramid = first_wedge + static_cast<Index>(others.wedges.size());

  HalfFaces<4> quads;
  HalfFaces<3> tris;
  quads.blocks = tris.blocks = &others;
  quads.add<CellKind::wedge>(others.wedges, first_wedge);
  quads.add<CellKind::pyramid>(others.pyramids, first_pyramid);
  tris.add<CellKind::tet>(others.tets, first_tet);
  tris.add<CellKind::wedge>(others.wedges, first_wedge);
  tris.add<CellKind::pyramid>(others.pyramids, first_pyramid);
  tbb::parallel_invoke([&] { quads.group(nv); }, [&] { tris.group(nv); });

  // Hex faces matched by a non-hex quad (or part of a non-conforming
  // interface) leave the boundary.
  std::vector<char> hex_face_covered(topo.faces.size(), 0);
  // Non-hex quads used once over all kinds: candidates for the boundary.
  std::vector<Index> lone_quads;  // half-faces, ascending key
  for (std::size_t g = 0; g < quads.num_groups(); ++g) {
    const Index hex_face = find_hex_face(topo, quads.key(quads.first_of(g)));
    const Index hex_uses = hex_face == kNoIndex ? 0 : topo.num_face_hexes(hex_face);
    const auto total = static_cast<Index>(quads.group_size(g)) + hex_uses;
    if (hex_face != kNoIndex) hex_face_covered[static_cast<std::size_t>(hex_face)] = 1;
    if (total == 1) lone_quads.push_back(quads.first_of(g));
    if (total > 2) ++topo.num_non_manifold_faces_non_hex;
  }
  // Triangles used once: candidates for the boundary or an interface.
  std::vector<Index> lone_tris;  // half-faces, ascending key
  for (std::size_t g = 0; g < tris.num_groups(); ++g) {
    if (tris.group_size(g) == 1) lone_tris.push_back(tris.first_of(g));
    if (tris.group_size(g) > 2) ++topo.num_non_manifold_faces_non_hex;
  }
  std::vector<char> tri_consumed(lone_tris.size(), 0);
  const auto find_lone_tri = [&](const Tri& t) -> std::ptrdiff_t {
    const Tri key = sorted_tri(t);
    const auto it = std::lower_bound(lone_tris.begin(), lone_tris.end(), key,
                                     [&](Index h, const Tri& k) { return tris.key(h) < k; });
    if (it == lone_tris.end() || tris.key(*it) != key || tri_consumed[static_cast<std::size_t>(it - lone_tris.begin())])
      return -1;
    return it - lone_tris.begin();
  };
  // A lone quad whose two halves along one diagonal are lone triangles.
  const auto try_non_conforming = [&](const Quad& q, Index quad_cell, CellKind quad_kind) {
    if (lone_tris.empty()) return false;
    const std::array<std::array<Tri, 2>, 2> splits = {{{{{q[0], q[1], q[2]}, {q[0], q[2], q[3]}}},
                                                       {{{q[0], q[1], q[3]}, {q[1], q[2], q[3]}}}}};
    for (const auto& split : splits) {
      const std::ptrdiff_t a = find_lone_tri(split[0]), b = find_lone_tri(split[1]);
      if (a < 0 || b < 0) continue;
      tri_consumed[static_cast<std::size_t>(a)] = tri_consumed[static_cast<std::size_t>(b)] = 1;
      Index ta = lone_tris[static_cast<std::size_t>(a)], tb = lone_tris[static_cast<std::size_t>(b)];
      if (tris.cell(tb) < tris.cell(ta)) std::swap(ta, tb);
      NonConformingFace nc{q, quad_cell, quad_kind};
      nc.triangle_cells = {tris.cell(ta), tris.cell(tb)};
      nc.triangle_kinds = {tris.kind(ta), tris.kind(tb)};
      nc.triangles = {tris.corners(ta), tris.corners(tb)};
      topo.non_conforming_faces.push_back(nc);
      return true;
    }
    return false;
  };
  // Hex boundary quads first (face ids ascend with sorted ids), then the
  // non-hex lone quads; sorted by the quad's ids at the end.
  std::vector<Index> hex_boundary;
  hex_boundary.reserve(topo.boundary_faces.size());
  for (Index f : topo.boundary_faces) {
    const auto fi = static_cast<std::size_t>(f);
    if (hex_face_covered[fi]) continue;
    if (try_non_conforming(topo.faces[fi], topo.face_hexes[static_cast<std::size_t>(topo.face_hex_offsets[fi])],
                           CellKind::hex))
      continue;
    hex_boundary.push_back(f);
  }
  topo.boundary_faces = std::move(hex_boundary);
  for (Index h : lone_quads) {
    const Quad q = quads.corners(h);
    if (try_non_conforming(q, quads.cell(h), quads.kind(h))) continue;
    topo.boundary_quads_non_hex.push_back(q);
    topo.boundary_quad_non_hex_cells.push_back(quads.cell(h));
  }
  std::sort(topo.non_conforming_faces.begin(), topo.non_conforming_faces.end(),
            [](const NonConformingFace& a, const NonConformingFace& b) {
              return sorted_quad(a.quad) < sorted_quad(b.quad);
            });
  for (std::size_t k = 0; k < lone_tris.size(); ++k) {
    if (tri_consumed[k]) continue;
    topo.boundary_triangles.push_back(tris.corners(lone_tris[k]));
    topo.boundary_triangle_cells.push_back(tris.cell(lone_tris[k]));
  }

  // Every face matched, for the overlap; the triangles' keys are no longer
  // needed (released there), their order becomes the uses.
  build_cell_faces(mesh, others, tris, quads, topo);

  // Boundary vertices over every boundary face.
  topo.is_boundary_vertex.assign(nv, 0);
  const auto mark = [&](const auto& face) {
    for (Index v : face) topo.is_boundary_vertex[static_cast<std::size_t>(v)] = 1;
  };
  for (Index f : topo.boundary_faces) mark(topo.faces[static_cast<std::size_t>(f)]);
  for (const Quad& q : topo.boundary_quads_non_hex) mark(q);
  for (const Tri& t : topo.boundary_triangles) mark(t);
  topo.boundary_vertices.clear();
  for (std::size_t v = 0; v < nv; ++v)
    if (topo.is_boundary_vertex[v]) topo.boundary_vertices.push_back(static_cast<Index>(v));

  // Vertices used by no cell of any kind.
  std::vector<char> used(nv, 0);
  const auto use = [&](const auto& cells) {
    for (const auto& cell : cells)
      for (Index v : cell) used[static_cast<std::size_t>(v)] = 1;
  };
  use(others.tets);
  use(others.wedges);
  use(others.pyramids);
  std::erase_if(topo.unreferenced_vertices, [&](Index v) { return used[static_cast<std::size_t>(v)] != 0; });

  // Every edge over all kinds, and the hex edges that are also edges of a
  // non-hex cell.
  const std::vector<Edge> non_hex_edges = unique_non_hex_edges(others, nv);
  topo.all_edges.clear();
  topo.all_edges.reserve(topo.edges.size() + non_hex_edges.size());
  std::set_union(topo.edges.begin(), topo.edges.end(), non_hex_edges.begin(), non_hex_edges.end(),
                 std::back_inserter(topo.all_edges));
  topo.edge_touches_non_hex.assign(topo.edges.size(), 0);
  std::size_t j = 0;
  for (std::size_t i = 0; i < topo.edges.size(); ++i) {
    while (j < non_hex_edges.size() && non_hex_edges[j] < topo.edges[i]) ++j;
    if (j < non_hex_edges.size() && non_hex_edges[j] == topo.edges[i]) topo.edge_touches_non_hex[i] = 1;
  }

}

// A surface mesh: its edges, boundary vertices (on an edge used by one
// face) and unreferenced vertices from the quads and triangles.
void add_surface_topology(const Mesh& mesh, Topology& topo) {
  topo.surface = build_surface_topology(mesh);
  const SurfaceTopology& s = topo.surface;
  topo.edges = s.edges;
  const std::size_t nv = mesh.points.size();
  topo.is_boundary_vertex.assign(nv, 0);
  for (std::size_t e = 0; e < s.edges.size(); ++e)
    if (s.edge_num_faces[e] == 1)
      for (Index v : s.edges[e]) topo.is_boundary_vertex[static_cast<std::size_t>(v)] = 1;
  topo.boundary_vertices.clear();
  for (std::size_t v = 0; v < nv; ++v)
    if (topo.is_boundary_vertex[v]) topo.boundary_vertices.push_back(static_cast<Index>(v));
  std::vector<char> used(nv, 0);
  for_each_surface_cell(mesh, [&](const std::array<Index, 4>& c, int size) {
    for (int i = 0; i < size; ++i) used[static_cast<std::size_t>(c[static_cast<std::size_t>(i)])] = 1;
  });
  topo.unreferenced_vertices.clear();
  for (std::size_t v = 0; v < nv; ++v)
    if (!used[v]) topo.unreferenced_vertices.push_back(static_cast<Index>(v));
}

}  // namespace

Topology build_topology(const Mesh& mesh) {
  Topology topo;
  // Three independent parts, each filling its own members.
  tbb::parallel_invoke([&] { build_vertex_hexes(mesh, topo); }, [&] { build_faces(mesh, topo); },
                       [&] { build_edges(mesh, topo); });
  const NonHexBlocks others{mesh.tets, mesh.wedges, mesh.pyramids};
  if (!others.empty()) match_across_kinds(mesh, others, topo);
  if (mesh.hexes.empty() && others.empty() && (!mesh.quads.empty() || !mesh.triangles.empty()))
    add_surface_topology(mesh, topo);
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
