#pragma once
// A UV atlas of a reference surface that reads like a map and never fails
// (ALGORITHMS.md §5, docs/analysis.md "UV atlas"): charts are grown over
// manifold edges while their normals stay in a cone, then neighbouring charts
// are merged while the union stays in a wider cone; each chart is projected on
// the plane of its mean normal (one-sided, so no flip), the model's up axis
// up, and replaced by its LSCM layout where that is one-to-one and distorts
// less; then neighbouring charts are merged, small ones first, while the
// union's LSCM layout stays one-to-one and within a distortion bound (two
// charts that share several border arcs are glued along the longest and cut
// open along the others: seams); charts that are not topological disks (as
// laid out), and charts whose layout
// overlaps itself (exact check), are split until they are (one triangle
// always is); all charts get one scale and are packed on a raster
// (uv_pack.h); the final UVs are checked again exactly and failing triangles
// become charts of their own. Works on any triangle soup: non-manifold edges,
// duplicate and zero-area triangles, any genus, several components.

#include <array>
#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/uv/uv_validation.h"

namespace hq {

enum class UvCharts {
  grown,      // charts grown over the surface and merged (default)
  projected,  // the first atlas: best of 26 projection directions per triangle
};

struct UvOptions {
  UvCharts charts = UvCharts::grown;
  // Growing: a triangle joins a chart while its normal is within this angle
  // of the chart's mean normal. Merging: two neighbouring charts join while
  // every triangle stays within merge_cone of the union's mean normal; a
  // chart of less than merge_small_area of the surface joins a neighbour
  // while within absorb_cone of that neighbour's normal.
  double grow_cone_degrees = 55.0;
  double merge_cone_degrees = 70.0;
  double absorb_cone_degrees = 84.0;
  double merge_small_area = 0.01;
  // The model's up axis: charts are laid out with it pointing up in UV
  // where they are not seen along it.
  Vec3 up{0.0, 0.0, 1.0};
  // Cells along the side of the packing grid (uv_pack.h).
  int pack_resolution = 256;
  // Rounds of "re-chart the triangles that fail the final exact check, pack again".
  int max_repair_rounds = 4;
  // While the packed charts fill less than pack_target of the square, one of
  // the largest charts that covers less than pack_split_max_box_fill of its
  // bounding box (a strip bent in UV, a hand; not a rectangle or a disk,
  // which pack well whole) is halved (its layout kept) when that packs better
  // and at most pack_max_charts_95 charts still hold 95 % of the area; at
  // most pack_max_splits halvings (0: off). Only on surfaces of up to
  // pack_split_max_triangles.
  double pack_target = 0.6;
  int pack_max_charts_95 = 8;
  int pack_max_splits = 6;
  Index pack_split_max_triangles = 250'000;
  double pack_split_max_box_fill = 0.6;
  // Replace the projection of each chart (of at least lscm_min_triangles) by
  // its LSCM layout (CGAL LSCM_parameterizer_3) when that is one-to-one
  // (exact checks) and distorts less.
  bool improve_with_lscm = false;
  int lscm_min_triangles = 8;
  // Then merge neighbouring LSCM charts while the union's LSCM layout is
  // one-to-one and keeps at least merge_min_area_within_2 of its area within
  // [0.5, 2] of its mean area ratio (conformal distortion at most 2), cut open
  // along seams where two charts share more than one border arc.
  bool merge_by_layout = true;
  double merge_min_area_within_2 = 0.95;
  // A union whose LSCM layout fails the bound is laid out again by ARAP
  // (LSCM refined as rigidly as possible), which keeps areas better.
  bool merge_with_arap = true;
  // The merge's work budget: triangles laid out by its trial layouts, in
  // multiples of the surface's triangle count (it stops when spent).
  double merge_work_surfaces = 40;
  // ...and only on surfaces of at most this many triangles (LSCM on the 1M
  // benchmark surface takes seconds).
  Index lscm_max_surface_triangles = 250'000;
};

// Area-weighted quantiles of a per-triangle value.
struct UvDistortionStats {
  double min = 0, p5 = 0, p50 = 0, p95 = 0, max = 0;
};

struct UvAtlas {
  // Per triangle corner (3 per triangle, in the surface's corner order): UV in [0,1]².
  std::vector<Uv> uvs;
  std::vector<Index> triangle_chart;  // per triangle, chart id in [0, num_charts)
  Index num_charts = 0;
  Index num_splits = 0;           // charts split to become disks or to remove an overlap
  Index num_lscm_charts = 0;      // charts laid out by LSCM (improve_with_lscm)
  Index num_flipped = 0;          // final exact check: triangles not strictly counter-clockwise (0)
  Index num_overlaps = 0;         // final exact check: pairs of triangles whose interiors meet (0)
  double packing_efficiency = 0;  // summed UV triangle area / area of [0,1]²
  // Shares of the 3D area in the largest chart, the 4 and the 8 largest.
  double area_fraction_largest_chart = 0;
  double area_fraction_top_4_charts = 0;
  double area_fraction_top_8_charts = 0;
  // Per triangle: (UV area / 3D area) / (total UV area / total 3D area), and
  // the conformal distortion sigma_max / sigma_min; area-weighted.
  UvDistortionStats area_ratio, conformal_distortion;
  double area_fraction_area_ratio_within_2 = 0;  // share of 3D area with area ratio in [0.5, 2]
};

// Builds the atlas; throws only what stop::check() throws (a stop request
// or the calling thread's deadline, polled while charts are laid out).
// Deterministic for any thread count (the merging's layouts and the exact
// overlap search run on TBB threads).
UvAtlas build_uv_atlas(const TriSurface& surface, const UvOptions& options = {});

// Per-corner values of a per-point field (e.g. the reference -> hex boundary
// distance), for interpolation over each UV triangle: out[3t+k] = field[tri[t][k]].
std::vector<double> uv_corner_values(const TriSurface& surface, std::span<const double> point_field);

}  // namespace hq
