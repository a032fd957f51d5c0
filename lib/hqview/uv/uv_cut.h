#pragma once
// A cut graph that opens one chart into a topological disk (tree-cotree,
// Eppstein 2003; shortest loops as Erickson and Whittlesey 2005).

#include <cstdint>
#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/mesh/hex_mesh.h"

namespace hq {

// The triangles `chart` of `surface`, glued as lscm_chart_layout glues them
// (across every edge exactly two of them share, except `seams`), form a
// connected surface with handles or several borders: returns the extra
// seams (ascending edge keys min(a, b) << 32 | max(a, b)) that, with
// `seams`, cut it into one disk. The extra seams are shortest paths from
// the chart's borders and seams (or from one vertex when it has none):
// a primal shortest-path forest grown from them, a dual spanning tree of
// the other edges kept longest-loop first, and the edges in neither
// closing the loops; dangling branches are glued back. Returns nothing when
// no cut is needed (already a disk), when no cut helps (a closed surface of
// genus 0: a disk needs a slit, which no layout flattens well) or when the
// chart is not connected.
std::vector<std::uint64_t> disk_cut(const TriSurface& surface, std::span<const Index> chart,
                                    std::span<const std::uint64_t> seams);

}  // namespace hq
