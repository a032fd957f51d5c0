#pragma once
// Greedy label placement in screen space (issue 44, "no pile-ups"; the
// paper's future work asks for "a view-dependent placement of arrows"):
// labels are placed one by one, in the caller's order of importance, each at
// the first free candidate position around its anchor, so that no two labels
// overlap and no label covers an obstacle disc (the glyphs). A label that
// cannot sit next to its anchor moves outwards and gets a leader line.
// Pure geometry on pixel coordinates; nothing here draws.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "hqview/render/annotate.h"

namespace hq {

// A disc on screen, pixels (a glyph's silhouette, an anchor's marker).
// id: whose disc it is (>= 0), so that an obstacle with its label's anchor
// id is that label's own (its glyph, its fan); -1: no id (then an obstacle
// centred exactly on the anchor is its own).
struct ScreenDisc {
  double x = 0, y = 0, radius = 0;
  std::int64_t id = -1;
};

// One label to place: its anchor (a disc: the label stays outside it) and
// its box size in pixels. leader_from: where its leader line starts (a disc
// inside the visible part of a partly hidden glyph: the leader begins on
// its edge, so it ends on what the reader sees); none: the anchor.
// always_leader: the label gets a leader wherever it sits (its glyph is
// mostly hidden, so a label merely beside it would not say which it names).
// protect_below: the obstacle discs with 0 <= id < protect_below (the
// glyphs ranked before this label's, issue 44) are never crossed by its
// leader, in any pass (unless the leader starts inside one); 0: none.
struct LabelRequest {
  ScreenDisc anchor;
  int width = 0, height = 0;
  std::optional<ScreenDisc> leader_from = std::nullopt;
  bool always_leader = false;
  std::int64_t protect_below = 0;
  // Its leader never crosses an earlier leader or a placed box, nor its box
  // an earlier leader, in any pass (view A, issue 44's fifth round);
  // false: only the first two passes keep to that.
  bool strict_leaders = false;
};

struct LabelLayoutOptions {
  PixelRect bounds;         // labels stay inside
  double gap = 4.0;         // pixels between the anchor disc and a label next to it
  double ring_step = 14.0;  // pixels between successive rings of candidates
  int rings = 24;           // rings tried before a label is given up
  // A label whose box is farther than this from its anchor disc gets a
  // leader line (pixels); so does one that another obstacle disc comes
  // within this distance of (nearer than its own anchor plus this), which
  // would read as naming that one.
  double leader_distance = 10.0;
  // Pixels a clear leader (the first pass) keeps off the other discs, so
  // that its line and halo do not graze them (0: it may touch a rim).
  double leader_clearance = 0.0;
};

struct PlacedLabel {
  PixelRect box;
  bool has_leader = false;
  // Leader line from the anchor disc's edge to the box's nearest point.
  double leader_x0 = 0, leader_y0 = 0, leader_x1 = 0, leader_y1 = 0;
};

// Places the labels in order. Candidates: 8 directions around the anchor
// (right, upper right, lower right, left, upper left, lower left, above,
// below: the box's nearest corner or edge centre at that point), then,
// where a ring is long enough, the directions halfway between them and so on
// (up to 64 a ring) until neighbouring candidates are at most the label's
// height (or ring_step) apart, first at
// gap from the anchor disc, then on rings ring_step farther out; of a ring's
// free candidates the one with the most room to the other obstacle discs
// (counted up to 3 leader distances; ties in that order). A candidate
// is free when it lies inside bounds and overlaps no box placed before it,
// no box in taken, and no obstacle disc (nor the anchor disc). A candidate
// needs a leader when its box is farther than leader_distance from the
// anchor disc or another obstacle disc is not clearly farther (within the
// anchor's gap + leader_distance: the label would read as that one's).
// The first pass takes only clear candidates: not beside another disc
// unless it has a leader, its leader crossing no earlier leader, no placed
// box and no obstacle disc but its own anchor (nor coming within
// leader_clearance of one), its box crossed by no earlier
// leader. When none is clear, the second pass lets the leader run over
// other discs, and the third takes the first free place (with a leader
// when it needs one) whose leader runs along no earlier leader
// (leaders_run_together), the fourth any free place. In every pass a
// leader crosses no protected disc (LabelRequest::protect_below), and with LabelRequest::strict_leaders no
// earlier leader or placed box, nor a box an earlier leader. A label with no free
// candidate is
// nullopt (the caller says what was left out). An obstacle with the
// anchor's id (ScreenDisc::id) is the label's own (its glyph or fan): the
// label may be beside it and its leader may cross it.
//   obstacles: discs no label may cover (glyphs), pixels.
//   taken:     boxes already used (e.g. legend, earlier labels).
//   earlier:   labels placed by an earlier call: their boxes are taken and
//              their leaders count as the leaders of this call's labels.
std::vector<std::optional<PlacedLabel>> place_labels(std::span<const LabelRequest> labels,
                                                     std::span<const ScreenDisc> obstacles,
                                                     std::span<const PixelRect> taken,
                                                     const LabelLayoutOptions& options,
                                                     std::span<const PlacedLabel> earlier = {});

// Obstacle discs in a grid of 64-pixel cells (each in the cells its disc's
// square meets), so that a label's candidate looks at its neighbourhood
// only (with up to 64 candidates a ring and a thousand glyphs, scanning
// them all was the cost of a view). Built once for every label placed
// among the same discs (LabelPlacer::place).
class DiscIndex {
 public:
  explicit DiscIndex(std::span<const ScreenDisc> discs);
  // Whether a disc registered in a cell that [x0, x1] x [y0, y1] meets
  // satisfies pred (label_layout.cpp only).
  template <class Pred>
  bool any_near(double x0, double y0, double x1, double y1, Pred&& pred) const;

 private:
  std::vector<ScreenDisc> discs_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

// The greedy placement one label at a time (place_labels is a loop over
// it): the boxes and leaders placed so far in a grid of 64-pixel cells, so
// a label's checks look at its neighbourhood only (near-linear in the
// labels), and each candidate checked once for all three passes.
class LabelPlacer {
 public:
  // avoid: boxes no label's box overlaps, its leader may cross them (the
  // model under the labels, inverted_callout.h).
  LabelPlacer(std::span<const PixelRect> taken, const LabelLayoutOptions& options, std::span<const PixelRect> avoid = {});
  // Where label goes among obstacles (place_labels' rules), given what was
  // added so far; nullopt when there is no free place. Adds nothing.
  std::optional<PlacedLabel> place(const LabelRequest& label, const DiscIndex& obstacles) const;
  std::optional<PlacedLabel> place(const LabelRequest& label, std::span<const ScreenDisc> obstacles) const {
    return place(label, DiscIndex(obstacles));
  }
  // A placed label: its box is taken, its leader counts for later labels.
  void add(const PlacedLabel& label);

 private:
  void add_box(const PixelRect& box);
  template <class Pred>
  bool any_box_near(double x0, double y0, double x1, double y1, Pred&& pred) const;
  template <class Pred>
  bool any_leader_near(double x0, double y0, double x1, double y1, Pred&& pred) const;

  LabelLayoutOptions options_;
  std::vector<PixelRect> boxes_;
  std::vector<PlacedLabel> leaders_;
  std::vector<PixelRect> avoid_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> box_cells_, leader_cells_, avoid_cells_;
};

// Margin callout columns (issue 44 part V: dolphin_rot's pile-up of a
// dozen glyphs at one end had labels 200 px away and leaders over rings).
// Labels that find no clear place near their glyph are stacked in a column
// at the left or right edge of bounds, each with a leader from its start
// disc's edge to the middle of its box's inner side (the side facing the
// model). Slots start every quarter of a step (the tallest label's height
// plus 3 gap) from bounds.y + gap down, two labels a step apart; a slot is
// free when the column's widest box there overlaps no taken box and meets
// no obstacle disc. The labels, by the x
// of their start disc, go to the left column up to a split and to the
// right one after it (so a left leader and a right one never cross); in a
// column they take free slots in the order of their start's y (a dynamic
// program over the slots, cost: the leader's length plus box_cost of the
// slot's box, e.g. the model pixels it would hide; a label whose start is
// not on a column's inner side, at least gap in, cannot go there: its
// leader would cross that column's boxes), then two leaders that
// cross swap slots until none do (a swap shortens their total length, so
// it ends). The split of least total cost wins. Empty when there are not
// enough free slots for all labels (nothing is left out half way).
//   starts: where each leader starts (a disc inside its glyph; radius 0:
//           at the point), widths/heights: the boxes' sizes, pixels.
//   protect_below: as LabelRequest's (the leader crosses no obstacle with
//           0 <= id < protect_below but start's own, unless it starts in
//           it, wherever the columns allow: a crossing costs 1e6).
// The same with rows at the top and bottom of bounds (x and y swapped:
// leaders to the middle of the box's bottom or top side); of columns and
// rows the layout of least cost.
struct CalloutLabel {
  ScreenDisc start;
  int width = 0, height = 0;
  std::int64_t protect_below = 0;
};
std::vector<PlacedLabel> place_callout_columns(std::span<const CalloutLabel> labels,
                                               std::span<const ScreenDisc> obstacles,
                                               std::span<const PixelRect> taken, const PixelRect& bounds, double gap,
                                               const std::function<double(const PixelRect&)>& box_cost = {});

// A placement of box with a leader line from the anchor disc's edge
// towards the box's point nearest the anchor's centre.
PlacedLabel with_leader(const ScreenDisc& anchor, const PixelRect& box);

// Whether two boxes share interior pixels / a box meets a disc's interior.
bool boxes_overlap(const PixelRect& a, const PixelRect& b);
// Whether two leader lines cross (share a point; touching ends count).
bool leaders_cross(const PlacedLabel& a, const PlacedLabel& b);
// Whether more than 15 px of b's leader lie within 8 px of a's (they would
// read as one line, or as two labels of one mark).
bool leaders_run_together(const PlacedLabel& a, const PlacedLabel& b);
// Whether a leader line passes through a box's / a disc's interior.
bool leader_meets_box(const PlacedLabel& leader, const PixelRect& box);
bool leader_meets_disc(const PlacedLabel& leader, const ScreenDisc& disc);
// Whether a leader runs over a disc: meets it, and when the disc holds its
// start, reaches more than a pixel nearer its centre than the start (the
// 44l review: "#3 behind #1" started on #1's disc and ran through all of
// it; a leader heading out of the disc does not count).
bool leader_over_disc(const PlacedLabel& leader, const ScreenDisc& disc);
bool box_meets_disc(const PixelRect& box, const ScreenDisc& disc);
// Distance in pixels from a disc's edge to a box (0 when they meet).
double disc_box_gap(const ScreenDisc& disc, const PixelRect& box);

}  // namespace hq
