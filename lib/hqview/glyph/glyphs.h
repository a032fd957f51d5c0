#pragma once
// Vertex glyphs and aggregated glyphs (ALGORITHMS.md §3, the paper's goal G1:
// reveal bad elements regardless of their size).
//
// Every vertex with quality Jm gets the ratio c = 1 − Jm ∈ [0, 2] and, when
// c is above the threshold, a sphere glyph of radius c · rmax, so that a tiny
// bad element is as visible as a large one. Overlapping glyphs
// (glyph_clusters.h) form clusters; each cluster is drawn as one aggregated
// glyph with radius = ratio · rmax. By the size rule (GlyphSizeRule):
// - severity (default): the overlap components are split into clusters of
//   bounded extent around their worst glyphs (bounded_clusters.h: every
//   member within cluster_reach · r of the worst one), so that a band of bad
//   vertices does not chain into one cluster across the model; the glyph
//   sits at the worst member (min quality, ties: the smallest vertex id);
//   ratio = the largest member ratio, 1 − min quality, so that a worse
//   cluster is never drawn smaller than a better one; the cluster's size is
//   told by its member count (labels, table), not by its radius;
// - paper: HQViewer's aggregated glyphs: the overlap components as they
//   are, the glyph at the member closest to the members' mean position
//   (ties: the smallest vertex id), ratio = the largest member ratio + a
//   size bonus of 0.1 per 10 members (the bonus at most 1.0), so a large
//   mild cluster can outgrow a small severe one. Clusters are
// ranked worst first: by min quality, then by size (larger first), then by
// smallest member vertex id; a cluster's id is its rank.

#include <cstdint>
#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/vec3.h"

namespace hq {

enum class RmaxUnit {
  kModel,           // rmax in model units
  kMeanEdgeLength,  // rmax as a multiple of the mesh's mean edge length
};

// How an aggregated glyph's ratio is made from its members (see above).
enum class GlyphSizeRule {
  kSeverity,  // 1 − min quality
  kPaper,     // 1 − min quality + glyph_size_bonus(size) (HQViewer)
};

// "severity" / "paper": the --glyph-size value and report.json glyphs.size_rule.
const char* glyph_size_rule_name(GlyphSizeRule rule);

struct GlyphOptions {
  // The radius of a glyph of ratio 1 (a vertex with Jm = 0). Default: one mean
  // edge length, so that two neighbouring vertices with Jm ≤ 0.5 (c ≥ 0.5) merge
  // across any edge shorter than the mean, and clearly bad ones (Jm ≤ 0.25)
  // across edges up to 1.5 times the mean (README, "Glyphs and clusters").
  double rmax = 1.0;
  RmaxUnit rmax_unit = RmaxUnit::kMeanEdgeLength;
  // No glyph for c ≤ threshold. Default 0.5: glyphs for Jm < 0.5, the vertices
  // outside Verdict's acceptable scaled-Jacobian range [0.5, 1].
  double threshold = 0.5;
  // How many of the top-ranked clusters later views show in detail (not how
  // many are found).
  int top_clusters = 8;
  // The aggregated glyphs' size rule (--glyph-size).
  GlyphSizeRule size_rule = GlyphSizeRule::kSeverity;
  // Under kSeverity: a cluster's members lie within this many times its
  // worst glyph's radius of it (bounded_clusters.h; kClusterReach = 2).
  double cluster_reach = 2.0;
};

struct AggregatedGlyph {
  Index id = 0;                     // rank: 0 = worst cluster
  Index size = 0;                   // member glyphs
  Index representative_vertex = 0;  // the member the aggregated glyph sits on
  Vec3 position;                    // of representative_vertex
  double min_quality = 0;           // min Jm over the members
  double ratio = 0;                 // max member ratio (+ size bonus under GlyphSizeRule::kPaper)
  double radius = 0;                // ratio · rmax
};

struct GlyphResult {
  GlyphOptions options;  // as asked for
  double rmax = 0;       // resolved, model units
  Index num_glyphs = 0;
  // Per vertex: glyph radius (0: no glyph, also for a vertex without quality)
  // and cluster id (kNoIndex: no glyph).
  std::vector<double> vertex_radius;
  std::vector<Index> vertex_cluster;
  // All clusters, by rank (clusters[i].id == i).
  std::vector<AggregatedGlyph> clusters;
  // Members of cluster c: cluster_vertices[cluster_offsets[c] .. cluster_offsets[c+1]), ascending.
  std::vector<Index> cluster_offsets;
  std::vector<Index> cluster_vertices;
};

// c = 1 − Jm (NaN stays NaN).
inline double glyph_ratio(double vertex_quality) { return 1.0 - vertex_quality; }

// The size bonus of an aggregated glyph of `size` members: 0.1 per complete
// group of 10 members, at most 1.0 (reached at 100 members). Computed as
// min(size / 10, 10) / 10 so that the values are the exact decimals' doubles
// (0.3, not 0.1 · 3 = 0.30000000000000004).
double glyph_size_bonus(std::int64_t size);

// rmax in model units: options.rmax itself, or times mean_edge_length.
double resolve_rmax(const GlyphOptions& options, double mean_edge_length);

// Per-vertex glyph radii: c · rmax where c = 1 − Jm > threshold, else 0
// (also 0 for a NaN quality and when rmax is 0).
std::vector<double> glyph_radii(std::span<const double> vertex_quality, double rmax, double threshold);

// The aggregated glyph of one cluster (id left 0).
//   members:        the cluster's vertex ids, ascending, not empty.
//   points:         all vertex positions; vertex_quality: all Jm.
// Position: under kSeverity the worst member (min quality, ties to the
// smallest id); under kPaper the member nearest to the mean of the members'
// positions (summed in ascending id order), ties to the smallest id.
//   size_rule:      how the position and ratio are made (GlyphSizeRule).
AggregatedGlyph aggregate_glyph(std::span<const Index> members, std::span<const Vec3> points,
                                std::span<const double> vertex_quality, double rmax,
                                GlyphSizeRule size_rule = GlyphSizeRule::kSeverity);

// The whole stage: glyph radii, clusters, aggregated glyphs, ranks.
//   points, vertex_quality: #V each (Jm per vertex, NaN for unused vertices).
//   mean_edge_length: for RmaxUnit::kMeanEdgeLength.
// Parallel; identical results for every thread count. Throws Error when the
// spans differ in size.
GlyphResult compute_glyphs(std::span<const Vec3> points, std::span<const double> vertex_quality,
                           double mean_edge_length, const GlyphOptions& options);

}  // namespace hq
