#include "hqview/structure/structure.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "hqview/core/hex_topology.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/quality/cell_volume.h"
#include "hqview/quality/hex_metrics.h"

namespace hq {
namespace {

// Edge ids of Topology::edges (sorted by (a, b)) by vertex pair.
class EdgeIndex {
 public:
  explicit EdgeIndex(const Topology& topology, std::size_t num_vertices) : edges_(topology.edges) {
    first_.assign(num_vertices + 1, 0);
    for (const Edge& e : edges_) ++first_[static_cast<std::size_t>(e[0]) + 1];
    for (std::size_t v = 0; v < num_vertices; ++v) first_[v + 1] += first_[v];
  }
  // kNoIndex when a == b or the pair is no edge.
  Index find(Index a, Index b) const {
    if (a == b) return kNoIndex;
    if (a > b) std::swap(a, b);
    const auto lo = edges_.begin() + first_[static_cast<std::size_t>(a)];
    const auto hi = edges_.begin() + first_[static_cast<std::size_t>(a) + 1];
    // Every edge of [lo, hi) starts at a: compared on its other end only
    // (std::array's == would call memcmp for each of the 12 edges of a hex).
    const auto it = std::lower_bound(lo, hi, b, [](const Edge& e, Index v) { return e[1] < v; });
    return it != hi && (*it)[1] == b ? static_cast<Index>(it - edges_.begin()) : kNoIndex;
  }

 private:
  const std::vector<Edge>& edges_;
  std::vector<std::ptrdiff_t> first_;
};

Vec3 quad_normal(const HexMesh& mesh, const Quad& q) {
  const auto& p = mesh.points;
  const Vec3 n = cross(p[static_cast<std::size_t>(q[2])] - p[static_cast<std::size_t>(q[0])],
                       p[static_cast<std::size_t>(q[3])] - p[static_cast<std::size_t>(q[1])]);
  return squared_norm(n) > 0.0 ? normalized(n) : n;
}

Vec3 quad_centre(const HexMesh& mesh, const Quad& q) {
  Vec3 c{};
  for (Index v : q) c = c + mesh.points[static_cast<std::size_t>(v)];
  return 0.25 * c;
}

// The valence a boundary edge between two outward boundary faces should
// have: round(theta / 90 deg), at least 1, theta the dihedral angle inside
// the mesh (180 on a flat surface, 90 along a convex box edge, 270 along a
// concave one).
Index ideal_boundary_valence(const HexMesh& mesh, const Quad& f1, const Quad& f2) {
  const Vec3 n1 = quad_normal(mesh, f1), n2 = quad_normal(mesh, f2);
  const double phi = std::acos(std::clamp(dot(n1, n2), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  const bool convex = dot(n1, quad_centre(mesh, f2) - quad_centre(mesh, f1)) < 0.0;
  const double theta = convex ? 180.0 - phi : 180.0 + phi;
  return std::max<Index>(1, static_cast<Index>(std::lround(theta / 90.0)));
}

// Numbers the singular curves (over the singular edges of s.edges): chains from each node (ascending) along
// unvisited singular edges until the next node, then the closed chains.
void number_curves(HexStructure& s, std::size_t num_vertices) {
  std::vector<std::ptrdiff_t> first(num_vertices + 1, 0);
  for (const StructureEdge& e : s.edges)
    if (e.singular)
      for (Index v : e.vertices) ++first[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < num_vertices; ++v) first[v + 1] += first[v];
  std::vector<Index> incident(static_cast<std::size_t>(first[num_vertices]));
  std::vector<std::ptrdiff_t> fill(first.begin(), first.end() - 1);
  for (std::size_t i = 0; i < s.edges.size(); ++i)
    if (s.edges[i].singular)
      for (Index v : s.edges[i].vertices) incident[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = static_cast<Index>(i);
  auto degree = [&](Index v) { return first[static_cast<std::size_t>(v) + 1] - first[static_cast<std::size_t>(v)]; };
  // A hybrid mesh: a vertex of an edge that touches a non-hex cell is where
  // the hex part's graph meets the rest of the mesh; a curve ending there is
  // cut by the interface, not at a node of the structure.
  std::vector<char> on_interface(num_vertices, 0);
  for (const StructureEdge& e : s.edges)
    if (e.touches_non_hex)
      for (Index v : e.vertices) on_interface[static_cast<std::size_t>(v)] = 1;
  // Curve ends: nodes, and interface vertices with one singular edge.
  std::vector<char> is_node(num_vertices, 0);
  std::vector<Index> ends;
  for (std::size_t v = 0; v < num_vertices; ++v)
    if (degree(static_cast<Index>(v)) > 0 && degree(static_cast<Index>(v)) != 2) {
      is_node[v] = 1;
      ends.push_back(static_cast<Index>(v));
      if (on_interface[v] && degree(static_cast<Index>(v)) == 1) ++s.num_interface_ends;
      else s.nodes.push_back(static_cast<Index>(v));
    }
  // Walks from vertex `from` along edge `e` until a node or a visited edge.
  auto walk = [&](Index from, Index e) {
    const Index curve = s.num_curves++;
    Index length = 0;
    while (e != kNoIndex && s.edges[static_cast<std::size_t>(e)].curve == kNoIndex) {
      StructureEdge& edge = s.edges[static_cast<std::size_t>(e)];
      edge.curve = curve;
      ++length;
      const Index to = edge.vertices[0] == from ? edge.vertices[1] : edge.vertices[0];
      if (is_node[static_cast<std::size_t>(to)]) break;
      Index next = kNoIndex;
      for (auto k = first[static_cast<std::size_t>(to)]; k < first[static_cast<std::size_t>(to) + 1]; ++k)
        if (s.edges[static_cast<std::size_t>(incident[static_cast<std::size_t>(k)])].curve == kNoIndex)
          next = incident[static_cast<std::size_t>(k)];
      from = to;
      e = next;
    }
    s.curve_lengths.push_back(length);
  };
  for (Index v : ends)
    for (auto k = first[static_cast<std::size_t>(v)]; k < first[static_cast<std::size_t>(v) + 1]; ++k)
      if (s.edges[static_cast<std::size_t>(incident[static_cast<std::size_t>(k)])].curve == kNoIndex)
        walk(v, incident[static_cast<std::size_t>(k)]);
  for (std::size_t i = 0; i < s.edges.size(); ++i)
    if (s.edges[i].singular && s.edges[i].curve == kNoIndex) walk(s.edges[i].vertices[0], static_cast<Index>(i));
}

void size_gradation(const HexMesh& mesh, const Topology& topology, HexStructure& s) {
  const std::size_t n = mesh.hexes.size();
  std::vector<double> volume(n);
  for (std::size_t h = 0; h < n; ++h) {
    HexCorners p;
    for (int i = 0; i < 8; ++i) p[static_cast<std::size_t>(i)] = mesh.points[static_cast<std::size_t>(mesh.hexes[h][static_cast<std::size_t>(i)])];
    volume[h] = hex_volume(p);
  }
  s.cell_gradation.assign(n, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t h = 0; h < n; ++h) {
    if (!(volume[h] > 0.0) || topology.hex_faces.size() < 6 * n) continue;
    double worst = std::numeric_limits<double>::quiet_NaN();
    for (int f = 0; f < 6; ++f) {
      const Index face = topology.hex_faces[6 * h + static_cast<std::size_t>(f)];
      for (Index k = topology.face_hex_offsets[static_cast<std::size_t>(face)];
           k < topology.face_hex_offsets[static_cast<std::size_t>(face) + 1]; ++k) {
        const auto o = static_cast<std::size_t>(topology.face_hexes[static_cast<std::size_t>(k)]);
        if (o == h || !(volume[o] > 0.0)) continue;
        // Lengths: the cube roots of the volumes (issue 46, 46q review Q-M5).
        const double r = std::cbrt(std::max(volume[h] / volume[o], volume[o] / volume[h]));
        if (!(worst >= r)) worst = r;
      }
    }
    s.cell_gradation[h] = worst;
  }
  s.gradation = compute_statistics(s.cell_gradation);
  for (double g : s.cell_gradation) {
    s.num_gradation_above_2 += g > 2.0;
    s.num_gradation_above_4 += g > 4.0;
  }
}

// ---- Size gradation across kinds ----------------------------------------

// Per volume cell id (hexes, tets, wedges, pyramids): the equivalent edge
// length, the cube root of Verdict's volume over the volume of its kind's
// regular unit cell (cell_volume.h): the edge of the regular cell of that
// kind with that volume (for a hex the cube root of its volume); a cell
// without a positive volume keeps its volume (no size).
std::vector<double> equivalent_edge_lengths(const Mesh& mesh) {
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(num_volume_cells(mesh)));
  for_each_block(mesh, [&](auto kind, const auto& cells) {
    if constexpr (CellKindTable<kind()>::dimension == 3) {
      constexpr int N = CellKindTable<kind()>::num_corners;
      for (const auto& cell : cells) {
        std::array<Vec3, N> p;
        for (int k = 0; k < N; ++k) p[static_cast<std::size_t>(k)] = mesh.points[static_cast<std::size_t>(cell[static_cast<std::size_t>(k)])];
        const double v = cell_volume<kind()>(p) / regular_unit_volume<kind()>();
        out.push_back(v > 0.0 ? std::cbrt(v) : v);
      }
    }
  });
  return out;
}

// Face f of volume cell `id`: its corner ids sorted ascending, a triangle's
// padded with kNoIndex at the end.
std::array<Index, 4> sorted_face(const Mesh& mesh, Index id, int f) {
  std::array<Index, 4> v{kNoIndex, kNoIndex, kNoIndex, kNoIndex};
  int i = 0, size = 0;
  for_each_face_of(volume_cell(mesh, id), [&](const std::array<Index, 4>& corners, int n) {
    if (i++ == f) {
      v = corners;
      size = n;
    }
  });
  std::sort(v.begin(), v.begin() + size);
  return v;
}

// Raises the gradation of cells a and b to their ratio when both have a
// positive size.
void compare_sizes(const std::vector<double>& size, Index a, Index b, std::vector<double>& gradation) {
  const double va = size[static_cast<std::size_t>(a)], vb = size[static_cast<std::size_t>(b)];
  if (a == b || !(va > 0.0) || !(vb > 0.0)) return;
  const double r = std::max(va / vb, vb / va);
  for (Index c : {a, b}) {
    double& g = gradation[static_cast<std::size_t>(c)];
    if (!(g >= r)) g = r;
  }
}

// Every pair of volume cells sharing a face (the same three or four
// vertices; a non-manifold face's cells pairwise), the faces matched here:
// bucketed by their smallest vertex (linear), matched inside a bucket by
// sorting its few faces on their other vertices.
void compare_across_own_matched_faces(const Mesh& mesh, const std::vector<double>& size,
                                      std::vector<double>& gradation) {
  const std::size_t nc = size.size(), nv = mesh.points.size();
  struct FaceOf {
    Index cell;
    std::int32_t face;  // its index in CellKindTable<kind>::faces
  };
  std::vector<Index> first(nv + 1, 0);
  std::vector<FaceOf> faces;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<Index> fill;
    if (pass == 1) {
      for (std::size_t v = 0; v < nv; ++v) first[v + 1] += first[v];
      faces.resize(static_cast<std::size_t>(first[nv]));
      fill.assign(first.begin(), first.end() - 1);
    }
    for (Index c = 0; c < static_cast<Index>(nc); ++c) {
      std::int32_t f = 0;
      for_each_face_of(volume_cell(mesh, c), [&](const std::array<Index, 4>& corners, int n) {
        const auto lowest = static_cast<std::size_t>(*std::min_element(corners.begin(), corners.begin() + n));
        if (pass == 0) ++first[lowest + 1];
        else faces[static_cast<std::size_t>(fill[lowest]++)] = {c, f};
        ++f;
      });
    }
  }
  std::vector<std::pair<std::array<Index, 4>, Index>> bucket;
  for (std::size_t v = 0; v < nv; ++v) {
    bucket.clear();
    for (Index k = first[v]; k < first[v + 1]; ++k) {
      const FaceOf& face = faces[static_cast<std::size_t>(k)];
      bucket.push_back({sorted_face(mesh, face.cell, face.face), face.cell});
    }
    std::sort(bucket.begin(), bucket.end());
    for (std::size_t i = 0; i < bucket.size();) {
      std::size_t j = i + 1;
      while (j < bucket.size() && bucket[j].first == bucket[i].first) ++j;
      for (std::size_t a = i; a < j; ++a)
        for (std::size_t b = a + 1; b < j; ++b) compare_sizes(size, bucket[a].second, bucket[b].second, gradation);
      i = j;
    }
  }
}

// A mesh of several kinds: every pair of volume cells sharing a face and the
// quad cell of each non-conforming interface with its two triangle cells.
// The faces are the topology's matched faces (Topology::cell_face_uses: no
// second matching, no face array beside the overlap's stages); without them
// (a topology of the hexes alone) matched here. Either way the same pairs,
// and a cell's gradation is the largest ratio over its pairs, in any order.
std::vector<double> gradation_across_kinds(const Mesh& mesh, const Topology& topology) {
  const std::vector<double> size = equivalent_edge_lengths(mesh);
  const std::size_t nc = size.size();
  std::vector<double> gradation(nc, std::numeric_limits<double>::quiet_NaN());
  if (topology.cell_face_offsets.empty()) {
    compare_across_own_matched_faces(mesh, size, gradation);
  } else {
    const std::array<Index, 5> first_cell = {
        0, static_cast<Index>(mesh.hexes.size()), static_cast<Index>(mesh.hexes.size() + mesh.tets.size()),
        static_cast<Index>(mesh.hexes.size() + mesh.tets.size() + mesh.wedges.size()), static_cast<Index>(nc)};
    const std::vector<Index>& offsets = topology.cell_face_offsets;
    const auto cell = [&](Index use) {
      return cell_half_face(first_cell, topology.cell_face_uses[static_cast<std::size_t>(use)]).cell;
    };
    for (std::size_t f = 0; f + 1 < offsets.size(); ++f)
      for (Index a = offsets[f]; a < offsets[f + 1]; ++a)
        for (Index b = a + 1; b < offsets[f + 1]; ++b) compare_sizes(size, cell(a), cell(b), gradation);
  }
  for (const NonConformingFace& f : topology.non_conforming_faces)
    for (Index t : f.triangle_cells)
      if (t != kNoIndex) compare_sizes(size, f.quad_cell, t, gradation);
  return gradation;
}

void size_gradation_across_kinds(const Mesh& mesh, const Topology& topology, HexStructure& s) {
  s.cell_gradation = gradation_across_kinds(mesh, topology);
  s.gradation = compute_statistics(s.cell_gradation);
  for (double g : s.cell_gradation) {
    s.num_gradation_above_2 += g > 2.0;
    s.num_gradation_above_4 += g > 4.0;
  }
}

}  // namespace

HexStructure compute_structure(const HexMesh& mesh, const Topology& topology) {
  HexStructure s;
  const std::size_t nv = mesh.points.size(), ne = topology.edges.size();
  s.num_edges = static_cast<Index>(ne);
  const EdgeIndex index(topology, nv);
  std::vector<Index> valence(ne, 0);
  for (const Hex& h : mesh.hexes)
    for (const auto& e : kHexEdges) {
      const Index id = index.find(h[static_cast<std::size_t>(e[0])], h[static_cast<std::size_t>(e[1])]);
      if (id != kNoIndex) ++valence[static_cast<std::size_t>(id)];
    }
  // Boundary faces per edge, and the first two of them (the dihedral angle).
  std::vector<Index> num_faces(ne, 0);
  std::vector<std::array<Index, 2>> faces(ne, {kNoIndex, kNoIndex});
  for (Index f : topology.boundary_faces) {
    const Quad& q = topology.faces[static_cast<std::size_t>(f)];
    for (int c = 0; c < 4; ++c) {
      const Index id = index.find(q[static_cast<std::size_t>(c)], q[static_cast<std::size_t>((c + 1) % 4)]);
      if (id == kNoIndex) continue;
      const auto i = static_cast<std::size_t>(id);
      if (num_faces[i] < 2) faces[i][static_cast<std::size_t>(num_faces[i])] = f;
      ++num_faces[i];
    }
  }
  // A hybrid mesh's other boundary faces: their hex edges touch non-hex
  // cells, so only their interior/boundary kind is used.
  const auto count_non_hex_face = [&](const auto& face) {
    for (std::size_t c = 0; c < face.size(); ++c) {
      const Index id = index.find(face[c], face[(c + 1) % face.size()]);
      if (id != kNoIndex) ++num_faces[static_cast<std::size_t>(id)];
    }
  };
  for (const Quad& q : topology.boundary_quads_non_hex) count_non_hex_face(q);
  for (const Tri& t : topology.boundary_triangles) count_non_hex_face(t);
  const bool hybrid = topology.edge_touches_non_hex.size() == ne;
  s.vertex_singular.assign(nv, 0);
  for (std::size_t i = 0; i < ne; ++i) {
    StructureEdge e{topology.edges[i], valence[i]};
    if (hybrid && topology.edge_touches_non_hex[i]) {
      e.touches_non_hex = true;
      e.kind = num_faces[i] == 0 ? EdgeKind::interior : num_faces[i] == 2 ? EdgeKind::boundary : EdgeKind::nonmanifold;
      s.num_nonmanifold_edges += e.kind == EdgeKind::nonmanifold;
      ++s.num_edges_touching_non_hex;
      s.edges.push_back(e);
      continue;
    }
    if (num_faces[i] == 0) {
      e.singular = e.valence != 4;
      if (e.singular) {
        ++s.num_singular_edges_interior;
        ++s.interior_by_valence[e.valence];
      }
    } else if (num_faces[i] == 2) {
      e.kind = EdgeKind::boundary;
      e.ideal_valence = ideal_boundary_valence(mesh, topology.faces[static_cast<std::size_t>(faces[i][0])],
                                               topology.faces[static_cast<std::size_t>(faces[i][1])]);
      e.irregular = e.valence != e.ideal_valence;
      e.singular = e.valence != 2;
      s.num_irregular_edges_boundary += e.irregular;
      if (e.singular) {
        ++s.num_singular_edges_boundary;
        ++s.boundary_by_valence[e.valence];
      }
    } else {
      e.kind = EdgeKind::nonmanifold;  // on 1 or more than 2 boundary faces
      ++s.num_nonmanifold_edges;
    }
    if (e.singular)
      for (Index w : e.vertices) s.vertex_singular[static_cast<std::size_t>(w)] = 1;
    if (e.singular || e.irregular || e.kind == EdgeKind::nonmanifold) s.edges.push_back(e);
  }
  s.num_singular_vertices = static_cast<Index>(std::count(s.vertex_singular.begin(), s.vertex_singular.end(), 1));
  number_curves(s, nv);
  if (mesh.tets.empty() && mesh.wedges.empty() && mesh.pyramids.empty())
    size_gradation(mesh, topology, s);
  else
    size_gradation_across_kinds(mesh, topology, s);
  return s;
}

std::map<Edge, Index> edge_valences_by_map(const HexMesh& mesh) {
  std::map<Edge, Index> valence;
  for (const Hex& h : mesh.hexes)
    for (const auto& e : kHexEdges) {
      Index a = h[static_cast<std::size_t>(e[0])], b = h[static_cast<std::size_t>(e[1])];
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      ++valence[{a, b}];
    }
  return valence;
}

}  // namespace hq
