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

namespace hq {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
namespace SMP = CGAL::Surface_mesh_parameterization;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

}  // namespace

bool lscm_chart_layout(const TriSurface& surface, std::span<const Index> chart, std::vector<Uv>& uvs) {
  if (chart.size() < 2) return false;
  std::vector<Index> ids;
  ids.reserve(3 * chart.size());
  for (Index t : chart) ids.insert(ids.end(), surface.triangles[t].begin(), surface.triangles[t].end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  auto local = [&](Index v) {
    return static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), v) - ids.begin());
  };
  std::vector<Kernel::Point_3> points;
  points.reserve(ids.size());
  for (Index v : ids) points.emplace_back(surface.points[v].x, surface.points[v].y, surface.points[v].z);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(chart.size());
  double area_3d = 0.0;
  for (Index t : chart) {
    const auto& tri = surface.triangles[t];
    polygons.push_back({local(tri[0]), local(tri[1]), local(tri[2])});
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
      const Kernel::Point_2& p = uv_map[Mesh::Vertex_index(static_cast<Mesh::size_type>(local(tri[k])))];
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
