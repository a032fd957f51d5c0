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

// A cut of a chart into two pieces along triangle borders (side[t] 1 or 2
// for each triangle t of `triangles`) zigzags where it crosses rows of
// triangles at a slant. Straightens it: a triangle with two or three
// neighbours on the other side (neighbour: 3 per triangle of the surface,
// kNoIndex across a border; only edges with glued(t, k, n) count) moves
// there, over `triangles` in their order, until a pass moves none (at most
// `passes`). Each move shortens the cut by at least one edge; the pieces
// keep the layout they had, so their layouts stay one-to-one.
template <class Glued>
void straighten_two_way_cut(std::span<const Index> triangles, std::span<const Index> neighbour,
                            std::span<std::uint8_t> side, const Glued& glued, int passes = 4) {
  for (int pass = 0; pass < passes; ++pass) {
    bool moved = false;
    for (Index t : triangles) {
      const std::uint8_t other = side[t] == 1 ? 2 : 1;
      int glued_to_other = 0;
      for (int k = 0; k < 3; ++k) {
        const Index n = neighbour[3 * static_cast<std::size_t>(t) + k];
        glued_to_other += n != kNoIndex && side[n] == other && glued(t, k, n);
      }
      if (glued_to_other >= 2) side[t] = other, moved = true;
    }
    if (!moved) break;
  }
}

}  // namespace hq
