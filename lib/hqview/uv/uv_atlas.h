#pragma once
// A UV atlas of a reference surface that never fails (ALGORITHMS.md §5): every
// triangle is labelled with the best of 26 projection directions; charts are
// connected components of same-label triangles across manifold edges; each
// chart is projected on its plane (no flips by construction, checked
// exactly); a chart whose projection overlaps itself is split in two and both
// halves are checked again (a single triangle is always valid); charts are
// turned to their principal axes (when that shrinks their box), a chart
// longer than half the ideal atlas side is split, and all are shelf-packed
// into [0,1]²; the final UVs are checked again exactly. Works on any triangle
// soup: non-manifold edges, duplicate and zero-area triangles, any genus,
// several components.

#include <array>
#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/uv/uv_validation.h"

namespace hq {

struct UvOptions {
  // Gap between packed charts, as a fraction of the square root of the
  // summed chart bounding-box areas (about the atlas side).
  double padding = 2e-3;
  // Rounds of "re-chart the triangles that fail the final exact check, pack again".
  int max_repair_rounds = 4;
  // Replace the projection of each chart that is a topological disk (of at
  // least lscm_min_triangles) by its LSCM layout (CGAL LSCM_parameterizer_3),
  // kept only when the exact checks find no flipped and no overlapping
  // triangle in it (one-to-one). Off by default: projection is faster and
  // already valid.
  bool improve_with_lscm = false;
  int lscm_min_triangles = 8;
  // ...and only on surfaces of at most this many triangles (LSCM on the 1M
  // benchmark surface takes 10 s against 1.8 s for the projected atlas).
  Index lscm_max_surface_triangles = 250'000;
};

struct UvAtlas {
  // Per triangle corner (3 per triangle, in the surface's corner order): UV in [0,1]².
  std::vector<Uv> uvs;
  std::vector<Index> triangle_chart;  // per triangle, chart id in [0, num_charts)
  Index num_charts = 0;
  Index num_splits = 0;           // overlapping charts split in two
  Index num_lscm_charts = 0;      // charts laid out by LSCM (improve_with_lscm)
  Index num_flipped = 0;          // final exact check: triangles not strictly counter-clockwise (0)
  Index num_overlaps = 0;         // final exact check: pairs of triangles whose interiors meet (0)
  double packing_efficiency = 0;  // summed UV triangle area / area of [0,1]²
};

// Builds the atlas; throws nothing. Deterministic for any thread count (the
// exact overlap search runs on TBB threads).
UvAtlas build_uv_atlas(const TriSurface& surface, const UvOptions& options = {});

// Per-corner values of a per-point field (e.g. the reference -> hex boundary
// distance), for interpolation over each UV triangle: out[3t+k] = field[tri[t][k]].
std::vector<double> uv_corner_values(const TriSurface& surface, std::span<const double> point_field);

}  // namespace hq
