#pragma once
// View A, the main view (paper §G1, §G2), orthographic so that glyph sizes
// compare across depth: the boundary wireframe, the edges
// of each glyph cluster in its cluster colour, one aggregated glyph per
// cluster sized by its ratio, arrows on overlap markers and the intersecting
// cells translucent. Shown from the viewpoints (among 26 axis and diagonal
// directions) that show the most glyph area.

#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hqview/glyph/glyph_ties.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/image/image.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/overlap.h"
#include "hqview/quality/quality_field.h"
#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/id_image.h"
#include "hqview/render/label_layout.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"
#include "hqview/render/upright.h"

namespace hq {

// Colours of view A's elements (fixed, documented in the legend).
inline constexpr Rgba8 kWireframeColor{120, 124, 134, 255};
// A surface mesh's edges in view A: darker, over its filled faces (the
// volume meshes' grey all but vanished on the near-white 0.9-1 faces; issue
// 47 part F). Their width stays the wireframe's: wider lines at the plane
// hid the thin parts of a folded quad that its neighbours overlap.
inline constexpr Rgba8 kSurfaceEdgeColor{62, 66, 76, 255};
// Coincident vertices: a green #00cc33. Intersections: a lilac #cc88ff for
// the pairs' arrows and the cells' edges, the cells' faces a translucent
// tint of it (the legend gives the pairs an arrow swatch, the cells a
// square of the tint as drawn on the background: two things, two
// swatches). Both CIEDE2000 >= 20 from the cluster colours, the pale grey
// and each other for normal vision, and >= 8 from the cluster colours
// under simulated protanopia, deuteranopia and tritanopia, away from the
// quality map, the rings' greys and the cell kinds' edges
// (image/colormap.cpp, tests/views/palette_test.cpp; the colours they
// replaced: CHANGELOG, issue 44).
inline constexpr Rgba8 kCoincidentArrowColor{0, 204, 51, 255};
inline constexpr Rgba8 kIntersectionArrowColor{204, 136, 255, 255};
inline constexpr Rgba8 kIntersectingCellColor{204, 136, 255, 96};  // translucent lilac
// The band around cluster #0's glyph, inside its dark ring (issue 44 part
// C, the 44r review: the crimson #0 is a neutral dark grey to protanopes,
// L* 39 with chroma 4, darker than the grey "others"): a bright yellow
// #ffdd00 whose lightness (CIE L* 86-90) and, but for tritanopia (where the
// crimson keeps chroma 94), chroma (>= 85) survive every Machado 2009
// simulation, so #0 reads as a dark or red disc in a yellow-and-black ring
// for every reader (docs/analysis.md, "Colours": the table per vision).
inline constexpr Rgba8 kWorstBandColor{255, 221, 0, 255};
// top (straight alpha) drawn over an opaque bottom, per sRGB channel as the
// renderer blends: what a translucent colour looks like on it (the
// intersecting cells' legend swatch).
inline Rgba8 blend_over(const Rgba8& top, const Rgba8& bottom) {
  auto channel = [&](std::uint8_t t, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround((t * top.a + b * (255 - top.a)) / 255.0));
  };
  return {channel(top.r, bottom.r), channel(top.g, bottom.g), channel(top.b, bottom.b), 255};
}

// The edge colour of each volume kind where the views tell kinds apart (view
// A's boundary wireframe, view D's one ring): hexes a near-black aubergine
// #220033, tets dark blue #000099, wedges olive #668800, pyramids dusty
// rose #bb6688 (issue 44 part P, the 46r review's M3: the charcoal hex was
// the coincident near-black, the violet pyramid the intersection magenta).
// Each is CIEDE2000 >= 12.9 from the other kinds and from every colour of
// view A's legend but the cluster colours (pale grey, rings, overlap
// colours, the non-conforming brown) for normal vision and under
// protanopia, deuteranopia and tritanopia; from the 5 cluster colours >= 15
// for normal vision and >= 8 simulated (the critical-pair bound: no
// 4 edge colours keep 12.9 from all of them, 12.3 at best), and more
// than 60 apart in RGB from the quality map, the inverted and undefined
// colours, the pure-hex wireframe grey and the non-conforming brown; with a
// swatch per kind present.
Rgba8 cell_kind_edge_color(CellKind kind);
inline constexpr std::size_t kMaxInteriorPyramids = 50000;
// The legend swatches of a "cells: 64 hex, 484 tet, 16 pyramid" text
// (mesh_kinds_text): one per kind named, "64 hex" in its edge colour.
std::vector<std::pair<Rgba8, std::string>> cell_kind_swatches(std::string_view cell_kinds);

struct MainViewOptions {
  int width = 1600;  // figure size in pixels, legend and title included
  int height = 1200;
  std::string title;  // empty: no title band
  Rgba8 background{255, 255, 255, 255};
  float wire_width = 1.0f;            // boundary edges, output pixels
  float cluster_edge_width = 2.5f;    // cluster edges, output pixels
  // Cluster edges are drawn around this many of each cluster's worst vertices.
  int cluster_edge_vertices = 48;
  double arrow_pixels = 70.0;         // arrow length on screen (at the marker's depth)
  double arrow_start_degrees = 45.0;  // first arrow's angle in the image plane (deterministic)
  int max_arrows_per_marker = 12;
  // Markers of one kind closer on screen are drawn as one (an arrow and a
  // head's length: nearer fans' arrows interleaved, the 44e review).
  double marker_merge_pixels = 100.0;
  // At most this many marker groups (one arrow fan and one count label
  // each): the merge distance grows by half until the groups are this few.
  int max_marker_groups = 12;
  double pixel_scale = 1.0;           // multiplies the arrow sizes and marker_merge_pixels; render_main_view
                                      // sets it to the figure's annotation scale (height / 1200)
  double fov_y_degrees = 30.0;
  Vec3 up{0.0, 0.0, 1.0};  // the model axis drawn upwards (--up)
  // A legend line naming the mesh's cell kinds ("cells: 64 hex, 484 tet,
  // 16 pyramid", mesh_kinds_text); empty (pure-hex meshes): no line.
  std::string cell_kinds;
  // The mesh's cells in the legend's counts ("inverted hexes: N"): "hex",
  // or "cell" on a mesh with other volume cells (views.cpp cell_noun).
  std::string cell_noun = "hex";
  // A legend line for a mesh whose cells are mostly inverted
  // (mostly_inverted_note); empty: none.
  std::string orientation_note;
  // A surface mesh: its faces filled by their cell scaled Jacobian in bins
  // (surface_views.h), with the bins in the legend; null: no fill (volume
  // meshes: the boundary wireframe only). Lit unless surface_fill_lit is
  // false (a planar mesh seen along its normal: the bins' colours exactly).
  const std::vector<double>* surface_cell_quality = nullptr;
  // Its inverted cells (the fill's inverted bin whatever their value); not
  // owned.
  std::span<const Index> surface_inverted_cells;
  // A curved surface: those cells are its reversed faces (orientation
  // flipped against their neighbours), the fill's first bin says so
  // (surface_fill_legend_lines' `reversed`).
  bool surface_inverted_are_reversed = false;
  bool surface_fill_lit = true;
  // The on-screen diagonal (pixels, the 3D area) of the model's bounding
  // box as the view's camera projects it (render_main_view sets it; issue
  // 44 part U): the glyph radius cap's screen term
  // (displayed_glyph_scale). 0: no screen term.
  double model_diagonal_pixels = 0.0;
  // Per volume cell (or surface face) whether it is inverted
  // (cell_is_inverted), or null: the boundary faces of inverted cells that
  // show from the camera are drawn in the inverted colour (scene 5b, issue
  // 44 part U) unless more than half of the cells are inverted
  // (orientation_note says so) or there are more than
  // kMaxInvertedOverlayFaces such faces (a volume mesh:
  // kMaxInvertedOverlayVolumeFaces; dolphin_rot's 759 would turn it blue).
  const std::vector<std::uint8_t>* inverted_cells = nullptr;
  // What main_view_frame found (inverted_boundary_faces) for the legend:
  // the faces drawn, the inverted cells, their boundary faces. A volume
  // mesh's legend says "inverted cells: N", then "  all F boundary faces
  // drawn" / "  (see-through, as glyphs)", "  their F boundary faces" /
  // "  not drawn (more than 64)" over the limit, or "  none on the
  // boundary".
  std::size_t inverted_overlay_faces = 0;
  std::size_t inverted_cell_count = 0;
  std::size_t inverted_face_count = 0;
  // A surface mesh's inverted faces, which no label box covers (the 47r
  // review: "#2 (8)" sat on half a reversed face): each a disc about its
  // centre of radius its centre's distance to its nearest edge midpoint
  // (main_view_frame sets them when it draws at most
  // kMaxLabelFreeFaces; leaders may cross them).
  std::vector<Vec3> label_free_centres;
  std::vector<double> label_free_radii;
  // A surface mesh's glyphs on the far side of the surface from this view
  // (their centre behind a face: FaceDepthGrid), per cluster, 1 = far
  // (main_view_frame sets it): drawn pale (kFarSideGlyphPale of the way to
  // white), their label says "far side", the legend "pale: glyph on the
  // far side" (the 47r review: a glyph shown through the bell was read as
  // marking the perfect faces in front of it).
  std::vector<char> far_side_glyphs;
  // glyph_tie_classes(glyphs.clusters), per cluster: computed once for all
  // of a mesh's main views (issue 44 part V: it was computed 5 times a
  // view); empty: render_main_view and main_view_labels compute it once
  // and pass it down. Not owned.
  std::span<const Index> glyph_ties;
  // The glyph scale of all of a mesh's main views (mesh_glyph_scale; issue
  // 44 part V: each view scaled its own, so one cluster was drawn at two
  // world radii); 0: each view its own (displayed_glyph_scale).
  double glyph_scale = 0.0;
};
inline constexpr std::size_t kMaxInvertedOverlayFaces = 20000, kMaxInvertedOverlayVolumeFaces = 64;
inline constexpr std::size_t kMaxLabelFreeFaces = 200;
inline constexpr double kFarSideGlyphPale = 0.6;

// "inverted: 1200 of 1200 cells" when more than half of the volume cells
// are inverted (cell_is_inverted): a mirrored mesh, or one with reversed
// node order, whose glyphs then mark every cell, not a local defect; the
// legend says so (issue 44's fifth round). Empty otherwise.
std::string mostly_inverted_note(const QualityField& quality);

// The fraction of an aspect-sized image covered by the union of the spheres
// seen through camera (rasterised on a grid of about 40k cells). Spheres
// behind the eye are skipped.
double glyph_coverage(std::span<const Vec3> centers, std::span<const double> radii, const Camera& camera,
                      double aspect);

// The points a main view frames: the boundary vertices, and the 6 axis
// extremes of each aggregated glyph.
std::vector<Vec3> main_view_points(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs);

// The count view directions whose orthographic camera (fit_camera_to_points
// on points, the model's up axis up) shows the largest visible area (in model
// units: glyph_coverage times the view's area) of the aggregated glyphs,
// best first; ties keep candidate order. Candidates are the upright ones
// (upright_view_candidates: 12 azimuths at 15-35 degrees of elevation); the
// views from the horizon and below (below_view_candidates) only when no
// upright one shows a glyph. Each further view is at least 90 degrees of
// azimuth away from the earlier ones when such a candidate exists. Without
// glyphs (or none visible): the three-quarter view and the one behind it.
std::vector<Vec3> choose_main_viewpoints(std::span<const Vec3> points, const GlyphResult& glyphs, double aspect,
                                         int count, const Vec3& up, double fov_y_degrees = 30.0);

// A further view is no copy of a chosen one (issue 44 part U: the twisted
// cross, 4-fold symmetric, looked the same from azimuth 30 and 210): a
// candidate whose view_signature has view_signature_similarity >=
// kSameViewSimilarity with a chosen view's is skipped; when every
// candidate is such a copy, the next view looks from kHighViewElevation
// degrees at the first view's azimuth.
inline constexpr int kViewSignatureWidth = 96, kViewSignatureHeight = 72;
inline constexpr double kSameViewSimilarity = 0.9;
inline constexpr double kHighViewElevation = 70.0;
// Two masks of kViewSignatureWidth x kViewSignatureHeight cells over the
// framed orthographic view along direction (fit_camera_to_points),
// row-major, 1 = covered: the cells of the points, then the cells of the
// sphere discs.
std::vector<std::uint8_t> view_signature(std::span<const Vec3> points, std::span<const Vec3> centers,
                                         std::span<const double> radii, const Vec3& direction, double aspect,
                                         const Vec3& up, double fov_y_degrees = 30.0);
// The smaller of the two masks' intersection over union (1 for two empty
// masks): a view of another outline, or with the glyphs elsewhere, differs;
// the larger of that and the same with b mirrored left to right (a plate
// seen face-on from its other side, the twisted star: the wireframe hides
// no glyph, so that view is the first's mirror image).
double view_signature_similarity(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b);

// The same choice for any spheres (centres, radii).
std::vector<Vec3> choose_viewpoints(std::span<const Vec3> points, std::span<const Vec3> centers,
                                    std::span<const double> radii, double aspect, int count, const Vec3& up,
                                    double fov_y_degrees = 30.0);

// Overlap markers as view A draws them. Arrows of markers a few pixels apart
// tangle into an unreadable knot, so markers closer on screen than
// min_pixels are merged: markers are taken in report order, each joins the
// first drawn marker of its own kind (in creation order) whose anchor is
// strictly closer than min_pixels on screen, else it becomes a new drawn
// marker anchored at its own position. Drawn markers of one kind are
// therefore at least min_pixels apart; a drawn marker counts one kind only
// (coincident vertices or intersecting pairs), so its label can wear that
// kind's colour and the labels of a kind add up to that kind's findings.
struct ScreenMarker {
  Vec3 position;         // the first member's position (the anchor)
  Index coincident = 0;  // findings of the members, by kind
  Index intersections = 0;
  Index members = 0;  // markers merged into this one
  Index count() const { return coincident + intersections; }
  MarkerKind kind = MarkerKind::coincident;  // every member's kind (markers of one kind only are merged)
};
std::vector<ScreenMarker> merge_markers_on_screen(std::span<const OverlapMarker> markers, const Camera& camera,
                                                  int view_height, double min_pixels);

// The marker groups view A draws: merge_markers_on_screen with min_pixels,
// then with 1.5 times that (1 pixel after 0), and so on, until there are at
// most max_groups (>= 1; >= 2 when both kinds occur). Every finding is in one group: the groups' count() sum to the
// markers' findings (a marker counts max(count, 1)).
std::vector<ScreenMarker> group_markers_on_screen(std::span<const OverlapMarker> markers, const Camera& camera,
                                                  int view_height, double min_pixels, int max_groups);

// View A's scene for a camera (arrows are laid out in its image plane and
// sized for an image view_height pixels high):
//   lines[0]     unique boundary edges, kWireframeColor;
//   lines[1]     every mesh edge (of any cell kind) with an endpoint among
//                the options.cluster_edge_vertices worst vertices (largest
//                glyph radius) of a coloured cluster (worst_cluster_vertices),
//                in that cluster's colour (cluster_color(rank, K); the lower
//                rank when both endpoints are marked), drawn under the
//                coloured glyphs (LineSet::under_ranked_spheres, as lines[0]);
//   lines[2]     edges of intersecting cells, kIntersectionArrowColor,
//                under the coloured glyphs (as lines[0]);
//   spheres[0]   the grey aggregated glyphs (pale), spheres[1] the coloured
//                ones (drawn over them and over the translucent faces:
//                over_translucent), spheres[2] the grey ones of min
//                quality < kUnfadedGlyphQuality (not pale): one per cluster,
//                radius as displayed_glyph_radii, colour = its cluster colour;
//   overlay[0]   arrows, over everything (a marker inside a glyph still
//                shows its arrows): per marker group (group_markers_on_screen
//                with options.marker_merge_pixels and max_marker_groups)
//                n = min(count, max) arrows whose tips point at the group's
//                anchor, spread every 360/n degrees, coincident ones first
//                (their share of n, at least one). The worst cluster's glyph
//                is never covered: an arrow whose shaft would cross its disc
//                on screen is left out (when all would, one arrow comes from
//                the side away from the glyph), and the arrows of an anchor
//                inside the disc start at the disc's edge;
//   translucent[0] the faces of the intersecting cells;
//   triangles[last] when inverted_boundary_faces(...).drawn is not empty:
//                those faces, unlit, in the inverted colour (a surface
//                mesh: its fill bin's, the same), lifted kInvertedFaceLift
//                towards the camera, depth-tested (under the ranked
//                glyphs, which keep their colour), with their edges in
//                kWireframeColor (lines[last], lifted alike, under the
//                coloured glyphs);
//   lines[3]     on a mesh of several kinds with 1 to kMaxInteriorPyramids
//                pyramids: the pyramids' edges that are not boundary edges,
//                in cell_kind_edge_color(pyramid) (the interface the
//                pyramids make between hexes and tets, inside the mesh).
// overlap may be null (no arrows, no intersecting cells).
// 1 for the per_cluster worst members (largest glyph radius, then lowest
// id) of every coloured cluster (the first labelled_cluster_count(K)
// ranks), per mesh vertex.
// ties: glyph_tie_classes(glyphs.clusters), or empty (computed here).
std::vector<std::uint8_t> worst_cluster_vertices(const GlyphResult& glyphs, int per_cluster,
                                                 std::span<const Index> ties = {});

// The boundary faces (boundary_polygons order) of the cells
// options.inverted_cells marks, as view A draws them (scene 5b): none when
// options.inverted_cells is null or more than half of the cells are
// inverted (options.orientation_note is set); none drawn (over_limit) when
// there are more than kMaxInvertedOverlayFaces (a volume mesh:
// kMaxInvertedOverlayVolumeFaces) of them. One depth rule for view A (issue
// 44 part V): a volume mesh is drawn as a see-through wireframe whose
// glyphs show near and far, so all of these faces are drawn, near and far
// side alike (part U round 2 hid the far ones while far glyphs showed); a
// surface mesh is drawn filled, and depth hides its far side, faces and
// glyphs alike.
struct InvertedFaces {
  std::vector<BoundaryPolygon> drawn;
  std::size_t cells = 0;   // inverted cells
  std::size_t faces = 0;   // their boundary faces
  bool over_limit = false;
};
InvertedFaces inverted_boundary_faces(const Topology& topology, const MainViewOptions& options);
// How far (a fraction of the model's bounding box diagonal) scene 5b moves
// the inverted faces towards the camera.
inline constexpr double kInvertedFaceLift = 2e-3;
// render_main_view draws those faces' outlines over the glyphs that hide
// them (issue 44 part V: an inverted face stays in sight), this wide (px
// at 1200 px height), in the face's colour, except within this share of a
// coloured glyph's radius from its centre (the vertex it marks).
inline constexpr double kInvertedOutlineWidth = 2.0, kInvertedOutlineCore = 0.5;

// inverted: inverted_boundary_faces(topology, options) when the caller has
// it (plan_main_view walks the boundary once a view); null: computed here.
Scene build_main_scene(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                       const OverlapReport* overlap, const Camera& camera, int view_height,
                       const MainViewOptions& options, const InvertedFaces* inverted = nullptr);

// How view A draws the glyphs (issue 44: on a long model a glyph of one
// mean edge is 10-15 pixels and cluster #0 does not stand out). Every
// aggregated glyph is drawn scale times its radius, scale the smallest
// factor >= 1 that makes cluster #0 at least kWorstGlyphMinPixels pixels
// in radius (times pixel_scale: 1 at a 1200-pixel-high figure), so the
// radii keep their ratios (size = severity) and #0 is the largest. The grey
// (unlabelled) clusters keep their severity radius too (issue 44 part T:
// before, they were drawn 0.6 of it, so a grey glyph as bad as a coloured
// one looked milder); they are de-emphasised by lightness instead
// (kGreyGlyphPale) and thinned on screen (main_view_glyphs_drawn).
// report.json keeps the radii.
inline constexpr double kWorstGlyphMinPixels = 24.0;
// And from above (issue 44 part U: the Gmsh star's and the mirrored
// kitten's glyphs buried the model): the scale is the largest factor <= 1
// (below the floor's) that keeps #0's drawn radius at most
// kWorstGlyphMaxEdges mean edge lengths (rmax / options.rmax under the
// default rmax unit) and at most kWorstGlyphMaxDiagonal of the model's
// on-screen diagonal (MainViewOptions::model_diagonal_pixels), but never
// below the floor: #0's radius in pixels is
// clamp(natural, floor, max(floor, cap)). The legend says "#0 radius N px".
inline constexpr double kWorstGlyphMaxEdges = 1.0;
inline constexpr double kWorstGlyphMaxDiagonal = 0.03;
// On a surface mesh the faces are the finding (issue 47 part R: the bell's
// 6 reversed faces hid under glyphs of one mean edge; part C: every surface
// mesh, curved or planar, with inverted faces or not, its worst faces
// filled by their bin; the planar L-shape's fold lay under a glyph of one
// mean edge): #0 at most kSurfaceInvertedGlyphMaxEdges mean edges and
// at least kSurfaceInvertedGlyphMinPixels, so most of each face shows; the
// legend says "  0.3 mean edge and 3% of" / "  model size, so faces show".
inline constexpr double kSurfaceInvertedGlyphMaxEdges = 0.3;
inline constexpr double kSurfaceInvertedGlyphMinPixels = 12.0;
// #0's drawn radius limits of a main view: the floor in pixels (at scale 1)
// and the cap in mean edges (the surface mesh's above, or the defaults).
struct GlyphSizeLimits {
  double min_pixels = kWorstGlyphMinPixels;
  double max_edges = kWorstGlyphMaxEdges;
};
// The grey glyphs' lit colour is mixed this far towards white (SphereSet::pale).
inline constexpr float kGreyGlyphPale = 0.45f;
// The colour of a grey glyph's lit side as drawn (the legend's swatch).
Rgba8 pale_grey_glyph_color();
// The same mixed pale towards white (0: the unfaded grey).
Rgba8 grey_glyph_color(float pale);
// Grey glyphs of min quality below this (inverted, or about 0: degenerate
// cells) are not faded (issue 44 part U: the bunny's ~0 clusters and the
// kitten's -0.95 ones read as "don't care"): scene spheres[2], unpaled,
// and a legend line "N others: a to b" of their own (an unfaded swatch).
inline constexpr double kUnfadedGlyphQuality = 0.01;
bool is_faded_grey_glyph(const AggregatedGlyph& g);
double displayed_glyph_scale(const GlyphResult& glyphs, const Camera& camera, int view_height, double pixel_scale,
                             double model_diagonal_pixels = 0.0, const GlyphSizeLimits& limits = {});
// One glyph scale for all the main views along directions (issue 44 part
// V): displayed_glyph_scale's rule with the floor the largest any view
// needs and the cap the smallest any view allows (the floor wins), so a
// cluster has one radius in model units in every view of its mesh.
// The limits of options' view: a surface mesh with inverted faces
// (options.surface_inverted_cells) gets the surface ones.
GlyphSizeLimits glyph_size_limits(const MainViewOptions& options);
double mesh_glyph_scale(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                        std::span<const Vec3> directions, const MainViewOptions& options);
// The boundary bounding box's on-screen diagonal in pixels (the 8 corners
// projected through camera into a view view_width x view_height).
double model_diagonal_pixels(const HexMesh& mesh, const Topology& topology, const Camera& camera, int view_width,
                             int view_height);
// The drawn radius of each cluster (by rank), model units.
std::vector<double> displayed_glyph_radii(const GlyphResult& glyphs, double scale);

// Which glyphs view A draws (issue 44 part T: heaps of grey glyphs made the
// Gmsh star, the mirrored kitten and the Dolphin's fin unrecognisable).
// Ranks are visited worst first; the first glyph of each coloured tie class
// (glyph_tie_classes; classes below labelled_cluster_count(K), the labelled
// ones) is always drawn; any other glyph (a tied member of a coloured class
// or a grey one) is left out when at least kThinnedCoverage of its disc on
// screen (drawn radius, image plane of camera, pixels) lies inside the discs
// of glyphs already drawn, i.e. of worse or equally bad ones. The coverage
// is measured on kThinSamples points spread evenly over the disc (Vogel's
// sunflower pattern). Pure; linear in the glyphs for bounded crowding.
inline constexpr double kThinnedCoverage = 0.5;
inline constexpr int kThinSamples = 32;
struct GlyphsDrawn {
  std::vector<Index> tie_class;      // per cluster, glyph_tie_classes
  std::vector<std::uint8_t> drawn;   // per cluster: 1 drawn, 0 left out
  Index num_left_out = 0;            // glyphs with radius > 0 left out
  Index num_left_out_coloured = 0;   // of those, tied members of a coloured class
  Index coloured_classes = 0;        // coloured_tie_classes: the classes in colour
};
// ties: glyph_tie_classes(glyphs.clusters), or empty (computed here).
GlyphsDrawn main_view_glyphs_drawn(const GlyphResult& glyphs, const Camera& camera, int view_height,
                                   std::span<const double> drawn_radii, std::span<const Index> ties = {});

// The lines of view A's legend (draw_legend): the clusters, the size rule,
// the rings (ring swatches: #0's dark ring in style.text_color, the
// inverted ring), the findings and the boundary edges; glyph_scale as
// displayed_glyph_scale.
// A cluster in hidden (MainViewLabels::hidden_clusters) reads "…, hidden",
// one in unlabelled (MainViewLabels::unlabelled_clusters) "…, no label
// room"; left_out: MainViewLabels::left_out_glyphs; worst_pixels: #0's
// drawn radius in figure pixels (MainViewLabels::worst_glyph), said in the
// lines "glyph radius ∝ 1 - min quality", "#0 radius N px" (always when
// known) and, when s != 1, why all glyphs are drawn x s: "  all shrunk xs:
// #0 at most" / "  1 mean edge, 3% of model size" (kWorstGlyphMaxEdges,
// kWorstGlyphMaxDiagonal) or "  all enlarged xs: #0 at" / "  least 24 px
// (at 1600 x 1200)" (kWorstGlyphMinPixels).
std::vector<LegendLine> main_legend_lines(const GlyphResult& glyphs, const OverlapReport* overlap,
                                          const AnnotationStyle& style, const MainViewOptions& options,
                                          double glyph_scale, std::span<const Index> hidden = {},
                                          Index left_out = 0, std::span<const Index> unlabelled = {},
                                          double worst_pixels = 0.0,
                                          std::span<const Rgba8> outlines_over_glyphs = {},
                                          bool cluster_edges_seen = true);

// Width / height of the 3D part of the figure render_main_view draws.
double main_view_aspect(const MainViewOptions& options);

// A label of view A, in figure pixels.
struct MainViewLabel {
  enum class Kind { cluster, marker };
  Kind kind = Kind::cluster;
  std::string text;          // "#k (n)": rank and member count; "xN": findings of a marker group
  Index cluster = kNoIndex;  // the cluster's rank (cluster labels)
  // Its leader crosses no glyph ranked before this (cluster labels): its
  // own rank, or for a tie one past its class's last rank (issue 44 part U:
  // no leader over another tied glyph).
  Index protect_end = 0;
  Index count = 0;           // findings (marker labels)
  Rgba8 color;               // text colour
  ScreenDisc anchor;         // the glyph's disc, or a 3-pixel disc at the marker group's position
  // Where its leader starts (inside its glyph's visible pixels; none: the
  // anchor's edge) and whether it always has one (its glyph mostly hidden).
  std::optional<ScreenDisc> leader_from;
  bool always_leader = false;
  // In a margin callout (issue 44 part V): it had no clear place near its glyph.
  bool is_callout = false;
  PlacedLabel placement;
};
struct MainViewLabels {
  std::vector<MainViewLabel> labels;
  ScreenDisc worst_glyph;      // cluster #0 on screen (radius 0 without glyphs)
  Index omitted_clusters = 0;  // cluster labels with no free place (left out)
  Camera camera;               // the camera and the figure's 3D area they were laid out for
  PixelRect view;
  double glyph_scale = 1.0;    // displayed_glyph_scale of this view
  // The glyphs of the clusters with an inverted vertex (min quality < 0)
  // on screen, by rank: render_main_view rings each in the inverted colour.
  std::vector<ScreenDisc> inverted_glyphs;
  // The coloured (labelled) glyphs on screen, by rank: drawn over every
  // glyph ranked after them, they hide those glyphs' rings too.
  std::vector<ScreenDisc> coloured_glyphs;
  // Ranks of the labelled clusters on screen whose glyph shows no pixel
  // (hidden behind other glyphs, edges or arrows): they get no label (it
  // would point at something else) and the legend says "hidden".
  std::vector<Index> hidden_clusters;
  // main_view_glyphs_drawn's count of glyphs left out where they pile up
  // (the legend says so).
  Index left_out_glyphs = 0;
  // Ranks of the labelled clusters on screen whose label found no place
  // (omitted_clusters of them): the legend line ends ", no label room".
  std::vector<Index> unlabelled_clusters;
  // Cluster #0 ties another (glyph_tie_classes): no "worst" ring (it would
  // single out one of equals); its label and legend line say "N tied".
  bool worst_is_tied = false;
  // When #0 ties: the glyphs of its class on screen, each drawn in #0's
  // yellow band and dark ring (all equal, none singled out; issue 44 part C:
  // warrior's tied crimson #0-#1 were dark grey balls to protanopes).
  std::vector<ScreenDisc> worst_class_glyphs;
  // The id image the labels were placed on (main_view_id_image with the
  // markers, the rings marked kIdAnnotation); empty when placed without one.
  IdImage ids;
};

// Whether some pixel of the clusters' coloured edges shows in labels.ids
// outside every label box and inverted ring (drawn in style; true without
// an id image): the legend's line
// "edges at ..." has their swatch only then (the 44r/44p reviews: on
// bunny_in all of #0's edges lay under its glyph, yet the legend showed a
// crimson line).
bool cluster_edges_in_sight(const MainViewLabels& labels, const AnnotationStyle& style);

// View A's id image (issue 44: each label points at a visible part of its
// own glyph): scene (as render_main_view draws it) drawn through camera by
// renderer.render_ids into the figure's 3D area view, each pixel
//   kIdGlyph + rank  a glyph (grey or coloured);
//   kIdEdge          a line drawn at least half opaque (the faded wireframe
//                    and the translucent cells do not hide what is behind);
//   kIdClusterEdge   one of the clusters' coloured edges (scene.lines[1]),
//                    otherwise as kIdEdge;
//   kIdMarker        an overlap arrow (with_markers; otherwise left out);
//   kIdBackground    nothing.
// Empty when the renderer draws no id images.
// Whether view A rings g's glyph in the inverted colour: a cluster with an
// inverted vertex, but not on a surface mesh, whose faces show that colour
// themselves (issue 47 part C: on the bell the ring and its halo covered
// most of the reversed faces the glyph marks).
bool has_inverted_ring(const AggregatedGlyph& g, const MainViewOptions& options);
// options.far_side_glyphs says cluster is on the far side; its colour there.
bool is_far_side(Index cluster, const MainViewOptions& options);
Rgba8 far_side_color(Rgba8 c);
// How far #0's rings reach around its glyph's screen radius (pixels; their
// halo's outer edge): no label or leader of another cluster crosses them.
double worst_rings_extent(double radius, bool is_inverted, const AnnotationStyle& style);
inline constexpr std::uint32_t kIdBackground = 0, kIdEdge = 1, kIdMarker = 2, kIdAnnotation = 3, kIdClusterEdge = 4,
                                kIdGlyph = 16;
// ties: glyph_tie_classes(glyphs.clusters), or empty (computed here).
IdImage main_view_id_image(Renderer& renderer, const Scene& scene, const GlyphResult& glyphs, const Camera& camera,
                           const PixelRect& view, bool with_markers, std::span<const Index> ties = {});

// Marks kIdAnnotation on ids where render_main_view draws over the 3D
// view: the rings, the leader lines and the label boxes (the pixels those
// drawings cover at least half).
void mark_main_view_annotations(IdImage& ids, const MainViewLabels& labels, const GlyphResult& glyphs,
                                const MainViewOptions& options);

// Where view A's labels go (pure; render_main_view draws them): one count
// label per marker group (group_markers_on_screen; their counts add up to
// the findings) and a rank label "#k (n)" for each of the first
// labelled_cluster_count(K) clusters on screen, at most
// max_marker_groups + 10 labels. Placed greedily (place_labels): cluster #0
// first, then the marker groups (largest count first), then clusters #1 ..;
// none overlaps another label, a glyph disc of the 200 largest clusters on
// screen, or an arrow fan (its own too); a label farther than 10 pixels (at
// 1200 px height) from its anchor, or with another glyph disc or fan within
// its anchor's gap + 10 pixels, has a leader line; a label sits beside
// another glyph or fan only with a leader, and leader lines cross no other
// leader, label or glyph, when such a place exists (place_labels). A marker label's anchor
// is its group's position (a 3-pixel disc at the fans' centre, where the
// arrows point), so it sits just outside its own fan with a leader line to
// the centre, never reading as the label of a neighbouring fan; it wears the
// colour of its kind. A marker label that
// finds no such place is placed ignoring the other glyphs (never the worst
// one), so the counts always add up. Issue 44 part V (pile-ups, round 2): a
// label keeps its place near its glyph; one with no place, or only one
// whose leader is longer than a third of the view's diagonal, goes to a
// margin callout column or row (place_callout_columns), kept only if its
// leader crosses no coloured glyph but its own class's, no near label or
// leader, and is at most that long; else the near place, else a cluster
// label is left out (omitted_clusters) and a marker label sits at its
// anchor's right, clamped to the view. Near labels are never moved.
// With ids (main_view_id_image; the rings are drawn over it first), a
// cluster label points at a visible part of its own glyph: its leader starts 1 px inside the largest disc of the
// glyph's visible pixels about the glyph's centre when that disc has at
// least half the glyph's radius, else about the visible pixel farthest from
// any other (the glyph is mostly hidden: then the label always has a
// leader); a cluster whose glyph shows no pixel gets no label
// (hidden_clusters).
MainViewLabels layout_main_view_labels(const GlyphResult& glyphs, const OverlapReport* overlap, const Camera& camera,
                                       const FigureLayout& layout, const AnnotationStyle& style,
                                       const MainViewOptions& scaled, const IdImage* ids = nullptr);

// The labels render_main_view draws for view_direction (and, when scene is
// not null, the scene it draws), figure pixels: plan_main_view's (placed
// on the id image when renderer is not null, as render_main_view does).
MainViewLabels main_view_labels(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                                const OverlapReport* overlap, const Vec3& view_direction,
                                const MainViewOptions& options, Scene* scene = nullptr, Renderer* renderer = nullptr);

// A stretch of an inverted face's outline that render_main_view draws
// over a glyph hiding it, figure pixels.
struct OutlineRun {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  Rgba8 color;
};
// Those runs for the view labels were laid out for (MainViewLabels'
// camera, view and id image): the outlines of the inverted faces drawn
// (scene 5b) where a glyph or a glyph ring hides them, but never on #0's
// disc (its glyph stays whole) nor within kInvertedOutlineCore of another
// coloured glyph's radius of its centre. options and style: as
// render_main_view's; inverted_faces: inverted_boundary_faces(...).drawn.
std::vector<OutlineRun> main_view_outlines_over_glyphs(const HexMesh& mesh, const Topology& topology,
                                                       const GlyphResult& glyphs, const MainViewLabels& labels,
                                                       const MainViewOptions& options,
                                                       const AnnotationStyle& style,
                                                       std::span<const BoundaryPolygon> inverted_faces);
// The distinct colours of runs, in order of first use (main_legend_lines'
// outlines_over_glyphs: one line swatch each).
std::vector<Rgba8> outline_colors(std::span<const OutlineRun> runs);

// What render_main_view draws for view_direction, before it draws it: the
// figure's style and layout, the scaled options, the scene, the labels
// (placed on the id image), the outlines drawn over glyphs and the legend
// lines (main_legend_lines, with the outlines' colours). Every mark the
// figure shows is in scene, labels (the rings: worst_glyph,
// inverted_glyphs) or outlines, and the legend names each (tests/views/
// main_view_legend_test.cpp). renderer null: the labels are placed without
// an id image (and no outline is drawn over a glyph).
struct MainViewPlan {
  AnnotationStyle style;
  FigureLayout layout;
  MainViewOptions scaled;  // its glyph_ties are the given options' (empty: computed where needed)
  Scene scene;
  MainViewLabels labels;
  std::vector<OutlineRun> outlines;
  std::vector<LegendLine> legend;
};
MainViewPlan plan_main_view(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                            const OverlapReport* overlap, const Vec3& view_direction, const MainViewOptions& options,
                            Renderer* renderer);

// The figure: title, the 3D view, the labels (layout_main_view_labels:
// every marker group with its number of findings "xN", the worst clusters
// "#k (n)"), and a legend on the right. Where a glyph hides them (the id
// image), the inverted faces' outlines (kInvertedOutlineWidth) are drawn
// over it (the clusters' edge lines are not: over a glyph they showed other
// clusters' colours, issue 44 part V round 2), but not within
// kInvertedOutlineCore of a coloured glyph's radius of its centre (issue 44
// part V) nor on #0's glyph (part P round 3): main_view_outlines_over_glyphs.
// What it draws is plan_main_view's.
Image render_main_view(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                       const OverlapReport* overlap, const Vec3& view_direction, const MainViewOptions& options,
                       Renderer& renderer);

// Where the eye of a view direction sits, for titles: "azimuth 30,
// elevation 25 deg" (azimuth in [0, 360) from the front, upright.h), or
// "straight above" / "straight below".
std::string viewpoint_name(const Vec3& view_direction, const Vec3& up);

}  // namespace hq
