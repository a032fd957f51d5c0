// The LSCM translation unit (CGAL Surface_mesh_parameterization and Eigen):
// heavy to compile, so nothing else lives here.

#include "hqview/uv/uv_lscm.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace hq {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
namespace SMP = CGAL::Surface_mesh_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

}  // namespace

bool lscm_chart_layout(const TriSurface& surface, std::span<const Index> chart, std::vector<Uv>& uvs,
                       std::span<const std::uint64_t> seams) {
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
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return false;
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (mesh.number_of_faces() != chart.size() || mesh.number_of_vertices() != ids.size()) return false;

  // A disk: one border cycle and V - E + F = 1.
  const long euler = static_cast<long>(mesh.number_of_vertices()) - static_cast<long>(mesh.number_of_edges()) +
                     static_cast<long>(mesh.number_of_faces());
  if (euler != 1) return false;
  Mesh::Halfedge_index border;
  int cycles = 0;
  std::vector<char> seen(mesh.number_of_halfedges(), 0);
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_border(h) || seen[h.idx()]) continue;
    ++cycles;
    border = h;
    for (auto g = h; !seen[g.idx()]; g = mesh.next(g)) seen[g.idx()] = 1;
  }
  if (cycles != 1) return false;

  auto uv_map = mesh.add_property_map<Mesh::Vertex_index, Kernel::Point_2>("v:uv").first;
  if (SMP::parameterize(mesh, SMP::LSCM_parameterizer_3<Mesh>(), border, uv_map) != SMP::OK) return false;

  std::vector<Uv> out(3 * chart.size());
  double area_uv = 0.0;
  for (std::size_t i = 0; i < chart.size(); ++i) {
    const auto& tri = surface.triangles[chart[i]];
    for (int k = 0; k < 3; ++k) {
      const Kernel::Point_2& p = uv_map[Mesh::Vertex_index(static_cast<Mesh::size_type>(vertex_of[3 * i + k]))];
      out[3 * i + k] = {p.x(), p.y()};
    }
    const Uv &a = out[3 * i], &b = out[3 * i + 1], &c = out[3 * i + 2];
    area_uv += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  }
  if (!(area_uv > 0.0) || !std::isfinite(area_uv)) return false;
  const double scale = std::sqrt(area_3d / area_uv);
  for (Uv& p : out) p = {p[0] * scale, p[1] * scale};
  uvs = std::move(out);
  return true;
}

}  // namespace hq
