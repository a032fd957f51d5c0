#pragma once
// Overlap clustering of sphere glyphs (ALGORITHMS.md §3, paper goal G1):
// the connected components of the graph whose edges join two glyphs that
// overlap, |pi − pj| < ri + rj (strictly). The paper's implementation tests
// all pairs and merges sets repeatedly (O(n²) and worse); this one finds the
// candidate pairs with a uniform grid and merges them with a concurrent
// union-find, in expected O(n) time for glyphs of comparable size.

#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/vec3.h"

namespace hq {

// The overlap predicate, |a − b| < ra + rb, decided exactly as written here:
// the squared distance ((dx² + dy²) + dz²) against (ra + rb)², both in double
// precision. It is symmetric, bit for bit. Glyphs exactly at distance ra + rb
// touch and do not overlap; coincident glyphs with a positive radius overlap
// (as long as (ra + rb)² does not underflow, i.e. for radii above ~1e-154).
// Every pair cluster_glyphs() merges satisfies this predicate and every pair
// that satisfies it ends up in one cluster.
inline bool glyphs_overlap(const Vec3& a, double ra, const Vec3& b, double rb) {
  const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  const double sum = ra + rb;
  return dx * dx + dy * dy + dz * dz < sum * sum;
}

struct GlyphClusters {
  // Per point: its cluster, or kNoIndex (−1) for a point without a glyph.
  std::vector<Index> point_cluster;
  // Members of cluster c: members[offsets[c] .. offsets[c+1]), ascending ids.
  // Clusters are numbered by their smallest member id (cluster 0 holds the
  // glyph with the lowest id), so the numbering depends on the input only.
  std::vector<Index> offsets;  // num_clusters() + 1
  std::vector<Index> members;  // every glyph once

  Index num_clusters() const { return offsets.empty() ? 0 : static_cast<Index>(offsets.size()) - 1; }
};

// Clusters the glyphs centred at positions[i] with radius radii[i].
//   positions: #P points, model units, finite.
//   radii:     #P radii, model units. A point has a glyph when its radius is
//              finite and > 0; 0, negative, NaN and infinite radii mean no glyph.
// Every glyph, even one that overlaps nothing, belongs to exactly one cluster.
// Parallel (TBB); the result is identical for every thread count.
// Throws Error when the spans differ in size.
//
// Cost: sorting the glyphs into grid cells (cell size twice the 99th
// percentile radius, at least half the largest radius), then testing each
// glyph against the glyphs of the neighbouring cells that are within reach;
// the 1% larger glyphs search a box of ±2r around themselves. A glyph stops
// testing a neighbour cell whose glyphs already form one cluster at its
// first overlap, so dense regions of overlapping glyphs stay cheap. Linear
// in the number of glyphs for a bounded number of glyphs per cell.
GlyphClusters cluster_glyphs(std::span<const Vec3> positions, std::span<const double> radii);

}  // namespace hq
