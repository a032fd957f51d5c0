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
// the anchor when more than 10 px (at 1200 px height) away. Numbers are
// placed in the anchors' order; one with no free place in the frame is left
// out (placed false). The boxes of placed numbers are pairwise disjoint.
struct UvKeyNumberAnchor {
  Index chart = 0;
  int x = 0, y = 0;  // the anchor pixel, on the chart
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

// The figure: options.width x options.height, title on top. Throws
// RenderError from the renderer or the font.
Image render_uv_key(const TriSurface& reference, const UvAtlas& atlas, const BoundaryViewOptions& options,
                    Renderer& renderer);

}  // namespace hq
