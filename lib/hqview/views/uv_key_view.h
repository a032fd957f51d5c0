#pragma once
// The UV key (boundary.html, beside the UV error map): which chart of the
// reference's UV atlas is which part of the model. Left, the reference in 3D
// from the three-quarter view and from behind, each chart in its own light
// tint with its number; right, the atlas laid out as the UV error map lays
// it out, in the same tints and with the same numbers.

#include <array>
#include <string>
#include <vector>

#include "hqview/core/vec3.h"
#include "hqview/image/color.h"
#include "hqview/image/image.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/render/annotate.h"
#include "hqview/render/renderer.h"
#include "hqview/uv/uv_atlas.h"
#include "hqview/views/boundary_views.h"

namespace hq {

// The light tint of chart c (of n): hues spread by the golden angle, pale
// enough that numbers and outlines read on them.
Rgba8 chart_tint(Index chart);

// Where a chart's number goes in the atlas: on the chart's triangle whose UV
// centroid is nearest the chart's area-weighted UV centroid, so the number
// sits on its own chart even when the chart is not convex (and likewise in
// 3D; the 3D views use the chart's triangles facing the eye instead).
struct UvChartLabel {
  Index chart = 0;
  Index triangle = kNoIndex;  // into reference.triangles
  Vec3 position;              // the triangle's 3D centroid
  Vec3 normal;                // the triangle's unit normal
  std::array<double, 2> uv{}; // the triangle's UV centroid (for the map's anchor: uv_triangle)
  Index uv_triangle = kNoIndex;
};
// One per chart, chart order. Charts without a triangle of positive area get
// none.
std::vector<UvChartLabel> uv_chart_labels(const TriSurface& reference, const UvAtlas& atlas);

// Where the chart numbers of one frame (a 3D view or the atlas) go, pixels.
// Each number's box is centred on its anchor (a point of its chart) when
// that box is inside `bounds` and overlaps no box placed before it; else it
// goes to the first free place around the anchor (render/label_layout's
// candidates: 8 directions, rings farther out) with a leader line back to
// the anchor and a dot on it (however short: beside its anchor, the box may
// lie on another chart). A box centred on its anchor must also lie on the
// anchor's chart (room below). Numbers are
// placed in the anchors' order; one with no free place in the frame is left
// out (placed false). The boxes of placed numbers are pairwise disjoint.
struct UvKeyNumberAnchor {
  Index chart = 0;
  int x = 0, y = 0;  // the anchor pixel, on the chart
  // The chart's room around the anchor: the box centred on it lies on the
  // chart's own pixels when its half width and half height are < room
  // (chessboard distance to the nearest pixel of anything else). A number
  // whose centred box does not fit is placed beside it with a leader line,
  // whatever the distance, so that it never reads as another chart's.
  int room = 1 << 30;
};
struct UvKeyNumber {
  Index chart = 0;
  int anchor_x = 0, anchor_y = 0;
  bool placed = false;
  PixelRect box;             // the pale box the number is written in
  bool has_leader = false;   // the box is off its anchor: a line joins them
};
std::vector<UvKeyNumber> place_uv_key_numbers(const std::vector<UvKeyNumberAnchor>& anchors, const PixelRect& bounds,
                                              int text_size, const AnnotationStyle& style);

// Which chart each pixel of a frame shows: the frame drawn unlit, without
// outlines, each chart in chart_id_color; a pixel is its chart's only when it
// and its 4 neighbours have that exact colour (supersampled edges blend),
// else kNoIndex (also the background and other charts' blends).
Rgba8 chart_id_color(Index chart);
struct ChartIdImage {
  int width = 0, height = 0;
  std::vector<Index> ids;  // row-major, top row first
  Index at(int x, int y) const {
    return x < 0 || y < 0 || x >= width || y >= height ? kNoIndex
                                                       : ids[static_cast<std::size_t>(y) * width + x];
  }
};
ChartIdImage chart_ids(const Image& id_frame);

// Per chart with at least min_pixels pixels in the frame, the anchor of its
// number: its pixel farthest (chessboard distance) from any other pixel
// (the first in row order of those), with that distance as room; offset by
// (x0, y0), the frame's place in the figure. Chart order. With islands (the
// atlas, where a chart can lie in several pieces): the anchor of the
// chart's largest island (4-connected pixels), then one for each other
// island of at least kIslandFraction of the chart's pixels (and
// min_pixels), then (after every chart's) one for each lobe without an
// anchor (up to kMaxLobes per chart): the parts of the chart's pixels of
// at least R room (kLobeRoom, or kLobeFraction of the chart's most room if
// more) that are not 8-connected, i.e. pieces joined to the rest by a neck
// thinner than 2R; so that no piece of a chart is left unnumbered.
inline constexpr double kIslandFraction = 0.02;
inline constexpr int kLobeRoom = 32;
inline constexpr double kLobeFraction = 0.3;
inline constexpr int kMaxLobes = 3;
// An atlas chart whose anchor has at most this room (UvKeyNumberAnchor) is a
// sliver: ringed in the figure, with a note under the atlas.
inline constexpr int kSliverRoom = 2;
std::vector<UvKeyNumberAnchor> visible_chart_anchors(const ChartIdImage& ids, int x0, int y0, int min_pixels,
                                                     bool islands = false);

// What a frame of the figure shows (for tests): its place, its chart ids,
// its numbers.
struct UvKeyFrame {
  PixelRect area;
  ChartIdImage ids;
  std::vector<UvKeyNumber> numbers;
};

// The figure: options.width x options.height, title on top; each frame's
// numbers anchored by visible_chart_anchors on the frame's chart ids (so a
// number names a chart the eye sees, not one hidden behind another). Throws
// RenderError from the renderer or the font. frames: when given, the three
// frames (front, back, atlas).
Image render_uv_key(const TriSurface& reference, const UvAtlas& atlas, const BoundaryViewOptions& options,
                    Renderer& renderer, std::vector<UvKeyFrame>* frames = nullptr);

}  // namespace hq
