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
  return method == SignMethod::kPseudoNormal ? "pseudo_normal" : "winding_number";
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
  for (const auto& q : mesh.quads)
    for (Index v : q) used[static_cast<std::size_t>(v)] = 1;
  for (const auto& t : mesh.triangles)
    for (Index v : t) used[static_cast<std::size_t>(v)] = 1;
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

// Repairs the reference and builds its closest-point tree and sign structure.
void prepare_reference(const TriSurface& reference, ReferenceSide& side, BoundaryError& out) {
  side.repaired = repair_reference(reference);
  out.num_repaired_triangles = side.repaired.num_removed_triangles;
  out.num_zero_area_triangles = side.repaired.num_zero_area_triangles;
  if (!has_positive_area(side.repaired.surface))
    throw InputError("the reference surface has no triangle of positive area after repair");
  out.sign_method = side.repaired.is_closed_manifold ? SignMethod::kPseudoNormal : SignMethod::kWindingNumber;
  side.tree = std::make_unique<ClosestPointTree>(side.repaired.surface);
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
  auto& s = out.sampled_mesh_to_reference;
  s.max = d.max_distance;
  s.upper_bound = d.upper_bound;
  s.num_samples = d.num_samples;
  patch_means(out.mesh_patches, s);
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
  for (std::size_t v = 0; v < reference.points.size(); ++v)
    if (used[v]) {
      samples.push_back(reference.points[v]);
      sample_vertex.push_back(static_cast<Index>(v));
    }
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
    auto& s = out.sampled_reference_to_mesh;
    s.max = d.max_distance;
    s.upper_bound = d.upper_bound;
    s.num_samples = d.num_samples;
    patch_means(out.reference_patches, s);
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
  prepare_reference(reference, side, out);
  signed_vertex_errors(mesh, vertices, side, options, out);
  sampled_mesh_errors(mesh, topo, vertices, side, options, out);
  vertex_areas(mesh, topo, out);
  reference_to_mesh_errors(mesh, topo, reference, used, options, out);
  summarize_errors(vertices, options, out);
  add_warnings(options, out);
  return out;
}

}  // namespace hq
