#include "reference_overlap.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "hqview/core/hex_topology.h"

namespace hq::test {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using P = K::Point_3;

struct RefCell {
  Hex sorted_ids;
  Vec3 lo, hi;                             // box of the 8 vertices
  std::vector<K::Tetrahedron_3> tets;      // the non-flat ones
  std::vector<std::array<P, 3>> boundary;  // 24 triangles, possibly degenerate
};

P exact(const Vec3& v) { return P(v.x, v.y, v.z); }

// The same doubles as overlap.h defines them, computed here on their own.
Vec3 centre_of_face(const HexMesh& mesh, std::array<Index, 4> ids) {
  std::sort(ids.begin(), ids.end());
  const auto& p = mesh.points;
  return ((p[ids[0]] + p[ids[1]]) + (p[ids[2]] + p[ids[3]])) * 0.25;
}

RefCell cell_of(const HexMesh& mesh, const Hex& hex) {
  const auto& p = mesh.points;
  const Vec3 centre =
      (((p[hex[0]] + p[hex[1]]) + (p[hex[2]] + p[hex[3]])) + ((p[hex[4]] + p[hex[5]]) + (p[hex[6]] + p[hex[7]]))) *
      0.125;
  RefCell cell;
  cell.sorted_ids = hex;
  std::sort(cell.sorted_ids.begin(), cell.sorted_ids.end());
  cell.lo = cell.hi = p[hex[0]];
  for (Index v : hex) {
    cell.lo = {std::min(cell.lo.x, p[v].x), std::min(cell.lo.y, p[v].y), std::min(cell.lo.z, p[v].z)};
    cell.hi = {std::max(cell.hi.x, p[v].x), std::max(cell.hi.y, p[v].y), std::max(cell.hi.z, p[v].z)};
  }
  for (const auto& face : kHexFaces) {
    const P fc = exact(centre_of_face(mesh, {hex[face[0]], hex[face[1]], hex[face[2]], hex[face[3]]}));
    for (int e = 0; e < 4; ++e) {
      const P pi = exact(p[hex[face[e]]]), pj = exact(p[hex[face[(e + 1) % 4]]]);
      const K::Tetrahedron_3 tet(pj, pi, fc, exact(centre));
      if (!tet.is_degenerate()) cell.tets.push_back(tet);
      cell.boundary.push_back({pi, pj, fc});
    }
  }
  return cell;
}

bool on_boundary(const RefCell& cell, const P& x) {
  for (const auto& t : cell.boundary) {
    if (CGAL::collinear(t[0], t[1], t[2])) {
      for (int i = 0; i < 3; ++i)
        if (CGAL::squared_distance(x, K::Segment_3(t[i], t[(i + 1) % 3])) == 0) return true;
    } else if (CGAL::squared_distance(x, K::Triangle_3(t[0], t[1], t[2])) == 0) {
      return true;
    }
  }
  return false;
}

bool inside(const RefCell& cell, const P& x) {
  const bool covered = std::any_of(cell.tets.begin(), cell.tets.end(),
                                   [&](const K::Tetrahedron_3& t) { return !t.has_on_unbounded_side(x); });
  return covered && !on_boundary(cell, x);
}

bool has_vertex_inside(const HexMesh& mesh, const RefCell& from, const RefCell& to) {
  for (Index v : from.sorted_ids) {
    const Vec3& x = mesh.points[v];
    // Face and cell centres are averages of the vertices: the solid lies in
    // the vertices' box, its interior strictly inside. (Only a shortcut.)
    if (!(to.lo.x < x.x && x.x < to.hi.x && to.lo.y < x.y && x.y < to.hi.y && to.lo.z < x.z && x.z < to.hi.z)) continue;
    if (!std::binary_search(to.sorted_ids.begin(), to.sorted_ids.end(), v) && inside(to, exact(x))) return true;
  }
  return false;
}

using Tet = std::array<P, 4>;

// The 24 tets of a hex with the face centres of the interior test (corners
// sorted by position), and whether one of the id-sorted 24 is not positive.
std::vector<Tet> positive_position_tets(const HexMesh& mesh, const Hex& hex) {
  const auto& p = mesh.points;
  const Vec3 centre =
      (((p[hex[0]] + p[hex[1]]) + (p[hex[2]] + p[hex[3]])) + ((p[hex[4]] + p[hex[5]]) + (p[hex[6]] + p[hex[7]]))) *
      0.125;
  std::vector<Tet> tets;
  for (const auto& face : kHexFaces) {
    std::array<Vec3, 4> s;
    for (int e = 0; e < 4; ++e) s[e] = p[hex[face[e]]];
    std::sort(s.begin(), s.end(), [](const Vec3& u, const Vec3& v) {
      return std::make_tuple(u.x, u.y, u.z) < std::make_tuple(v.x, v.y, v.z);
    });
    const P fc = exact(((s[0] + s[1]) + (s[2] + s[3])) * 0.25);
    for (int e = 0; e < 4; ++e) {
      const Tet t{exact(p[hex[face[(e + 1) % 4]]]), exact(p[hex[face[e]]]), fc, exact(centre)};
      if (CGAL::orientation(t[0], t[1], t[2], t[3]) == CGAL::POSITIVE) tets.push_back(t);
    }
  }
  return tets;
}

bool is_folded(const HexMesh& mesh, const Hex& hex) {
  const auto& p = mesh.points;
  const P centre = exact(
      (((p[hex[0]] + p[hex[1]]) + (p[hex[2]] + p[hex[3]])) + ((p[hex[4]] + p[hex[5]]) + (p[hex[6]] + p[hex[7]]))) *
      0.125);
  for (const auto& face : kHexFaces) {
    const P fc = exact(centre_of_face(mesh, {hex[face[0]], hex[face[1]], hex[face[2]], hex[face[3]]}));
    for (int e = 0; e < 4; ++e)
      if (CGAL::orientation(exact(p[hex[face[(e + 1) % 4]]]), exact(p[hex[face[e]]]), fc, centre) != CGAL::POSITIVE)
        return true;
  }
  return false;
}

bool in_closed(const Tet& t, const P& x) { return !K::Tetrahedron_3(t[0], t[1], t[2], t[3]).has_on_unbounded_side(x); }

// The points whose hull is the closed s ∩ t, and whether they span a volume.
bool interiors_meet(const Tet& s, const Tet& t) {
  if (!CGAL::do_intersect(K::Tetrahedron_3(s[0], s[1], s[2], s[3]), K::Tetrahedron_3(t[0], t[1], t[2], t[3])))
    return false;
  std::vector<P> points;
  auto clip = [&](const Tet& a, const Tet& b) {
    for (const P& x : a)
      if (in_closed(b, x)) points.push_back(x);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const K::Segment_3 edge(a[i], a[j]);
        for (int k = 0; k < 4; ++k) {
          const K::Triangle_3 face(b[(k + 1) % 4], b[(k + 2) % 4], b[(k + 3) % 4]);
          const auto hit = CGAL::intersection(edge, face);
          if (!hit) continue;
          if (const P* q = boost::get<P>(&*hit)) points.push_back(*q);
          if (const K::Segment_3* g = boost::get<K::Segment_3>(&*hit)) {
            points.push_back(g->source());
            points.push_back(g->target());
          }
        }
      }
  };
  clip(s, t);
  clip(t, s);
  // Affine rank 3: a tetrahedron among the points.
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (points[i] == points[0]) continue;
    for (std::size_t j = i + 1; j < points.size(); ++j) {
      if (CGAL::collinear(points[0], points[i], points[j])) continue;
      for (std::size_t k = j + 1; k < points.size(); ++k)
        if (!CGAL::coplanar(points[0], points[i], points[j], points[k])) return true;
    }
  }
  return false;
}

}  // namespace

std::vector<std::array<Index, 2>> reference_interior_pairs(const HexMesh& mesh) {
  const std::size_t n = mesh.hexes.size();
  std::vector<std::vector<Tet>> tets(n);
  std::vector<char> folded(n);
  std::vector<Vec3> lo(n), hi(n);
  for (std::size_t h = 0; h < n; ++h) {
    lo[h] = hi[h] = mesh.points[mesh.hexes[h][0]];
    for (Index v : mesh.hexes[h]) {
      const Vec3& x = mesh.points[v];
      lo[h] = {std::min(lo[h].x, x.x), std::min(lo[h].y, x.y), std::min(lo[h].z, x.z)};
      hi[h] = {std::max(hi[h].x, x.x), std::max(hi[h].y, x.y), std::max(hi[h].z, x.z)};
    }
  }
  for (std::size_t h = 0; h < n; ++h) {
    tets[h] = positive_position_tets(mesh, mesh.hexes[h]);
    folded[h] = is_folded(mesh, mesh.hexes[h]);
  }
  // Per vertex, the folded cells holding it.
  std::vector<std::vector<Index>> folded_at(mesh.points.size());
  for (std::size_t h = 0; h < n; ++h)
    if (folded[h])
      for (Index v : mesh.hexes[h]) folded_at[v].push_back(static_cast<Index>(h));
  auto folded_near = [&](const Hex& hex) {
    std::vector<Index> cells;
    for (Index v : hex) cells.insert(cells.end(), folded_at[v].begin(), folded_at[v].end());
    std::sort(cells.begin(), cells.end());
    return cells;
  };
  std::vector<std::array<Index, 2>> pairs;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      const Hex &ha = mesh.hexes[a], &hb = mesh.hexes[b];
      // Interiors that meet lie in both boxes' interiors (a shortcut only).
      if (!(lo[a].x < hi[b].x && lo[b].x < hi[a].x && lo[a].y < hi[b].y && lo[b].y < hi[a].y && lo[a].z < hi[b].z &&
            lo[b].z < hi[a].z))
        continue;
      if (std::any_of(ha.begin(), ha.end(), [&](Index v) { return std::find(hb.begin(), hb.end(), v) != hb.end(); }))
        continue;
      const std::vector<Index> fa = folded_near(ha), fb = folded_near(hb);
      if (std::any_of(fb.begin(), fb.end(), [&](Index c) { return std::binary_search(fa.begin(), fa.end(), c); }))
        continue;
      bool meet = false;
      for (std::size_t i = 0; i < tets[a].size() && !meet; ++i)
        for (std::size_t j = 0; j < tets[b].size() && !meet; ++j) meet = interiors_meet(tets[a][i], tets[b][j]);
      if (meet) pairs.push_back({static_cast<Index>(a), static_cast<Index>(b)});
    }
  return pairs;
}

std::vector<std::array<Index, 2>> reference_intersecting_pairs(const HexMesh& mesh) {
  std::vector<RefCell> cells;
  for (const Hex& hex : mesh.hexes) cells.push_back(cell_of(mesh, hex));
  std::vector<std::array<Index, 2>> pairs;
  for (std::size_t a = 0; a < cells.size(); ++a)
    for (std::size_t b = a + 1; b < cells.size(); ++b)
      if (cells[a].sorted_ids == cells[b].sorted_ids || has_vertex_inside(mesh, cells[a], cells[b]) ||
          has_vertex_inside(mesh, cells[b], cells[a]))
        pairs.push_back({static_cast<Index>(a), static_cast<Index>(b)});
  return pairs;
}

std::vector<std::array<Index, 2>> reference_all_pairs(const HexMesh& mesh) {
  std::vector<std::array<Index, 2>> pairs = reference_intersecting_pairs(mesh);
  for (const auto& pair : reference_interior_pairs(mesh)) pairs.push_back(pair);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

namespace {

using RefTriangle = std::array<Index, 3>;

// Whether the exact intersection of two triangles (ids welded) is more
// than what their shared ids span.
bool surface_triangles_meet(const std::vector<P>& x, const RefTriangle& a, const RefTriangle& b) {
  const K::Triangle_3 ta(x[a[0]], x[a[1]], x[a[2]]), tb(x[b[0]], x[b[1]], x[b[2]]);
  const auto meet = CGAL::intersection(ta, tb);
  if (!meet) return false;
  std::vector<Index> shared;
  for (Index i : a)
    if (std::find(b.begin(), b.end(), i) != b.end()) shared.push_back(i);
  if (shared.size() == 0 || shared.size() == 3) return true;
  if (const P* point = boost::get<P>(&*meet)) return !(shared.size() == 1 && *point == x[shared[0]]);
  if (const K::Segment_3* segment = boost::get<K::Segment_3>(&*meet))
    return !(shared.size() == 2 && ((segment->source() == x[shared[0]] && segment->target() == x[shared[1]]) ||
                                    (segment->source() == x[shared[1]] && segment->target() == x[shared[0]])));
  return true;  // a triangle or a polygon: an area in common
}

}  // namespace

std::vector<std::array<Index, 2>> reference_surface_pairs(const Mesh& mesh) {
  const auto& p = mesh.points;
  // Exact coincidence: the lowest id at each position.
  std::map<std::tuple<double, double, double>, Index> first_at;
  std::vector<Index> welded(p.size());
  for (std::size_t v = 0; v < p.size(); ++v)
    welded[v] = first_at.emplace(std::make_tuple(p[v].x, p[v].y, p[v].z), static_cast<Index>(v)).first->second;
  std::vector<P> x;
  for (const Vec3& v : p) x.push_back(exact(v));
  // Each face's triangles: a quad split along the diagonal whose triangles
  // face the same way when only one does, else the shorter (p0-p2 on a tie).
  std::vector<std::vector<RefTriangle>> faces;
  for (const auto& q : mesh.quads) {
    const Index a = welded[q[0]], b = welded[q[1]], c = welded[q[2]], d = welded[q[3]];
    const Vec3 &pa = p[a], &pb = p[b], &pc = p[c], &pd = p[d];
    const bool ac = dot(cross(pb - pa, pc - pa), cross(pc - pa, pd - pa)) > 0.0;
    const bool bd = dot(cross(pb - pa, pd - pa), cross(pc - pb, pd - pb)) > 0.0;
    const bool use_ac = ac != bd ? ac : squared_norm(pc - pa) <= squared_norm(pd - pb);
    faces.push_back(use_ac ? std::vector<RefTriangle>{{a, b, c}, {a, c, d}} : std::vector<RefTriangle>{{a, b, d}, {b, c, d}});
  }
  for (const auto& t : mesh.triangles) faces.push_back({{welded[t[0]], welded[t[1]], welded[t[2]]}});
  for (auto& f : faces)
    f.erase(std::remove_if(f.begin(), f.end(), [&](const RefTriangle& t) { return CGAL::collinear(x[t[0]], x[t[1]], x[t[2]]); }),
            f.end());
  std::vector<std::array<Index, 2>> pairs;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (std::size_t g = f; g < faces.size(); ++g) {
      bool meet = false;
      for (std::size_t i = 0; i < faces[f].size() && !meet; ++i)
        for (std::size_t j = f == g ? i + 1 : 0; j < faces[g].size() && !meet; ++j)
          meet = surface_triangles_meet(x, faces[f][i], faces[g][j]);
      if (meet) pairs.push_back({static_cast<Index>(f), static_cast<Index>(g)});
    }
  return pairs;
}

}  // namespace hq::test
