#pragma once
// Boundary error of a hex mesh against a reference surface (paper goal G4,
// ALGORITHMS.md §5): the signed distance from every hex boundary vertex to the
// reference (positive = outside the reference solid), the unsigned distance
// from the reference (its vertices and face centres) to the hex boundary,
// Hausdorff distances both ways and area-weighted statistics.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hqview/boundary/sampled_distance.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/statistics.h"

namespace hq {

enum class SignMethod {
  kPseudoNormal,   // closed manifold reference bounding a volume
  kWindingNumber,  // open or non-manifold reference
  kPlanarDomain,   // a planar mesh against a planar reference: inside or outside the domain, in the plane
};
// "pseudo_normal" / "winding_number" / "planar_domain", as report.json writes it.
const char* sign_method_name(SignMethod method);

struct BoundaryOptions {
  // Winding-number signs with |w - 0.5| below this are counted as uncertain.
  double uncertain_winding_band = 0.1;
  // |error| at or below this fraction of the reference's bbox diagonal counts
  // as "on" the reference (the noise floor of fraction_outside / _inside):
  // neither outside nor inside.
  double on_surface_tolerance = 1e-3;
  // Sampled distances over the surfaces: each bound within this fraction of
  // the diagonal of the maximum found (--boundary-tolerance).
  double sampling_tolerance = 1e-4;
  // The first patches of each triangle are no wider (centroid to corner)
  // than this fraction of the diagonal (the resolution of the colours and
  // of the sampled means); finer triangles are sampled at their centroid.
  double sampling_radius = 5e-3;
  // Relative Hausdorff distance above which a warning says the reference
  // may be misplaced or in other units.
  double far_warning_relative = 0.1;
};

struct BoundaryError {
  SignMethod sign_method = SignMethod::kPseudoNormal;
  double reference_bbox_diagonal = 0;
  Vec3 reference_bbox_min, reference_bbox_max;
  Index num_reference_triangles = 0;  // as read
  Index num_repaired_triangles = 0;   // removed by the repair (degenerate, duplicate)
  Index num_zero_area_triangles = 0;  // kept out of the distance structure

  // Per hex vertex (num_vertices): signed distance to the reference in model
  // units, NaN where the vertex is not on the hex boundary.
  std::vector<double> vertex_error;
  // Per hex vertex: a quarter of the incident boundary quads' areas (0 inside).
  std::vector<double> vertex_area;
  // Per hex vertex: 1 when the sign of vertex_error is uncertain.
  std::vector<std::uint8_t> sign_uncertain;
  Index num_uncertain_signs = 0;

  // Per reference point (as read): distance to the hex boundary, signed with
  // the same convention as vertex_error (positive where the hex boundary
  // passes outside the reference, i.e. the reference point lies inside the hex
  // solid; sign by pseudo-normals of the triangulated hex boundary), NaN for a
  // point no triangle uses. Per reference triangle: the same at its centroid.
  // This is the error field of the UV error map.
  std::vector<double> reference_vertex_error;
  std::vector<double> reference_face_error;

  double hausdorff_mesh_to_reference = 0;  // max |vertex_error|
  double hausdorff_reference_to_mesh = 0;  // max over reference vertices and face centres
  double hausdorff_symmetric = 0;          // the larger of the two
  double hausdorff_relative = 0;           // symmetric / reference_bbox_diagonal
  // Each direction over the diagonal; mesh -> reference is the per-vertex
  // figure of the paper's reference implementation (VTK distance at hex
  // boundary vertices), blind to reference parts the mesh leaves out.
  double relative_mesh_to_reference = 0;
  double relative_reference_to_mesh = 0;

  // Sampled over the surfaces (certified; docs/analysis.md "Sampled boundary
  // error"): the hex boundary triangles (quads split 0-2, as
  // boundary_triangles()) against the reference, and the reference's
  // triangles against the hex boundary, each cut into patches sampled at
  // their centroid. error: signed like vertex_error / reference_vertex_error.
  struct ErrorPatch {
    std::array<Vec3, 3> corners;
    double error = 0;  // model units, at the centroid
    double area = 0;
  };
  struct SampledSide {
    double max = 0;          // largest |error| sampled (the vertex figure included)
    double upper_bound = 0;  // no point of the surface is farther
    std::int64_t num_samples = 0;  // closest-point queries
    double mean = 0, mean_abs = 0, rms = 0;  // area-weighted over the patches
  };
  std::vector<ErrorPatch> mesh_patches;       // hex boundary -> reference
  std::vector<ErrorPatch> reference_patches;  // reference -> hex boundary
  SampledSide sampled_mesh_to_reference, sampled_reference_to_mesh;
  double sampled_symmetric = 0;    // the larger max
  double sampled_upper_bound = 0;  // the larger upper bound
  double sampling_tolerance = 0;   // model units
  double on_surface_tolerance = 0;  // model units: the noise floor of the fractions

  Statistics signed_stats;            // of vertex_error over boundary vertices, histogram symmetric about 0
  double area_weighted_mean = 0;      // sum(a_i e_i) / sum(a_i)
  double area_weighted_mean_abs = 0;  // sum(a_i |e_i|) / sum(a_i)
  double area_weighted_rms = 0;       // sqrt(sum(a_i e_i^2) / sum(a_i))
  // Of the sampled hex boundary area (mesh_patches): error above
  // on_surface_tolerance, below its negative, and within it.
  double fraction_outside = 0;
  double fraction_inside = 0;
  double fraction_on_surface = 0;

  // A planar surface mesh against a planar reference (docs/analysis.md,
  // "Planar meshes against a reference outline"): the mesh's boundary
  // polylines against the reference's outline (its boundary edges after
  // the repair), in the mesh's plane. vertex_error is then set on the
  // mesh's boundary vertices only, vertex_area is half the length of their
  // boundary edges, mesh_patches and reference_patches are pieces of the
  // two polylines (SamplePatch: the flat triangle (a, midpoint, b), area =
  // length), reference_vertex_error and reference_face_error stay NaN: the
  // outline's vertices carry outline_vertex_error instead.
  bool planar = false;
  Vec3 plane_normal;                         // the mesh's (planarity.h), unit
  SegmentSet reference_outline;              // the reference's boundary edges
  std::vector<double> outline_vertex_error;  // per reference_outline point; NaN off the outline

  std::vector<std::string> warnings;
};

// Computes the boundary error. Throws InputError (without a path; the caller
// prefixes it) when the reference has no triangle of positive area, or when
// the bounding boxes of the hex boundary and the reference do not overlap.
// A planar surface mesh is measured in its plane (BoundaryError::planar);
// then the reference must be planar and lie in the mesh's plane (within
// kPlanarTolerance of the larger diagonal), else InputError.
// Deterministic for any thread count (TBB inside).
BoundaryError compute_boundary_error(const HexMesh& mesh, const Topology& topo, const TriSurface& reference,
                                     const BoundaryOptions& options = {});

// compute_boundary_error()'s first checks alone (a reference with a triangle
// of positive area, the two bounding boxes overlapping), for a caller that
// starts other work on the reference first. Throws the same InputError.
void check_reference_placement(const HexMesh& mesh, const Topology& topo, const TriSurface& reference);

// The hex boundary quads split into two triangles each (diagonal 0-2), with
// the mesh's points (outward oriented as the topology's boundary faces). A
// surface mesh (issue 47): its quads split the same way, then its
// triangles, as oriented in the file.
TriSurface boundary_triangles(const HexMesh& mesh, const Topology& topo);

// The vertices whose distance to the reference is measured (vertex_error):
// a volume mesh's boundary vertices (topo.boundary_vertices); a surface
// mesh's vertices that a face uses, ascending (issue 47); a planar surface
// mesh's vertices on a boundary edge (one face), ascending.
std::vector<Index> measured_vertices(const HexMesh& mesh, const Topology& topo);

// A surface mesh's boundary edges (used by one face) as segments over its
// points: the boundary polylines of a planar mesh.
SegmentSet surface_boundary_segments(const std::vector<Vec3>& points, const SurfaceTopology& topology);

// Whether a mesh is measured in its plane: a planar surface mesh.
bool is_planar_surface(const HexMesh& mesh, const Topology& topo);

}  // namespace hq
