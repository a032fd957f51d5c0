#pragma once
// Detail views: C, the sub-region of one glyph cluster, and D, the one-ring
// of hexes around one vertex with the scaled Jacobian of each corner there.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hqview/glyph/glyphs.h"
#include "hqview/core/cell_kinds.h"
#include "hqview/image/image.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/label_layout.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"

namespace hq {

struct DetailViewOptions {
  int width = 1600, height = 1200;
  std::string title;
  Rgba8 background{255, 255, 255, 255};
  Vec3 up{0.0, 0.0, 1.0};  // the model axis drawn upwards (--up)
  // A planar surface mesh: the direction C and D see it along (flat, from
  // above: planar_view_direction); none: each view chooses its own.
  std::optional<Vec3> view_direction;
  // A surface mesh: its cell scaled Jacobians by cell id (the lowest signed
  // corner, QualityField::cell_scaled_jacobian); view C fills the cluster's
  // faces with quality_color of them. Empty for a volume mesh.
  std::span<const double> cell_quality;
};
// View C's legend line on a surface mesh (under the colour bar's title).
inline constexpr const char* kClusterFaceFillLegend = "faces: their lowest corner";
// View C of a surface mesh: what a sphere is and what its size says (47i
// review #7: nothing in the PNG explained the glyphs; their rule: one per
// vertex whose quality is below the glyph threshold, radius growing with
// 1 - quality, all scaled by one factor).
inline constexpr const char* kClusterSphereLegend = "sphere: a vertex below the threshold\nsize: how far below";

// The hexes of a cluster (those with a member vertex), ascending.
struct ClusterRegion {
  std::vector<Index> cells;
};
ClusterRegion cluster_region(const Topology& topology, const GlyphResult& glyphs, Index cluster);
// The same over every kind: the hexes, tets, wedges and pyramids using a
// member vertex (cell ids over all blocks, ascending); what view C draws.
ClusterRegion cluster_region(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs, Index cluster);

// View C's scene (cells of every kind, each with its CellKindTable faces
// and edges):
//   lines[0]       edges of the neighbour cells, grey;
//   lines[1]       edges of the cluster's cells, in the cluster's colour;
//   spheres[0]     the cluster's glyphs, not aggregated: one per member at
//                  half its radius (full-size glyphs overlap and hide the
//                  cells), at most 0.35 times the mean edge length of the
//                  cluster's cells, coloured by quality_color(vertex quality);
//   translucent[0] the region's outer faces (faces of region cells not
//                  shared by two region cells), pale, so its shape reads.
Scene build_cluster_scene(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                          const GlyphResult& glyphs, Index cluster);

// The figure of view C: framed on the cluster's cells, from the direction
// (among 26) that shows the most glyph area; quality colour bar.
Image render_cluster_view(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                          const GlyphResult& glyphs, Index cluster, const DetailViewOptions& options,
                          Renderer& renderer);

// The same in two steps: the scene and its camera (no drawing; safe to run
// for several clusters at once), then the figure drawn from them.
// The inset of views C and D where the faces are slivers (an edge a few
// pixels on screen: 47g review #5, #6): its scene drawn from `camera`,
// zoomed on the worst vertex (C) or the vertex (D), in `rect` (figure
// pixels, a corner of the view), the area it shows boxed at `box`.
struct DetailInset {
  Scene scene;
  Camera camera;
  PixelRect rect, box;
  double zoom = 1.0;  // its pixels per model unit over the view's
};

struct ClusterShot {
  Scene scene;
  Camera camera;
  std::string cell_kinds;  // on a mesh with non-hex cells, the region's kinds (cell_kinds_legend) for the legend
  // A surface mesh: the legend's entries for the figure's marks (the
  // cluster's edges, its worst vertex's ring, the neighbours' faces and
  // edges), under the colour bar.
  std::vector<ColorBarSwatch> swatches;
  std::optional<DetailInset> inset;
};
ClusterShot cluster_shot(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                         const GlyphResult& glyphs, Index cluster, const DetailViewOptions& options);
Image render_cluster_shot(const ClusterShot& shot, const DetailViewOptions& options, Renderer& renderer);

// The corners at vertex v: one per incident hex (ascending hex id), with its
// corner scaled Jacobian read from corner_values (QualityField's
// corner_scaled_jacobian: 8 per hex); then one per incident tet, wedge and
// pyramid (ascending cell id), its value computed by the quality kernels'
// per-corner functions (cell_corner_jacobian.h; a pyramid's apex has no
// value and no entry).
struct VertexCorner {
  Index hex = 0;     // the cell id over all blocks (hexes first)
  int local = 0;     // corner index of v in the cell (VTK order)
  double value = 0;  // corner scaled Jacobian
  CellKind kind = CellKind::hex;
};
std::vector<VertexCorner> vertex_corners(const HexMesh& mesh, const Topology& topology,
                                         std::span<const double> corner_values, Index v);

// The tets, wedges and pyramids using vertex v (cell ids over all blocks,
// ascending): a scan of those blocks.
std::vector<Index> non_hex_cells_of(const HexMesh& mesh, Index v);

// View D's one ring: the hexes of v (ascending), then non_hex_cells_of(v).
std::vector<Index> local_ring(const HexMesh& mesh, const Topology& topology, Index v);

// "cells: 4 hex, 9 tet, 2 pyramid": the count of each kind among `cells`
// (ids over all blocks), kinds in block order; empty for no cells.
std::string cell_kinds_legend(const HexMesh& mesh, std::span<const Index> cells);

// View D's corner marker radius (model units) for a corner's scaled
// Jacobian: size is severity, as in view A (issue 44): 0.1 · size · (1 − SJ),
// (1 − SJ) clamped to [0.25, 2] (NaN: 0.25). The legend says so
// (kLocalMarkerSizeLegend, under the colour bar).
double local_marker_radius(double scaled_jacobian, double size);
inline constexpr const char* kLocalMarkerSizeLegend = "disc size grows with 1 - SJ";
// View D's colour bar title: each disc is one cell's corner at the vertex.
inline constexpr const char* kLocalBarHeading = "corner scaled Jacobian\n(one disc per cell corner)";
// View D draws its corner discs at this fraction of local_marker_radius.
inline constexpr double kLocalDiscScale = 0.6;

// View D's scene:
//   lines[0]       edges of the one-ring cells (local_ring: every kind,
//                  each with its CellKindTable faces), dark grey;
//   spheres[0]     one marker per corner (vertex_corners), 45% of the way
//                  from v towards its cell's centre, coloured by
//                  quality_color(value), radius local_marker_radius(value,
//                  the mean distance from v to its cells' centres);
//   spheres[1]     v itself, small, white (drawn on a black ring: local_marker_discs);
//   translucent[0] the one-ring cells' faces, pale.
Scene build_local_scene(const HexMesh& mesh, const Topology& topology, std::span<const double> corner_values, Index v);

// View D's viewpoint (46t2 review: hexwedge v128 was a flat elevation, lshape
// v199 head-on): the corners' cells seen in depth, never along an axis or a
// face's plane. The faces of the ring's cells that contain v (each once,
// by its vector area A_f, unit normal n_f) are what the eye must see:
//   projected area  P(d) = sum_f |A_f . d| (largest for a box's corner seen
//                   along its diagonal, smallest along an axis);
//   face angle      a(d) = min_f asin |n_f . d| (0: some face seen edge-on).
// Candidates: upright directions (the eye kLocalViewElevations above the
// horizon, every kLocalViewAzimuthStep degrees of azimuth). Kept: those with
// a(d) >= kLocalMinFaceAngle degrees (or, when none reaches it, at least
// 3/4 of the best a(d)); of them those with P(d) >= kLocalAreaShare times
// the best kept P; of those the one whose discs (centers, radii) cover the
// most area (as choose_viewpoints), ties to the first.
// View D frames its whole ring (46w review: a closer frame cut the ring's
// cells and lost its silhouette); corners with no room are listed in the
// table.
inline constexpr double kLocalViewElevations[] = {20, 25, 30, 35, 40, 45, 50, 55, 60};
inline constexpr double kLocalViewAzimuthStep = 5.0;
inline constexpr double kLocalMinFaceAngle = 10.0;  // degrees
inline constexpr double kLocalAreaShare = 0.95;
struct LocalViewScore {
  double projected_area = 0;  // P(d), model units squared
  double min_face_angle = 0;  // a(d), degrees (90 with no face)
};
// The faces of `cells` containing v (every face when v is kNoIndex; a
// surface cell is its own face), each once (sorted corner set), as vector
// areas (a quad's from its two triangles 012 and 023). View C of a curved
// surface mesh takes its viewpoint by the same rule over the cluster's faces.
std::vector<Vec3> local_face_areas(const HexMesh& mesh, std::span<const Index> cells, Index v);
LocalViewScore local_view_score(std::span<const Vec3> face_areas, const Vec3& direction);
Vec3 choose_local_viewpoint(std::span<const Vec3> face_areas, std::span<const Vec3> points,
                            std::span<const Vec3> centers, std::span<const double> radii, double aspect,
                            const Vec3& up);

// View D's scene as drawn for `camera`: the corner markers (spheres[0]) as
// flat discs facing the camera on a dark rim, and v's dot (spheres[1]) as a
// dark disc, all moved to the overlay, in the plane through v facing the
// camera and stacked by value: each rank kLocalStackStep * size nearer the
// camera, the lowest value (values[i]: marker i's; NaN lowest) on top of
// the others, v's dot (at kLocalDiscScale of its radius) on top of all
// (46q review Q-M1: discs hid one another, the worst and the vertex).
inline constexpr double kLocalStackStep = 1e-3;
// Each disc's dark rim: a disc of this many times its radius under it.
inline constexpr double kLocalRimScale = 1.12;
// The leaders: local_leader_width(scale) pixels wide (scale: the figure's
// AnnotationStyle::scale) on a halo kLocalHaloWidths times as wide; a leader
// keeps local_leader_clearance pixels (its halo's half width and a pixel)
// off every other disc's rim.
inline constexpr double kLocalHaloWidths = 3.0;
inline double local_leader_width(double scale) { return scale * 1.2 > 1.0 ? scale * 1.2 : 1.0; }
inline double local_leader_clearance(double leader_width) { return 0.5 * kLocalHaloWidths * leader_width + 1.0; }
Scene local_marker_discs(const Scene& scene, const Camera& camera, const std::vector<double>& values, double size);
// The discs' stack, top down: the worst corner first (NaN last; ties: the
// later corner on top), as local_marker_discs draws them.
std::vector<std::size_t> local_stack_order(std::span<const double> values);
// The share (0-1) of `disc`'s area under the union of `over` (sampled on a
// 17 x 17 grid over the disc).
double covered_share(const ScreenDisc& disc, std::span<const ScreenDisc> over);
// Spider (46w review: discs hidden under the vertex's dot or under another
// disc got a number that read as the other's): going down the stack
// (top_down), a disc with more than kLocalMaxCoveredShare of it under the
// dot and the discs above it is moved on screen, away from the dot, to the
// nearest spot (steps of 0.2 radius up to 4 radii, turned up to 90 degrees)
// where at most that share is covered (else the least covered). Returns each
// disc's move in pixels ({0, 0}: not moved).
inline constexpr double kLocalMaxCoveredShare = 0.2;
// View D numbers corners in up to this many layouts, those with no room in
// the last going first (local_shot).
inline constexpr int kLocalLayoutRounds = 6;
// A number with no room within kLocalMaxLeaderLabels label heights of its
// disc may take a leader this many times as long.
inline constexpr double kLocalFarLeaderShare = 3.0;
std::vector<std::array<double, 2>> local_spider_moves(std::span<const ScreenDisc> discs,
                                                      std::span<const std::size_t> top_down, const ScreenDisc& dot);

// The figure of view D: the one ring framed, each corner marker labelled
// with its value, its cell's kind and id ("0.812  hex 12", as in chart E),
// quality colour bar with kLocalMarkerSizeLegend under its title; on a mesh
// with non-hex cells the legend's title ends with the ring's
// cell_kinds_legend.
Image render_local_view(const HexMesh& mesh, const Topology& topology, std::span<const double> corner_values, Index v,
                        const DetailViewOptions& options, Renderer& renderer);

// One corner's label in view D, as laid out on the figure (pixels).
//   text:   "0.812  hex 12" (value, kind, cell id; chart E's names);
//   box:    where the text is drawn (its extent plus 2 px each side);
//   marker: its disc on screen with its rim (kLocalRimScale times the
//           disc, at least kLocalMinDiscPixels in radius);
//   placed: false when no free place was found: the label is left out
//           (never drawn over another; the legend counts the left out);
//   leader: from the disc's edge to the box (every placed label has one
//           unless its box touches its disc).
struct LocalLabel {
  std::string text;
  PixelRect box;
  ScreenDisc marker;
  bool is_inverted = false;  // its value < 0: drawn in the inverted colour
  double value = 0;          // its corner scaled Jacobian
  bool placed = false;
  bool has_leader = false;
  double leader_x0 = 0, leader_y0 = 0, leader_x1 = 0, leader_y1 = 0;
  // > 0: a numbered callout (the number drawn in box, the text in the
  // shot's table), 1 the worst numbered corner; 0: the text drawn in box.
  int number = 0;
  // Its rank over the ring by value (1 = worst): a corner left out is
  // listed with it (the 44m brief: the table's leftover rows had no rank).
  int rank = 0;
};
// View D before drawing (no renderer needed): its scene with the discs
// (local_marker_discs), camera, figure layout, the vertex's dot and its
// clear zone on screen, and every corner's label placed (issue 46, 46r
// review M1): worst corner first, no box over another box, a disc, the
// dot's clear zone (kLocalDotClearLabels label heights: a label there read
// as the vertex's own), or outside the view; a leader crosses no other
// disc, the dot or another leader where any place allows it (a second
// pass lets it cross discs); a label with no free place is left out.
inline constexpr double kLocalMinDiscPixels = 6.0;   // at scale 1 (a 1200-pixel-high figure)
inline constexpr double kLocalDotClearLabels = 1.0;  // the dot's clear zone radius, in label heights
// Leaders are at most kLocalMaxLeaderLabels label heights long and cross no
// other label's box, no other corner's disc, the dot or another leader
// (46t review: 300-450 px leaders under other boxes read as the wrong
// corner's). A corner whose label cannot keep to that, and every corner of
// a ring of more than kLocalMaxFullLabels, gets a numbered callout instead
// (worst first from 1, the same rules), its value and cell listed in a
// table beside the view headed kLocalTableHeading; one that finds no place
// even so is left out and counted.
inline constexpr double kLocalMaxLeaderLabels = 4.0;
inline constexpr std::size_t kLocalMaxFullLabels = 16;
// A number whose place breaks the leader rules asks again, up to this many
// times, with the places refused so far taken.
inline constexpr int kLocalRetries = 8;
inline constexpr const char* kLocalTableHeading = "numbered corners (1 = worst)";
// The table's last rows: the corners left out (no place even for a
// number), worst first, under this heading and keyed by their ranks (the
// 44m brief; not "-": 46t2 review, it read as a minus sign).
inline constexpr const char* kLocalLeftOutHeading = "not numbered (no room):";
struct LocalShot {
  Scene scene;  // as drawn (discs in the overlay)
  Camera camera;
  AnnotationStyle style;
  FigureLayout layout;
  std::string legend;  // the colour bar's title's lines under "vertex quality ..."
  ScreenDisc dot;      // the vertex's dot on screen
  double dot_clear_radius = 0;
  int text_size = 0;   // pixels
  std::vector<LocalLabel> labels;  // vertex_corners' order
  std::size_t num_left_out = 0;
  double max_leader = 0;    // pixels (kLocalMaxLeaderLabels label heights)
  int table_text_size = 0;  // pixels
  PixelRect table_box;      // the numbered corners' table (width 0: none); layout.view is narrowed by it
  bool kind_swatches = false;  // the legend's edge colour per kind (a mesh with non-hex cells)
  // A surface mesh's ring with an edge at the vertex a few pixels long: the
  // faces at the vertex zoomed, each corner's disc at its place inside its
  // face (no labels: the view's name them), in a corner free of labels.
  std::optional<DetailInset> inset;
};
LocalShot local_shot(const HexMesh& mesh, const Topology& topology, std::span<const double> corner_values, Index v,
                     const DetailViewOptions& options);
// The table beside view D, row by row: the numbered corners by number
// (key "1", "2", ...; text "0.812  hex 12"), then, when any corner was left
// out, a heading row kLocalLeftOutHeading and those corners by value (worst
// first, NaN last; key its rank). Empty when no corner is numbered or left out.
struct LocalTableRow {
  std::string key, text;
  bool is_heading = false;
  bool is_inverted = false;  // drawn in the inverted colour
};
std::vector<LocalTableRow> local_table_rows(const LocalShot& shot);
Image render_local_shot(const LocalShot& shot, const DetailViewOptions& options, Renderer& renderer);

}  // namespace hq
