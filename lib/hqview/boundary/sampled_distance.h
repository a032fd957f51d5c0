#pragma once
// Certified sampled distance from one triangle surface to another (the
// boundary error over the surfaces, not only at vertices; docs/analysis.md
// "Sampled boundary error"). Over a triangle patch the distance to the
// target surface is at most
//  - the distance at the patch's centroid plus the patch's covering radius
//    (the largest centroid-to-corner length): the distance is 1-Lipschitz,
//    and the distance from a point is convex, so its maximum over a triangle
//    is at a corner;
//  - the largest distance of the patch's corners to the target triangle
//    closest to its centroid: the distance to one triangle is convex, so its
//    maximum over the patch is at a corner, and it bounds the distance to
//    the whole target (tight where the target is flat under the patch).
// The smaller of the two is the patch's bound. Patches are split at their
// edge midpoints (4 similar children, the radius halves) until their bound is
// within `tolerance` of the largest distance found. Plain code over
// ClosestPointTree; no CGAL here.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "hqview/boundary/surface_distance.h"
#include "hqview/core/types.h"

namespace hq {

struct SampledDistanceOptions {
  // Model units: stop splitting a patch once centroid distance + radius is at
  // most (largest distance found) + tolerance.
  double tolerance = 0;
  // Model units: the first patches of a triangle are its midpoint subdivision
  // to the coarsest level whose radius is at most this (0: the triangles
  // themselves), at most max_initial_level; sets the resolution of the
  // colour and of the area-weighted means.
  double initial_radius = 0;
  int max_initial_level = 6;
  // No patch is split beyond this level, nor once more samples than
  // max_samples, or than 1e6 + 8 x the initial patches, were taken (the
  // bound then says so: upper_bound - max_distance > tolerance).
  int max_level = 24;
  std::int64_t max_samples = 50'000'000;
  // A distance already known to be reached on the source (e.g. at its
  // vertices): patches below it are not split.
  double known_distance = 0;
  // When not empty: the closest point of each source triangle's centroid,
  // already queried; a triangle sampled whole (initial level 0) takes it
  // instead of a new query.
  std::span<const ClosestPoint> triangle_centroids;
};

// Line segments: the boundary polylines of a planar mesh and the outline of
// a planar reference (docs/analysis.md, "Planar meshes").
struct SegmentSet {
  std::vector<Vec3> points;
  std::vector<std::array<Index, 2>> segments;
};

// A leaf patch: a triangle of the subdivision with its centroid sample (of
// a segment source: a piece (a, b) of a segment, stored as the flat
// triangle (a, (a + b) / 2, b), whose centroid is its midpoint).
struct SamplePatch {
  std::array<Vec3, 3> corners;
  Index source_triangle = kNoIndex;  // the source triangle it subdivides
  Vec3 centre;                       // the sample: the centroid
  double area = 0;                   // model units squared (a segment's piece: its length)
  ClosestPoint closest;              // on the target, for the centre
};

struct SampledDistance {
  // Leaves in a fixed order (level by level, each level in source order):
  // they tile the source triangles exactly.
  std::vector<SamplePatch> patches;
  double max_distance = 0;  // the largest distance sampled (and known_distance)
  double upper_bound = 0;   // certified: no point of the source is farther from the target
  std::int64_t num_samples = 0;  // samples taken (every level; given centroids included)
  int deepest_level = 0;
};

// Source triangles of zero area contribute nothing. Deterministic for any
// thread count. The target tree must hold a triangle of positive area.
SampledDistance sample_distance(const TriSurface& source, const ClosestPointTree& target,
                                const SampledDistanceOptions& options);

// The same over segments (a boundary polyline): each piece is split in two
// halves, its radius half its length, the same two bounds (the distance
// to a surface is 1-Lipschitz along the segment; the distance to one
// triangle is convex along it). Segments of zero length contribute nothing.
SampledDistance sample_distance(const SegmentSet& source, const ClosestPointTree& target,
                                const SampledDistanceOptions& options);

}  // namespace hq
