// The chart-layout translation unit (CGAL Surface_mesh_parameterization's
// LSCM, then optionally our ARAP iterations on Eigen): heavy to compile, so
// nothing else lives here.

#include "hqview/uv/uv_lscm.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <tuple>

namespace hq {
namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;

// As-rigid-as-possible refinement of a disk's layout (the local/global
// iterations of Liu et al., "A local/global approach to mesh
// parameterization", 2008): each triangle's best rotation onto its 3D shape
// (local), then the cotangent-weighted least-squares positions that follow
// those rotations (global: one sparse Cholesky factorisation, vertex 0
// pinned, two back-substitutions an iteration). Starts from `uv` (the LSCM
// layout) and replaces it; false when the system cannot be factorised.
// `iterates`, when given, gets the layout after each iteration but the last.
bool arap_refine(const std::vector<Vec3>& points, const std::vector<std::vector<std::size_t>>& polygons,
                 std::vector<std::array<double, 2>>& uv, int iterations,
                 std::vector<std::vector<std::array<double, 2>>>* iterates = nullptr) {
  const std::size_t n = points.size(), nf = polygons.size();
  // Per triangle: its corners' 2D isometric coordinates and the cotangent
  // of each corner's angle (the weight of the opposite edge).
  std::vector<std::array<std::array<double, 2>, 3>> flat(nf);
  std::vector<std::array<double, 3>> cot(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const Vec3 &a = points[polygons[f][0]], &b = points[polygons[f][1]], &c = points[polygons[f][2]];
    const Vec3 e1 = b - a, e2 = c - a;
    const double l1 = norm(e1), twice_area = norm(cross(e1, e2));
    if (!(l1 > 0.0) || !(twice_area > 0.0)) {
      cot[f] = {0.0, 0.0, 0.0};
      flat[f] = {};
      continue;
    }
    flat[f] = {std::array<double, 2>{0.0, 0.0}, {l1, 0.0}, {dot(e2, e1) / l1, twice_area / l1}};
    const Vec3* p[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = *p[(k + 1) % 3] - *p[k], v = *p[(k + 2) % 3] - *p[k];
      cot[f][static_cast<std::size_t>(k)] = std::clamp(dot(u, v) / twice_area, -1e3, 1e3);
    }
  }
  // The Laplacian of the cotangent weights, vertex 0 left out (pinned).
  using SparseMatrix = Eigen::SparseMatrix<double>;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(12 * nf);
  const auto add = [&](std::size_t i, std::size_t j, double w) {
    if (i == 0 || j == 0) return;
    entries.emplace_back(static_cast<int>(i - 1), static_cast<int>(j - 1), w);
  };
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = polygons[f][static_cast<std::size_t>((k + 1) % 3)],
                        j = polygons[f][static_cast<std::size_t>((k + 2) % 3)];
      const double w = cot[f][static_cast<std::size_t>(k)];
      add(i, i, w), add(j, j, w), add(i, j, -w), add(j, i, -w);
    }
  if (n < 3) return false;
  SparseMatrix laplacian(static_cast<int>(n - 1), static_cast<int>(n - 1));
  laplacian.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<SparseMatrix> solver(laplacian);
  if (solver.info() != Eigen::Success) return false;
  const std::array<double, 2> pinned = uv[0];
  std::vector<std::array<double, 4>> rotation(nf);  // row-major 2x2
  Eigen::VectorXd bu(static_cast<Eigen::Index>(n - 1)), bv(static_cast<Eigen::Index>(n - 1));
  for (int iteration = 0; iteration < iterations; ++iteration) {
    if (iterates != nullptr && iteration > 0) iterates->push_back(uv);
    // Local: the rotation closest to the cotangent-weighted covariance of
    // each triangle's layout edges against its flat edges.
    for (std::size_t f = 0; f < nf; ++f) {
      double s00 = 0, s01 = 0, s10 = 0, s11 = 0;
      for (int k = 0; k < 3; ++k) {
        const std::size_t a = static_cast<std::size_t>((k + 1) % 3), b = static_cast<std::size_t>((k + 2) % 3);
        const double w = cot[f][static_cast<std::size_t>(k)];
        const double ux = uv[polygons[f][a]][0] - uv[polygons[f][b]][0], uy = uv[polygons[f][a]][1] - uv[polygons[f][b]][1];
        const double xx = flat[f][a][0] - flat[f][b][0], xy = flat[f][a][1] - flat[f][b][1];
        s00 += w * ux * xx, s01 += w * ux * xy, s10 += w * uy * xx, s11 += w * uy * xy;
      }
      const double angle = std::atan2(s10 - s01, s00 + s11);
      const double c = std::cos(angle), sn = std::sin(angle);
      rotation[f] = {c, -sn, sn, c};
    }
    // Global: L u = sum over edges of w R (x_i - x_j), with vertex 0 moved
    // to the right-hand side.
    bu.setZero(), bv.setZero();
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const std::size_t a = static_cast<std::size_t>((k + 1) % 3), b = static_cast<std::size_t>((k + 2) % 3);
        const std::size_t i = polygons[f][a], j = polygons[f][b];
        const double w = cot[f][static_cast<std::size_t>(k)];
        const double xx = flat[f][a][0] - flat[f][b][0], xy = flat[f][a][1] - flat[f][b][1];
        const auto& r = rotation[f];
        const double rx = r[0] * xx + r[1] * xy, ry = r[2] * xx + r[3] * xy;
        for (const auto& [p, q, sign] : {std::tuple{i, j, 1.0}, std::tuple{j, i, -1.0}}) {
          if (p == 0) continue;
          bu[static_cast<Eigen::Index>(p - 1)] += sign * w * rx;
          bv[static_cast<Eigen::Index>(p - 1)] += sign * w * ry;
          if (q == 0) {  // the pinned neighbour's term of L u
            bu[static_cast<Eigen::Index>(p - 1)] += w * pinned[0];
            bv[static_cast<Eigen::Index>(p - 1)] += w * pinned[1];
          }
        }
      }
    const Eigen::VectorXd u = solver.solve(bu), v = solver.solve(bv);
    if (solver.info() != Eigen::Success) return false;
    for (std::size_t i = 1; i < n; ++i) {
      uv[i] = {u[static_cast<Eigen::Index>(i - 1)], v[static_cast<Eigen::Index>(i - 1)]};
      if (!std::isfinite(uv[i][0]) || !std::isfinite(uv[i][1])) return false;
    }
  }
  return true;
}

// Whether every face of the mesh is reached from the first across edges.
bool is_connected(const SurfaceMesh& mesh) {
  if (mesh.number_of_faces() == 0) return true;
  std::vector<char> seen(mesh.number_of_faces(), 0);
  std::vector<SurfaceMesh::Face_index> stack{*mesh.faces().begin()};
  seen[stack.back().idx()] = 1;
  std::size_t reached = 1;
  while (!stack.empty()) {
    const SurfaceMesh::Face_index f = stack.back();
    stack.pop_back();
    for (SurfaceMesh::Halfedge_index h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh)) {
      const SurfaceMesh::Face_index g = mesh.face(mesh.opposite(h));
      if (g == SurfaceMesh::null_face() || seen[g.idx()]) continue;
      seen[g.idx()] = 1;
      ++reached;
      stack.push_back(g);
    }
  }
  return reached == mesh.number_of_faces();
}

}  // namespace

bool lscm_chart_layout(const TriSurface& surface, std::span<const Index> chart, std::vector<Uv>& uvs,
                       std::span<const std::uint64_t> seams, ChartLayout method,
                       const std::function<bool(std::span<const Uv>)>& good_enough) {
  if (chart.size() < 2) return false;
  // The chart's own vertices: the corners around a surface vertex are one
  // vertex where their triangles are glued, across an edge that two chart
  // triangles share and that is not a seam. So a seam opens the chart, and a
  // vertex where two fans only touch becomes two.
  const std::size_t nc = 3 * chart.size();
  auto key = [&](std::size_t corner, int step) {
    const auto& tri = surface.triangles[chart[corner / 3]];
    const auto a = static_cast<std::uint32_t>(tri[corner % 3]);
    const auto b = static_cast<std::uint32_t>(tri[(corner % 3 + static_cast<std::size_t>(step)) % 3]);
    return static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> edges(nc);  // edge key, corner it starts at
  for (std::size_t c = 0; c < nc; ++c) edges[c] = {key(c, 1), c};
  std::sort(edges.begin(), edges.end());
  std::vector<std::size_t> parent(nc);
  for (std::size_t c = 0; c < nc; ++c) parent[c] = c;
  auto root = [&](std::size_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  auto glue = [&](std::size_t a, std::size_t b) {
    a = root(a), b = root(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  for (std::size_t i = 0; i < nc;) {
    std::size_t j = i;
    while (j < nc && edges[j].first == edges[i].first) ++j;
    if (j - i == 2 && !std::binary_search(seams.begin(), seams.end(), edges[i].first)) {
      // Corners c (start) and c+1 (end) of one edge, against the other's.
      const std::size_t c = edges[i].second, d = edges[i + 1].second;
      const std::size_t c1 = c / 3 * 3 + (c % 3 + 1) % 3, d1 = d / 3 * 3 + (d % 3 + 1) % 3;
      const auto& tc = surface.triangles[chart[c / 3]];
      const auto& td = surface.triangles[chart[d / 3]];
      if (tc[c % 3] == td[d % 3]) glue(c, d), glue(c1, d1);
      else glue(c, d1), glue(c1, d);
    }
    i = j;
  }
  std::vector<std::size_t> vertex_of(nc);
  std::vector<Index> ids;  // surface vertex of each chart vertex
  {
    std::vector<std::size_t> id_of_root(nc, static_cast<std::size_t>(-1));
    for (std::size_t c = 0; c < nc; ++c) {
      const std::size_t r = root(c);
      if (id_of_root[r] == static_cast<std::size_t>(-1)) {
        id_of_root[r] = ids.size();
        ids.push_back(surface.triangles[chart[c / 3]][c % 3]);
      }
      vertex_of[c] = id_of_root[r];
    }
  }
  std::vector<Kernel::Point_3> points;
  points.reserve(ids.size());
  for (Index v : ids) points.emplace_back(surface.points[v].x, surface.points[v].y, surface.points[v].z);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(chart.size());
  double area_3d = 0.0;
  for (std::size_t i = 0; i < chart.size(); ++i) {
    const auto& tri = surface.triangles[chart[i]];
    const std::size_t c = 3 * i;
    polygons.push_back({vertex_of[c], vertex_of[c + 1], vertex_of[c + 2]});
    area_3d += 0.5 * norm(cross(surface.points[tri[1]] - surface.points[tri[0]],
                                surface.points[tri[2]] - surface.points[tri[0]]));
  }
  // The mesh as PMP::polygon_soup_to_polygon_mesh builds it (the same
  // calls in the same order, so the same indices and the same layout), but
  // without PMP::is_polygon_soup_a_polygon_mesh's std::set of every edge
  // (as costly as the LSCM solve): Euler::add_face refuses a face that
  // repeats a vertex or uses an edge side already taken (an edge of three
  // triangles, or two of the same orientation), and a vertex whose faces
  // form two fans (which add_face may create) is found by counting the faces
  // around it against its corners.
  SurfaceMesh mesh;
  mesh.reserve(static_cast<SurfaceMesh::size_type>(points.size()), static_cast<SurfaceMesh::size_type>(2 * polygons.size()),
               static_cast<SurfaceMesh::size_type>(polygons.size()));
  for (const Kernel::Point_3& p : points) mesh.add_vertex(p);
  {
    std::vector<SurfaceMesh::Vertex_index> face(3);
    for (const auto& polygon : polygons) {
      for (std::size_t k = 0; k < 3; ++k) face[k] = SurfaceMesh::Vertex_index(static_cast<SurfaceMesh::size_type>(polygon[k]));
      if (CGAL::Euler::add_face(face, mesh) == SurfaceMesh::null_face()) return false;
    }
    std::vector<std::size_t> corners_at(ids.size(), 0);
    for (std::size_t c = 0; c < nc; ++c) ++corners_at[vertex_of[c]];
    for (SurfaceMesh::Vertex_index v : mesh.vertices()) {
      std::size_t faces = 0;
      for (SurfaceMesh::Halfedge_index h : CGAL::halfedges_around_target(mesh.halfedge(v), mesh))
        faces += mesh.is_border(h) ? 0 : 1;
      if (faces != corners_at[v.idx()]) return false;
    }
  }
  if (mesh.number_of_faces() != chart.size() || mesh.number_of_vertices() != ids.size()) return false;

  // A disk: one border cycle and V - E + F = 1.
  const long euler = static_cast<long>(mesh.number_of_vertices()) - static_cast<long>(mesh.number_of_edges()) +
                     static_cast<long>(mesh.number_of_faces());
  if (euler != 1) return false;
  SurfaceMesh::Halfedge_index border;
  int cycles = 0;
  std::vector<char> seen(mesh.number_of_halfedges(), 0);
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_border(h) || seen[h.idx()]) continue;
    ++cycles;
    border = h;
    for (auto g = h; !seen[g.idx()]; g = mesh.next(g)) seen[g.idx()] = 1;
  }
  if (cycles != 1) return false;

  auto uv_map = mesh.add_property_map<SurfaceMesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  // SMP::parameterize numbers the vertices of the border's component (by a
  // search that keeps a std::set of faces), which for a connected chart is
  // every vertex in index order: a connected chart (checked by a walk over
  // face neighbours) is handed that numbering directly, the same system.
  if (is_connected(mesh)) {
    auto index_map = mesh.add_property_map<SurfaceMesh::Vertex_index, int>("v:lscm_index", 0).first;
    for (SurfaceMesh::Vertex_index v : mesh.vertices()) index_map[v] = static_cast<int>(v.idx());
    auto parameterized = mesh.add_property_map<SurfaceMesh::Vertex_index, bool>("v:lscm_parameterized", false).first;
    if (SMP::LSCM_parameterizer_3<SurfaceMesh>().parameterize(mesh, border, uv_map, index_map, parameterized) != SMP::OK)
      return false;
  } else if (SMP::parameterize(mesh, SMP::LSCM_parameterizer_3<SurfaceMesh>(), border, uv_map) != SMP::OK) {
    return false;
  }

  std::vector<std::array<double, 2>> vertex_uv(ids.size());
  for (std::size_t v = 0; v < ids.size(); ++v) {
    const Kernel::Point_2& p = uv_map[SurfaceMesh::Vertex_index(static_cast<SurfaceMesh::size_type>(v))];
    vertex_uv[v] = {p.x(), p.y()};
  }
  // Corners of the chart triangles, scaled to the chart's 3D area.
  const auto corners = [&](std::vector<Uv>& out) {
    out.assign(3 * chart.size(), Uv{});
    double area_uv = 0.0;
    for (std::size_t i = 0; i < chart.size(); ++i) {
      for (int k = 0; k < 3; ++k)
        out[3 * i + k] = {vertex_uv[vertex_of[3 * i + k]][0], vertex_uv[vertex_of[3 * i + k]][1]};
      const Uv &a = out[3 * i], &b = out[3 * i + 1], &c = out[3 * i + 2];
      area_uv += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    if (!(area_uv > 0.0) || !std::isfinite(area_uv)) return false;
    const double scale = std::sqrt(area_3d / area_uv);
    for (Uv& p : out) p = {p[0] * scale, p[1] * scale};
    return true;
  };
  std::vector<Uv> out;
  if (method == ChartLayout::lscm) {
    if (!corners(out)) return false;
    uvs = std::move(out);
    return true;
  }
  // ARAP, from the LSCM layout, unless good_enough keeps that.
  if (good_enough && corners(out) && good_enough(out)) {
    uvs = std::move(out);
    return true;
  }
  std::vector<Vec3> vertex_points(ids.size());
  for (std::size_t v = 0; v < ids.size(); ++v) vertex_points[v] = surface.points[ids[v]];
  std::vector<std::vector<std::array<double, 2>>> iterates;
  if (!arap_refine(vertex_points, polygons, vertex_uv, kArapIterations, good_enough ? &iterates : nullptr) ||
      !corners(out))
    return false;
  // ARAP evens the areas out from LSCM's and may fold on the way (a
  // finger's tip turned over): when its layout is not good enough, the
  // latest iterate that is wins (it has the least area distortion of those
  // that pass).
  if (good_enough && !good_enough(out)) {
    std::vector<Uv> earlier;
    for (auto it = iterates.rbegin(); it != iterates.rend(); ++it) {
      vertex_uv = std::move(*it);
      if (corners(earlier) && good_enough(earlier)) {
        uvs = std::move(earlier);
        return true;
      }
    }
  }
  uvs = std::move(out);
  return true;
}

}  // namespace hq
