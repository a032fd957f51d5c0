#pragma once
// The overview's cut-away insets (issue 45e): a group of inverted cells
// inside the volume (or on the far side) is only ringed on the overview, and
// the ring circles a spot where nothing looks wrong. An inset beside it
// draws that group's cells themselves, cut out of the model: the inverted
// cells opaque in the inverted colour (kInvertedColor, lit) with their
// edges, and the cells that share a vertex with them as a grey wire cage,
// seen from the overview's direction with the overview's up, zoomed to the
// neighbourhood. A caption names it ("A: 14 inverted hexes, inside") and
// says what the colours are; the ring's label says "see inset A". Drawn
// over the rings (a ring as large as the model may pass under it).
//
// Placed in a corner of the overview's view where it covers the fewest
// model pixels and no ring (deterministic: ties in the order bottom right,
// bottom left, top right, top left).

#include <span>
#include <string>
#include <vector>

#include "hqview/image/image.h"
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

// The 3D scene of an inset: `cells` as lit opaque faces in kInvertedColor
// with dark edges, `neighbours` as a grey wire cage; origin at the centre of
// their corners' bounding box.
Scene inverted_inset_scene(const HexMesh& mesh, std::span<const Index> cells, std::span<const Index> neighbours);

// Plans the insets for the callouts out of sight (callout_in_sight false),
// the largest first (the callouts' order), at most kMaxInvertedInsets: each
// one's cells, neighbours, size (kInset*Fraction of `view`; rect at the
// view's origin until placed) and camera (`view_camera`'s direction and up,
// fitted to the cage); sets each such callout's `inset` letter.
std::vector<InvertedInset> plan_inverted_insets(const HexMesh& mesh, std::vector<InvertedCallout>& callouts,
                                                const PixelRect& view, const Camera& view_camera, int text_size);

// The insets' pictures (picture.width x picture.height each). Rendered
// before the overview's own frame, so that the renderer's last frame (what
// report.json views[].cameras records) is the overview's.
std::vector<Image> render_inverted_insets(const HexMesh& mesh, std::span<const InvertedInset> insets,
                                          Renderer& renderer);

// Moves each inset to a corner of `view`: the free one covering the fewest
// pixels of `figure` unlike `background` (the model) and no ring.
void place_inverted_insets(std::vector<InvertedInset>& insets, std::span<const InvertedCallout> callouts,
                           const Image& figure, const PixelRect& view, Rgba8 background, const AnnotationStyle& style);

// Draws each placed inset: a white box framed in kInsetFrameColor, two
// caption lines ("A: 14 inverted hexes, inside"; "blue: inverted · grey:
// their neighbours"), its picture.
void draw_inverted_insets(Image& figure, std::span<const InvertedInset> insets, std::span<const Image> pictures,
                          std::span<const InvertedCallout> callouts, const std::string& noun, int text_size,
                          const AnnotationStyle& style);

}  // namespace hq
