#pragma once
// Colour maps for HQView's views: a sequential map for vertex quality, a
// diverging map for signed error and a qualitative palette for clusters.
// Every function is pure and deterministic (fixed tables, no libm calls that
// could differ between platforms in the sampled colours).

#include <cstdint>
#include <vector>

#include "hqview/image/color.h"

namespace hq {

// The quality map, "bad = conspicuous": t = 1 (a perfect element) is a calm,
// pale blue-grey close to the background; lowering t walks through beige and
// orange to a saturated red at t = 0. Lightness falls monotonically (CIE L*
// 91 -> 42) and the path through CIELAB is sampled at equal colour-difference
// steps (ΔE*ab), so equal quality differences read as equal colour
// differences, and the few bad elements stand out against the many good ones
// that a viridis-like map would paint as loudly. t is clamped to [0, 1].
//
// Table: 33 samples of the polyline through CIELAB control points
// (t, L*, a*, b*) = (0, 42, 64, 46), (.25, 55, 50, 56), (.5, 68, 26, 60),
// (.75, 80, 6, 34), (1, 91, -2, -6), re-parameterised by arc length, D65 sRGB;
// all samples are inside the sRGB gamut.
Color sample_quality_map(double t);
// The quality map's 33 table samples, t = 0 first (sample_quality_map is
// their piecewise-linear interpolation): for renderers that map per fragment.
std::vector<Color> quality_map_samples();

// Inverted elements (quality < 0): a saturated blue-violet, outside the
// quality map's hues, and far from its red end for colour-blind readers too.
inline constexpr Color kInvertedColor{0.24f, 0.20f, 0.92f, 1.0f};
// Undefined values (NaN: e.g. vertices no hex uses): a dark neutral grey
// (#6c6c6c), CIEDE2000 >= 19 from the neutral cluster grey and >= 28 from
// the quality map (docs/analysis.md, "Colours").
inline constexpr Color kUndefinedColor{108.0f / 255.0f, 108.0f / 255.0f, 108.0f / 255.0f, 1.0f};

// Vertex quality (min corner scaled Jacobian, in [-1, 1]) to colour: [0, 1]
// through sample_quality_map, < 0 kInvertedColor, NaN kUndefinedColor,
// > 1 (rounding) as 1.
Color quality_color(double vertex_quality);

// Diverging blue - white - red (ColorBrewer RdBu, 11 classes, interpolated in
// sRGB) for signed values: t = -1 dark blue, 0 near-white, +1 dark red;
// clamped to [-1, 1]; NaN is kUndefinedColor.
Color diverging_color(double t);

// Colours of glyph clusters (ranked 0 = worst). The labelled clusters, the
// first labelled_cluster_count(K) ranks, each get their own colour of a
// 3-colour palette (issue 44 part R: #0 a vivid crimson, the most salient
// mark, then sea blue and pale mint; image/colormap.cpp says why no more
// fit); every other cluster wears the one neutral tone, so a colour in a
// picture always means one legend entry.
inline constexpr int kLabelledClusterPaletteSize = 3;
inline constexpr std::int64_t labelled_cluster_count(std::int64_t top_clusters) {
  return top_clusters < 0 ? 0 : (top_clusters > kLabelledClusterPaletteSize ? kLabelledClusterPaletteSize : top_clusters);
}
Color labelled_cluster_color(int i);  // i in [0, kLabelledClusterPaletteSize)
Color neutral_cluster_color();
Color cluster_color(std::int64_t rank, std::int64_t top_clusters);

// CIE L* (0 = black, 100 = white) of an sRGB colour, D65. For tests and for
// picking a readable text colour over a fill.
double cie_lightness(const Color& c);

}  // namespace hq
