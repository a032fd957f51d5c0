#pragma once
// Bounded glyph clusters (issue 44): the connected components of the glyph
// overlap graph (glyph_clusters.h) chain across a model wherever a band of
// bad vertices runs through it (bunny_in: one component of 1,876 vertices
// from the hind leg to the front paws), and one glyph for such a chain sits
// where there is no defect. This splits every component into clusters of
// bounded extent, each around its own worst glyph:
//
//   repeat while the component has glyphs left:
//     seed = its largest remaining glyph (ties: the smallest id);
//     ball = the points closer than reach · r_seed to the seed (strictly);
//     cluster = the remaining glyphs of the ball that the seed reaches
//               through overlapping pairs of remaining glyphs of the ball.
//
// So every member of a cluster lies within reach · r_seed of its seed, a
// cluster is connected in the overlap graph, and, for reach ≥ 2, it holds
// every remaining glyph that overlaps its seed (a glyph overlapping the
// seed is closer than r_seed + r ≤ 2 r_seed). A component whose glyphs all
// lie that close to its largest one stays whole. Pure function of the
// positions and radii; identical for every thread count.

#include <span>

#include "hqview/core/vec3.h"
#include "hqview/glyph/glyph_clusters.h"

namespace hq {

// The default reach: a cluster's members lie within twice its worst glyph's
// radius of it, i.e. inside the drawn disc's diameter (docs/analysis.md,
// "Glyphs and clusters", measured counts).
inline constexpr double kClusterReach = 2.0;

// Splits the clusters of `components` (cluster_glyphs() of the same
// positions and radii) as above.
//   positions, radii: as given to cluster_glyphs (model units).
//   reach:            > 0, the ball's radius in units of the seed's radius.
// The result follows GlyphClusters' conventions (members ascending, clusters
// numbered by their smallest member). Throws Error when the sizes differ or
// reach is not a positive finite number.
GlyphClusters bound_glyph_clusters(const GlyphClusters& components, std::span<const Vec3> positions,
                                   std::span<const double> radii, double reach = kClusterReach);

}  // namespace hq
