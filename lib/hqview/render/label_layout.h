#pragma once
// Greedy label placement in screen space (issue 44, "no pile-ups"; the
// paper's future work asks for "a view-dependent placement of arrows"):
// labels are placed one by one, in the caller's order of importance, each at
// the first free candidate position around its anchor, so that no two labels
// overlap and no label covers an obstacle disc (the glyphs). A label that
// cannot sit next to its anchor moves outwards and gets a leader line.
// Pure geometry on pixel coordinates; nothing here draws.

#include <optional>
#include <span>
#include <vector>

#include "hqview/render/annotate.h"

namespace hq {

// A disc on screen, pixels (a glyph's silhouette, an anchor's marker).
struct ScreenDisc {
  double x = 0, y = 0, radius = 0;
};

// One label to place: its anchor (a disc: the label stays outside it) and
// its box size in pixels.
struct LabelRequest {
  ScreenDisc anchor;
  int width = 0, height = 0;
};

struct LabelLayoutOptions {
  PixelRect bounds;         // labels stay inside
  double gap = 4.0;         // pixels between the anchor disc and a label next to it
  double ring_step = 14.0;  // pixels between successive rings of candidates
  int rings = 24;           // rings tried before a label is given up
  // A label whose box is farther than this from its anchor disc gets a
  // leader line (pixels).
  double leader_distance = 10.0;
};

struct PlacedLabel {
  PixelRect box;
  bool has_leader = false;
  // Leader line from the anchor disc's edge to the box's nearest point.
  double leader_x0 = 0, leader_y0 = 0, leader_x1 = 0, leader_y1 = 0;
};

// Places the labels in order. Candidates: 8 directions around the anchor
// (right, upper right, lower right, left, upper left, lower left, above,
// below: the box's nearest corner or edge centre at that point), first at
// gap from the anchor disc, then on rings ring_step farther out. A candidate
// is free when it lies inside bounds and overlaps no box placed before it,
// no box in taken, and no obstacle disc (nor the anchor disc). A label with
// no free candidate is nullopt (the caller says what was left out).
//   obstacles: discs no label may cover (glyphs), pixels.
//   taken:     boxes already used (e.g. legend, earlier labels).
std::vector<std::optional<PlacedLabel>> place_labels(std::span<const LabelRequest> labels,
                                                     std::span<const ScreenDisc> obstacles,
                                                     std::span<const PixelRect> taken,
                                                     const LabelLayoutOptions& options);

// A placement of box with a leader line from the anchor disc's edge
// towards the box's point nearest the anchor's centre.
PlacedLabel with_leader(const ScreenDisc& anchor, const PixelRect& box);

// Whether two boxes share interior pixels / a box meets a disc's interior.
bool boxes_overlap(const PixelRect& a, const PixelRect& b);
bool box_meets_disc(const PixelRect& box, const ScreenDisc& disc);
// Distance in pixels from a disc's edge to a box (0 when they meet).
double disc_box_gap(const ScreenDisc& disc, const PixelRect& box);

}  // namespace hq
