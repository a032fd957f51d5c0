#include "hqview/glyph/glyphs.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hqview/core/error.h"
#include "hqview/glyph/bounded_clusters.h"
#include "hqview/glyph/glyph_clusters.h"

namespace hq {

double glyph_size_bonus(std::int64_t size) {
  const std::int64_t tens = std::clamp<std::int64_t>(size / 10, 0, 10);
  return static_cast<double>(tens) / 10.0;
}

const char* glyph_size_rule_name(GlyphSizeRule rule) { return rule == GlyphSizeRule::kPaper ? "paper" : "severity"; }

double resolve_rmax(const GlyphOptions& options, double mean_edge_length) {
  return options.rmax_unit == RmaxUnit::kMeanEdgeLength ? options.rmax * mean_edge_length : options.rmax;
}

std::vector<double> glyph_radii(std::span<const double> vertex_quality, double rmax, double threshold) {
  std::vector<double> radii(vertex_quality.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, radii.size(), 8192),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t v = r.begin(); v != r.end(); ++v) {
                        const double c = glyph_ratio(vertex_quality[v]);
                        if (c > threshold) radii[v] = c * rmax;  // NaN compares false: no glyph
                      }
                    });
  return radii;
}

AggregatedGlyph aggregate_glyph(std::span<const Index> members, std::span<const Vec3> points,
                                std::span<const double> vertex_quality, double rmax, GlyphSizeRule size_rule) {
  AggregatedGlyph glyph;
  glyph.size = static_cast<Index>(members.size());
  if (members.empty()) return glyph;
  Vec3 sum;
  double min_quality = vertex_quality[static_cast<std::size_t>(members[0])];
  for (Index v : members) {
    sum = sum + points[static_cast<std::size_t>(v)];
    min_quality = std::min(min_quality, vertex_quality[static_cast<std::size_t>(v)]);
  }
  Index at = members[0];
  if (size_rule == GlyphSizeRule::kPaper) {
    // HQViewer: the member nearest to the members' mean.
    const Vec3 mean = sum / static_cast<double>(members.size());
    double nearest_distance = squared_norm(points[static_cast<std::size_t>(at)] - mean);
    for (Index v : members) {
      const double d = squared_norm(points[static_cast<std::size_t>(v)] - mean);
      if (d < nearest_distance || (d == nearest_distance && v < at)) {
        at = v;
        nearest_distance = d;
      }
    }
  } else {
    // The worst member (members ascend, so the first of equal ones).
    for (Index v : members)
      if (vertex_quality[static_cast<std::size_t>(v)] < vertex_quality[static_cast<std::size_t>(at)]) at = v;
  }
  glyph.representative_vertex = at;
  glyph.position = points[static_cast<std::size_t>(at)];
  glyph.min_quality = min_quality;
  // The largest member ratio is the ratio of the smallest quality (1 − x is
  // monotone in floating point too).
  glyph.ratio = glyph_ratio(min_quality);
  if (size_rule == GlyphSizeRule::kPaper) glyph.ratio += glyph_size_bonus(glyph.size);
  glyph.radius = glyph.ratio * rmax;
  return glyph;
}

GlyphResult compute_glyphs(std::span<const Vec3> points, std::span<const double> vertex_quality,
                           double mean_edge_length, const GlyphOptions& options) {
  if (points.size() != vertex_quality.size())
    throw Error("compute_glyphs: " + std::to_string(points.size()) + " points but " +
                std::to_string(vertex_quality.size()) + " vertex qualities");
  GlyphResult result;
  result.options = options;
  result.rmax = resolve_rmax(options, mean_edge_length);
  result.vertex_radius = glyph_radii(vertex_quality, result.rmax, options.threshold);
  // Severity: the overlap components split into clusters around their worst
  // glyphs (bounded_clusters.h); paper: HQViewer's components as they are.
  GlyphClusters clusters = cluster_glyphs(points, result.vertex_radius);
  if (options.size_rule == GlyphSizeRule::kSeverity)
    clusters = bound_glyph_clusters(clusters, points, result.vertex_radius, options.cluster_reach);
  // A radius that is not a positive finite number (rmax 0 or absurdly large)
  // is no glyph for the clustering: keep the two consistent.
  for (std::size_t v = 0; v < points.size(); ++v)
    if (clusters.point_cluster[v] == kNoIndex) result.vertex_radius[v] = 0.0;
  result.num_glyphs = static_cast<Index>(clusters.members.size());

  const Index n = clusters.num_clusters();
  std::vector<AggregatedGlyph> unranked(static_cast<std::size_t>(n));
  tbb::parallel_for(tbb::blocked_range<Index>(0, n, 64), [&](const tbb::blocked_range<Index>& r) {
    for (Index c = r.begin(); c != r.end(); ++c) {
      const auto begin = clusters.members.begin() + clusters.offsets[static_cast<std::size_t>(c)];
      const auto end = clusters.members.begin() + clusters.offsets[static_cast<std::size_t>(c) + 1];
      unranked[static_cast<std::size_t>(c)] =
          aggregate_glyph(std::span<const Index>(begin, end), points, vertex_quality, result.rmax, options.size_rule);
    }
  });

  // Rank: worst min quality first, then larger first, then by smallest member
  // id (= the canonical cluster number, as cluster_glyphs numbers them so).
  std::vector<Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    const AggregatedGlyph& ga = unranked[static_cast<std::size_t>(a)];
    const AggregatedGlyph& gb = unranked[static_cast<std::size_t>(b)];
    if (ga.min_quality != gb.min_quality) return ga.min_quality < gb.min_quality;
    if (ga.size != gb.size) return ga.size > gb.size;
    return a < b;
  });
  std::vector<Index> rank_of(static_cast<std::size_t>(n));
  result.clusters.resize(static_cast<std::size_t>(n));
  result.cluster_offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  for (Index rank = 0; rank < n; ++rank) {
    const Index c = order[static_cast<std::size_t>(rank)];
    rank_of[static_cast<std::size_t>(c)] = rank;
    result.clusters[static_cast<std::size_t>(rank)] = unranked[static_cast<std::size_t>(c)];
    result.clusters[static_cast<std::size_t>(rank)].id = rank;
    result.cluster_offsets[static_cast<std::size_t>(rank) + 1] =
        result.cluster_offsets[static_cast<std::size_t>(rank)] + unranked[static_cast<std::size_t>(c)].size;
  }
  result.cluster_vertices.resize(clusters.members.size());
  for (Index rank = 0; rank < n; ++rank) {
    const auto c = static_cast<std::size_t>(order[static_cast<std::size_t>(rank)]);
    std::copy(clusters.members.begin() + clusters.offsets[c], clusters.members.begin() + clusters.offsets[c + 1],
              result.cluster_vertices.begin() + result.cluster_offsets[static_cast<std::size_t>(rank)]);
  }
  result.vertex_cluster.assign(points.size(), kNoIndex);
  for (std::size_t v = 0; v < points.size(); ++v)
    if (clusters.point_cluster[v] != kNoIndex)
      result.vertex_cluster[v] = rank_of[static_cast<std::size_t>(clusters.point_cluster[v])];
  return result;
}

}  // namespace hq
