#include "reference_overlap.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>

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

}  // namespace

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

}  // namespace hq::test
