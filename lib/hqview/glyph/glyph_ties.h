#pragma once
// Ties among ranked glyph clusters (issue 44, part T). Clusters are ranked
// by min quality, but many meshes have clusters whose min qualities are the
// same (a Gmsh-twisted star: 96 clusters at 0.21; a mirrored mesh: every
// cluster at -0.999) or differ by noise (1e-4). Ranking them into one red
// #0, five coloured and ninety grey glyphs tells a hierarchy the data does
// not have. A tie class is a run of consecutive ranks whose min qualities
// lie within kGlyphTieTolerance of the run's first (worst) one, on the same
// side of 0 (an inverted cluster never ties a merely poor one). The views
// draw a class alike (one colour, radii by the same rule) and label it as a
// tie ("N tied at q").

#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/glyph/glyphs.h"

namespace hq {

// Scaled-Jacobian units: min qualities closer than this to the class's
// first are "the same worst value" (the views print 3 significant figures).
inline constexpr double kGlyphTieTolerance = 1e-3;

// Per cluster (by rank), its tie class: 0 for the first class (holding #0),
// ascending, consecutive ranks share a class. A class starts at rank r when
// min_quality[r] - min_quality[first of the current class] > tolerance, or
// the two lie on different sides of 0 (q < 0 against q >= 0). NaN min
// qualities never tie. Pure; linear in the number of clusters.
//   clusters:  by rank (GlyphResult::clusters).
//   tolerance: >= 0, scaled-Jacobian units.
std::vector<Index> glyph_tie_classes(std::span<const AggregatedGlyph> clusters,
                                     double tolerance = kGlyphTieTolerance);

// Members per class (by class index) of glyph_tie_classes' result.
std::vector<Index> tie_class_sizes(std::span<const Index> classes);

// At most this many glyphs wear a cluster colour (issue 44 part T: six tie
// classes of 30, 6, 18, ... coloured glyphs buried a Gmsh star): classes
// are coloured in order while their members add up to at most this; the
// first class always is.
inline constexpr Index kMaxColouredGlyphs = 12;

// How many tie classes (the first ones) wear a cluster colour: at most
// max_classes (the palette's, labelled_cluster_count(K)), and while their
// sizes sum to at most max_glyphs (the first class whatever its size).
Index coloured_tie_classes(std::span<const Index> class_sizes, Index max_classes, Index max_glyphs = kMaxColouredGlyphs);

// Per cluster its colour slot: its tie class when that class is coloured
// (coloured_tie_classes), else -1 (the neutral grey); cluster_color(slot, K)
// (image/colormap.h) is its colour in every output.
std::vector<Index> glyph_colour_slots(std::span<const AggregatedGlyph> clusters, Index max_classes);

}  // namespace hq
