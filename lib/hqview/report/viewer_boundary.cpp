#include "hqview/report/viewer_boundary.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "hqview/analysis/analysis.h"
#include "hqview/core/box3.h"
#include "hqview/mesh/boundary_polygons.h"

namespace hq {

namespace {

ViewerBoundary surface_faces(const Mesh& mesh) {
  ViewerBoundary b;
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> slot(mesh.points.size(), kUnused);
  for (const auto& q : mesh.quads)
    for (Index v : q) slot[static_cast<std::size_t>(v)] = 0;
  for (const auto& t : mesh.triangles)
    for (Index v : t) slot[static_cast<std::size_t>(v)] = 0;
  for (std::size_t v = 0; v < slot.size(); ++v) {
    if (slot[v] == kUnused) continue;
    slot[v] = static_cast<std::uint32_t>(b.vertices.size());
    b.vertices.push_back(static_cast<Index>(v));
  }
  Index cell = 0;
  for (const auto& q : mesh.quads) {
    for (Index v : q) b.quads.push_back(slot[static_cast<std::size_t>(v)]);
    b.face_hex.push_back(cell++);
  }
  for (const auto& t : mesh.triangles) {
    for (int i = 0; i < 4; ++i) b.quads.push_back(slot[static_cast<std::size_t>(t[static_cast<std::size_t>(std::min(i, 2))])]);
    b.face_hex.push_back(cell++);
  }
  b.num_source_faces = b.face_hex.size();
  return b;
}

}  // namespace

ViewerBoundary viewer_boundary(const Analysis& a) {
  if (is_surface_mesh(a.mesh)) return surface_faces(a.mesh);
  const Topology& t = a.topology;
  ViewerBoundary b;
  b.vertices = t.boundary_vertices;
  std::vector<std::uint32_t> slot(a.mesh.points.size(), 0);
  for (std::size_t i = 0; i < b.vertices.size(); ++i) slot[static_cast<std::size_t>(b.vertices[i])] = static_cast<std::uint32_t>(i);
  // Every kind's boundary faces (boundary_polygons: hex quads first, in
  // their order, then the non-hex quads and the triangles).
  for (const BoundaryPolygon& face : boundary_polygons(t)) {
    for (int i = 0; i < 4; ++i)
      b.quads.push_back(slot[static_cast<std::size_t>(face.v[static_cast<std::size_t>(std::min(i, face.size - 1))])]);
    b.face_hex.push_back(face.cell);
  }
  b.num_source_faces = b.face_hex.size();
  return b;
}

namespace {

// Lower is worse; a value that is not finite (no value, degenerate) is worst.
double badness_key(double q) { return std::isfinite(q) ? q : -std::numeric_limits<double>::infinity(); }

// A cell's key: a cell the values do not cover (a non-hex cell while only
// hexes have a scaled Jacobian) is never preferred to one they cover.
double cell_badness_key(const std::vector<double>& values, Index cell) {
  return static_cast<std::size_t>(cell) < values.size() ? badness_key(values[static_cast<std::size_t>(cell)])
                                                         : std::numeric_limits<double>::infinity();
}

ViewerBoundary cluster_on_grid(const ViewerBoundary& full, const std::vector<Vec3>& points,
                               const std::vector<double>& vertex_quality,
                               const std::vector<double>& cell_scaled_jacobian, const Box3& box, double h) {
  // Grid cell of each boundary vertex; clusters numbered in vertex order.
  std::array<std::uint64_t, 3> n{};
  for (int k = 0; k < 3; ++k) n[k] = static_cast<std::uint64_t>(std::floor((box.hi[k] - box.lo[k]) / h)) + 1;
  std::unordered_map<std::uint64_t, std::uint32_t> cluster_of_cell;
  std::vector<std::uint32_t> cluster(full.vertices.size());
  std::vector<Index> representative;
  for (std::size_t i = 0; i < full.vertices.size(); ++i) {
    const Index v = full.vertices[i];
    const Vec3& p = points[static_cast<std::size_t>(v)];
    std::array<std::uint64_t, 3> c{};
    for (int k = 0; k < 3; ++k)
      c[k] = std::min(n[k] - 1, static_cast<std::uint64_t>(std::max(0.0, std::floor((p[k] - box.lo[k]) / h))));
    const std::uint64_t key = c[0] + n[0] * (c[1] + n[1] * c[2]);
    const auto [it, added] = cluster_of_cell.try_emplace(key, static_cast<std::uint32_t>(representative.size()));
    if (added) {
      representative.push_back(v);
    } else {
      Index& r = representative[it->second];
      const double qv = badness_key(vertex_quality[static_cast<std::size_t>(v)]);
      const double qr = badness_key(vertex_quality[static_cast<std::size_t>(r)]);
      if (qv < qr || (qv == qr && v < r)) r = v;
    }
    cluster[i] = it->second;
  }

  // Faces on at least three distinct cells, in cyclic order; of the faces on
  // the same cells, the one whose hex is worst.
  struct Kept {
    std::array<std::uint32_t, 4> corners;
    Index hex;
  };
  struct CellsHash {
    std::size_t operator()(const std::array<std::uint32_t, 4>& a) const {
      std::uint64_t h = 1469598103934665603ull;
      for (std::uint32_t x : a) h = (h ^ x) * 1099511628211ull;
      return static_cast<std::size_t>(h);
    }
  };
  std::vector<Kept> kept;
  std::unordered_map<std::array<std::uint32_t, 4>, std::size_t, CellsHash> kept_on_cells;
  const std::size_t num_faces = full.face_hex.size();
  for (std::size_t f = 0; f < num_faces; ++f) {
    std::array<std::uint32_t, 4> c{};
    int m = 0;
    for (int k = 0; k < 4; ++k) {
      const std::uint32_t x = cluster[full.quads[4 * f + static_cast<std::size_t>(k)]];
      if (m == 0 || c[static_cast<std::size_t>(m - 1)] != x) c[static_cast<std::size_t>(m++)] = x;
    }
    while (m > 1 && c[static_cast<std::size_t>(m - 1)] == c[0]) --m;
    if (m < 3) continue;
    std::array<std::uint32_t, 4> cells = c;
    if (m == 3) cells[3] = std::numeric_limits<std::uint32_t>::max();
    std::sort(cells.begin(), cells.end());
    if (std::adjacent_find(cells.begin(), cells.end()) != cells.end()) continue;  // a bow-tie
    if (m == 3) c[3] = c[2];
    const Index hex = full.face_hex[f];
    const auto [it, added] = kept_on_cells.try_emplace(cells, kept.size());
    if (added) {
      kept.push_back({c, hex});
      continue;
    }
    Kept& other = kept[it->second];
    const double s = cell_badness_key(cell_scaled_jacobian, hex);
    const double t = cell_badness_key(cell_scaled_jacobian, other.hex);
    if (s < t || (s == t && hex < other.hex)) other = {c, hex};
  }

  // Vertices in order of first use.
  ViewerBoundary out;
  out.num_source_faces = full.num_source_faces;
  out.cell_size = h;
  std::vector<std::uint32_t> slot(representative.size(), std::numeric_limits<std::uint32_t>::max());
  for (const Kept& k : kept) {
    for (std::uint32_t x : k.corners) {
      if (slot[x] == std::numeric_limits<std::uint32_t>::max()) {
        slot[x] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(representative[x]);
      }
      out.quads.push_back(slot[x]);
    }
    out.face_hex.push_back(k.hex);
  }
  return out;
}

}  // namespace

ViewerBoundary reduce_boundary(const ViewerBoundary& full, const std::vector<Vec3>& points,
                               const std::vector<double>& vertex_quality,
                               const std::vector<double>& cell_scaled_jacobian, std::size_t max_faces) {
  const std::size_t num_faces = full.face_hex.size();
  if (num_faces <= max_faces) return full;
  Box3 box;
  for (Index v : full.vertices) box.add(points[static_cast<std::size_t>(v)]);
  double area = 0;
  for (std::size_t f = 0; f < num_faces; ++f) {
    const auto p = [&](int k) { return points[static_cast<std::size_t>(full.vertices[full.quads[4 * f + static_cast<std::size_t>(k)]])]; };
    area += 0.5 * (norm(cross(p(1) - p(0), p(2) - p(0))) + norm(cross(p(2) - p(0), p(3) - p(0))));
  }
  const double diagonal = norm(box.hi - box.lo);
  if (!(diagonal > 0)) return full;
  // About one vertex per cell of the surface: a cell of side h holds h^2 of area.
  double h = std::clamp(std::sqrt(area / static_cast<double>(std::max<std::size_t>(max_faces, 1))), diagonal * 1e-6, diagonal);
  ViewerBoundary best = cluster_on_grid(full, points, vertex_quality, cell_scaled_jacobian, box, h);
  for (int round = 0; round < 60 && best.face_hex.size() > max_faces && h < diagonal; ++round) {
    const double grow = std::sqrt(static_cast<double>(best.face_hex.size()) / static_cast<double>(std::max<std::size_t>(max_faces, 1)));
    h = std::min(diagonal, h * std::clamp(grow, 1.05, 2.0));
    best = cluster_on_grid(full, points, vertex_quality, cell_scaled_jacobian, box, h);
  }
  return best;
}

}  // namespace hq
