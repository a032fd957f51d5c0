#pragma once
// The overview's cut-away insets (issue 45e): a group of inverted cells
// inside the volume (or on the far side) is only ringed on the overview, and
// the ring circles a spot where nothing looks wrong. An inset beside it
// draws that group's cells themselves, cut out of the model: the inverted
// cells opaque in the inverted colour (kInvertedColor, lit) with their
// edges, and the cells that share a vertex with them as a grey wire cage,
// seen from the overview's direction with the overview's up, zoomed to the
// neighbourhood. Each inverted cell is drawn shrunk towards its centre
// (kInsetShrink), so that cells that share faces stay apart and a folded
// one shows its crossing faces, and the vertices where a corner's scaled
// Jacobian is negative (vertex quality < 0) carry a dot in kInsetCornerColor
// (issue 45f, the 45e review's M5). A caption names it ("A: 14 inverted
// hexes, inside") and says what the colours are; the ring's label says
// "see inset A".
//
// Never over the model (issue 45f, the 45e review's M1): the insets take a
// strip of the overview's view, a column on its right or a row at its
// bottom, whichever leaves the model drawn larger (inset_strip), and the
// model is fitted into the rest.

#include <array>
#include <span>
#include <string>
#include <vector>

#include "hqview/image/image.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"
#include "hqview/views/inverted_callout.h"

namespace hq {

// At most this many insets per figure (the largest groups out of sight).
inline constexpr int kMaxInvertedInsets = 2;
// An inset's size, as fractions of the view's width and height.
inline constexpr double kInsetWidthFraction = 0.40;
inline constexpr double kInsetHeightFraction = 0.42;
// The neighbours' wire cage and the inset's frame and caption rule.
inline constexpr Rgba8 kInsetNeighbourColor{120, 124, 132, 255};
inline constexpr Rgba8 kInsetFrameColor{70, 70, 70, 255};
// Each inverted cell's corners are drawn this fraction of the way from its
// centre (1: as they are).
inline constexpr double kInsetShrink = 0.82;
// The dots on the vertices with a negative corner (vertex quality < 0):
// crimson on a white rim, in no other colour of the inset.
inline constexpr Rgba8 kInsetCornerColor{200, 0, 70, 255};

// A corner with det J < 0 has its three frame edges drawn in
// kInsetCornerColor (on a white halo, over everything) from its vertex this
// fraction of the way along each edge: where the cell folds (issue 45g).
inline constexpr double kInsetFoldReach = 0.6;

// Which groups get an inset (issue 45g): those out of sight (no inverted
// colour visible: inside, or on the far side; or a merged ring's groups out
// of sight, which the inset then draws alone), then those in sight but
// small (fewer inverted pixels than kSmallInvertedFraction of the view:
// "(small)"), up to kMaxInvertedInsets; a group whose blue is plainly in
// sight has none (the overview shows it).
inline bool callout_has_hidden(const InvertedCallout& c) { return !callout_in_sight(c) || !c.hidden_cells.empty(); }
inline bool callout_wants_inset(const InvertedCallout& c, double view_area) {
  return !c.cells.empty() &&
         (callout_has_hidden(c) || static_cast<double>(c.visible_pixels) < kSmallInvertedFraction * view_area);
}
// What an inset of c draws, as a callout of its own: a merged ring's
// hidden groups (InvertedCallout::hidden_cells) when it has any, else c.
InvertedCallout inset_part(const InvertedCallout& c);

// The corners of `cell` whose frame (CellKindTable corner_frames) is
// left-handed: each as {vertex, its three frame neighbours}, in corner order.
std::vector<std::array<Index, 4>> negative_corner_frames(const Mesh& mesh, const CellRef& cell);

// Where the insets go: `model` is the part of `view` the model is fitted
// into, `slots` the insets' rectangles (figure pixels), outside it. A column
// on the right (slots stacked from the top) or a row at the bottom
// (right-aligned, the first on the left), each inset kInset*Fraction of the view or less so that
// `count` of them fit with `margin` pixels around each: whichever lets a
// silhouette of silhouette_width x silhouette_height pixels (the model as
// fitted to the whole view) be drawn larger; ties: the column. count 0:
// model = view, no slots. Pure.
struct InsetStrip {
  PixelRect model;
  std::vector<PixelRect> slots;
};
InsetStrip inset_strip(const PixelRect& view, double silhouette_width, double silhouette_height, int count, int margin);

struct InvertedInset {
  std::size_t callout = 0;        // index into the callouts it shows
  std::string letter;             // "A", "B"
  PixelRect rect;                 // figure pixels: frame, caption and picture
  PixelRect picture;              // where the 3D picture is drawn, inside rect
  Camera camera;                  // the picture's camera (aspect: picture's)
  std::vector<Index> cells;       // the group's inverted cells (volume cell ids)
  std::vector<Index> neighbours;  // the cells sharing a vertex with them, not inverted, ascending
};

// The cells (ids over all volume cells, ascending) that share a vertex with
// any of `cells` and are not among them.
std::vector<Index> cells_touching(const HexMesh& mesh, std::span<const Index> cells);

// The 3D scene of an inset: `cells` shrunk by kInsetShrink as lit opaque
// faces in kInvertedColor with dark edges, a kInsetCornerColor dot on each
// of their corners whose vertex_quality is < 0 (empty: none), `neighbours`
// as a grey wire cage; origin at the centre of their corners' bounding box.
Scene inverted_inset_scene(const HexMesh& mesh, std::span<const Index> cells, std::span<const Index> neighbours,
                           std::span<const double> vertex_quality = {});

// The callouts that get an inset, in the slots' order: those that want one
// (callout_wants_inset: out of sight first, then small; each the largest
// first, the callouts' order), one per slot, until a slot too small for the
// caption and a picture.
std::vector<std::size_t> inset_callouts(std::span<const InvertedCallout> callouts, std::span<const PixelRect> slots,
                                        int text_size, double view_area);

// Plans the insets for inset_callouts, one per slot: each one's cells,
// neighbours, rect (its slot) and camera (`view_camera`'s direction and up,
// fitted to the cage); sets each such callout's `inset` letter.
std::vector<InvertedInset> plan_inverted_insets(const HexMesh& mesh, std::vector<InvertedCallout>& callouts,
                                                std::span<const PixelRect> slots, const Camera& view_camera,
                                                int text_size, double view_area);

// The insets' pictures (picture.width x picture.height each). Rendered
// before the overview's own frame, so that the renderer's last frame (what
// report.json views[].cameras records) is the overview's.
std::vector<Image> render_inverted_insets(const HexMesh& mesh, std::span<const InvertedInset> insets,
                                          std::span<const double> vertex_quality, Renderer& renderer);

// Draws each placed inset: a white box framed in kInsetFrameColor, two
// caption lines ("A: 14 inverted hexes, inside"; "blue: inverted, shrunk ·
// grey: nearby"; "dots, red edges: corners with det J < 0"), its picture.
void draw_inverted_insets(Image& figure, std::span<const InvertedInset> insets, std::span<const Image> pictures,
                          std::span<const InvertedCallout> callouts, const std::string& noun, int text_size,
                          const AnnotationStyle& style);

}  // namespace hq
