#pragma once
// Where the inverted cells are, on the overview and the thumbnail (issue 45):
// an inverted hex inside the volume, on the far side of the model or only a
// few pixels wide shows no blue, so a picture of a mesh with 14 inverted
// hexes can look healthy. Each group of inverted cells that lie together on
// screen gets a ring (sized in screen pixels, at least min_radius, so that
// it survives the thumbnail's scaling down), and on the overview a label
// with a leader: "14 inverted hexes, inside" says how many and why no blue
// shows. The ring is solid when the group's inverted colour is in sight,
// dashed when it is not (inside the volume or hidden behind the model).

#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hqview/image/image.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/label_layout.h"
#include "hqview/render/renderer.h"

namespace hq {

// The ring's colour (with a white halo): dark, in neither the quality map
// nor the inverted colour.
inline constexpr Rgba8 kCalloutColor{20, 20, 20, 255};
// At most this many rings (the groups with the most cells first); the rest
// are named in the last label ("+N more").
inline constexpr int kMaxInvertedCallouts = 4;
// A group whose inverted colour covers fewer pixels than this fraction of the
// view's area counts as small ("(small)" in its label).
inline constexpr double kSmallInvertedFraction = 2e-4;

// The thumbnail (views.cpp build_thumbnail): with inverted cells, a band
// this many pixels high on top of its 320 x 240 saying "N inverted" in text
// this many pixels high (11 px where the batch index shows it at 128 x 96).
inline constexpr int kThumbnailBadgeBand = 40;
inline constexpr int kThumbnailBadgeText = 28;

struct InvertedCallout {
  double x = 0, y = 0;        // ring centre, figure pixels
  double radius = 0;          // ring radius, pixels
  int num_cells = 0;          // inverted cells in the group
  int num_groups = 1;         // 3D groups ringed together (their rings overlapped on screen)
  // A merged ring in sight: the cells of its groups out of sight (none in
  // sight: empty), how many such groups, and whether any reaches the
  // boundary (far side) or none does (inside).
  std::vector<Index> hidden_cells;
  int num_hidden_groups = 0;
  bool hidden_on_boundary = false;
  // Such a ring is split by sight (issue 45: one solid ring over groups on
  // the far side said they were in sight): (x, y, radius) rings its groups
  // in sight only, solid, and this second ring, dashed, its groups out of
  // sight; hidden_radius 0: no second ring.
  double hidden_x = 0, hidden_y = 0, hidden_radius = 0;
  long visible_pixels = 0;    // view pixels where the overview paints their inverted corners, depth-tested
  // Its cells (of its groups in sight) with the blue of a corner in sight:
  // the labels' "N in sight" (a group in sight has cells inside too).
  int num_seen_cells = 0;
  // Of those, the cells with a pixel of that blue beyond the (solid) ring's
  // radius: the labels' "k of them reach outside the ring" (issue 45, the
  // 45c/45d reviews: blue wider than the largest ring lay outside it, and
  // "32 in sight" did not say whether it counted them).
  int num_seen_outside = 0;
  // The box of those pixels (figure pixels, their outer edges; empty when
  // none): the solid ring encloses it (issue 45: a visible blue face stuck
  // out of the solid ring).
  double visible_x0 = 0, visible_y0 = 0, visible_x1 = 0, visible_y1 = 0;
  bool on_boundary = false;   // some corner of theirs on the boundary is inverted (vertex quality < 0)
  int num_more_cells = 0;     // inverted cells of groups left without a ring (the last callout only)
  std::vector<Index> cells;   // the group's inverted cells (volume cell ids, in the order given)
  std::string inset;          // the letter of the overview's inset that draws them (inverted_inset.h); empty: none
};

// The screen discs a callout's rings take (ring radius + thickness): its
// ring, then its dashed ring of hidden groups when it has one.
std::vector<ScreenDisc> callout_discs(const InvertedCallout& c, double thickness);

// The largest ring: this fraction of the view's smaller side (or min_radius).
inline constexpr double kMaxCalloutRadiusShare = 0.45;
inline double max_callout_radius(const PixelRect& view, double min_radius) {
  return std::max(min_radius, kMaxCalloutRadiusShare * std::min(view.width, view.height));
}

// Rings closer than this times min_radius (edge to edge) are merged.
inline constexpr double kRingMergeGap = 0.5;
// A merged ring is split by sight only when its solid and dashed rings
// would overlap by at most this fraction of the smaller disc's area; more,
// and one ring (solid, around the box of the blue in sight) holds both, its label saying how many are in sight
// and how many hidden (issue 45: rings overlapping by 40 % left the blue in
// the overlap neither in sight nor hidden).
inline constexpr double kMaxSplitOverlap = 0.25;

// Groups the inverted cells (ids over all volume cells, then a surface
// mesh's quads and triangles: any_cell, mesh/cell_faces.h; a surface cell's
// corners all count as its inverted corners)
// in 3D: cells that share a vertex, transitively, form one group (issue
// 45f: the same groups from every eye and at every size, so the overview,
// its turned copies and the thumbnail ring the same places). Each group's
// ring is centred on the bounding box of its cells' projected corners and
// passes half its diagonal (plus 0.2 min_radius) from there, at least
// min_radius and at most 0.45 of the view's smaller side. visible_pixels comes from an id
// image of the boundary drawn with the camera into view (the part of each
// face the overview paints in an inverted corner's colour carries that
// corner's group): 0 when the renderer draws no id images. Groups in
// descending cell count (ties: the first cell id), at most
// kMaxInvertedCallouts. Each callout counts its cells in sight whose blue
// reaches beyond its ring (num_seen_outside). Deterministic.
std::vector<InvertedCallout> inverted_callouts(const HexMesh& mesh, const Topology& topology,
                                               std::span<const Index> inverted_cells,
                                               std::span<const double> vertex_quality, const Camera& camera,
                                               const PixelRect& view, double min_radius, Renderer& renderer);

// "14 inverted hexes" (noun: "hex" or "cell", made plural but for 1; empty:
// "14 inverted"), then " in 3 groups" for a merged ring; a merged ring in
// sight with hidden groups: split (hidden_radius > 0), the solid ring's
// "4 inverted hexes in sight" (its groups in sight only: the dashed ring has
// its label, inverted_hidden_label; "4 inverted hexes, 3 in sight" when one
// shows no blue), else one ring's ": 9 in sight, 28 unseen beside them, 21
// on the far side" (or " inside"; "in sight" counts num_seen_cells, the
// middle part the rest of the groups in sight, left out when none), then
// "; +N more" and the inset; else ", inside" (no inverted corner on the
// boundary), ", far side" (on the boundary, none in sight) or, in sight,
// ", 3 in sight" when fewer than all its cells show blue and " (small)"
// (fewer pixels than kSmallInvertedFraction of view_area); "in sight"
// is followed by " (5 reach outside the ring)" when num_seen_outside is 5
// (and then said even when all are in sight); then "; +N
// more" for the cells without a ring; then ": see inset A" when an inset
// draws them.
std::string inverted_callout_label(const InvertedCallout& callout, const std::string& noun, double view_area);
// A split ring's dashed ring's label: "6 inverted hexes in 2 groups, far
// side" (or ", inside"), then ": see inset A" when an inset draws them.
std::string inverted_hidden_label(const InvertedCallout& callout, const std::string& noun);
// Whether the ring is drawn solid: some of the group's inverted colour is in sight.
inline bool callout_in_sight(const InvertedCallout& c) { return c.visible_pixels > 0; }

// The labels' placement (draw_inverted_callouts'): each label's text and
// its box and leader (nullopt: no free place). Every leader runs from its
// own ring outwards and crosses no other ring, no other leader and no
// other label's box; no box covers a ring (label_layout.h strict_leaders,
// every ring protected; issue 45g); a split callout's dashed ring gets its
// own label and leader (issue 45). A label with no place on one line
// tries 2, then 3, then 4 lines (words wrapped). `model`: rectangles the model
// covers; every label is tried off them first (1 to 8 lines), then over
// them when no such place is free (1 to 4 lines). bounds: where the boxes
// may go (default: view; the overview's also take the free part of the
// legend's column, the legend and insets `taken`).
struct InvertedRingLabel {
  std::string text;
  std::size_t callout = 0;  // the callout whose ring it names
  bool dashed_ring = false;  // a split callout's dashed ring (after every callout's own label)
  std::vector<std::string> lines;  // as drawn: text on 1 line, or wrapped on 2 to 8 when 1 found no place
  std::optional<PlacedLabel> placed;
};
std::vector<InvertedRingLabel> place_callout_labels(const PixelRect& view, std::span<const InvertedCallout> callouts,
                                               const std::string& noun, double thickness, int text_size,
                                               const AnnotationStyle& style, std::span<const PixelRect> taken = {},
                                               std::span<const PixelRect> model = {},
                                               std::optional<PixelRect> bounds = std::nullopt);

// Draws each callout's ring (kCalloutColor core of `thickness` pixels on a
// white halo; dashed when not in sight) and, with labels (text_size > 0),
// its label on a pale box placed outside the ring inside view, off the
// `taken` rectangles (the insets), always with a leader from the ring to
// the box (label_layout.h), so that no label sits between two rings
// unattached. draw_rings false: the labels only (the overview draws its
// rings before its insets, the labels after).
void draw_inverted_callouts(Image& figure, const PixelRect& view, std::span<const InvertedCallout> callouts,
                            const std::string& noun, double thickness, int text_size, const AnnotationStyle& style,
                            std::span<const PixelRect> taken = {}, bool draw_rings = true,
                            std::span<const PixelRect> model = {}, std::optional<PixelRect> bounds = std::nullopt);

// A callout's rings: its ring (solid when in sight, else dashed) and its
// dashed ring of hidden groups when it has one, their pixels inside `clip`
// only (the overview's 3D view: issue 45, the 45c review: a ring around
// blue at the view's edge ran on under the legend).
void draw_callout_rings(Image& image, const InvertedCallout& c, double thickness, const PixelRect& clip);

// A ring: an annulus of `color` (core thickness / 2 either side of radius)
// on a white halo (as wide again), solid or dashed (dashes of about 14
// pixels along the ring, at least 8 of them, evenly spaced); only its
// pixels inside `clip` (none: the whole image) are drawn.
void draw_marker_ring(Image& image, double cx, double cy, double radius, double thickness, bool dashed, Rgba8 color,
                      std::optional<PixelRect> clip = std::nullopt);

}  // namespace hq
