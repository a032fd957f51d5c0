#include "hqview/boundary/sampled_distance.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hqview/boundary/triangle_closest_point.h"

namespace hq {
namespace {

// A patch of a source triangle (N = 3) or segment (N = 2).
template <int N>
struct Patch {
  std::array<Vec3, N> corners;
  Index source = kNoIndex;
  int level = 0;
  bool whole = false;  // the source triangle or segment itself
};

template <int N>
Vec3 centroid(const std::array<Vec3, N>& c) {
  Vec3 sum = c[0];
  for (int k = 1; k < N; ++k) sum = sum + c[k];
  return sum / static_cast<double>(N);
}

template <int N>
double radius(const std::array<Vec3, N>& c) {
  const Vec3 m = centroid<N>(c);
  double r = 0;
  for (const Vec3& p : c) r = std::max(r, norm(p - m));
  return r;
}

// The patch's bound (sampled_distance.h): the smaller of the Lipschitz bound
// and the corners' largest distance to the centroid's closest triangle.
template <int N>
double patch_bound(const std::array<Vec3, N>& corners, const ClosestPoint& closest, const TriSurface& target) {
  double bound = closest.distance + radius<N>(corners);
  if (closest.triangle == kNoIndex) return bound;
  const auto& t = target.triangles[static_cast<std::size_t>(closest.triangle)];
  const Vec3 &a = target.points[t[0]], &b = target.points[t[1]], &c = target.points[t[2]];
  double corner_max = 0;
  for (const Vec3& p : corners) corner_max = std::max(corner_max, norm(p - closest_point_on_triangle(p, a, b, c)));
  return std::min(bound, corner_max);
}

// A triangle's area, a segment's length.
double measure(const std::array<Vec3, 3>& c) { return 0.5 * norm(cross(c[1] - c[0], c[2] - c[0])); }
double measure(const std::array<Vec3, 2>& c) { return norm(c[1] - c[0]); }

// As SamplePatch stores it: a segment (a, b) as the flat triangle (a, midpoint, b).
std::array<Vec3, 3> as_triangle(const std::array<Vec3, 3>& c) { return c; }
std::array<Vec3, 3> as_triangle(const std::array<Vec3, 2>& c) { return {c[0], (c[0] + c[1]) * 0.5, c[1]}; }

// The children of the midpoint subdivision: a triangle's four (corner
// children first, then the middle one), a segment's two halves.
void split(const Patch<3>& p, std::vector<Patch<3>>& out) {
  const Vec3 &a = p.corners[0], &b = p.corners[1], &c = p.corners[2];
  const Vec3 ab = (a + b) * 0.5, bc = (b + c) * 0.5, ca = (c + a) * 0.5;
  out.push_back({{a, ab, ca}, p.source, p.level + 1});
  out.push_back({{ab, b, bc}, p.source, p.level + 1});
  out.push_back({{ca, bc, c}, p.source, p.level + 1});
  out.push_back({{ab, bc, ca}, p.source, p.level + 1});
}
void split(const Patch<2>& p, std::vector<Patch<2>>& out) {
  const Vec3 m = (p.corners[0] + p.corners[1]) * 0.5;
  out.push_back({{p.corners[0], m}, p.source, p.level + 1});
  out.push_back({{m, p.corners[1]}, p.source, p.level + 1});
}

// p subdivided `levels` times, appended to out as level-0 patches.
template <int N>
void subdivide_into(const Patch<N>& p, int levels, std::vector<Patch<N>>& out) {
  if (levels == 0) {
    out.push_back({p.corners, p.source, 0, false});
    return;
  }
  std::vector<Patch<N>> children;
  split(p, children);
  for (const Patch<N>& child : children) subdivide_into(child, levels - 1, out);
}

// Level-0 patches: each source element (corners_of(0 .. count - 1)) of
// positive measure subdivided to the coarsest level whose radius is at most
// options.initial_radius.
template <int N, class Corners>
std::vector<Patch<N>> initial_patches(std::size_t count, Corners&& corners_of, const SampledDistanceOptions& options) {
  std::vector<Patch<N>> patches;
  patches.reserve(count);
  for (std::size_t t = 0; t < count; ++t) {
    const Patch<N> p{corners_of(t), static_cast<Index>(t), 0, true};
    if (!(measure(p.corners) > 0.0)) continue;
    int level = 0;
    if (options.initial_radius > 0.0) {
      const double r = radius<N>(p.corners);
      while (level < options.max_initial_level && r / std::ldexp(1.0, level) > options.initial_radius) ++level;
    }
    if (level == 0)
      patches.push_back(p);
    else
      subdivide_into(p, level, patches);
  }
  return patches;
}

// sample_distance over the `count` elements (triangles or segments) of a
// source, corners_of(i) the corners of element i.
template <int N, class Corners>
SampledDistance sample_elements(std::size_t count, Corners&& corners_of, const ClosestPointTree& target,
                                const SampledDistanceOptions& options) {
  constexpr std::size_t kChildren = N == 3 ? 4 : 2;
  SampledDistance out;
  out.max_distance = options.known_distance;
  std::vector<Patch<N>> current = initial_patches<N>(count, corners_of, options), next;
  const std::int64_t budget =
      std::min<std::int64_t>(options.max_samples, 1'000'000 + 8 * static_cast<std::int64_t>(current.size()));
  std::vector<Vec3> centres, queries;
  std::vector<std::size_t> asked;
  for (int level = 0; !current.empty(); ++level) {
    // Centroids: given (a whole source element at level 0) or queried.
    centres.clear();
    queries.clear();
    asked.clear();
    for (std::size_t i = 0; i < current.size(); ++i) {
      centres.push_back(centroid<N>(current[i].corners));
      if (level > 0 || !current[i].whole || options.triangle_centroids.empty()) {
        queries.push_back(centres.back());
        asked.push_back(i);
      }
    }
    std::vector<ClosestPoint> closest(current.size());
    if (level == 0 && !options.triangle_centroids.empty())
      for (std::size_t i = 0; i < current.size(); ++i)
        if (current[i].whole) closest[i] = options.triangle_centroids[static_cast<std::size_t>(current[i].source)];
    const std::vector<ClosestPoint> answers = target.query(queries);
    for (std::size_t k = 0; k < asked.size(); ++k) closest[asked[k]] = answers[k];
    out.num_samples += static_cast<std::int64_t>(closest.size());
    out.deepest_level = level;
    for (const ClosestPoint& c : closest) out.max_distance = std::max(out.max_distance, c.distance);
    next.clear();
    const TriSurface& surface = target.surface();
    std::vector<double> bounds(current.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, current.size()), [&](const auto& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
        bounds[i] = patch_bound<N>(current[i].corners, closest[i], surface);
    });
    if (level == 0) out.patches.reserve(current.size());
    for (std::size_t i = 0; i < current.size(); ++i) {
      const double bound = bounds[i];
      const bool within_budget = out.num_samples + static_cast<std::int64_t>(next.size() + kChildren) <= budget;
      if (bound > out.max_distance + options.tolerance && level < options.max_level && within_budget) {
        split(current[i], next);
        continue;
      }
      out.upper_bound = std::max(out.upper_bound, bound);
      out.patches.push_back({as_triangle(current[i].corners), current[i].source, centres[i], measure(current[i].corners),
                             closest[i]});
    }
    current.swap(next);
  }
  out.upper_bound = std::max(out.upper_bound, out.max_distance);
  return out;
}

}  // namespace

SampledDistance sample_distance(const TriSurface& source, const ClosestPointTree& target,
                                const SampledDistanceOptions& options) {
  return sample_elements<3>(
      source.triangles.size(),
      [&](std::size_t i) {
        const auto& t = source.triangles[i];
        return std::array<Vec3, 3>{source.points[t[0]], source.points[t[1]], source.points[t[2]]};
      },
      target, options);
}

SampledDistance sample_distance(const SegmentSet& source, const ClosestPointTree& target,
                                const SampledDistanceOptions& options) {
  return sample_elements<2>(
      source.segments.size(),
      [&](std::size_t i) {
        const auto& s = source.segments[i];
        return std::array<Vec3, 2>{source.points[s[0]], source.points[s[1]]};
      },
      target, options);
}

}  // namespace hq
