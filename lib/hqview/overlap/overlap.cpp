#include "hqview/overlap/overlap.h"


#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <tuple>
#include <utility>

#include "hqview/core/hex_topology.h"
#include "hqview/core/progress.h"
#include "hqview/mesh/planarity.h"
#include "hqview/overlap/box_pairs.h"
#include "hqview/overlap/cell_faces.h"
#include "hqview/overlap/exact_geometry.h"
#include "hqview/overlap/tet_geometry.h"

namespace hq {
namespace {

using detail::BoundaryFace;
using detail::CellCornerIds;
using detail::TetPoints;
using detail::VertexCells;
using detail::VolumeCells;

// E/F passes before the certificate gives up on the unflagged part and hands
// every cell to G (correct, only slower). Real defects settle in 2-3 passes.
constexpr int kMaxCertificateRounds = 16;
// Stage F walks every boundary triangle once per sheet; past this many
// sheet x quad steps the remaining sheets are simply flagged.
constexpr double kWindingBudget = 4e8;

std::size_t sz(Index i) { return static_cast<std::size_t>(i); }

// Union-find whose roots are the smallest members, so components come out
// the same whatever the order of unions.
struct UnionFind {
  std::vector<Index> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  Index find(Index x) {
    while (parent[sz(x)] != x) {
      parent[sz(x)] = parent[sz(parent[sz(x)])];
      x = parent[sz(x)];
    }
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a < b) std::swap(a, b);
    parent[sz(a)] = b;
  }
};

// Used by a volume cell of any kind.
bool is_referenced(const VertexCells& vertex_cells, std::size_t v) {
  return vertex_cells.begin(static_cast<Index>(v)) != vertex_cells.end(static_cast<Index>(v));
}

double referenced_bbox_diagonal(const Mesh& mesh, const VertexCells& vertex_cells) {
  Box3 box;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (is_referenced(vertex_cells, v)) box.add(mesh.points[v]);
  return box.diagonal();
}

// ---- A. Coincident vertices ---------------------------------------------------

void find_coincident_vertices(const Mesh& mesh, const VertexCells& vertex_cells, double tolerance, OverlapReport& r) {
  const auto& p = mesh.points;
  std::vector<Index> vertices;
  for (std::size_t v = 0; v < p.size(); ++v)
    if (is_referenced(vertex_cells, v)) vertices.push_back(static_cast<Index>(v));
  UnionFind sets(p.size());
  bool any_coincident = false;

  // A grid of cell `tolerance` puts points within the tolerance in
  // neighbouring cells; below the coordinates' resolution it degenerates to
  // exact equality.
  double max_abs = 0.0;
  for (Index v : vertices)
    max_abs = std::max({max_abs, std::abs(p[sz(v)].x), std::abs(p[sz(v)].y), std::abs(p[sz(v)].z)});
  const bool exact = !(tolerance > 0.0) || max_abs / tolerance > 0x1p52;
  if (exact) {
    auto less = [&](Index a, Index b) {
      const Vec3 &pa = p[sz(a)], &pb = p[sz(b)];
      return std::tie(pa.x, pa.y, pa.z, a) < std::tie(pb.x, pb.y, pb.z, b);
    };
    std::vector<Index> by_position = vertices;
    tbb::parallel_sort(by_position.begin(), by_position.end(), less);  // a total order: deterministic
    for (std::size_t i = 1; i < by_position.size(); ++i)
      if (p[sz(by_position[i])] == p[sz(by_position[i - 1])]) {
        sets.unite(by_position[i], by_position[i - 1]);
        any_coincident = true;
      }
  } else {
    using Key = std::array<std::int64_t, 3>;
    auto key_of = [&](Index v) {
      const Vec3& q = p[sz(v)];
      return Key{static_cast<std::int64_t>(std::floor(q.x / tolerance)),
                 static_cast<std::int64_t>(std::floor(q.y / tolerance)),
                 static_cast<std::int64_t>(std::floor(q.z / tolerance))};
    };
    std::vector<std::pair<Key, Index>> keyed;
    keyed.reserve(vertices.size());
    for (Index v : vertices) keyed.push_back({key_of(v), v});
    std::sort(keyed.begin(), keyed.end());
    const double tol2 = tolerance * tolerance;
    for (const auto& [key, v] : keyed)
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dz = -1; dz <= 1; ++dz) {
            const Key k{key[0] + dx, key[1] + dy, key[2] + dz};
            auto it = std::lower_bound(keyed.begin(), keyed.end(),
                                       std::pair<Key, Index>{k, std::numeric_limits<Index>::min()});
            for (; it != keyed.end() && it->first == k; ++it)
              if (it->second > v && squared_norm(p[sz(it->second)] - p[sz(v)]) <= tol2) {
                sets.unite(v, it->second);
                any_coincident = true;
              }
          }
  }

  // Groups ordered by their smallest vertex (the root), members ascending
  // (`vertices` is ascending).
  r.vertex_coincident_group.assign(p.size(), kNoIndex);
  if (!any_coincident) return;
  std::vector<Index> size(p.size(), 0);
  for (Index v : vertices) ++size[sz(sets.find(v))];
  for (Index v : vertices) {
    const Index root = sets.find(v);
    if (size[sz(root)] < 2) continue;
    if (root == v) {
      r.vertex_coincident_group[sz(v)] = static_cast<Index>(r.coincident_groups.size());
      r.coincident_groups.push_back({{}, p[sz(v)]});
    } else {
      r.vertex_coincident_group[sz(v)] = r.vertex_coincident_group[sz(root)];
    }
    r.coincident_groups[sz(r.vertex_coincident_group[sz(v)])].vertices.push_back(v);
    ++r.num_coincident_vertices;
  }
}

// ---- D. Face map ----------------------------------------------------------------

// The unique edges (a < b) of every volume cell of a mesh that is not pure
// hex, ascending (a pure-hex mesh uses the topology's).
std::vector<Edge> non_hex_and_hex_edges(const VolumeCells& cells, const Topology& topo) {
  std::vector<Edge> edges = topo.edges;
  const auto add = [&](const auto& block, const auto& table_edges) {
    for (const auto& cell : block)
      for (const auto& e : table_edges) {
        const Index a = cell[static_cast<std::size_t>(e[0])], b = cell[static_cast<std::size_t>(e[1])];
        edges.push_back(a < b ? Edge{a, b} : Edge{b, a});
      }
  };
  add(cells.mesh->tets, CellKindTable<CellKind::tet>::edges);
  add(cells.mesh->wedges, CellKindTable<CellKind::wedge>::edges);
  add(cells.mesh->pyramids, CellKindTable<CellKind::pyramid>::edges);
  tbb::parallel_sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

int local_face(const Topology& topo, Index h, Index face) {
  for (int k = 0; k < 6; ++k)
    if (topo.hex_faces[6 * sz(h) + static_cast<std::size_t>(k)] == face) return k;
  return -1;
}

Quad local_quad(const Mesh& mesh, Index h, int k) {
  const Hex& hex = mesh.hexes[sz(h)];
  const auto& f = kHexFaces[static_cast<std::size_t>(k)];
  return {hex[sz(f[0])], hex[sz(f[1])], hex[sz(f[2])], hex[sz(f[3])]};
}

// b runs through a's cycle backwards: the two cells lie on opposite sides.
// Cycles of n = 3 or 4 corners.
bool opposite_winding(const Quad& a, const Quad& b, std::size_t n = 4) {
  const auto it = std::find(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n), a[0]);
  if (it == b.begin() + static_cast<std::ptrdiff_t>(n)) return false;
  const auto j = static_cast<std::size_t>(it - b.begin());
  for (std::size_t m = 1; m < n; ++m)
    if (b[(j + n - m) % n] != a[m]) return false;
  return true;
}

std::vector<Index> find_same_winding_faces(const Mesh& mesh, const Topology& topo) {
  std::vector<Index> faces;
  for (std::size_t f = 0; f < topo.faces.size(); ++f) {
    if (topo.num_face_hexes(static_cast<Index>(f)) != 2) continue;
    // faces[f] is seen from outside the first (lowest) hex; the second must
    // see the same cycle reversed.
    const Index h2 = topo.face_hexes[sz(topo.face_hex_offsets[f]) + 1];
    const Quad q2 = local_quad(mesh, h2, local_face(topo, h2, static_cast<Index>(f)));
    if (!opposite_winding(topo.faces[f], q2)) faces.push_back(static_cast<Index>(f));
  }
  return faces;
}

// Cells with the same vertex set as a lower-numbered cell. Such cells share
// their smallest vertex id, so the cells are put into buckets by it (a
// counting sort: linear, each bucket in ascending cell order) and only the
// cells of one bucket are compared, by their sorted ids (a tet mesh coned
// from each hex's smallest vertex has up to 48 cells in a bucket, most
// meshes one or two). The buckets are compared in parallel; each cell is in
// one bucket, so each flag is written by one task; the list comes out in
// cell order, the same for any thread count.
std::vector<Index> find_duplicate_cells(const VolumeCells& cells, std::vector<char>& flagged) {
  const auto nh = static_cast<std::size_t>(cells.size());
  const std::vector<Hex>& mesh_hexes = cells.mesh->hexes;
  // Sorted corner ids, padded with kNoIndex after a cell's n corners (so
  // cells of different kinds never compare equal).
  const auto sorted_ids = [&](std::size_t h) {
    Hex k;
    std::size_t n = 8;
    if (h < mesh_hexes.size()) {  // a hex: all 8 slots
      k = mesh_hexes[h];
    } else {
      const CellCornerIds c = cells.corners(static_cast<Index>(h));
      k.fill(kNoIndex);
      std::copy(c.begin(), c.end(), k.begin());
      n = static_cast<std::size_t>(c.n);
    }
    for (std::size_t i = 1; i < n; ++i) {  // ascending, by insertion (at most 8 ids)
      const Index x = k[i];
      std::size_t j = i;
      for (; j > 0 && k[j - 1] > x; --j) k[j] = k[j - 1];
      k[j] = x;
    }
    return k;
  };
  const auto smallest_id = [&](std::size_t h) {
    if (h < mesh_hexes.size()) return *std::min_element(mesh_hexes[h].begin(), mesh_hexes[h].end());
    const CellCornerIds c = cells.corners(static_cast<Index>(h));
    return *std::min_element(c.begin(), c.end());
  };
  const auto nv = static_cast<std::size_t>(cells.mesh->num_vertices());
  std::vector<std::size_t> start(nv + 1, 0);
  for (std::size_t h = 0; h < nh; ++h) ++start[sz(smallest_id(h)) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<Index> bucketed(nh);
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t h = 0; h < nh; ++h) bucketed[next[sz(smallest_id(h))]++] = static_cast<Index>(h);
  }
  std::vector<char> is_duplicate(nh, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::pair<Hex, Index>> bucket;
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      if (start[v + 1] - start[v] < 2) continue;
      bucket.clear();
      for (std::size_t i = start[v]; i < start[v + 1]; ++i) bucket.emplace_back(sorted_ids(sz(bucketed[i])), bucketed[i]);
      std::sort(bucket.begin(), bucket.end());
      for (std::size_t i = 1; i < bucket.size(); ++i)
        if (bucket[i].first == bucket[i - 1].first) {
          is_duplicate[sz(bucket[i].second)] = 1;
          flagged[sz(bucket[i].second)] = flagged[sz(bucket[i - 1].second)] = 1;
        }
    }
  });
  std::vector<Index> duplicates;
  for (std::size_t h = 0; h < nh; ++h)
    if (is_duplicate[h]) duplicates.push_back(static_cast<Index>(h));
  return duplicates;
}

// ---- E/F. The boundary of the unflagged cells -------------------------------------

std::vector<BoundaryFace> boundary_of_unflagged(const Mesh& mesh, const Topology& topo, const TetPoints& tp,
                                                const std::vector<char>& flagged) {
  std::vector<BoundaryFace> quads;
  for (std::size_t f = 0; f < topo.faces.size(); ++f) {
    Index owner = kNoIndex;
    int count = 0;
    for (Index i = topo.face_hex_offsets[f]; i < topo.face_hex_offsets[f + 1]; ++i) {
      const Index h = topo.face_hexes[sz(i)];
      if (!flagged[sz(h)]) {
        owner = h;
        ++count;
      }
    }
    if (count != 1) continue;
    const int k = local_face(topo, owner, static_cast<Index>(f));
    quads.push_back({static_cast<Index>(f), owner, local_quad(mesh, owner, k), tp.face_base + static_cast<Index>(f)});
  }
  return quads;
}

// ---- D, E/F on a mesh with cells of other kinds: the face map of every cell ----

struct MixedFaces {
  std::vector<Index> non_manifold_faces;  // map face ids, ascending
  std::vector<Index> same_winding_faces;
};

MixedFaces check_mixed_faces(const VolumeCells& cells, const detail::CellFaceMap& map) {
  MixedFaces out;
  for (Index f = 0; f < map.num_faces(); ++f) {
    const Index n = map.end(f) - map.begin(f);
    if (n > 2) out.non_manifold_faces.push_back(f);
    if (n != 2) continue;
    const detail::FaceUse u1 = map.use(map.begin(f)), u2 = map.use(map.begin(f) + 1);
    const auto a = detail::local_face_corners(cells.corners(u1.cell), u1.local);
    const auto b = detail::local_face_corners(cells.corners(u2.cell), u2.local);
    if (!opposite_winding(a, b, a[3] == kNoIndex ? 3 : 4)) out.same_winding_faces.push_back(f);
  }
  return out;
}

std::vector<BoundaryFace> mixed_boundary_of_unflagged(const VolumeCells& cells, const Topology& topo,
                                                      const TetPoints& tp, const detail::CellFaceMap& map,
                                                      const std::vector<char>& flagged) {
  std::vector<BoundaryFace> faces;
  for (Index f = 0; f < map.num_faces(); ++f) {
    detail::FaceUse owner;
    int count = 0;
    for (Index i = map.begin(f); i < map.end(f); ++i) {
      const detail::FaceUse u = map.use(i);
      if (!flagged[sz(u.cell)]) {
        owner = u;
        ++count;
      }
    }
    if (count != 1) continue;
    const CellCornerIds c = cells.corners(owner.cell);
    const auto corners = detail::local_face_corners(c, owner.local);
    const Index centre = corners[3] == kNoIndex ? kNoIndex : detail::quad_centre_id(topo, tp, cells, c, owner.local);
    faces.push_back({f, owner.cell, corners, centre});
  }
  return faces;
}

// Sheets: quads connected across edges that exactly two quads share (a
// consistently oriented piece of surface). Returns the sheet of every quad;
// sheets are numbered by their first quad.
std::vector<Index> find_sheets(const std::vector<BoundaryFace>& quads, Index& num_sheets) {
  std::vector<std::tuple<Index, Index, Index>> edges;
  edges.reserve(4 * quads.size());
  for (std::size_t q = 0; q < quads.size(); ++q)
    for (std::size_t e = 0, n = static_cast<std::size_t>(quads[q].size()); e < n; ++e) {
      const Index a = quads[q].corners[e], b = quads[q].corners[(e + 1) % n];
      edges.emplace_back(std::min(a, b), std::max(a, b), static_cast<Index>(q));
    }
  std::sort(edges.begin(), edges.end());
  UnionFind sets(quads.size());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) &&
           std::get<1>(edges[j]) == std::get<1>(edges[i]))
      ++j;
    if (j - i == 2) sets.unite(std::get<2>(edges[i]), std::get<2>(edges[i + 1]));
    i = j;
  }
  std::vector<Index> sheet(quads.size(), kNoIndex);
  num_sheets = 0;
  for (std::size_t q = 0; q < quads.size(); ++q) {
    const Index root = sets.find(static_cast<Index>(q));
    sheet[q] = root == static_cast<Index>(q) ? num_sheets++ : sheet[sz(root)];
  }
  return sheet;
}

Box3 bounds_of(const TetPoints& tp, const std::vector<BoundaryFace>& quads) {
  Box3 b;
  for (const BoundaryFace& q : quads)
    for (int e = 0; e < q.num_fan_triangles(); ++e) {
      const auto t = detail::fan_triangle(q, e);
      for (Index id : t) b.add(tp.points[sz(id)]);
    }
  return b;
}

struct BoundaryCheck {
  std::vector<std::array<Index, 2>> intersecting;  // indices into quads
  detail::BoxPairs budget;                         // E's candidate pairs: within the budget?
  std::vector<Index> bad_sheet_quads;              // quads of sheets whose winding is not 1
  Index num_bad_sheets = 0;
};

std::int64_t pair_budget(const OverlapOptions& options, std::size_t num_boxes) {
  return std::max(options.min_pair_budget, options.pairs_per_box * static_cast<std::int64_t>(num_boxes));
}

// Records that a pair stage stopped at its budget.
void record_over_budget(OverlapReport& r, const char* stage, std::int64_t budget, const detail::BoxPairs& pairs) {
  r.is_over_budget = true;
  r.over_budget_stage = stage;
  r.pair_budget = budget;
  r.num_untested_pairs = pairs.num_found;
  r.is_untested_count_exact = pairs.is_count_exact;
}

BoundaryCheck check_boundary(const TetPoints& tp, const std::vector<BoundaryFace>& quads, std::int64_t max_pairs) {
  BoundaryCheck check;
  detail::FacePairs pairs = detail::intersecting_face_pairs(tp, quads, max_pairs);
  check.intersecting = std::move(pairs.pairs);
  check.budget = pairs.budget;
  if (!check.budget.is_complete || quads.empty()) return check;
  Index num_sheets = 0;
  const std::vector<Index> sheet = find_sheets(quads, num_sheets);
  std::vector<Index> first(sz(num_sheets), kNoIndex);
  for (std::size_t q = quads.size(); q-- > 0;) first[sz(sheet[q])] = static_cast<Index>(q);
  const Box3 bounds = bounds_of(tp, quads);
  const auto affordable = static_cast<std::size_t>(std::max(1.0, kWindingBudget / static_cast<double>(quads.size())));
  std::vector<char> bad(sz(num_sheets), 1);  // beyond the budget: not certified
  const std::size_t computed = std::min<std::size_t>(affordable, sz(num_sheets));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, computed, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t s = r.begin(); s != r.end(); ++s) {
      const auto w = detail::winding_behind_face(tp, quads, first[s], bounds);
      bad[s] = !(w && *w == 1);
    }
  });
  for (std::size_t q = 0; q < quads.size(); ++q)
    if (bad[sz(sheet[q])]) check.bad_sheet_quads.push_back(static_cast<Index>(q));
  check.num_bad_sheets = static_cast<Index>(std::count(bad.begin(), bad.end(), 1));
  return check;
}

// ---- Markers ------------------------------------------------------------------------

void build_markers(OverlapReport& r) {
  for (const CoincidentGroup& g : r.coincident_groups)
    r.markers.push_back({MarkerKind::coincident, g.position, static_cast<Index>(g.vertices.size())});
  // Pairs pointing at the same position share one marker (its arrows are
  // spread around it), in the order of their first pair.
  std::vector<Index> order(r.intersecting_pairs.size());
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](Index i) {
    const Vec3& q = r.intersecting_pairs[sz(i)].position;
    return std::make_tuple(q.x, q.y, q.z, i);
  };
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return key(a) < key(b); });
  std::vector<std::pair<Index, Index>> groups;  // (first pair, count)
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j < order.size() &&
           r.intersecting_pairs[sz(order[j])].position == r.intersecting_pairs[sz(order[i])].position)
      ++j;
    groups.push_back({order[i], static_cast<Index>(j - i)});
    i = j;
  }
  std::sort(groups.begin(), groups.end());
  for (const auto& [first, count] : groups)
    r.markers.push_back({MarkerKind::intersection, r.intersecting_pairs[sz(first)].position, count});
}

}  // namespace

OverlapReport check_overlap(const Mesh& mesh, const Topology& topo, const OverlapOptions& options) {
  OverlapReport r;
  r.mode = options.mode;
  const VolumeCells cells(mesh);
  const auto nh = static_cast<std::size_t>(cells.size());  // volume cells of every kind
  const auto& p = mesh.points;
  const VertexCells vertex_cells = detail::build_vertex_cells(cells, topo);
  r.coincident_tolerance =
      options.coincident_eps > 0.0 ? options.coincident_eps * referenced_bbox_diagonal(mesh, vertex_cells) : 0.0;
  std::vector<char> flagged(nh, 0);
  auto flag_vertex_cells = [&](Index v) {
    for (Index i = vertex_cells.begin(v); i < vertex_cells.end(v); ++i) flagged[sz(vertex_cells.cell(i))] = 1;
  };

  // The progress bar: steps A-B, C, D, E-F, G of the paper's order.
  progress::set_total(5);
  // A, B.
  find_coincident_vertices(mesh, vertex_cells, r.coincident_tolerance, r);
  for (const CoincidentGroup& g : r.coincident_groups)
    for (Index v : g.vertices) flag_vertex_cells(v);
  const double tol2 = r.coincident_tolerance * r.coincident_tolerance;
  // Every edge: the hex topology's on a pure-hex mesh, the topology's edges
  // over all kinds on any other (or, from a topology of the hexes alone,
  // gathered here).
  const std::vector<Edge> mixed_edges =
      cells.is_pure_hex() || topo.across_kinds ? std::vector<Edge>{} : non_hex_and_hex_edges(cells, topo);
  for (const Edge& e : cells.is_pure_hex() ? topo.edges : topo.across_kinds ? topo.all_edges : mixed_edges) {
    const Vec3 d = p[sz(e[1])] - p[sz(e[0])];
    if (tol2 > 0.0 ? squared_norm(d) <= tol2 : d == Vec3{}) {
      r.zero_length_edges.push_back(e);
      flag_vertex_cells(e[0]);  // every cell of the edge holds e[0]
    }
  }

  progress::add_done(1);
  // C.
  const TetPoints tp = detail::build_tet_points(cells, topo);
  r.cell_orientation = detail::classify_cell_orientations(cells, topo, tp);
  for (std::size_t h = 0; h < nh; ++h) {
    const std::uint8_t f = r.cell_orientation[h];
    if (f & kCornerNegative)
      r.inverted_cells.push_back(static_cast<Index>(h));
    else if (f & kCornerFlat)
      r.degenerate_cells.push_back(static_cast<Index>(h));
    if (f & (kTetNegative | kTetFlat)) r.nonpositive_tet_cells.push_back(static_cast<Index>(h));
    if (f != 0) flagged[h] = 1;
  }

  progress::add_done(1);
  // D. A pure-hex mesh reads the hex topology's faces; any other the face
  // map of every cell.
  std::optional<detail::CellFaceMap> face_map;
  if (cells.is_pure_hex()) {
    r.non_manifold_faces = topo.non_manifold_faces;
    r.same_winding_faces = find_same_winding_faces(mesh, topo);
    for (const auto* faces : {&r.non_manifold_faces, &r.same_winding_faces})
      for (Index f : *faces)
        for (Index i = topo.face_hex_offsets[sz(f)]; i < topo.face_hex_offsets[sz(f) + 1]; ++i)
          flagged[sz(topo.face_hexes[sz(i)])] = 1;
  } else {
    face_map.emplace(cells, topo);
    MixedFaces faces = check_mixed_faces(cells, *face_map);
    r.non_manifold_faces = std::move(faces.non_manifold_faces);
    r.same_winding_faces = std::move(faces.same_winding_faces);
    for (const auto* list : {&r.non_manifold_faces, &r.same_winding_faces})
      for (Index f : *list)
        for (Index i = face_map->begin(f); i < face_map->end(f); ++i) flagged[sz(face_map->use(i).cell)] = 1;
  }
  r.duplicate_cells = find_duplicate_cells(cells, flagged);
  const bool clean_a_to_d = std::find(flagged.begin(), flagged.end(), 1) == flagged.end();

  progress::add_done(1);
  // E, F on the boundary of the unflagged cells K', until K' is certified.
  for (int round = 0;; ++round) {
    const std::vector<BoundaryFace> quads = cells.is_pure_hex()
                                                ? boundary_of_unflagged(mesh, topo, tp, flagged)
                                                : mixed_boundary_of_unflagged(cells, topo, tp, *face_map, flagged);
    // E tests the faces' fan triangles: 4 per quad, 1 per triangle.
    std::size_t num_triangles = 0;
    for (const BoundaryFace& q : quads) num_triangles += static_cast<std::size_t>(q.num_fan_triangles());
    const std::int64_t budget = pair_budget(options, num_triangles);
    const BoundaryCheck check = check_boundary(tp, quads, budget);
    r.certificate_rounds = round + 1;
    if (!check.budget.is_complete) {  // nothing is known of this boundary: every cell goes to G
      record_over_budget(r, "boundary", budget, check.budget);
      std::fill(flagged.begin(), flagged.end(), 1);
      break;
    }
    if (round == 0) {
      for (const auto& pair : check.intersecting) {
        const Index a = quads[sz(pair[0])].face, b = quads[sz(pair[1])].face;
        r.boundary_self_intersections.push_back({std::min(a, b), std::max(a, b)});
      }
      std::sort(r.boundary_self_intersections.begin(), r.boundary_self_intersections.end());
      r.num_nested_shells = check.num_bad_sheets;
    }
    bool changed = false;
    for (const auto& pair : check.intersecting)
      for (Index q : pair) changed |= !std::exchange(flagged[sz(quads[sz(q)].cell)], 1);
    for (Index q : check.bad_sheet_quads) changed |= !std::exchange(flagged[sz(quads[sz(q)].cell)], 1);
    // Until K' is certified, in both modes: G's test of interiors that meet
    // with no vertex inside runs on the pairs with a flagged cell only.
    if (!changed) break;
    if (round + 1 >= kMaxCertificateRounds) {
      std::fill(flagged.begin(), flagged.end(), 1);
      break;
    }
  }
  r.certified_clean =
      clean_a_to_d && !r.is_over_budget && r.boundary_self_intersections.empty() && r.num_nested_shells == 0;

  progress::add_done(1);
  // G.
  std::vector<Index> flagged_cells;
  for (std::size_t h = 0; h < nh; ++h)
    if (flagged[h]) flagged_cells.push_back(static_cast<Index>(h));
  r.num_flagged_cells = static_cast<Index>(flagged_cells.size());
  std::vector<std::array<Index, 2>> candidates;
  if (options.mode == OverlapMode::exhaustive || !flagged_cells.empty()) {
    const auto box_of_cell = [&](std::size_t h) {
      if (cells.is_pure_hex()) return detail::box_of(p, mesh.hexes[h].data(), 8);
      const CellCornerIds c = cells.corners(static_cast<Index>(h));
      return detail::box_of(p, c.v.data(), c.n);
    };
    const std::int64_t budget = pair_budget(options, nh);
    detail::BoxPairs pairs;
    if (options.mode == OverlapMode::exhaustive) {
      // Each cell's box on its own (in parallel: the same boxes for any
      // thread count).
      std::vector<Box3> boxes(nh);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nh, 8192), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t h = range.begin(); h != range.end(); ++h) boxes[h] = box_of_cell(h);
      });
      pairs = detail::box_self_pairs(boxes, detail::BoxContact::open, budget);
    } else {
      // The flagged cells against the boxes near them, each box made as it
      // is read (no array of every cell's box).
      pairs = detail::box_subset_pairs(nh, box_of_cell, flagged_cells, detail::BoxContact::open, budget);
    }
    if (pairs.is_complete)
      candidates = std::move(pairs.pairs);
    else if (!r.is_over_budget)  // a stopped E already says what was not tested
      record_over_budget(r, "cells", budget, pairs);
  }
  r.num_candidate_pairs = static_cast<std::int64_t>(candidates.size());
  std::vector<char> folded(nh, 0);
  for (std::size_t h = 0; h < nh; ++h) folded[h] = (r.cell_orientation[h] & (kTetNegative | kTetFlat)) != 0;
  const auto tests = detail::test_cell_pairs(cells, vertex_cells, topo, tp, candidates, flagged, folded);
  r.cell_intersecting.assign(nh, 0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!tests[i].intersect) continue;
    IntersectingPair pair{candidates[i], tests[i].inside_vertex, tests[i].position, {}, {}};
    for (std::size_t k = 0; k < 2; ++k) {
      const CellCornerIds c = cells.corners(candidates[i][k]);
      pair.kinds[k] = c.kind;
      pair.source_indices[k] = cell_source_index(mesh, c.kind, static_cast<std::size_t>(c.local));
    }
    r.intersecting_pairs.push_back(pair);
    r.cell_intersecting[sz(candidates[i][0])] = r.cell_intersecting[sz(candidates[i][1])] = 1;
  }
  r.num_intersecting_cells = static_cast<Index>(std::count(r.cell_intersecting.begin(), r.cell_intersecting.end(), 1));
  build_markers(r);
  return r;
}

// ---- Surface meshes ------------------------------------------------------------

namespace {

// The face ids (quads, then triangles) and their corners.
template <class F>
void for_each_face(const Mesh& mesh, F&& f) {
  Index id = 0;
  for (const auto& q : mesh.quads) f(id++, q.data(), 4);
  for (const auto& t : mesh.triangles) f(id++, t.data(), 3);
}

// vertex -> faces (CSR); stage A reads which vertices a face uses.
VertexCells surface_vertex_faces(const Mesh& mesh) {
  VertexCells vc;
  const std::size_t nv = mesh.points.size();
  vc.own_offsets.assign(nv + 1, 0);
  for_each_face(mesh, [&](Index, const Index* c, int n) {
    for (int i = 0; i < n; ++i) ++vc.own_offsets[sz(c[i]) + 1];
  });
  for (std::size_t v = 0; v < nv; ++v) vc.own_offsets[v + 1] += vc.own_offsets[v];
  vc.own_cells.resize(sz(vc.own_offsets[nv]));
  std::vector<Index> next(vc.own_offsets.begin(), vc.own_offsets.end() - 1);
  for_each_face(mesh, [&](Index f, const Index* c, int n) {
    for (int i = 0; i < n; ++i) vc.own_cells[sz(next[sz(c[i])]++)] = f;
  });
  vc.offsets = vc.own_offsets.data();
  vc.cells = vc.own_cells.data();
  return vc;
}

}  // namespace

int quad_split_diagonal(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  const bool along_02 = dot(cross(p1 - p0, p2 - p0), cross(p2 - p0, p3 - p0)) > 0.0;
  const bool along_13 = dot(cross(p1 - p0, p3 - p0), cross(p2 - p1, p3 - p1)) > 0.0;
  if (along_02 != along_13) return along_02 ? 0 : 1;
  return squared_norm(p2 - p0) <= squared_norm(p3 - p1) ? 0 : 1;
}

OverlapReport check_surface_overlap(const Mesh& mesh, const SurfaceTopology& topology, const Planarity& planarity,
                                    const OverlapOptions& options, const std::function<void()>& on_self_intersection) {
  OverlapReport r;
  r.mode = options.mode;
  r.is_surface = true;
  const auto& p = mesh.points;
  const auto num_faces = static_cast<std::size_t>(mesh.quads.size() + mesh.triangles.size());
  const VertexCells vertex_faces = surface_vertex_faces(mesh);
  const double diagonal = referenced_bbox_diagonal(mesh, vertex_faces);
  r.coincident_tolerance = options.coincident_eps > 0.0 ? options.coincident_eps * diagonal : 0.0;
  progress::set_total(2);
  // A. Each vertex then stands for its group's lowest vertex.
  find_coincident_vertices(mesh, vertex_faces, r.coincident_tolerance, r);
  std::vector<Index> welded(p.size());
  std::iota(welded.begin(), welded.end(), 0);
  for (const CoincidentGroup& g : r.coincident_groups)
    for (Index v : g.vertices) welded[sz(v)] = g.vertices.front();
  // B. Unique edges of the faces, by their original ids: the surface
  // topology's (no second table and sort of every side), with a side from a
  // vertex to itself as the edge {v, v} in its sorted place.
  const double tol2 = r.coincident_tolerance * r.coincident_tolerance;
  std::vector<Index> repeated;  // v of each side from v to itself
  for_each_face(mesh, [&](Index, const Index* c, int n) {
    for (int i = 0; i < n; ++i)
      if (c[i] == c[(i + 1) % n]) repeated.push_back(c[i]);
  });
  std::sort(repeated.begin(), repeated.end());
  repeated.erase(std::unique(repeated.begin(), repeated.end()), repeated.end());
  const auto add_if_zero_length = [&](const Edge& e) {
    const Vec3 d = p[sz(e[1])] - p[sz(e[0])];
    if (tol2 > 0.0 ? squared_norm(d) <= tol2 : d == Vec3{}) r.zero_length_edges.push_back(e);
  };
  auto next_repeated = repeated.begin();
  const auto add_repeated_up_to = [&](Index last) {
    for (; next_repeated != repeated.end() && *next_repeated <= last; ++next_repeated)
      add_if_zero_length({*next_repeated, *next_repeated});
  };
  for (const Edge& e : topology.edges) {
    add_repeated_up_to(e[0]);  // {v, v} before {v, w > v}
    add_if_zero_length(e);
  }
  add_repeated_up_to(std::numeric_limits<Index>::max());
  // Duplicate faces: sorted vertex ids (a triangle's padded with kNoIndex).
  {
    std::vector<std::pair<std::array<Index, 4>, Index>> keyed;
    keyed.reserve(num_faces);
    for_each_face(mesh, [&](Index f, const Index* c, int n) {
      std::array<Index, 4> key{kNoIndex, kNoIndex, kNoIndex, kNoIndex};
      std::copy(c, c + n, key.begin());
      std::sort(key.begin(), key.end());
      keyed.push_back({key, f});
    });
    tbb::parallel_sort(keyed.begin(), keyed.end());
    for (std::size_t i = 1; i < keyed.size(); ++i)
      if (keyed[i].first == keyed[i - 1].first) r.duplicate_cells.push_back(keyed[i].second);
    std::sort(r.duplicate_cells.begin(), r.duplicate_cells.end());
  }
  progress::add_done(1);

  // S. A planar mesh in its plane: its rotated or mirrored copies are
  // decided as it is (in 3-D their coplanar triangles would lie a rounding
  // apart, and meet nowhere or along a line).
  if (on_self_intersection) on_self_intersection();
  r.is_decided_in_plane = planarity.is_planar;
  std::optional<PlaneFrame> frame;
  std::vector<Vec3> in_plane;
  if (planarity.is_planar) {
    frame = plane_frame(mesh, planarity);
    in_plane.resize(p.size());
    for (std::size_t v = 0; v < p.size(); ++v)
      if (is_referenced(vertex_faces, v)) in_plane[v] = frame->to_plane(p[v]);
  }
  const std::vector<Vec3>& q = frame ? in_plane : p;
  // Each face's triangles, on the welded ids.
  std::vector<detail::Triangle> triangles;
  std::vector<Index> first;
  triangles.reserve(2 * mesh.quads.size() + mesh.triangles.size());
  first.reserve(num_faces + 1);
  first.push_back(0);
  for_each_face(mesh, [&](Index, const Index* c, int n) {
    const auto w = [&](int i) { return welded[sz(c[i])]; };
    if (n == 3) {
      triangles.push_back({w(0), w(1), w(2)});
    } else if (quad_split_diagonal(q[sz(w(0))], q[sz(w(1))], q[sz(w(2))], q[sz(w(3))]) == 0) {
      triangles.push_back({w(0), w(1), w(2)});
      triangles.push_back({w(0), w(2), w(3)});
    } else {
      triangles.push_back({w(0), w(1), w(3)});
      triangles.push_back({w(1), w(2), w(3)});
    }
    first.push_back(static_cast<Index>(triangles.size()));
  });
  const std::int64_t budget = pair_budget(options, triangles.size());
  detail::SurfaceFacePairs found = detail::intersecting_surface_faces(q, triangles, first, budget);
  if (frame)
    for (Vec3& x : found.positions) x = frame->from_plane(x);
  if (!found.budget.is_complete) record_over_budget(r, "faces", budget, found.budget);
  r.num_candidate_pairs = found.num_tested;
  r.cell_intersecting.assign(num_faces, 0);
  const auto nq = static_cast<Index>(mesh.quads.size());
  for (std::size_t i = 0; i < found.pairs.size(); ++i) {
    const std::array<Index, 2>& faces = found.pairs[i];
    r.cell_intersecting[sz(faces[0])] = r.cell_intersecting[sz(faces[1])] = 1;
    if (faces[0] == faces[1]) {
      r.self_intersecting_faces.push_back(faces[0]);
      continue;
    }
    IntersectingPair pair{faces, kNoIndex, found.positions[i], {}, {}};
    for (std::size_t k = 0; k < 2; ++k) {
      const bool is_quad = faces[k] < nq;
      pair.kinds[k] = is_quad ? CellKind::quad : CellKind::triangle;
      pair.source_indices[k] = cell_source_index(mesh, pair.kinds[k], sz(is_quad ? faces[k] : faces[k] - nq));
    }
    r.intersecting_pairs.push_back(pair);
  }
  r.num_intersecting_cells = static_cast<Index>(std::count(r.cell_intersecting.begin(), r.cell_intersecting.end(), 1));
  r.certified_clean = !r.is_over_budget && r.coincident_groups.empty() && r.zero_length_edges.empty() &&
                      r.duplicate_cells.empty() && r.num_intersecting_cells == 0;
  build_markers(r);
  // Then one arrow per folded face, at where its triangles meet.
  for (std::size_t i = 0; i < found.pairs.size(); ++i)
    if (found.pairs[i][0] == found.pairs[i][1]) r.markers.push_back({MarkerKind::intersection, found.positions[i], 1});
  progress::add_done(1);
  return r;
}

}  // namespace hq
