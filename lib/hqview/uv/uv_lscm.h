#pragma once
// Least-squares conformal layout of one chart (CGAL LSCM_parameterizer_3 with
// Eigen; CGAL stays inside uv_lscm.cpp), optionally refined as rigidly as
// possible (ARAP local/global iterations, Eigen's sparse Cholesky).

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/uv/uv_validation.h"

namespace hq {

enum class ChartLayout {
  lscm,  // least-squares conformal (CGAL)
  arap,  // LSCM, then as-rigid-as-possible iterations: less area distortion
};
// ARAP's local/global iterations.
inline constexpr int kArapIterations = 12;

// Lays out the triangles `chart` of `surface` with LSCM when they form a
// topological disk (one border, Euler characteristic 1, a valid polygon
// mesh); `uvs` gets 3 corners per chart triangle, in chart order, scaled to
// the chart's 3D area; with `method` arap, the LSCM layout is then refined
// as rigidly as possible. Triangles are glued across the edges that exactly two
// of them share, except `seams` (ascending keys min(a, b) << 32 | max(a, b)
// of surface vertex ids), along which the chart is cut open. Returns false
// (uvs untouched) when the chart is not a disk or the solver fails. The
// caller validates the result (flips, overlaps). With method arap and
// `good_enough`, the LSCM layout is kept when good_enough accepts it, and
// refined by ARAP (without solving LSCM again) when not; when good_enough
// refuses the ARAP layout too, the latest ARAP iterate it accepts is
// returned (else the refused ARAP layout).
bool lscm_chart_layout(const TriSurface& surface, std::span<const Index> chart, std::vector<Uv>& uvs,
                       std::span<const std::uint64_t> seams = {}, ChartLayout method = ChartLayout::lscm,
                       const std::function<bool(std::span<const Uv>)>& good_enough = {});

}  // namespace hq
