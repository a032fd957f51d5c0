#pragma once
// What the views draw differently for a surface mesh (quads and triangles,
// no volume cell; docs/contract.md "Surface meshes"): which views exist, the
// camera of a planar mesh (seen along its normal), and view A's face fill
// (each face coloured by its cell scaled Jacobian in a few bins, each bin a
// legend entry). The faces themselves are the drawn "boundary"
// (mesh/surface_boundary.h).

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "hqview/analysis/analysis.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/image/color.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/topology.h"
#include "hqview/render/annotate.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"
#include "hqview/structure/quad_structure.h"

namespace hq {

// Lit faces keep most of their colour (TriangleSet::ambient): a shaded
// face's fill stays readable against its legend swatch or colour bar (view
// A's bins, view C's faces).
inline constexpr float kSurfaceFillAmbient = 0.7f;

// Whether view `id` (kViews) is drawn for a surface mesh: the overview, A,
// B, C (the cluster's faces), D (a vertex's faces and their corners), E,
// the histograms, the structure (its quad structure) and the thumbnail.
// The size gradation and the simulation views are not (yet).
bool is_surface_mesh_view(std::string_view id);

// The direction a planar surface mesh is seen along (eye towards the
// mesh): against the plane's normal, which the majority of the faces share
// (planarity.h), so that those faces face the camera. None when the mesh
// is not a planar surface mesh.
std::optional<Vec3> planar_view_direction(const Analysis& a);

// The main views of a curved surface mesh aim at faces, not glyphs (issue
// 47 part C: the bell's tied-worst reversed faces 40 and 41 were on the far
// side of view 1 and edge-on in view 2, under their glyph).
// A cluster's target faces (indices into boundary_polygons(topology)): the
// faces with a corner at one of its vertices whose cell scaled Jacobian
// (cell_quality, the lowest signed corner) is within kGlyphTieTolerance of
// the cluster's min quality, the faces that make it worst; none such: every
// face at its vertices.
std::vector<std::size_t> cluster_target_faces(const GlyphResult& glyphs, Index cluster,
                                              std::span<const BoundaryPolygon> faces,
                                              std::span<const double> cell_quality);
// The clusters aimed at: #0 to #kSurfaceViewTargets-1 (the coloured ranks).
inline constexpr int kSurfaceViewTargets = 3;
// The model's axis from its points' covariance: the eigenvector of the
// eigenvalue farther from the middle one (the longest axis of a vase, the
// shortest of a bell or a dish: a body of revolution's axis), none when it
// is within kAxisGap of the largest eigenvalue from the middle one (a
// ball, a cube, a kitten: no axis to avoid) or the points span no volume.
inline constexpr double kAxisGap = 0.15;
std::optional<Vec3> model_axis(std::span<const Vec3> points);
// A surface of revolution's axis: model_axis when the two other eigenvalues
// are alike (within kRevolutionAlike of the larger: the cross-section a
// circle, as a bowl's, a bell's, a vase's), else none (a kitten, a bar).
inline constexpr double kRevolutionAlike = 0.05;
std::optional<Vec3> revolution_axis(std::span<const Vec3> points);
// The up axis of a curved surface mesh's views under --up auto (a surface
// has no resting pose: resting_up.h needs a solid): the revolution_axis of
// the vertices its faces use, so a bowl or a bell turned in its file stands
// upright on screen (the 47d review: a bowl lay on its side like a dish, a
// bell leant 35-40 degrees); `up` for any other mesh, planar ones too.
// Its sign: towards the open end, the half of the axis's extent (split at
// its middle) holding at least kOpenEndShare of the boundary edges' length
// (by their midpoints), so a cup, a bowl, a vase or a goblet stands rim up
// however its file turns it (the 47f review: a goblet turned 115 degrees
// stood stem up), and so does a bell (its mouth is its open end); else
// (closed, or open at both ends alike: a tube) it agrees with `up` (the
// file's +z; an axis across it: its largest component positive).
inline constexpr double kOpenEndShare = 0.75;
Vec3 surface_view_up(const HexMesh& mesh, const Topology& topology, const Vec3& up);
// View 1's eye at least this far off that axis: seen along it a body of
// revolution is concentric rings (a disc, a funnel), its profile lost.
inline constexpr double kOffAxisDegrees = 45.0;
// #0's faces at least half their best projected area (f_0 below).
inline constexpr double kRecognisableFraction = 0.5;
// #0's faces in sight enough for an eye above the horizon to be taken
// before any below it (f_0 below).
inline constexpr double kInSightFraction = 0.25;
// Candidates: the upright ones (upright_view_candidates), the views from the
// horizon and below (below_view_candidates), and along each target's mean
// face normal (its faces' normals turned to agree with its largest face's,
// area-weighted), from either side: a surface has two sides and a reversed
// face is seen from either. Each candidate, through the main view's
// orthographic camera (fit_camera_to_points on points), scores per target
// cluster the projected area of its faces in sight (FaceDepthGrid against
// every face: each corner sample in sight counts a quarter of its face's
// projected area); f_k = that over the largest any candidate gives it.
// View 1 shows #0's faces with the model recognisable: the candidates are
// taken in tiers, the first tier with one: above the horizon and at least
// kOffAxisDegrees off model_axis (either sign), f_0 >= kNearBestFraction;
// the same with f_0 >= kRecognisableFraction; above the horizon (any
// axis), f_0 >= kNearBestFraction, then >= kRecognisableFraction; above
// the horizon with f_0 >= kInSightFraction, off the axis then any; off the
// axis (below too), f_0 >= kNearBestFraction then >= kRecognisableFraction;
// then any with f_0 >= kNearBestFraction.
// Within the tier, the first (upright ones first) whose sum of the other
// targets' f_k is at least kNearBestFraction of the largest such sum. View 2 shows what view 1
// shows least: the same near-best rule on the sum of (1 - f_k(view 1) +
// 0.1) f_k, among the candidates at least 90 degrees of azimuth away from
// view 1 when one of them scores. Either view from an eye below the
// horizon only when no eye above it is allowed and scores.
// No target face in sight from anywhere (no glyph): choose_main_viewpoints.
std::vector<Vec3> choose_surface_main_viewpoints(const HexMesh& mesh, const Topology& topology,
                                                 const GlyphResult& glyphs, std::span<const double> cell_quality,
                                                 std::span<const Vec3> points, double aspect, int count,
                                                 const Vec3& up, double fov_y_degrees = 30.0);

// View A's face fill bins of a face's cell scaled Jacobian q (the lowest
// signed corner): inverted (q <= 0) in the inverted colour, then (0, 0.3],
// (0.3, 0.6], (0.6, 0.9], (0.9, 1] dark red, orange-red, pale orange and
// near-white (a ramp stepping in lightness: a 0.3-0.6 face stands out),
// degenerate (Verdict's sentinel) or NaN in the undefined grey. Lit (a
// curved mesh) with ambient 0.7, so a shaded face keeps its bin's hue.
Rgba8 surface_fill_color(double q);

// The faces of boundary_polygons(topology), each flat in
// surface_fill_color(cell_quality[face.cell]); positions relative to origin.
// The cells of `inverted` (Analysis inverted cells: on a curved mesh the
// reversed faces, negative since issue 47p) take the inverted bin whatever
// their value.
// `reversed` as for surface_fill_legend_lines.
TriangleSet surface_fill_faces(const HexMesh& mesh, const Topology& topology, const std::vector<double>& cell_quality,
                               const Vec3& origin, std::span<const Index> inverted = {}, bool reversed = false);

// The legend lines of the fill: a heading of two lines and one swatch per
// bin with its count, empty bins too, in the bins' order; "degenerate: N"
// when a face has no value.
// The inverted bin reads "inverted or reversed" when a cell of `inverted`
// has a positive value (a reversed face given with its unsigned value).
// With `reversed` (a curved surface, whose inverted cells are exactly its
// reversed faces: orientation flipped against their neighbours; issue 47
// part F) the first bin holds those faces alone and
// reads "reversed: N" over a line "  (orientation flipped)"; a face with q <= 0 that is not
// reversed (a concave quad) falls in the next bin, which reads "up to 0.3".
std::vector<LegendLine> surface_fill_legend_lines(const std::vector<double>& cell_quality,
                                                  std::span<const Index> inverted = {}, bool reversed = false);

// The structure view of a surface mesh (`structure`, panel S): the faces
// tinted by patch (8 pale tints, repeating), the edges faint, the mesh
// boundary 2 px in kSurfaceBoundaryEdgeColor, the separatrices as dark
// 3-pixel lines (at 1200 pixels of height) over it, each
// irregular vertex a sphere in its class's colour (the hex structure view's
// Okabe-Ito palette: interior valence 3 blue, 5 vermillion, 6+ reddish
// purple, 1-2 sky blue; boundary below its ideal valence bluish green,
// above orange), radius 0.3 of the mean edge length and at least 0.6% of
// the bounding-box diagonal. Orthographic, along view_direction, `up`
// upright; lit unless is_lit is false (a planar mesh seen along its
// normal). The legend gives each class with its count (all six, zeros too,
// when any vertex is irregular), the separatrices with their edges' share
// of all edges, the patches with their mean size in quads ("not
// simplified": on an unstructured mesh a patch is a quad or two), the
// unclassified vertices, the boundary and the edges.
// The structure view's mesh boundary (its outline and holes, edges used by
// one face): it bounds patches as the separatrices do, drawn 2 px in this
// blue-grey, apart from the separatrices' near-black, with a legend entry.
inline constexpr Rgba8 kSurfaceBoundaryEdgeColor{70, 90, 125, 255};

struct QuadStructureViewOptions {
  int width = 1600, height = 1200;
  std::string title;
  Vec3 up{0.0, 0.0, 1.0};
  bool is_lit = true;
};
Image render_quad_structure_view(const HexMesh& mesh, const Topology& topology, const QuadStructure& structure,
                                 double mean_edge_length, const Vec3& view_direction,
                                 const QuadStructureViewOptions& options, Renderer& renderer);

// The colour of an irregular vertex of valence `valence` (ideal `ideal`, 4
// inside) and its legend text.
Rgba8 irregular_vertex_color(Index valence, int ideal, bool is_boundary);

}  // namespace hq
