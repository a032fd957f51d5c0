#include "hqview/boundary/boundary_error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "hqview/boundary/sampled_distance.h"
#include "hqview/boundary/surface_distance.h"
#include "hqview/boundary/surface_sign.h"
#include "hqview/core/box3.h"
#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/mesh/mesh_summary.h"
#include "hqview/mesh/planarity.h"

namespace hq {
namespace {

std::string box_text(const Box3& b) {
  std::ostringstream s;
  s.precision(6);
  s << "[" << b.lo.x << ", " << b.lo.y << ", " << b.lo.z << "] - [" << b.hi.x << ", " << b.hi.y << ", " << b.hi.z
    << "]";
  return s.str();
}

bool has_positive_area(const TriSurface& s) {
  for (const auto& t : s.triangles)
    if (squared_norm(cross(s.points[t[1]] - s.points[t[0]], s.points[t[2]] - s.points[t[0]])) > 0.0) return true;
  return false;
}

}  // namespace

const char* sign_method_name(SignMethod method) {
  switch (method) {
    case SignMethod::kPseudoNormal: return "pseudo_normal";
    case SignMethod::kWindingNumber: return "winding_number";
    case SignMethod::kPlanarDomain: return "planar_domain";
  }
  return "";
}

bool is_planar_surface(const HexMesh& mesh, const Topology& topo) {
  if (!is_surface_mesh(mesh)) return false;
  const Box3 box = referenced_bounding_box(mesh, topo);
  return measure_planarity(mesh, box.is_empty() ? 0.0 : norm(box.hi - box.lo)).is_planar;
}

SegmentSet surface_boundary_segments(const std::vector<Vec3>& points, const SurfaceTopology& topology) {
  SegmentSet s;
  s.points = points;
  for (std::size_t e = 0; e < topology.edges.size(); ++e)
    if (topology.edge_num_faces[e] == 1) s.segments.push_back(topology.edges[e]);
  return s;
}

TriSurface boundary_triangles(const HexMesh& mesh, const Topology& topo) {
  TriSurface s;
  s.points = mesh.points;
  if (is_surface_mesh(mesh)) {
    s.triangles.reserve(2 * mesh.quads.size() + mesh.triangles.size());
    for (const auto& q : mesh.quads) {
      s.triangles.push_back({q[0], q[1], q[2]});
      s.triangles.push_back({q[0], q[2], q[3]});
    }
    s.triangles.insert(s.triangles.end(), mesh.triangles.begin(), mesh.triangles.end());
    return s;
  }
  s.triangles.reserve(2 * topo.boundary_faces.size());
  for (Index f : topo.boundary_faces) {
    const Quad& q = topo.faces[f];
    s.triangles.push_back({q[0], q[1], q[2]});
    s.triangles.push_back({q[0], q[2], q[3]});
  }
  return s;
}

std::vector<Index> measured_vertices(const HexMesh& mesh, const Topology& topo) {
  if (!is_surface_mesh(mesh)) return topo.boundary_vertices;
  std::vector<char> used(mesh.points.size(), 0);
  if (is_planar_surface(mesh, topo)) {
    for (const auto& e : surface_boundary_segments({}, topo.surface).segments)
      for (Index v : e) used[static_cast<std::size_t>(v)] = 1;
  } else {
    for (const auto& q : mesh.quads)
      for (Index v : q) used[static_cast<std::size_t>(v)] = 1;
    for (const auto& t : mesh.triangles)
      for (Index v : t) used[static_cast<std::size_t>(v)] = 1;
  }
  std::vector<Index> out;
  for (std::size_t v = 0; v < used.size(); ++v)
    if (used[v]) out.push_back(static_cast<Index>(v));
  return out;
}

namespace {

// The reference's used vertices (those of a triangle). Throws InputError when
// the bounding boxes of the mesh boundary and the reference do not overlap.
std::vector<std::uint8_t> check_bounding_boxes(const HexMesh& mesh, const std::vector<Index>& vertices,
                                               const TriSurface& reference, BoundaryError& out) {
  Box3 reference_box, mesh_box;
  std::vector<std::uint8_t> used(reference.points.size(), 0);
  for (const auto& t : reference.triangles)
    for (Index v : t) used[v] = 1;
  for (std::size_t v = 0; v < reference.points.size(); ++v)
    if (used[v]) reference_box.add(reference.points[v]);
  for (Index v : vertices) mesh_box.add(mesh.points[v]);
  out.reference_bbox_min = reference_box.lo;
  out.reference_bbox_max = reference_box.hi;
  out.reference_bbox_diagonal = norm(reference_box.hi - reference_box.lo);
  if (!vertices.empty() && !reference_box.overlaps(mesh_box))
    throw InputError("the bounding boxes of the mesh boundary " + box_text(mesh_box) + " and the reference " +
                     box_text(reference_box) + " do not overlap (different units or placement?)");

  return used;
}

// The repaired reference with what distances and signs to it need.
struct ReferenceSide {
  RepairedSurface repaired;
  std::unique_ptr<ClosestPointTree> tree;
  PseudoNormals normals;  // closed manifold reference
  WindingTree winding;    // otherwise
};

// +1 outside the reference, -1 inside (0 on it); `uncertain` as the sign tests set it.
int reference_sign(const ReferenceSide& side, SignMethod method, double band, const Vec3& query,
                   const ClosestPoint& closest, bool& uncertain) {
  if (method == SignMethod::kPseudoNormal) {
    bool flag = false;
    const int s = pseudo_normal_sign(side.repaired.surface, side.normals, query, closest, flag);
    uncertain = flag && closest.distance > 0.0;
    return s;
  }
  const double w = winding_number_for_sign(side.repaired.surface, side.winding, query);
  uncertain = std::abs(w - 0.5) < band && closest.distance > 0.0;
  return w >= 0.5 ? -1 : 1;
}

// Repairs the reference and builds its closest-point tree and sign structure
// (none for a planar mesh: its signs are in the plane).
void prepare_reference(const TriSurface& reference, ReferenceSide& side, BoundaryError& out) {
  side.repaired = repair_reference(reference);
  out.num_repaired_triangles = side.repaired.num_removed_triangles;
  out.num_zero_area_triangles = side.repaired.num_zero_area_triangles;
  if (!has_positive_area(side.repaired.surface))
    throw InputError("the reference surface has no triangle of positive area after repair");
  side.tree = std::make_unique<ClosestPointTree>(side.repaired.surface);
  if (out.planar) {
    out.sign_method = SignMethod::kPlanarDomain;
    return;
  }
  out.sign_method = side.repaired.is_closed_manifold ? SignMethod::kPseudoNormal : SignMethod::kWindingNumber;
  if (out.sign_method == SignMethod::kPseudoNormal)
    side.normals = compute_pseudo_normals(side.repaired.surface);
  else
    side.winding = build_winding_tree(side.repaired.surface);
}

// Hex boundary -> reference: the signed distance of every boundary vertex
// (sign by pseudo-normals on a closed manifold reference, else by the
// generalized winding number).
void signed_vertex_errors(const HexMesh& mesh, const std::vector<Index>& vertices, const ReferenceSide& side,
                          const BoundaryOptions& options, BoundaryError& out) {
  std::vector<Vec3> queries;
  queries.reserve(vertices.size());
  for (Index v : vertices) queries.push_back(mesh.points[v]);
  const std::vector<ClosestPoint> closest = side.tree->query(queries);

  std::vector<int> sign(queries.size(), 0);
  std::vector<std::uint8_t> uncertain(queries.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, queries.size()), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      bool flag = false;
      sign[i] = reference_sign(side, out.sign_method, options.uncertain_winding_band, queries[i], closest[i], flag);
      uncertain[i] = flag;
    }
  });

  const std::size_t nv = mesh.points.size();
  out.vertex_error.assign(nv, NAN);
  out.sign_uncertain.assign(nv, 0);
  out.vertex_area.assign(nv, 0.0);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const Index v = vertices[i];
    out.vertex_error[v] = sign[i] < 0 ? -closest[i].distance : closest[i].distance;
    out.sign_uncertain[v] = uncertain[i];
    out.num_uncertain_signs += uncertain[i];
  }
}

SampledDistanceOptions sampling_options(const BoundaryOptions& options, const BoundaryError& out,
                                        double known_distance) {
  SampledDistanceOptions s;
  s.tolerance = options.sampling_tolerance * out.reference_bbox_diagonal;
  s.initial_radius = options.sampling_radius * out.reference_bbox_diagonal;
  s.known_distance = known_distance;
  return s;
}

// The reference's points marked in `used`, appended with their ids.
void used_points(const TriSurface& reference, const std::vector<std::uint8_t>& used, std::vector<Vec3>& points,
                 std::vector<Index>& ids) {
  for (std::size_t v = 0; v < reference.points.size(); ++v)
    if (used[v]) {
      points.push_back(reference.points[v]);
      ids.push_back(static_cast<Index>(v));
    }
}

// Area-weighted mean, mean |e| and rms over the patches (fixed order).
void patch_means(const std::vector<BoundaryError::ErrorPatch>& patches, BoundaryError::SampledSide& side) {
  double total = 0, sum = 0, sum_abs = 0, sum_sq = 0;
  for (const auto& p : patches) {
    total += p.area;
    sum += p.area * p.error;
    sum_abs += p.area * std::abs(p.error);
    sum_sq += p.area * p.error * p.error;
  }
  if (total > 0) {
    side.mean = sum / total;
    side.mean_abs = sum_abs / total;
    side.rms = std::sqrt(sum_sq / total);
  }
}

// One direction's sampled figures: the sampler's maximum, bound and count,
// the patches' means.
void summarize_side(const SampledDistance& d, const std::vector<BoundaryError::ErrorPatch>& patches,
                    BoundaryError::SampledSide& side) {
  side.max = d.max_distance;
  side.upper_bound = d.upper_bound;
  side.num_samples = d.num_samples;
  patch_means(patches, side);
}

// Hex boundary -> reference over the boundary triangles (certified maximum),
// each patch signed like the vertices.
void sampled_mesh_errors(const HexMesh& mesh, const Topology& topo, const std::vector<Index>& vertices,
                         const ReferenceSide& side, const BoundaryOptions& options, BoundaryError& out) {
  double vertex_max = 0;
  for (Index v : vertices) vertex_max = std::max(vertex_max, std::abs(out.vertex_error[v]));
  const SampledDistance d =
      sample_distance(boundary_triangles(mesh, topo), *side.tree, sampling_options(options, out, vertex_max));
  out.mesh_patches.resize(d.patches.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, d.patches.size()), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const SamplePatch& p = d.patches[i];
      bool flag = false;
      const int sign =
          reference_sign(side, out.sign_method, options.uncertain_winding_band, p.centre, p.closest, flag);
      out.mesh_patches[i] = {p.corners, sign < 0 ? -p.closest.distance : p.closest.distance, p.area};
    }
  });
  summarize_side(d, out.mesh_patches, out.sampled_mesh_to_reference);
}

// A quarter of each boundary quad's area to each of its corners (a surface
// mesh: of each quad; a third of each triangle's).
void vertex_areas(const HexMesh& mesh, const Topology& topo, BoundaryError& out) {
  const auto add_quad = [&](const Quad& q) {
    const Vec3 &a = mesh.points[q[0]], &b = mesh.points[q[1]], &c = mesh.points[q[2]], &d = mesh.points[q[3]];
    const double area = 0.5 * norm(cross(c - a, d - b));
    for (Index v : q) out.vertex_area[v] += 0.25 * area;
  };
  if (!is_surface_mesh(mesh)) {
    for (Index f : topo.boundary_faces) add_quad(topo.faces[f]);
    return;
  }
  for (const auto& q : mesh.quads) add_quad(q);
  for (const auto& t : mesh.triangles) {
    const Vec3 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
    const double area = 0.5 * norm(cross(b - a, c - a));
    for (Index v : t) out.vertex_area[v] += area / 3.0;
  }
}

// Reference -> hex boundary at reference vertices and face centres.
void reference_to_mesh_errors(const HexMesh& mesh, const Topology& topo, const TriSurface& reference,
                              const std::vector<std::uint8_t>& used, const BoundaryOptions& options,
                              BoundaryError& out) {
  const TriSurface hex_surface = boundary_triangles(mesh, topo);
  std::vector<Vec3> samples;
  std::vector<Index> sample_vertex;
  used_points(reference, used, samples, sample_vertex);
  const std::size_t num_vertex_samples = samples.size();
  for (const auto& t : reference.triangles)
    samples.push_back((reference.points[t[0]] + reference.points[t[1]] + reference.points[t[2]]) / 3.0);
  out.reference_vertex_error.assign(reference.points.size(), NAN);
  out.reference_face_error.assign(reference.triangles.size(), NAN);
  if (has_positive_area(hex_surface)) {
    const ClosestPointTree tree(hex_surface);
    const std::vector<ClosestPoint> back = tree.query(samples);
    const PseudoNormals hex_normals = compute_pseudo_normals(hex_surface);
    std::vector<double> signed_back(back.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, back.size()), [&](const auto& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        bool flag = false;
        // Outside the hex solid means the hex boundary is inside the reference there: negative.
        const int side = pseudo_normal_sign(hex_surface, hex_normals, samples[i], back[i], flag);
        signed_back[i] = side > 0 ? -back[i].distance : back[i].distance;
      }
    });
    for (std::size_t i = 0; i < num_vertex_samples; ++i) out.reference_vertex_error[sample_vertex[i]] = signed_back[i];
    for (std::size_t t = 0; t < reference.triangles.size(); ++t)
      out.reference_face_error[t] = signed_back[num_vertex_samples + t];
    for (const ClosestPoint& c : back)
      out.hausdorff_reference_to_mesh = std::max(out.hausdorff_reference_to_mesh, c.distance);

    // Over the reference triangles (certified maximum), signed as above.
    // The face centres above are the level-0 samples of the triangles sampled whole.
    SampledDistanceOptions sampling = sampling_options(options, out, out.hausdorff_reference_to_mesh);
    sampling.triangle_centroids = std::span<const ClosestPoint>(back).subspan(num_vertex_samples);
    const SampledDistance d = sample_distance(reference, tree, sampling);
    out.reference_patches.resize(d.patches.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, d.patches.size()), [&](const auto& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const SamplePatch& p = d.patches[i];
        bool flag = false;
        const int side = pseudo_normal_sign(hex_surface, hex_normals, p.centre, p.closest, flag);
        out.reference_patches[i] = {p.corners, side > 0 ? -p.closest.distance : p.closest.distance, p.area};
      }
    });
    summarize_side(d, out.reference_patches, out.sampled_reference_to_mesh);
  }
}

// Hausdorff distances, area-weighted errors and statistics (sequential,
// fixed order).
void summarize_errors(const std::vector<Index>& vertices, const BoundaryOptions& options, BoundaryError& out) {
  std::vector<double> errors;
  errors.reserve(vertices.size());
  double total_area = 0, sum = 0, sum_abs = 0, sum_sq = 0;
  for (Index v : vertices) {
    const double e = out.vertex_error[v], a = out.vertex_area[v];
    errors.push_back(e);
    out.hausdorff_mesh_to_reference = std::max(out.hausdorff_mesh_to_reference, std::abs(e));
    total_area += a;
    sum += a * e;
    sum_abs += a * std::abs(e);
    sum_sq += a * e * e;
  }
  if (total_area > 0) {
    out.area_weighted_mean = sum / total_area;
    out.area_weighted_mean_abs = sum_abs / total_area;
    out.area_weighted_rms = std::sqrt(sum_sq / total_area);
  }
  // Outside / inside / on, of the sampled hex boundary area.
  out.on_surface_tolerance = options.on_surface_tolerance * out.reference_bbox_diagonal;
  double sampled_area = 0, outside = 0, inside = 0;
  for (const auto& p : out.mesh_patches) {
    sampled_area += p.area;
    if (p.error > out.on_surface_tolerance) outside += p.area;
    if (p.error < -out.on_surface_tolerance) inside += p.area;
  }
  if (sampled_area > 0) {
    out.fraction_outside = outside / sampled_area;
    out.fraction_inside = inside / sampled_area;
    out.fraction_on_surface = std::max(0.0, 1.0 - out.fraction_outside - out.fraction_inside);
  }
  out.sampling_tolerance = options.sampling_tolerance * out.reference_bbox_diagonal;
  out.sampled_symmetric = std::max(out.sampled_mesh_to_reference.max, out.sampled_reference_to_mesh.max);
  out.sampled_upper_bound =
      std::max(out.sampled_mesh_to_reference.upper_bound, out.sampled_reference_to_mesh.upper_bound);
  out.hausdorff_symmetric = std::max(out.hausdorff_mesh_to_reference, out.hausdorff_reference_to_mesh);
  if (out.reference_bbox_diagonal > 0) {
    out.hausdorff_relative = out.hausdorff_symmetric / out.reference_bbox_diagonal;
    out.relative_mesh_to_reference = out.hausdorff_mesh_to_reference / out.reference_bbox_diagonal;
    out.relative_reference_to_mesh = out.hausdorff_reference_to_mesh / out.reference_bbox_diagonal;
  }
  StatisticsOptions histogram;
  const double range = out.hausdorff_mesh_to_reference > 0 ? out.hausdorff_mesh_to_reference : 1.0;
  histogram.histogram_min = -range;
  histogram.histogram_max = range;
  out.signed_stats = compute_statistics(errors, histogram);
}

void add_warnings(const BoundaryOptions& options, BoundaryError& out) {
  if (out.num_repaired_triangles > 0)
    out.warnings.push_back("reference: " + std::to_string(out.num_repaired_triangles) +
                           " degenerate or duplicate triangles removed by the repair");
  if (out.sign_method == SignMethod::kWindingNumber)
    out.warnings.push_back(
        "reference: not a closed manifold surface bounding a volume; boundary error signs come from the generalized "
        "winding number (" +
        std::to_string(out.num_uncertain_signs) + " uncertain)");
  if (out.hausdorff_relative > options.far_warning_relative) {
    std::ostringstream s;
    s.precision(3);
    s << "reference: relative Hausdorff distance " << 100.0 * out.hausdorff_relative
      << " % of the reference's bounding-box diagonal; is the reference in the same units and placement as the mesh?";
    out.warnings.push_back(s.str());
  }
}

// ---- A planar mesh against a planar reference (docs/analysis.md, "Planar
// meshes against a reference outline") ----

// The least-squares plane check of the reference (its used points), then
// that they lie in the mesh's plane, both within kPlanarTolerance of the
// larger diagonal. Throws InputError naming the farthest point (0-based, in
// the file's order).
void check_reference_plane(const Planarity& plane, const TriSurface& reference,
                           const std::vector<std::uint8_t>& used, double diagonal) {
  std::vector<Vec3> points;
  std::vector<Index> ids;
  used_points(reference, used, points, ids);
  const LeastSquaresPlane own = least_squares_plane(points);
  const double tolerance = kPlanarTolerance * diagonal;
  const auto farthest = [&](const Vec3& origin, const Vec3& normal) {
    std::size_t worst = 0;
    double d = -1;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (std::abs(dot(points[i] - origin, normal)) > d) {
        d = std::abs(dot(points[i] - origin, normal));
        worst = i;
      }
    return std::pair{worst, d};
  };
  const std::string what = "; a planar mesh is measured against a planar triangle mesh of its domain, in its plane";
  if (const auto [i, d] = farthest(own.centroid, own.normal); d > tolerance)
    throw InputError("the reference is not planar: its point " + std::to_string(ids[i]) + " lies " +
                     display_number(d, 3) + " from its best-fit plane (" + display_number(d / diagonal, 3) +
                     " of the diagonal)" + what);
  if (const auto [i, d] = farthest(plane.centroid, plane.normal); d > tolerance)
    throw InputError("the reference is not in the mesh's plane: its point " + std::to_string(ids[i]) + " lies " +
                     display_number(d, 3) + " from the mesh's plane (" + display_number(d / diagonal, 3) +
                     " of the diagonal)" + what);
}

// The segments as a wall: each (a, b) extruded along the plane's normal by
// `height` to both sides (two triangles). The wall's closest point to a
// point within `height` of the plane lies at the point's height, so its
// distance is the in-plane distance to the segments.
TriSurface segment_wall(const SegmentSet& segments, const Vec3& normal, double height) {
  TriSurface wall;
  wall.points.reserve(2 * segments.points.size());
  for (const Vec3& p : segments.points) {
    wall.points.push_back(p - height * normal);
    wall.points.push_back(p + height * normal);
  }
  for (const auto& [a, b] : segments.segments) {
    wall.triangles.push_back({2 * a, 2 * b, 2 * b + 1});
    wall.triangles.push_back({2 * a, 2 * b + 1, 2 * a + 1});
  }
  return wall;
}

// One side of the planar measurement: a domain (its faces) and its
// outline (the wall of its boundary segments).
struct PlanarDomain {
  const ClosestPointTree* faces = nullptr;
  TriSurface wall;                            // segment_wall of the outline
  std::unique_ptr<ClosestPointTree> outline;  // over wall
};

// The domain of `faces` with the wall of `outline` (built in place: the
// tree refers to the wall).
void set_planar_domain(const ClosestPointTree* faces, const SegmentSet& outline, const Vec3& normal, double height,
                       PlanarDomain& out) {
  out.faces = faces;
  out.wall = segment_wall(outline, normal, height);
  out.outline = std::make_unique<ClosestPointTree>(out.wall);
}

// The distances of `points` to the domain's outline (closest: their
// closest points on it), signed +outside_sign outside the domain, -outside_sign
// inside. A point is outside when its distance to the domain's faces is
// more than half its distance to the outline: outside, the two are equal
// (the closest point of the faces is on the outline); inside, the first is
// 0 up to rounding and the point's height over the plane.
std::vector<double> signed_planar_distances(const PlanarDomain& domain, std::span<const Vec3> points,
                                            std::span<const ClosestPoint> closest, int outside_sign) {
  const std::vector<ClosestPoint> to_faces = domain.faces->query(points);
  std::vector<double> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d = closest[i].distance;
    const bool outside = to_faces[i].distance > 0.5 * d;
    out[i] = (outside ? outside_sign : -outside_sign) * d;
  }
  return out;
}

// The signed distances of `points` to the domain's outline.
std::vector<double> signed_outline_distances(const PlanarDomain& domain, std::span<const Vec3> points,
                                             int outside_sign) {
  return signed_planar_distances(domain, points, domain.outline->query(points), outside_sign);
}

// linear_pieces() cuts a piece at most this many times.
constexpr int kMaxPieceLevel = 30;

// A piece (a, b) of a polyline segment with the signed errors at its ends.
struct PolylinePiece {
  Vec3 a, b;
  double error_a = 0, error_b = 0;
};

// The pieces cut further until the error is linear along each (its
// midpoint within tolerance / 4 of the ends' mean) and changes by at most
// `tolerance` over it, queried level by level (the ends always included:
// the polyline's vertices are the first pieces' ends). The signed distance
// to a polyline is continuous and piecewise smooth along a segment, so the
// pieces' linear interpolant converges to it as the tolerance goes to 0.
std::vector<PolylinePiece> linear_pieces(std::vector<PolylinePiece> pending, const PlanarDomain& target,
                                         int outside_sign, double tolerance) {
  std::vector<PolylinePiece> done;
  for (int level = 0; !pending.empty(); ++level) {
    std::vector<Vec3> midpoints;
    midpoints.reserve(pending.size());
    for (const PolylinePiece& p : pending) midpoints.push_back(0.5 * (p.a + p.b));
    const std::vector<double> errors = signed_outline_distances(target, midpoints, outside_sign);
    std::vector<PolylinePiece> next;
    for (std::size_t i = 0; i < pending.size(); ++i) {
      const PolylinePiece& p = pending[i];
      const bool linear = std::abs(errors[i] - 0.5 * (p.error_a + p.error_b)) <= 0.25 * tolerance &&
                          std::abs(p.error_b - p.error_a) <= tolerance;
      if (linear || level == kMaxPieceLevel) {
        done.push_back(p);
        continue;
      }
      next.push_back({p.a, midpoints[i], p.error_a, errors[i]});
      next.push_back({midpoints[i], p.b, errors[i], p.error_b});
    }
    pending = std::move(next);
  }
  return done;
}

// Each linear piece cut where its error crosses -on, 0 or +on (so each
// patch lies on one side of the fractions' thresholds), as patches whose
// error is the mean over them (exact for the linear interpolant).
void add_linear_patches(const PolylinePiece& p, double on, std::vector<BoundaryError::ErrorPatch>& patches) {
  std::vector<double> cuts{0.0};
  for (double level : {-on, 0.0, on}) {
    const double t = (level - p.error_a) / (p.error_b - p.error_a);
    if ((p.error_a - level) * (p.error_b - level) < 0 && t > 0 && t < 1) cuts.push_back(t);
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.push_back(1.0);
  const double length = norm(p.b - p.a);
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const Vec3 a = p.a + cuts[k] * (p.b - p.a), b = p.a + cuts[k + 1] * (p.b - p.a);
    const double mean = p.error_a + 0.5 * (cuts[k] + cuts[k + 1]) * (p.error_b - p.error_a);
    patches.push_back({{a, 0.5 * (a + b), b}, mean, (cuts[k + 1] - cuts[k]) * length});
  }
}

// One polyline against the other domain's outline, signed: the certified
// maximum from the sampler, the length-weighted figures (means, fractions,
// the patches the views draw) from the sampler's pieces cut to linear
// pieces (linear_pieces) and at the fractions' thresholds.
void sampled_planar_side(const SegmentSet& source, const PlanarDomain& target, int outside_sign,
                         const SampledDistanceOptions& options, double on_tolerance,
                         std::vector<BoundaryError::ErrorPatch>& patches, BoundaryError::SampledSide& side) {
  const SampledDistance d = sample_distance(source, *target.outline, options);
  std::vector<Vec3> ends;
  ends.reserve(2 * d.patches.size());
  for (const SamplePatch& p : d.patches) {
    ends.push_back(p.corners[0]);
    ends.push_back(p.corners[2]);
  }
  const std::vector<double> errors = signed_outline_distances(target, ends, outside_sign);
  std::vector<PolylinePiece> pieces(d.patches.size());
  for (std::size_t i = 0; i < d.patches.size(); ++i)
    pieces[i] = {ends[2 * i], ends[2 * i + 1], errors[2 * i], errors[2 * i + 1]};
  patches.clear();
  for (const PolylinePiece& p : linear_pieces(std::move(pieces), target, outside_sign, options.tolerance))
    add_linear_patches(p, on_tolerance, patches);
  summarize_side(d, patches, side);
}

// The largest |value| of the finite values.
double largest_magnitude(const std::vector<double>& values) {
  double m = 0;
  for (double v : values)
    if (std::isfinite(v)) m = std::max(m, std::abs(v));
  return m;
}

// The planar measurement: the mesh's boundary polylines against the
// reference's outline (signed + outside the reference's domain), and the
// outline against the mesh's boundary (signed + inside the mesh's domain:
// there the mesh passes outside the reference), at the vertices and
// sampled along the segments.
void planar_boundary_errors(const HexMesh& mesh, const Topology& topo, const TriSurface& reference,
                            const std::vector<Index>& vertices, const ReferenceSide& side,
                            const BoundaryOptions& options, BoundaryError& out) {
  const std::size_t reference_size = reference.points.size(), reference_triangles = reference.triangles.size();
  const TriSurface& repaired = side.repaired.surface;
  HexMesh reference_faces;
  reference_faces.points = repaired.points;
  reference_faces.triangles.assign(repaired.triangles.begin(), repaired.triangles.end());
  out.reference_outline = surface_boundary_segments(repaired.points, build_surface_topology(reference_faces));
  if (out.reference_outline.segments.empty()) throw InputError("the reference has no boundary edge (no outline)");
  const SegmentSet mesh_outline = surface_boundary_segments(mesh.points, topo.surface);
  const double height = out.reference_bbox_diagonal;
  const double on_tolerance = options.on_surface_tolerance * out.reference_bbox_diagonal;

  PlanarDomain reference_domain;
  set_planar_domain(side.tree.get(), out.reference_outline, out.plane_normal, height, reference_domain);

  // Mesh -> reference at the boundary vertices, then along the polylines.
  std::vector<Vec3> points;
  for (Index v : vertices) points.push_back(mesh.points[static_cast<std::size_t>(v)]);
  const std::vector<double> vertex_errors = signed_outline_distances(reference_domain, points, +1);
  out.vertex_error.assign(mesh.points.size(), NAN);
  out.sign_uncertain.assign(mesh.points.size(), 0);
  out.vertex_area.assign(mesh.points.size(), 0.0);
  for (std::size_t i = 0; i < vertices.size(); ++i) out.vertex_error[static_cast<std::size_t>(vertices[i])] = vertex_errors[i];
  for (const auto& [a, b] : mesh_outline.segments) {
    const double half = 0.5 * norm(mesh.points[static_cast<std::size_t>(b)] - mesh.points[static_cast<std::size_t>(a)]);
    out.vertex_area[static_cast<std::size_t>(a)] += half;
    out.vertex_area[static_cast<std::size_t>(b)] += half;
  }
  sampled_planar_side(mesh_outline, reference_domain, +1,
                      sampling_options(options, out, largest_magnitude(vertex_errors)), on_tolerance,
                      out.mesh_patches, out.sampled_mesh_to_reference);

  // Reference outline -> mesh boundary.
  out.reference_vertex_error.assign(reference_size, NAN);
  out.reference_face_error.assign(reference_triangles, NAN);
  out.outline_vertex_error.assign(out.reference_outline.points.size(), NAN);
  const TriSurface mesh_surface = boundary_triangles(mesh, topo);
  if (mesh_outline.segments.empty() || !has_positive_area(mesh_surface)) return;
  const ClosestPointTree mesh_faces(mesh_surface);
  PlanarDomain mesh_domain;
  set_planar_domain(&mesh_faces, mesh_outline, out.plane_normal, height, mesh_domain);
  std::vector<Index> outline_vertices;
  for (const auto& e : out.reference_outline.segments) outline_vertices.insert(outline_vertices.end(), e.begin(), e.end());
  std::sort(outline_vertices.begin(), outline_vertices.end());
  outline_vertices.erase(std::unique(outline_vertices.begin(), outline_vertices.end()), outline_vertices.end());
  points.clear();
  for (Index v : outline_vertices) points.push_back(out.reference_outline.points[static_cast<std::size_t>(v)]);
  const std::vector<double> outline_errors = signed_outline_distances(mesh_domain, points, -1);
  for (std::size_t i = 0; i < outline_vertices.size(); ++i)
    out.outline_vertex_error[static_cast<std::size_t>(outline_vertices[i])] = outline_errors[i];
  out.hausdorff_reference_to_mesh = largest_magnitude(outline_errors);
  sampled_planar_side(out.reference_outline, mesh_domain, -1,
                      sampling_options(options, out, out.hausdorff_reference_to_mesh), on_tolerance,
                      out.reference_patches, out.sampled_reference_to_mesh);
}

}  // namespace

void check_reference_placement(const HexMesh& mesh, const Topology& topo, const TriSurface& reference) {
  if (!has_positive_area(reference)) throw InputError("the reference surface has no triangle of positive area");
  BoundaryError scratch;
  check_bounding_boxes(mesh, measured_vertices(mesh, topo), reference, scratch);
}

BoundaryError compute_boundary_error(const HexMesh& mesh, const Topology& topo, const TriSurface& reference,
                                     const BoundaryOptions& options) {
  BoundaryError out;
  out.num_reference_triangles = static_cast<Index>(reference.triangles.size());
  if (!has_positive_area(reference)) throw InputError("the reference surface has no triangle of positive area");
  const std::vector<Index> vertices = measured_vertices(mesh, topo);
  const std::vector<std::uint8_t> used = check_bounding_boxes(mesh, vertices, reference, out);
  ReferenceSide side;
  if (is_planar_surface(mesh, topo)) {
    const Box3 box = referenced_bounding_box(mesh, topo);
    const double diagonal = norm(box.hi - box.lo);
    const Planarity plane = measure_planarity(mesh, diagonal);
    check_reference_plane(plane, reference, used, std::max(diagonal, out.reference_bbox_diagonal));
    out.planar = true;
    out.plane_normal = plane.normal;
    prepare_reference(reference, side, out);
    planar_boundary_errors(mesh, topo, reference, vertices, side, options, out);
  } else {
    prepare_reference(reference, side, out);
    signed_vertex_errors(mesh, vertices, side, options, out);
    sampled_mesh_errors(mesh, topo, vertices, side, options, out);
    vertex_areas(mesh, topo, out);
    reference_to_mesh_errors(mesh, topo, reference, used, options, out);
  }
  summarize_errors(vertices, options, out);
  add_warnings(options, out);
  return out;
}

}  // namespace hq
