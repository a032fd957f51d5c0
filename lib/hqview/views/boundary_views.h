#pragma once
// Boundary error views (paper §G4): the hex boundary coloured by the signed
// distance to the reference (front and back), and the UV error map of the
// reference (its atlas filled with the interpolated reference -> hex
// boundary error, chart outlines drawn). Symmetric diverging scales.

#include <span>
#include <string>
#include <vector>

#include "hqview/boundary/boundary_error.h"
#include "hqview/image/image.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"
#include "hqview/uv/uv_atlas.h"

namespace hq {

struct BoundaryViewOptions {
  int width = 1600, height = 1200;
  std::string title;
  Rgba8 background{255, 255, 255, 255};
  Vec3 up{0.0, 0.0, 1.0};  // the model axis drawn upwards in the 3D views (--up)
  std::string mesh_word = "hex";  // the legend's "+ = hex outside"; "mesh" for a surface mesh
  bool orthographic = false;      // the error figures' camera (a planar mesh's, seen from above)
  int text_height = 0;            // > 0: the text sized as in a figure this tall (not `height`)
};

// The 98th percentile of |e| over the finite values of field (1 when there
// is none): the viewer's scale of the per-vertex boundary error.
double error_scale(const std::vector<double>& field);

// The one colour scale of every boundary view (boundary_error front/back,
// reference_error front/back, uv_error), half-range in model units: the
// area-weighted 98th percentile of |error| over the sampled patches of both
// directions (mesh_patches and reference_patches), so that a few large
// errors (a cut-off fin) do not wash the rest out; larger errors saturate
// (the bar's ends read "<=" / ">="). Never below 0.01% of the diagonal
// (smaller errors are noise); 1 when there is no patch.
double boundary_error_scale(const BoundaryError& error);

// The step of the colour bar's round ticks for a half-range top (> 0): the
// largest of 1, 2, 2.5, 5 x 10^k that is at most top / 2 (2 to 4 ticks a
// side). 1 when top is not positive and finite.
double nice_tick_step(double top);
// The legend: diverging map over [-100 s / d, +100 s / d] percent of the
// reference's diagonal d, each tick in % of the diagonal and in model units:
// the two ends (the scale's exact values, "<=" / ">=": larger errors are
// drawn in the end colour), 0 and the multiples of nice_tick_step(100 s / d)
// not within 8 % of an end.
ColorBar error_color_bar(double scale, double diagonal, std::string_view mesh_word = "hex");
// The marker of the boundary_error and reference_error views: a dark ring
// on a white halo with the value beside it, and a legend swatch.
inline constexpr Rgba8 kWorstMarkerColor{20, 20, 20, 255};
// The marker's label right of the ring (left when it would leave the view;
// above or below it when neither side has room), on a pale box, inside `view`.
void draw_worst_label(Image& figure, const PixelRect& view, double cx, double cy, double radius,
                      const std::string& label, const AnnotationStyle& style);
// Where the flat view's marker label goes: of the boxes (box_w x box_h
// pixels) on an 8 px grid inside `view`, clear of every data pixel (a dark
// casing, ring or text, or a saturated colour) and of the ring, the one
// nearest the ring whose nearest point lies within kLabelReach of the
// view's smaller side beyond the ring and, when it is not beside the ring
// (over 24 px beyond it), whose leader line from the ring's edge to that
// point crosses no data pixel (issue 47: on a turned plate a label 450 px
// below its ring had its leader across the square hole). When no box that
// near qualifies and far_ok: the nearest at any distance with a clear
// leader (near = false). found = false when none qualifies.
inline constexpr double kLabelReach = 0.2;
struct LabelPlace {
  bool found = false;
  int x = 0, y = 0;  // the box's top left
  bool leader = false;
  double leader_x = 0, leader_y = 0;  // the leader's end on the box
  bool near = false;  // within kLabelReach
};
LabelPlace place_label_in_empty_space(const Image& figure, const PixelRect& view, double cx, double cy, double radius,
                                      int box_w, int box_h, bool far_ok = false);
// The sample of largest |error| of one direction (the first on ties):
// patches in order (their centroid; normal = the patch's area normal), then
// points (e.g. boundary vertices, whose vertex errors the sampled maximum
// includes; normal = the sum of the area normals of the patches with that
// corner). Non-finite errors are skipped; found = false when none is left.
struct WorstError {
  Vec3 position;
  Vec3 normal;      // not unit; faces the camera when dot(normal, eye - position) >= 0
  double error = 0;  // signed, model units
  bool found = false;
  std::string note;  // appended to the marker's label (a planar mesh: which polyline it lies on)
  std::string what = "max |error|";  // the marker's label and legend line start with it
};
// sign 0: the largest |error|; +1: the largest error above 0 (the most
// outside); -1: the smallest below 0 (the most inside).
WorstError worst_error(const std::vector<BoundaryError::ErrorPatch>& patches, std::span<const Vec3> points,
                       std::span<const double> point_error, int sign = 0);
// worst_error over mesh_patches and the boundary vertices' vertex_error.
WorstError worst_mesh_error(const HexMesh& mesh, const Topology& topology, const BoundaryError& error);
// Where the parts of an error figure go: the style, the colour bar (with
// `swatches`, then the marker's swatch when worst.found), the layout and the
// camera fitted to points from view_direction (orthographic when
// options.orthographic).
struct ErrorFigureFrame {
  AnnotationStyle style;
  ColorBar bar;
  FigureLayout layout;
  Camera camera;
};
ErrorFigureFrame error_figure_frame(const std::vector<Vec3>& points, const BoundaryError& error, double scale,
                                   const WorstError& worst, const Vec3& view_direction,
                                   const BoundaryViewOptions& options, std::vector<ColorBarSwatch> swatches = {});

// The hex boundary's sampled patches (mesh_patches), each flat-coloured by
// diverging_color(error / scale) of its centre sample; boundary edges faint.
Scene build_boundary_error_scene(const HexMesh& mesh, const Topology& topology, const BoundaryError& error,
                                 double scale);

// The front (view_direction) or back (its opposite) figure, the marker on
// worst_mesh_error (dashed and "far side" when its sample faces away).
Image render_boundary_error_view(const HexMesh& mesh, const Topology& topology, const BoundaryError& error,
                                 const Vec3& view_direction, const BoundaryViewOptions& options, Renderer& renderer);

// The reference's sampled patches (reference_patches), each flat-coloured by
// its signed distance to the hex boundary (negative, "inside" blue, where the
// reference lies outside the hex solid: the parts the mesh cuts off).
Scene build_reference_error_scene(const BoundaryError& error, double scale);

// The reference error figure, one camera fitted to the reference, the marker
// on worst_error(reference_patches, reference.points, reference_vertex_error).
Image render_reference_error_view(const TriSurface& reference, const BoundaryError& error, const Vec3& view_direction,
                                  const BoundaryViewOptions& options, Renderer& renderer);

// F with --reference: the hex boundary (opaque light grey faces, dark edges)
// under the reference surface (translucent orange, flat shaded): reference
// parts the mesh leaves out show plain orange. Where the two surfaces coincide
// within depth precision the depth test picks either (grey speckles, not an
// error reading: the boundary_error views give the signed error). triangles[0] the hex boundary,
// lines[0] its edges, translucent[0] the reference.
inline constexpr Rgba8 kReferenceOverlayColor{235, 125, 35, 96};
Scene build_reference_overlay_scene(const HexMesh& mesh, const Topology& topology, const TriSurface& reference);

// One camera (view_direction) fitted to both the hex boundary and the reference.
Image render_reference_overlay(const HexMesh& mesh, const Topology& topology, const TriSurface& reference,
                               const Vec3& view_direction, const BoundaryViewOptions& options, Renderer& renderer);

// A planar mesh against a planar reference (BoundaryError::planar), seen
// from above along the plane's normal: triangles[0] the reference's domain
// (pale grey), lines[0] the mesh's edges (faint), lines[2] its boundary
// polylines (thick; each sampled piece coloured by its mesh -> reference
// error), lines[4] the reference's outline on top (thin; by its reference ->
// mesh error), lines[1] and [3] their dark casings (so that white, error 0,
// shows). Each layer lies a little nearer the camera than the last. With
// `pixel` (model units a pixel of the figure) > 0, triangles[1] draws
// lines[1] to [4] again as strokes of their width (unlit, at their
// heights): a band across each piece (a wide GL line on a diagonal is
// narrower) and a disc at both its ends, so corners and joins are round
// and show no notch.
Scene build_planar_boundary_error_scene(const HexMesh& mesh, const Topology& topology, const TriSurface& reference,
                                        const BoundaryError& error, double scale, double pixel = 0.0);
// The planar figure's lines in pixels: the mesh boundary's coloured core
// and the reference outline's, each on a dark casing kPlanarCasing wider
// (1.5 px each side); the mesh's edges 1 px.
inline constexpr float kPlanarBoundaryWidth = 9.0f, kPlanarOutlineWidth = 3.0f, kPlanarCasing = 3.0f;
inline constexpr Rgba8 kPlanarDomainColor{222, 222, 226, 255};
inline constexpr Rgba8 kPlanarCasingColor{55, 55, 65, 255};
inline constexpr Rgba8 kPlanarEdgeColor{60, 60, 70, 90};

// The larger |error| of the two directions: worst_error over mesh_patches
// and the boundary vertices, or over reference_patches and the outline's
// vertices (ties: the mesh's), noted with its polyline.
WorstError worst_planar_error(const HexMesh& mesh, const BoundaryError& error);

// The planar figure's marks: the largest error above 0 ("max outside")
// and the smallest below 0 ("max inside") over both polylines (ties: the
// mesh's), each noted with its polyline; a sign with no such error has none.
std::vector<WorstError> planar_extremes(const HexMesh& mesh, const BoundaryError& error);
// The planar figure's frame (orthographic, along the plane's normal; the
// shared colour bar, capped at a third of the height and drawn from the
// legend's top, with a swatch for each line as it is drawn, the mesh's
// edges and the domain, then a ring line per mark), its marks and its
// options: as wide as asked, no taller than the domain at that width needs
// (its margin above and below as wide as the one beside it, plus a label
// line's height each) or the title and legend need, the text sized for the height asked (issue 47: a 2 : 1
// domain left a 200 px empty band above it on boundary.html).
struct PlanarErrorFigure {
  ErrorFigureFrame frame;
  std::vector<WorstError> marks;
  BoundaryViewOptions options;
};
PlanarErrorFigure planar_error_figure(const HexMesh& mesh, const BoundaryError& error,
                                      const BoundaryViewOptions& options);

// The planar figure: planar_error_figure's frame, a ring and a label (in
// empty space) on each mark.
Image render_planar_boundary_error_view(const HexMesh& mesh, const Topology& topology, const TriSurface& reference,
                                        const BoundaryError& error, const BoundaryViewOptions& options,
                                        Renderer& renderer);

// The UV map as a flat scene in the z = 0 plane (u, v in [0, 1]):
// triangles[0] unlit, corners coloured by the reference error; lines[0] the
// chart outlines (triangle edges not shared with a triangle of the same chart).
Scene build_uv_error_scene(const TriSurface& reference, const UvAtlas& atlas, const std::vector<double>& point_error,
                           double scale);

// The orthographic camera that frames the unit UV square (with a 3 % margin)
// in a view of the given aspect (width / height), v up.
Camera uv_map_camera(double aspect);

Image render_uv_error_map(const TriSurface& reference, const UvAtlas& atlas, const BoundaryError& error,
                          const BoundaryViewOptions& options, Renderer& renderer);

}  // namespace hq
