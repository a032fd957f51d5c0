// Exact predicates of the overlap stages. The one translation unit (with
// box_pairs.cpp) that includes CGAL's kernel: keep it that way, each such
// file costs 20+ s and > 1 GB to compile.
//
// Every decision below is the sign of a polynomial in the input doubles,
// taken by CGAL Epick's predicates (orientation, collinear, has_on,
// do_intersect: static filter, interval filter, exact fallback). Constructed
// points (face and cell centres, ray ends) are computed once in double and
// then taken as exact inputs.

#include "hqview/overlap/exact_geometry.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "hqview/overlap/box_pairs.h"
#include "hqview/overlap/overlap.h"

namespace hq::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle3 = Kernel::Triangle_3;

Point point(const Vec3& v) { return Point(v.x, v.y, v.z); }

// sign det[b - a, c - a, d - a] (CGAL::orientation): > 0 when d lies on the
// side of plane (a, b, c) that its right-hand normal points to.
int orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return static_cast<int>(CGAL::orientation(point(a), point(b), point(c), point(d)));
}

int orient(const std::vector<Vec3>& p, const Tet& t) {
  return orient(p[static_cast<std::size_t>(t[0])], p[static_cast<std::size_t>(t[1])], p[static_cast<std::size_t>(t[2])],
                p[static_cast<std::size_t>(t[3])]);
}

const Vec3& at(const std::vector<Vec3>& p, Index i) { return p[static_cast<std::size_t>(i)]; }

// ---- Stage G: a vertex of one cell inside the other -----------------------

struct TetData {
  Tet ids{};
  int sign = 0;  // orientation; 0 = flat, no interior
};

bool in_closed_tet(const std::vector<Vec3>& p, const TetData& t, const Vec3& x) {
  const Vec3 &t0 = at(p, t.ids[0]), &t1 = at(p, t.ids[1]), &t2 = at(p, t.ids[2]), &t3 = at(p, t.ids[3]);
  return orient(x, t1, t2, t3) * t.sign >= 0 && orient(t0, x, t2, t3) * t.sign >= 0 &&
         orient(t0, t1, x, t3) * t.sign >= 0 && orient(t0, t1, t2, x) * t.sign >= 0;
}

// x on the closed triangle (a, b, c), which may be degenerate.
bool on_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& x) {
  const Point pa = point(a), pb = point(b), pc = point(c), px = point(x);
  if (CGAL::collinear(pa, pb, pc))
    return Segment(pa, pb).has_on(px) || Segment(pb, pc).has_on(px) || Segment(pc, pa).has_on(px);
  return Triangle3(pa, pb, pc).has_on(px);
}

// The tets of a cell's solid (at most 24) with their orientations.
struct CellTets {
  std::array<TetData, 24> tets;
  int n = 0;
  const TetData* begin() const { return tets.data(); }
  const TetData* end() const { return tets.data() + n; }
};

CellTets cell_tet_data(const VolumeCells& cells, const Topology& topo, const TetPoints& tp, Index c) {
  CellTets data;
  const SolidTets solid = cell_solid_tets(cells, topo, tp, c);
  data.n = solid.n;
  for (std::size_t i = 0; i < static_cast<std::size_t>(solid.n); ++i) {
    data.tets[i].ids = solid.tets[i];
    data.tets[i].sign = orient(tp.points, solid.tets[i]);
  }
  return data;
}

// Inside = in one of the cell's closed tets of non-zero volume and on none of
// its boundary triangles: the interior of its solid.
bool inside_cell(const std::vector<Vec3>& p, const CellTets& cell, const Vec3& x) {
  bool covered = false;
  for (const TetData& t : cell)
    if (t.sign != 0 && in_closed_tet(p, t, x)) {
      covered = true;
      break;
    }
  if (!covered) return false;
  for (const TetData& t : cell)  // (p_j, p_i, c_f, c_h): boundary triangle (p_i, p_j, c_f); (p1, p0, p2, c_h): (p0, p1, p2)
    if (on_triangle(at(p, t.ids[1]), at(p, t.ids[0]), at(p, t.ids[2]), x)) return false;
  return true;
}

bool strictly_inside_box(const Box3& b, const Vec3& x) {
  for (int i = 0; i < 3; ++i)
    if (!(b.lo[static_cast<std::size_t>(i)] < x[i] && x[i] < b.hi[static_cast<std::size_t>(i)])) return false;
  return true;
}

bool has_corner(const CellCornerIds& c, Index v) { return std::find(c.begin(), c.end(), v) != c.end(); }

CellCornerIds sorted(CellCornerIds c) {
  std::sort(c.v.begin(), c.v.begin() + c.n);
  return c;
}

// The lowest vertex of cell `from` that is not a vertex of `to` and lies inside it.
Index vertex_inside(const std::vector<Vec3>& p, const CellCornerIds& from, const CellCornerIds& to,
                    const Box3& to_box, const CellTets& to_tets) {
  for (Index v : sorted(from)) {
    if (has_corner(to, v)) continue;
    if (strictly_inside_box(to_box, at(p, v)) && inside_cell(p, to_tets, at(p, v))) return v;
  }
  return kNoIndex;
}

// ---- Stage G: interiors that meet with no vertex inside -------------------

// sign det[u1 - u0, v1 - v0, w1 - w0] of differences of input doubles, exact:
// interval arithmetic, then rationals when the interval holds 0.
template <class Number>
Number det_of_differences(const std::array<const Vec3*, 6>& q) {
  Number d[3][3];
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) d[r][k] = Number((*q[2 * r + 1])[k]) - Number((*q[2 * r])[k]);
  return d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) - d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0]) +
         d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
}

int sign_det_of_differences(const Vec3& u0, const Vec3& u1, const Vec3& v0, const Vec3& v1, const Vec3& w0,
                            const Vec3& w1) {
  const std::array<const Vec3*, 6> q{&u0, &u1, &v0, &v1, &w0, &w1};
  const CGAL::Interval_nt<true> approx = det_of_differences<CGAL::Interval_nt<true>>(q);
  if (approx.inf() > 0) return 1;
  if (approx.sup() < 0) return -1;
  if (approx.inf() == 0 && approx.sup() == 0) return 0;  // the interval holds the exact value
  return static_cast<int>(CGAL::sign(det_of_differences<CGAL::Exact_rational>(q)));
}

using TetCorners = std::array<Vec3, 4>;

// A plane through a face of s has all of t on its other closed side.
bool face_separates(const TetCorners& s, const TetCorners& t) {
  for (std::size_t k = 0; k < 4; ++k) {
    const Vec3 &f0 = s[(k + 1) % 4], &f1 = s[(k + 2) % 4], &f2 = s[(k + 3) % 4];
    const int side = orient(f0, f1, f2, s[k]);  // not 0: s has volume
    if (std::all_of(t.begin(), t.end(), [&](const Vec3& q) { return orient(f0, f1, f2, q) * side <= 0; })) return true;
  }
  return false;
}

// The interiors of two tets of non-zero volume meet. By the separating axis
// theorem they do not exactly when a plane parallel to a face of one, or to
// an edge of each (the facet normals of their Minkowski difference), has one
// tet on each closed side; every side is an exact sign, so touching tets
// (a shared face, edge or vertex, coplanar faces) never count.
bool tet_interiors_meet(const TetCorners& s, const TetCorners& t) {
  if (face_separates(s, t) || face_separates(t, s)) return false;
  static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (const auto& ea : kEdges)
    for (const auto& eb : kEdges) {
      // n = ea x eb; n . (q - p) for every corner p of s and q of t.
      bool is_positive = false, is_negative = false;
      for (std::size_t i = 0; i < 4 && !(is_positive && is_negative); ++i)
        for (std::size_t j = 0; j < 4 && !(is_positive && is_negative); ++j) {
          const int g = sign_det_of_differences(s[ea[0]], s[ea[1]], t[eb[0]], t[eb[1]], s[i], t[j]);
          is_positive |= g > 0;
          is_negative |= g < 0;
        }
      // One sign only: separated along n. None: n = 0 (parallel edges), no axis.
      if (is_positive != is_negative) return false;
    }
  return true;
}

bool boxes_overlap_open(const Box3& a, const Box3& b) {
  for (int i = 0; i < 3; ++i)
    if (!(a.lo[i] < b.hi[i] && b.lo[i] < a.hi[i])) return false;
  return true;
}

// The tets of positive volume of cell c for the test of interiors: its
// solid's tets, with each quad's centre taken from the face's corners sorted by
// position (not by id), so two faces at one place whose vertex ids differ
// (coincident vertices, reported by stage A) get the same centre and their
// cells only touch. Negative tets are left out: there a cell's solid folds
// over its neighbour by construction (stage C reports the cell), which is
// not two cells overlapping.
struct SolidTet {
  TetCorners corners;
  Box3 box;
};

// At most 24 (a hex's 6 quads, 4 fan tets each), held in place: no
// allocation per tested pair.
struct NearSolidTets {
  std::array<SolidTet, 24> tets;
  int n = 0;
  const SolidTet* begin() const { return tets.data(); }
  const SolidTet* end() const { return tets.data() + n; }
  bool empty() const { return n == 0; }
};

// The positive tets of `cell` whose box overlaps `other_box` with volume, in
// the solid's order.
NearSolidTets positive_tets_near(const VolumeCells& cells, const TetPoints& tp, Index cell, const Box3& other_box) {
  const CellCornerIds corners = cells.corners(cell);
  const Vec3& centre = at(tp.points, tp.cell_base + cell);
  NearSolidTets tets;
  const auto keep_if_positive = [&](const TetCorners& t) {
    if (orient(t[0], t[1], t[2], t[3]) <= 0) return;
    Box3 box;
    for (const Vec3& x : t) box.add(x);
    if (boxes_overlap_open(box, other_box)) tets.tets[static_cast<std::size_t>(tets.n++)] = {t, box};
  };
  const KindFaces faces = kind_faces(corners.kind);
  for (int k = 0; k < faces.n; ++k) {
    const CellFace& f = faces.faces[k];
    std::array<Vec3, 4> c;
    for (int e = 0; e < f.size; ++e)
      c[static_cast<std::size_t>(e)] =
          at(cells.mesh->points, corners.v[static_cast<std::size_t>(f.v[static_cast<std::size_t>(e)])]);
    if (f.size == 3) {
      keep_if_positive({c[1], c[0], c[2], centre});
      continue;
    }
    std::array<Vec3, 4> s = c;
    std::sort(s.begin(), s.end(), [](const Vec3& u, const Vec3& v) {
      return u.x != v.x ? u.x < v.x : u.y != v.y ? u.y < v.y : u.z < v.z;
    });
    const Vec3 face = ((s[0] + s[1]) + (s[2] + s[3])) * 0.25;
    for (std::size_t e = 0; e < 4; ++e) keep_if_positive({c[(e + 1) % 4], c[e], face, centre});
  }
  return tets;
}

// Two tet cells whose fan tets cannot meet: a plane through a face of one
// has that cell's corners and centre on one closed side and the other's
// corners and centre on the other (each fan tet lies in the hull of its
// cell's corners and centre). Exact signs: the cheap common answer of
// interiors_meet for tets that are near but apart, with the same result as
// testing their fan tets pairwise (1 plane test instead of up to 16 tet
// pairs' separating axes).
bool tet_cells_separated(const std::vector<Vec3>& p, const CellCornerIds& a, const Vec3& centre_a,
                         const CellCornerIds& b, const Vec3& centre_b) {
  const auto by_face_of = [&](const CellCornerIds& s, const Vec3& centre_s, const CellCornerIds& t,
                              const Vec3& centre_t) {
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec3 &f0 = at(p, s.v[(k + 1) % 4]), &f1 = at(p, s.v[(k + 2) % 4]), &f2 = at(p, s.v[(k + 3) % 4]);
      const int side = orient(f0, f1, f2, at(p, s.v[k]));
      if (side == 0 || orient(f0, f1, f2, centre_s) * side < 0) continue;
      if (orient(f0, f1, f2, centre_t) * side > 0) continue;
      if (std::all_of(t.begin(), t.end(), [&](Index q) { return orient(f0, f1, f2, at(p, q)) * side <= 0; }))
        return true;
    }
    return false;
  };
  return by_face_of(a, centre_a, b, centre_b) || by_face_of(b, centre_b, a, centre_a);
}

// Where the interiors of two cells meet: their solids' interiors intersect
// exactly when the interiors of a tet of each do (the union of a solid's
// tets of volume is dense in it). A point at the mean of the corners of the
// first such pair (for the arrow), nullopt when none: the cells are
// disjoint or only touch. Only tets whose box overlaps the other cell's box
// with volume can meet it.
std::optional<Vec3> interiors_meet(const VolumeCells& cells, const TetPoints& tp, Index a, const Box3& box_a, Index b,
                                   const Box3& box_b) {
  const CellCornerIds corners_a = cells.corners(a), corners_b = cells.corners(b);
  if (corners_a.kind == CellKind::tet && corners_b.kind == CellKind::tet &&
      tet_cells_separated(cells.mesh->points, corners_a, at(tp.points, tp.cell_base + a), corners_b,
                          at(tp.points, tp.cell_base + b)))
    return std::nullopt;
  const NearSolidTets from_a = positive_tets_near(cells, tp, a, box_b);
  if (from_a.empty()) return std::nullopt;
  const NearSolidTets from_b = positive_tets_near(cells, tp, b, box_a);
  for (const SolidTet& s : from_a)
    for (const SolidTet& t : from_b)
      if (boxes_overlap_open(s.box, t.box) && tet_interiors_meet(s.corners, t.corners)) {
        Vec3 sum{};
        for (const Vec3& x : s.corners) sum = sum + x;
        for (const Vec3& x : t.corners) sum = sum + x;
        return sum * 0.125;
      }
  return std::nullopt;
}

bool share_a_vertex(const CellCornerIds& a, const CellCornerIds& b) {
  return std::any_of(a.begin(), a.end(), [&](Index v) { return has_corner(b, v); });
}

// Some cell with a non-positive tet (folded) holds a vertex of a and one of b.
bool touch_one_folded_cell(const VertexCells& vertex_cells, const std::vector<char>& folded, const CellCornerIds& a,
                           const CellCornerIds& b) {
  // Each thread's two lists keep their capacity from pair to pair (no
  // allocation per tested pair).
  thread_local std::vector<Index> of_a, of_b;
  auto folded_cells_of = [&](const CellCornerIds& corners, std::vector<Index>& cells) {
    cells.clear();
    for (Index v : corners)
      for (Index i = vertex_cells.begin(v); i < vertex_cells.end(v); ++i) {
        const Index c = vertex_cells.cell(i);
        if (folded[static_cast<std::size_t>(c)]) cells.push_back(c);
      }
    std::sort(cells.begin(), cells.end());
  };
  folded_cells_of(a, of_a);
  if (of_a.empty()) return false;
  folded_cells_of(b, of_b);
  return std::any_of(of_b.begin(), of_b.end(),
                     [&](Index c) { return std::binary_search(of_a.begin(), of_a.end(), c); });
}

CellPairTest test_cell_pair(const VolumeCells& cells, const VertexCells& vertex_cells, const Topology& topo,
                            const TetPoints& tp, Index a, Index b, bool test_interiors, const std::vector<char>& folded) {
  const auto& p = tp.points;
  const CellCornerIds hex_a = cells.corners(a), hex_b = cells.corners(b);
  CellPairTest result;
  if (hex_a.n == hex_b.n && sorted(hex_a).v == sorted(hex_b).v) {  // duplicates: the same solid twice
    result.intersect = true;
    result.position = at(p, tp.cell_base + a);
    return result;
  }
  // A vertex inside a cell lies strictly inside its box: most vertices stop here.
  const Box3 box_a = box_of(p, hex_a.v.data(), hex_a.n), box_b = box_of(p, hex_b.v.data(), hex_b.n);
  auto has_candidate = [&](const CellCornerIds& from, const CellCornerIds& to, const Box3& to_box) {
    for (Index v : from)
      if (!has_corner(to, v) && strictly_inside_box(to_box, at(p, v))) return true;
    return false;
  };
  if (has_candidate(hex_a, hex_b, box_b))
    result.inside_vertex = vertex_inside(p, hex_a, hex_b, box_b, cell_tet_data(cells, topo, tp, b));
  if (result.inside_vertex == kNoIndex && has_candidate(hex_b, hex_a, box_a))
    result.inside_vertex = vertex_inside(p, hex_b, hex_a, box_a, cell_tet_data(cells, topo, tp, a));
  if (result.inside_vertex != kNoIndex) {
    result.intersect = true;
    result.position = at(p, result.inside_vertex);
    return result;
  }
  // No vertex inside: the interiors may still meet (an edge or a face through
  // the other cell, coplanar faces overlapping, cells crossing). Not tested
  // on neighbours (cells that share a vertex) or on two cells that both
  // touch a cell with a non-positive tet: there the tet solids overlap with
  // no vertex inside by construction, at the fold of the tets of a thin
  // twisted cell that is valid as a trilinear hex (Dolphin_padded's 32920
  // between 32918 and 32922; docs/analysis.md "Overlap"), which stage C
  // reports.
  if (!test_interiors || share_a_vertex(hex_a, hex_b) || touch_one_folded_cell(vertex_cells, folded, hex_a, hex_b))
    return result;
  const std::optional<Vec3> where = interiors_meet(cells, tp, a, box_a, b, box_b);
  if (where) {
    result.intersect = true;
    result.position = *where;
  }
  return result;
}

// ---- Stage E: fan triangles meeting improperly ----------------------------

// Which ids of a appear in b, and how many.
struct SharedCorners {
  int count = 0;
  std::array<bool, 3> in_a{}, in_b{};
};

SharedCorners shared_corners(const Triangle& a, const Triangle& b) {
  SharedCorners s;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      if (a[i] == b[j]) {
        ++s.count;
        s.in_a[i] = s.in_b[j] = true;
      }
  return s;
}

// All corners of b (but those it shares with a) strictly on one side of a's plane.
bool strictly_beside(const std::vector<Vec3>& p, const Triangle& a, const Triangle& b,
                     const std::array<bool, 3>& b_shared, bool& coplanar) {
  int positive = 0, negative = 0, considered = 0;
  for (std::size_t j = 0; j < 3; ++j) {
    if (b_shared[j]) continue;
    ++considered;
    const int s = orient(at(p, a[0]), at(p, a[1]), at(p, a[2]), at(p, b[j]));
    positive += s > 0;
    negative += s < 0;
  }
  coplanar = positive == 0 && negative == 0;
  return considered > 0 && (positive == considered || negative == considered);
}

// 2D closed-set tests from exact orientations (CGAL's own 2D do_intersect
// constructs in interval arithmetic and is several times slower here).
using Point2 = Kernel::Point_2;

// Flat boundaries (grids, CAD parts) make many orientations exactly zero,
// which CGAL's static filter hands to its slower interval filter: those
// whose two products have an exactly zero factor are answered here first.
int orient2(const Point2& a, const Point2& b, const Point2& c) {
  const double acx = a.x() - c.x(), bcx = b.x() - c.x(), acy = a.y() - c.y(), bcy = b.y() - c.y();
  if ((acx == 0.0 || bcy == 0.0) && (acy == 0.0 || bcx == 0.0)) return 0;  // a difference is 0 only for equal inputs
  return static_cast<int>(CGAL::orientation(a, b, c));
}

// q on the closed segment [p, r], for collinear p, q, r: coordinate
// comparisons only, so exact.
bool between(const Point2& p, const Point2& q, const Point2& r) {
  return std::min(p.x(), r.x()) <= q.x() && q.x() <= std::max(p.x(), r.x()) && std::min(p.y(), r.y()) <= q.y() &&
         q.y() <= std::max(p.y(), r.y());
}

bool segments_meet(const Point2& p1, const Point2& p2, const Point2& q1, const Point2& q2) {
  const int o1 = orient2(p1, p2, q1), o2 = orient2(p1, p2, q2), o3 = orient2(q1, q2, p1), o4 = orient2(q1, q2, p2);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && between(p1, q1, p2)) || (o2 == 0 && between(p1, q2, p2)) || (o3 == 0 && between(q1, p1, q2)) ||
         (o4 == 0 && between(q1, p2, q2));
}

// x in the closed, non-degenerate triangle t.
bool in_triangle(const std::array<Point2, 3>& t, const Point2& x) {
  const int s = orient2(t[0], t[1], t[2]);
  return orient2(t[0], t[1], x) * s >= 0 && orient2(t[1], t[2], x) * s >= 0 && orient2(t[2], t[0], x) * s >= 0;
}

bool segment_meets_triangle(const Point2& a, const Point2& b, const std::array<Point2, 3>& t) {
  if (in_triangle(t, a) || in_triangle(t, b)) return true;
  for (std::size_t i = 0; i < 3; ++i)
    if (segments_meet(a, b, t[i], t[(i + 1) % 3])) return true;
  return false;
}

// The same decision for coplanar triangles, in the coordinate plane onto
// which their plane projects one to one.
bool coplanar_triangles_meet_improperly(const std::vector<Vec3>& p, const Triangle& a, const Triangle& b,
                                        const SharedCorners& shared) {
  int drop = 0;
  auto project = [&](Index i) {
    const Vec3& q = at(p, i);
    return drop == 0 ? Point2(q.y, q.z) : (drop == 1 ? Point2(q.z, q.x) : Point2(q.x, q.y));
  };
  for (drop = 0; drop < 3; ++drop)
    if (CGAL::orientation(project(a[0]), project(a[1]), project(a[2])) != CGAL::COLLINEAR) break;
  const std::array<Point2, 3> ta{project(a[0]), project(a[1]), project(a[2])},
      tb{project(b[0]), project(b[1]), project(b[2])};
  if (shared.count == 0) {
    for (std::size_t i = 0; i < 3; ++i)
      if (segment_meets_triangle(ta[i], ta[(i + 1) % 3], tb)) return true;
    return in_triangle(ta, tb[0]);  // b inside a
  }
  if (shared.count == 1) {
    auto opposite = [](const std::array<Point2, 3>& t, const std::array<bool, 3>& s) {
      const std::size_t k = s[0] ? 0 : (s[1] ? 1 : 2);
      return std::array<Point2, 2>{t[(k + 1) % 3], t[(k + 2) % 3]};
    };
    const auto ea = opposite(ta, shared.in_a), eb = opposite(tb, shared.in_b);
    return segment_meets_triangle(ea[0], ea[1], tb) || segment_meets_triangle(eb[0], eb[1], ta);
  }
  // Sharing an edge uv: they overlap iff their third corners lie on the same side of it.
  Index u = kNoIndex, v = kNoIndex, x = kNoIndex, y = kNoIndex;
  for (std::size_t i = 0; i < 3; ++i) {
    if (shared.in_a[i])
      (u == kNoIndex ? u : v) = a[i];
    else
      x = a[i];
    if (!shared.in_b[i]) y = b[i];
  }
  return orient2(project(u), project(v), project(x)) == orient2(project(u), project(v), project(y));
}

// The sign of orient2 when double arithmetic alone is sure of it, else 0:
// Shewchuk's bound for orient2dfast ((3 + 16 eps) eps of the products'
// magnitudes, eps = 2^-53), widened by 1e-4 of itself, and not trusted near
// underflow, overflow or NaN.
int sure_orient2(const Point2& a, const Point2& b, const Point2& c) {
  const double left = (a.x() - c.x()) * (b.y() - c.y()), right = (a.y() - c.y()) * (b.x() - c.x());
  const double det = left - right, bound = 3.3311e-16 * (std::abs(left) + std::abs(right));
  if (!(bound > 0x1p-1000 && bound < 0x1p1000)) return 0;
  return det > bound ? 1 : (det < -bound ? -1 : 0);
}

// The triangles meet at most in their shared corners (by id) and what lies
// between them, decided in one coordinate plane (the one a's normal points
// to most) by exact 2D orientations: some edge's line of one triangle, whose
// projection has area, has the other's corners but the edge's own ends
// strictly on its far side. Then the projections meet only within the hull
// of the shared corners' projections, and the projection is one to one on
// that triangle's plane, so the triangles meet only in the shared corners'
// hull: a shared vertex or edge, a contact. On a smooth surface this settles
// neighbours without the 3D orientations, which are nearly zero there and
// go to CGAL's exact fallback. The signs double arithmetic is sure of are
// tried first (a corner nearly on one line, e.g. the next point of a grid
// line, leaves another line to separate them), then CGAL's exact ones.
// False: not settled (the full test decides).
bool separated_in_projection(const std::vector<Vec3>& p, const Triangle& a, const Triangle& b) {
  const Vec3 &a0 = at(p, a[0]), &a1 = at(p, a[1]), &a2 = at(p, a[2]);
  const Vec3 n = cross(a1 - a0, a2 - a0);
  const double nx = std::abs(n.x), ny = std::abs(n.y), nz = std::abs(n.z);
  const int drop = nx >= ny && nx >= nz ? 0 : (ny >= nz ? 1 : 2);
  const auto project = [&](Index i) {
    const Vec3& q = at(p, i);
    return drop == 0 ? Point2(q.y, q.z) : (drop == 1 ? Point2(q.z, q.x) : Point2(q.x, q.y));
  };
  const std::array<Point2, 3> pa{project(a[0]), project(a[1]), project(a[2])},
      pb{project(b[0]), project(b[1]), project(b[2])};
  // sign(a, b, c): an exact sign, or 0 when not known (never a wrong sign).
  const auto edge_separates = [](const Triangle& s, const std::array<Point2, 3>& ps, const Triangle& t,
                                 const std::array<Point2, 3>& pt, auto sign) {
    const int side = sign(ps[0], ps[1], ps[2]);
    if (side == 0) return false;
    for (std::size_t e = 0; e < 3; ++e) {
      const std::size_t f = (e + 1) % 3;
      bool beyond = true;
      for (std::size_t k = 0; k < 3 && beyond; ++k)
        beyond = t[k] == s[e] || t[k] == s[f] || sign(ps[e], ps[f], pt[k]) == -side;
      if (beyond) return true;
    }
    return false;
  };
  return edge_separates(a, pa, b, pb, sure_orient2) || edge_separates(b, pb, a, pa, sure_orient2) ||
         edge_separates(a, pa, b, pb, orient2) || edge_separates(b, pb, a, pa, orient2);
}

bool triangles_meet_improperly(const std::vector<Vec3>& p, const Triangle& a, const Triangle& b) {
  const SharedCorners shared = shared_corners(a, b);
  if (shared.count == 3) return true;  // the same triangle twice
  if (separated_in_projection(p, a, b)) return false;
  // Most candidate pairs lie strictly on one side of each other's plane.
  bool coplanar = false, unused = false;
  if (strictly_beside(p, a, b, shared.in_b, coplanar) || strictly_beside(p, b, a, shared.in_a, unused)) return false;
  if (coplanar) return coplanar_triangles_meet_improperly(p, a, b, shared);
  auto pt = [&](Index i) { return point(at(p, i)); };
  const Triangle3 ta(pt(a[0]), pt(a[1]), pt(a[2])), tb(pt(b[0]), pt(b[1]), pt(b[2]));
  if (shared.count == 0) return CGAL::do_intersect(ta, tb);
  if (shared.count == 1) {
    // They meet beyond the shared corner iff the edge opposite it in one
    // triangle meets the other triangle.
    auto opposite = [&](const Triangle& t, const std::array<bool, 3>& s) {
      const std::size_t k = s[0] ? 0 : (s[1] ? 1 : 2);
      return Segment(pt(t[(k + 1) % 3]), pt(t[(k + 2) % 3]));
    };
    return CGAL::do_intersect(opposite(a, shared.in_a), tb) || CGAL::do_intersect(opposite(b, shared.in_b), ta);
  }
  return false;  // sharing an edge, not coplanar: they meet only along it
}

}  // namespace

// ---- Stage C ----------------------------------------------------------------

std::vector<std::uint8_t> classify_cell_orientations(const VolumeCells& cells, const Topology& topo,
                                                     const TetPoints& tp) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(cells.size()), 0);
  // One loop per kind, over its corner frames (the pyramid's apex has none).
  for_each_cell_kind([&](auto kind) {
    using Table = CellKindTable<kind()>;
    if constexpr (Table::dimension == 3) {
      const auto& block = cell_block<kind()>(*cells.mesh);
      const Index first = cells.first[static_cast<std::size_t>(kind())];
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, block.size(), 1024), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          std::uint8_t flags = 0;
          const SolidTets tets = kind_solid_tets<kind()>(block[i], static_cast<Index>(i), first + static_cast<Index>(i),
                                                         topo, tp, static_cast<Index>(cells.mesh->wedges.size()));
          for (std::size_t t = 0; t < static_cast<std::size_t>(tets.n); ++t) {
            const int s = orient(tp.points, tets.tets[t]);
            if (s < 0) flags |= kTetNegative;
            if (s == 0) flags |= kTetFlat;
          }
          const auto& cell = block[i];
          for (std::size_t c = 0; c < Table::corner_frames.size(); ++c) {
            const auto& f = Table::corner_frames[c];
            const int s = orient(at(tp.points, cell[c]), at(tp.points, cell[static_cast<std::size_t>(f[0])]),
                                 at(tp.points, cell[static_cast<std::size_t>(f[1])]),
                                 at(tp.points, cell[static_cast<std::size_t>(f[2])]));
            if (s < 0) flags |= kCornerNegative;
            if (s == 0) flags |= kCornerFlat;
          }
          out[static_cast<std::size_t>(first) + i] = flags;
        }
      });
    }
  });
  return out;
}

// ---- Stage E ----------------------------------------------------------------

namespace {

// Non-degenerate triangles in groups (a face's triangles are consecutive:
// the groups of the box search). Their boxes are made where they are
// compared, from the points the tests read anyway: no array of them (105
// MB of fresh pages for a 1M-quad surface's 2.2 M triangles).
struct TriangleGroups {
  const std::vector<Vec3>* points = nullptr;
  std::vector<Triangle> triangles;
  std::vector<Index> group;
  std::vector<Index> first{0};  // one entry more than there are groups
  explicit TriangleGroups(const std::vector<Vec3>& p) : points(&p) {}
  void add(const Triangle& t) {
    const std::vector<Vec3>& p = *points;
    if (CGAL::collinear(point(at(p, t[0])), point(at(p, t[1])), point(at(p, t[2])))) return;
    triangles.push_back(t);
    group.push_back(static_cast<Index>(first.size() - 1));
  }
  void close_group() { first.push_back(static_cast<Index>(triangles.size())); }
  // Room for this many triangles and groups at once: the arrays are not
  // grown by doubling (each doubling a copy into freshly zeroed pages).
  void reserve(std::size_t num_triangles, std::size_t num_groups) {
    triangles.reserve(num_triangles);
    group.reserve(num_triangles);
    first.reserve(num_groups + 1);
  }
  std::size_t num_groups() const { return first.size() - 1; }
  Box3 box(Index i) const { return box_of(*points, triangles[static_cast<std::size_t>(i)].data(), 3); }
  // The box around group g's triangles' boxes; nullopt when it has none.
  std::optional<Box3> bounds(std::size_t g) const {
    if (first[g] == first[g + 1]) return std::nullopt;
    Box3 out;
    for (Index i = first[g]; i < first[g + 1]; ++i) {
      const Box3 b = box(i);
      out.add(b.lo);
      out.add(b.hi);
    }
    return out;
  }
};

// The candidate pairs of triangles (boxes that touch, within the budget):
// how many, and those that meet improperly (sorted, {low, high}). TBB,
// deterministic.
struct TriangleHits {
  std::vector<std::array<Index, 2>> hits;
  std::int64_t num_candidates = 0;
  BoxPairs budget;  // its pairs are cleared
};

// The same, the candidates listed by grouped_box_self_pairs and then tested.
TriangleHits test_listed_triangle_pairs(const std::vector<Vec3>& p, const TriangleGroups& g, std::int64_t max_pairs) {
  TriangleHits out;
  std::vector<Box3> boxes(g.triangles.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) boxes[i] = g.box(static_cast<Index>(i));
  out.budget = grouped_box_self_pairs(boxes, g.first, max_pairs);
  const std::vector<std::array<Index, 2>> candidates = std::move(out.budget.pairs);
  out.budget.pairs = {};
  out.num_candidates = static_cast<std::int64_t>(candidates.size());
  std::vector<char> hit(candidates.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        hit[i] = triangles_meet_improperly(p, g.triangles[static_cast<std::size_t>(candidates[i][0])],
                                                           g.triangles[static_cast<std::size_t>(candidates[i][1])]);
                    });
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (hit[i]) out.hits.push_back(candidates[i]);
  return out;
}

// Group pairs the search may hand over per group (and at least) before
// test_triangle_groups leaves the work to test_listed_triangle_pairs: a
// surface's face meets 8 to 20 others; a tangle whose boxes all overlap is
// left to the budgeted search, which stops at its budget.
constexpr std::int64_t kGroupPairsPerGroup = 32;
constexpr std::int64_t kMinGroupPairs = 1'000'000;
// Work items (a group's own pairs, or a pair of groups) per parallel chunk.
constexpr std::size_t kItemsPerChunk = 8192;

// The same hits and count as test_listed_triangle_pairs without a list of
// every candidate: the pairs of groups whose bounds meet are found first,
// then, over fixed chunks of them in parallel, their triangles' boxes are
// compared and the pairs that touch tested at once. When the candidates
// could exceed the budget, the chunks keep a running total: once it is past
// the budget nothing more is tested (the run is over budget, its hits are
// dropped), once it reaches kBudgetCountFactor x the budget nothing more is
// counted (the count is then "at least" that). A chunk stops only at a
// total the whole count passes too, so the outcome does not depend on the
// order the chunks run in.
TriangleHits test_triangle_groups(const std::vector<Vec3>& p, const TriangleGroups& g, std::int64_t max_pairs) {
  const std::size_t num_groups = g.num_groups();
  const auto group_pairs =
      group_bound_pairs(num_groups, [&](std::size_t k) { return g.bounds(k); },
                        kMinGroupPairs + kGroupPairsPerGroup * static_cast<std::int64_t>(num_groups));
  if (!group_pairs) return test_listed_triangle_pairs(p, g, max_pairs);
  const auto size = [&](Index group) { return std::int64_t{g.first[static_cast<std::size_t>(group) + 1] - g.first[static_cast<std::size_t>(group)]}; };
  // Item k: group k's own pairs for k < num_groups, else group pair k - num_groups.
  const std::size_t num_items = num_groups + group_pairs->size();
  const auto for_each_candidate = [&](std::size_t k, auto&& f) {
    if (k < num_groups) {
      for (Index i = g.first[k]; i < g.first[k + 1]; ++i) {
        const Box3 box = g.box(i);
        for (Index j = i + 1; j < g.first[k + 1]; ++j)
          if (boxes_overlap_closed(box, g.box(j))) f(i, j);
      }
      return;
    }
    const auto [a, b] = (*group_pairs)[k - num_groups];  // a < b: a's triangles come first
    for (Index i = g.first[static_cast<std::size_t>(a)]; i < g.first[static_cast<std::size_t>(a) + 1]; ++i) {
      const Box3 box = g.box(i);
      for (Index j = g.first[static_cast<std::size_t>(b)]; j < g.first[static_cast<std::size_t>(b) + 1]; ++j)
        if (boxes_overlap_closed(box, g.box(j))) f(i, j);
    }
  };
  const std::size_t num_chunks = (num_items + kItemsPerChunk - 1) / kItemsPerChunk;
  const auto chunk_range = [&](std::size_t c) {
    return std::pair{c * kItemsPerChunk, std::min(num_items, (c + 1) * kItemsPerChunk)};
  };
  TriangleHits out;
  std::int64_t most = 0;  // the candidates there can be
  for (std::size_t k = 0; k < num_groups; ++k) most += size(static_cast<Index>(k)) * (size(static_cast<Index>(k)) - 1) / 2;
  for (const auto& [a, b] : *group_pairs) most += size(a) * size(b);
  const bool may_exceed = most > max_pairs;
  const std::int64_t count_cap = kBudgetCountFactor * max_pairs;
  std::atomic<std::int64_t> running{0};
  std::vector<std::int64_t> counts(num_chunks, 0);
  std::vector<std::vector<std::array<Index, 2>>> hits(num_chunks);
  tbb::parallel_for(std::size_t{0}, num_chunks, [&](std::size_t c) {
    const auto [begin, end] = chunk_range(c);
    std::int64_t count = 0;
    bool is_testing = true;
    for (std::size_t k = begin; k < end; ++k) {
      std::int64_t item = 0;
      for_each_candidate(k, [&](Index i, Index j) {
        ++item;
        if (is_testing && triangles_meet_improperly(p, g.triangles[static_cast<std::size_t>(i)],
                                                    g.triangles[static_cast<std::size_t>(j)]))
          hits[c].push_back({i, j});
      });
      count += item;
      if (may_exceed) {
        const std::int64_t total = running.fetch_add(item, std::memory_order_relaxed) + item;
        is_testing = total <= max_pairs;
        if (total >= count_cap) break;
      }
    }
    counts[c] = count;
  });
  std::int64_t total = 0;
  for (std::int64_t n : counts) total += n;
  if (total > max_pairs) {
    // As the budgeted search says it: counted up to kBudgetCountFactor x the budget.
    out.budget.is_complete = false;
    out.budget.num_found = std::min(total, count_cap);
    out.budget.is_count_exact = total < count_cap;
    return out;
  }
  for (std::size_t c = 0; c < num_chunks; ++c) {
    out.num_candidates += counts[c];
    out.hits.insert(out.hits.end(), hits[c].begin(), hits[c].end());
  }
  std::sort(out.hits.begin(), out.hits.end());
  out.budget.num_found = out.num_candidates;
  return out;
}

// x in the closed triangle (t0, t1, t2) of normal n, x assumed in its plane:
// each edge function at least -1e-9 |n|^2 (double arithmetic).
bool near_inside(const Vec3& x, const Vec3& t0, const Vec3& t1, const Vec3& t2, const Vec3& n) {
  const double slack = -1e-9 * squared_norm(n);
  return dot(n, cross(t1 - t0, x - t0)) >= slack && dot(n, cross(t2 - t1, x - t1)) >= slack &&
         dot(n, cross(t0 - t2, x - t2)) >= slack;
}

// Where the edges of a cross the plane of b inside b (a's corners in b's
// plane count when inside b), appended to out. Double arithmetic.
void crossings(const std::vector<Vec3>& p, const Triangle& a, const Triangle& b, std::vector<Vec3>& out) {
  const Vec3 &b0 = at(p, b[0]), &b1 = at(p, b[1]), &b2 = at(p, b[2]);
  const Vec3 n = cross(b1 - b0, b2 - b0);
  if (squared_norm(n) == 0.0) return;
  for (std::size_t e = 0; e < 3; ++e) {
    const Vec3 &u = at(p, a[e]), &v = at(p, a[(e + 1) % 3]);
    const double du = dot(n, u - b0), dv = dot(n, v - b0);
    if (du == 0.0 && near_inside(u, b0, b1, b2, n)) out.push_back(u);
    if (du == dv || (du < 0.0) == (dv < 0.0) || du == 0.0 || dv == 0.0) continue;
    const Vec3 x = u + (du / (du - dv)) * (v - u);
    if (near_inside(x, b0, b1, b2, n)) out.push_back(x);
  }
}

// A point where two triangles that meet improperly meet, for an arrow: the
// mean of the crossings of each one's edges with the other (and of corners
// of one lying in the other); the mean of their centroids when double
// arithmetic finds none (coplanar triangles crossing edge on edge).
Vec3 meeting_point(const std::vector<Vec3>& p, const Triangle& a, const Triangle& b) {
  std::vector<Vec3> found;
  crossings(p, a, b, found);
  crossings(p, b, a, found);
  Vec3 sum{};
  if (found.empty()) {
    for (const Triangle* t : {&a, &b})
      for (Index i : *t) found.push_back(at(p, i));
  }
  for (const Vec3& x : found) sum = sum + x;
  return sum / static_cast<double>(found.size());
}

}  // namespace

FacePairs intersecting_face_pairs(const TetPoints& tp, const std::vector<BoundaryFace>& quads, std::int64_t max_pairs) {
  const auto& p = tp.points;
  TriangleGroups groups(p);
  std::size_t num_fan_triangles = 0;
  for (const BoundaryFace& face : quads) num_fan_triangles += static_cast<std::size_t>(face.num_fan_triangles());
  groups.reserve(num_fan_triangles, quads.size());
  for (const BoundaryFace& face : quads) {
    for (int e = 0; e < face.num_fan_triangles(); ++e) groups.add(fan_triangle(face, e));
    groups.close_group();
  }
  const TriangleHits hits = test_triangle_groups(p, groups, max_pairs);
  FacePairs result;
  result.budget = hits.budget;
  std::vector<std::array<Index, 2>>& pairs = result.pairs;
  for (const auto& [i, j] : hits.hits) {
    const Index a = groups.group[static_cast<std::size_t>(i)], b = groups.group[static_cast<std::size_t>(j)];
    pairs.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return result;
}

SurfaceFacePairs intersecting_surface_faces(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                                            const std::vector<Index>& first, std::int64_t max_pairs) {
  TriangleGroups groups(points);
  groups.reserve(triangles.size(), first.size());
  for (std::size_t f = 0; f + 1 < first.size(); ++f) {
    for (Index t = first[f]; t < first[f + 1]; ++t) groups.add(triangles[static_cast<std::size_t>(t)]);
    groups.close_group();
  }
  const TriangleHits hits = test_triangle_groups(points, groups, max_pairs);
  SurfaceFacePairs result;
  result.budget = hits.budget;
  result.num_tested = hits.num_candidates;
  // (face pair, triangle pair that meets): the point of each face pair
  // comes from its first meeting triangles.
  std::vector<std::pair<std::array<Index, 2>, std::array<Index, 2>>> met;
  for (const auto& [i, j] : hits.hits) {
    const Index a = groups.group[static_cast<std::size_t>(i)], b = groups.group[static_cast<std::size_t>(j)];
    met.push_back({{std::min(a, b), std::max(a, b)}, {i, j}});
  }
  std::sort(met.begin(), met.end());
  for (std::size_t i = 0; i < met.size(); ++i) {
    if (i > 0 && met[i].first == met[i - 1].first) continue;
    const auto& c = met[i].second;
    result.pairs.push_back(met[i].first);
    result.positions.push_back(meeting_point(points, groups.triangles[static_cast<std::size_t>(c[0])],
                                             groups.triangles[static_cast<std::size_t>(c[1])]));
  }
  return result;
}

// ---- Stage F ----------------------------------------------------------------

// A point taken exactly as the mean of 1 or 3 input points: a quad's face
// centre (itself a double point), a triangle's centroid (not one).
struct MeanPoint {
  std::array<const Vec3*, 3> of{};
  int n = 1;
};

template <class Number>
Number det_of_means(const std::array<MeanPoint, 4>& q) {
  std::array<std::array<Number, 3>, 4> x;
  for (std::size_t i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      Number sum((*q[i].of[0])[k]);
      for (int m = 1; m < q[i].n; ++m) sum = sum + Number((*q[i].of[static_cast<std::size_t>(m)])[k]);
      x[i][static_cast<std::size_t>(k)] = q[i].n == 1 ? sum : sum / Number(q[i].n);
    }
  Number d[3][3];
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t k = 0; k < 3; ++k) d[r][k] = x[r + 1][k] - x[0][k];
  return d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) - d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0]) +
         d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
}

// orient() of four mean points, exact: CGAL's predicate when all are
// input points, else intervals, then rationals when the interval holds 0.
int orient(const MeanPoint& a, const MeanPoint& b, const MeanPoint& c, const MeanPoint& d) {
  if (a.n == 1 && b.n == 1 && c.n == 1 && d.n == 1) return orient(*a.of[0], *b.of[0], *c.of[0], *d.of[0]);
  const std::array<MeanPoint, 4> q{a, b, c, d};
  {
    // The rounding mode set upward once for the whole determinant, and the
    // unprotected intervals under it: the very intervals the protected ones
    // give (each of their operations sets and restores the mode, which cost
    // most of stage F on a tet mesh's boundary triangles).
    const CGAL::Protect_FPU_rounding<true> upward;
    const CGAL::Interval_nt<false> approx = det_of_means<CGAL::Interval_nt<false>>(q);
    if (approx.inf() > 0) return 1;
    if (approx.sup() < 0) return -1;
  }
  return static_cast<int>(CGAL::sign(det_of_means<CGAL::Exact_rational>(q)));
}

MeanPoint mean_of(const Vec3& x) { return {{&x, nullptr, nullptr}, 1}; }

std::optional<int> winding_behind_face(const TetPoints& tp, const std::vector<BoundaryFace>& quads, Index q,
                                       const Box3& bounds) {
  const auto& p = tp.points;
  const BoundaryFace& quad = quads[static_cast<std::size_t>(q)];
  const bool is_quad = quad.centre != kNoIndex;
  const int size = quad.size();
  const Index ch = tp.cell_base + quad.cell;
  const auto pt = [&](Index i) { return mean_of(at(p, i)); };
  const Vec3 &c0 = at(p, quad.corners[0]), &c1 = at(p, quad.corners[1]), &c2 = at(p, quad.corners[2]);
  // The start: the face centre, on every triangle of the fan; a triangle's
  // centroid, exactly (its double value is only used to aim the ray).
  const MeanPoint start = is_quad ? pt(quad.centre) : MeanPoint{{&c0, &c1, &c2}, 3};
  const Vec3 start_near = is_quad ? at(p, quad.centre) : (c0 + c1 + c2) / 3.0;
  Box3 start_box;
  if (is_quad) {
    start_box.add(start_near);
  } else {
    for (const Vec3* c : start.of) start_box.add(*c);
  }
  double extent = 1.0;
  for (std::size_t a = 0; a < 3; ++a)
    extent = std::max({extent, bounds.hi[a] - bounds.lo[a], std::abs(bounds.lo[a]), std::abs(bounds.hi[a])});
  // Barycentric weights of the ray's aim on a triangle (p_j, p_i, c_h) of a
  // tet of the face, tried in turn on each of its edges until a ray meets
  // no edge, vertex or plane degenerately.
  static constexpr double kWeights[][3] = {{1, 1, 1}, {1, 1, 2}, {2, 1, 1}, {1, 2, 1}, {3, 2, 1}, {1, 3, 2}, {2, 1, 3}};
  const int attempts = size * static_cast<int>(std::size(kWeights));
  for (int attempt = 0; attempt < attempts; ++attempt) {
    const int e = attempt % size;
    const double* w = kWeights[attempt / size];
    const Index a = quad.corners[static_cast<std::size_t>((e + 1) % size)], b = quad.corners[static_cast<std::size_t>(e)];
    // The tet whose interior the ray must enter: (p_j, p_i, c_f, c_h) of a
    // quad, the triangle's (p1, p0, p2, c_h).
    const int sigma = is_quad ? orient(pt(a), pt(b), start, pt(ch)) : orient(c1, c0, c2, at(p, ch));
    if (sigma == 0) return std::nullopt;
    const Vec3 aim = (at(p, a) * w[0] + at(p, b) * w[1] + at(p, ch) * w[2]) / (w[0] + w[1] + w[2]);
    const Vec3 d = aim - start_near;
    const double length = norm(d);
    if (!(length > 0.0)) continue;
    const Vec3 end = start_near + d * (4.0 * extent / length);
    bool outside = false;
    for (std::size_t i = 0; i < 3; ++i)
      outside = outside || end[static_cast<int>(i)] < bounds.lo[i] || end[static_cast<int>(i)] > bounds.hi[i];
    if (!outside || !is_finite(end)) continue;
    // The ray must leave the start into the tet, i.e. into the cell side,
    // and must not lie in the plane of any triangle of its own fan.
    if (is_quad ? (orient(pt(a), pt(b), start, mean_of(end)) != sigma ||
                   orient(mean_of(end), pt(b), start, pt(ch)) != sigma ||
                   orient(pt(a), mean_of(end), start, pt(ch)) != sigma)
                : orient(c1, c0, c2, end) != sigma)
      continue;
    bool degenerate = false;
    for (int k = 0; k < quad.num_fan_triangles() && !degenerate; ++k) {
      const Triangle t = fan_triangle(quad, k);
      degenerate = orient(at(p, t[0]), at(p, t[1]), at(p, t[2]), end) == 0;
    }
    if (degenerate) continue;

    Box3 ray_box = start_box;
    ray_box.add(end);
    int winding = 0;
    for (std::size_t other = 0; other < quads.size() && !degenerate; ++other) {
      if (static_cast<Index>(other) == q) continue;
      for (int k = 0; k < quads[other].num_fan_triangles() && !degenerate; ++k) {
        const Triangle t = fan_triangle(quads[other], k);
        if (!boxes_overlap_closed(box_of(p, t.data(), 3), ray_box)) continue;
        const Vec3 &t0 = at(p, t[0]), &t1 = at(p, t[1]), &t2 = at(p, t[2]);
        const MeanPoint m0 = mean_of(t0), m1 = mean_of(t1), m2 = mean_of(t2), me = mean_of(end);
        const int s_start = orient(m0, m1, m2, start), s_end = orient(t0, t1, t2, end);
        if (s_start == 0 && s_end == 0) {
          degenerate = true;  // the ray lies in the triangle's plane
          break;
        }
        // Touching the plane at an end is no crossing: the start lies on no
        // other fan (stage E) and the end is outside the bounds.
        if (s_start == 0 || s_end == 0 || s_start == s_end) continue;
        const int e1 = orient(start, me, m0, m1), e2 = orient(start, me, m1, m2), e3 = orient(start, me, m2, m0);
        if ((e1 > 0 && e2 > 0 && e3 > 0) || (e1 < 0 && e2 < 0 && e3 < 0)) {
          // Leaving the triangle's back (cell) side towards infinity: the
          // winding number drops by one on the way out.
          winding += s_start < 0 ? 1 : -1;
        } else if ((e1 >= 0 && e2 >= 0 && e3 >= 0) || (e1 <= 0 && e2 <= 0 && e3 <= 0)) {
          degenerate = true;  // through an edge or a vertex
        }
      }
    }
    if (!degenerate) return winding;
  }
  return std::nullopt;
}

// ---- Stage G ----------------------------------------------------------------

std::vector<CellPairTest> test_cell_pairs(const VolumeCells& cells, const VertexCells& vertex_cells,
                                          const Topology& topo, const TetPoints& tp,
                                          const std::vector<std::array<Index, 2>>& pairs,
                                          const std::vector<char>& flagged, const std::vector<char>& folded) {
  std::vector<CellPairTest> results(pairs.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        const auto [a, b] = pairs[i];
                        const bool test_interiors =
                            flagged[static_cast<std::size_t>(a)] != 0 || flagged[static_cast<std::size_t>(b)] != 0;
                        results[i] = test_cell_pair(cells, vertex_cells, topo, tp, a, b, test_interiors, folded);
                      }
                    });
  return results;
}

}  // namespace hq::detail
