#include "hqview/glyph/bounded_clusters.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hqview/core/error.h"
#include "hqview/glyph/cell_keys.h"

namespace hq {
namespace {

// Components up to this many glyphs find a seed's ball by scanning all of
// their glyphs; larger ones through a grid of cells one ball wide.
constexpr std::size_t kScanLimit = 64;

using glyph_cells::cell_coord;
using glyph_cells::cell_key;
using glyph_cells::kMaxCellCoord;

// The ball query of one component: the component's glyphs (local numbers
// 0..k-1) whose centre is strictly closer than `radius` to `centre`.
class BallQuery {
 public:
  BallQuery(std::span<const Index> members, std::span<const Vec3> positions, double max_ball)
      : members_(members), positions_(positions) {
    if (members.size() <= kScanLimit) return;
    // Cells a little wider than the largest ball, so a ball spans at most
    // the 3x3x3 cells around its centre's cell despite rounding.
    cell_ = max_ball * (1.0 + 1e-6);
    origin_ = positions[static_cast<std::size_t>(members[0])];
    for (Index v : members) {
      const Vec3& p = positions[static_cast<std::size_t>(v)];
      origin_ = {std::min(origin_.x, p.x), std::min(origin_.y, p.y), std::min(origin_.z, p.z)};
    }
    cells_.reserve(members.size());
    for (std::size_t i = 0; i < members.size(); ++i) {
      const Vec3& p = positions[static_cast<std::size_t>(members[i])];
      const auto c = coords(p);
      cells_.push_back({cell_key(c[0], c[1], c[2]), static_cast<Index>(i), p});
    }
    std::sort(cells_.begin(), cells_.end(),
              [](const Entry& a, const Entry& b) { return a.key != b.key ? a.key < b.key : a.local < b.local; });
  }

  // Appends to `out` the local numbers in the ball for which keep(i) holds.
  template <class Keep>
  void collect(const Vec3& centre, double radius, Keep keep, std::vector<Index>& out) const {
    const double r2 = radius * radius;
    auto test = [&](Index i, const Vec3& p) {
      if (!keep(i)) return;
      const Vec3 d = p - centre;
      if ((d.x * d.x + d.y * d.y) + d.z * d.z < r2) out.push_back(i);
    };
    if (cells_.empty()) {
      for (Index i = 0; i < static_cast<Index>(members_.size()); ++i)
        test(i, positions_[static_cast<std::size_t>(members_[static_cast<std::size_t>(i)])]);
      return;
    }
    // The three cells along x of each (y, z) row are consecutive keys: one
    // search a row, the entries read in place (their positions with them).
    const auto c = coords(centre);
    const std::int64_t x0 = std::max<std::int64_t>(c[0] - 1, 0), x1 = std::min(c[0] + 1, kMaxCellCoord);
    for (std::int64_t z = std::max<std::int64_t>(c[2] - 1, 0); z <= std::min(c[2] + 1, kMaxCellCoord); ++z)
      for (std::int64_t y = std::max<std::int64_t>(c[1] - 1, 0); y <= std::min(c[1] + 1, kMaxCellCoord); ++y) {
        const std::uint64_t last = cell_key(x1, y, z);
        auto it = std::partition_point(cells_.begin(), cells_.end(),
                                       [key = cell_key(x0, y, z)](const Entry& e) { return e.key < key; });
        for (; it != cells_.end() && it->key <= last; ++it) test(it->local, it->position);
      }
  }

 private:
  std::array<std::int64_t, 3> coords(const Vec3& p) const {
    return {cell_coord((p.x - origin_.x) / cell_), cell_coord((p.y - origin_.y) / cell_),
            cell_coord((p.z - origin_.z) / cell_)};
  }

  std::span<const Index> members_;
  std::span<const Vec3> positions_;
  double cell_ = 0;
  Vec3 origin_;
  struct Entry {
    std::uint64_t key;  // its cell
    Index local;        // its local number
    Vec3 position;
  };
  std::vector<Entry> cells_;  // by cell, then local number
};

// Splits one component (its members ascending) into bounded clusters, each
// as its members' global ids, ascending.
std::vector<std::vector<Index>> split_component(std::span<const Index> members, std::span<const Vec3> positions,
                                                std::span<const double> radii, double reach) {
  const std::size_t k = members.size();
  auto radius = [&](Index i) { return radii[static_cast<std::size_t>(members[static_cast<std::size_t>(i)])]; };
  auto position = [&](Index i) -> const Vec3& {
    return positions[static_cast<std::size_t>(members[static_cast<std::size_t>(i)])];
  };
  // Seeds in turn: largest radius first, then the smallest id (members are
  // ascending, so the smaller local number).
  std::vector<Index> order(k);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return radius(a) > radius(b); });
  double max_radius = 0;
  for (std::size_t i = 0; i < k; ++i) max_radius = std::max(max_radius, radius(static_cast<Index>(i)));
  const BallQuery query(members, positions, reach * max_radius);

  std::vector<char> taken(k, 0), reached(k, 0);
  std::vector<Index> ball, cluster;
  std::vector<std::vector<Index>> result;
  for (Index seed : order) {
    if (taken[static_cast<std::size_t>(seed)]) continue;
    ball.clear();
    query.collect(position(seed), reach * radius(seed),
                  [&](Index i) { return !taken[static_cast<std::size_t>(i)] && i != seed; }, ball);
    // Breadth first from the seed through overlapping glyphs of the ball.
    cluster.assign(1, seed);
    taken[static_cast<std::size_t>(seed)] = 1;
    for (std::size_t head = 0; head < cluster.size(); ++head) {
      const Index g = cluster[head];
      for (Index b : ball) {
        if (reached[static_cast<std::size_t>(b)]) continue;
        if (glyphs_overlap(position(g), radius(g), position(b), radius(b))) {
          reached[static_cast<std::size_t>(b)] = 1;
          cluster.push_back(b);
        }
      }
    }
    for (Index b : ball) reached[static_cast<std::size_t>(b)] = 0;
    std::vector<Index> ids;
    ids.reserve(cluster.size());
    for (Index i : cluster) {
      taken[static_cast<std::size_t>(i)] = 1;
      ids.push_back(members[static_cast<std::size_t>(i)]);
    }
    std::sort(ids.begin(), ids.end());
    result.push_back(std::move(ids));
  }
  return result;
}

}  // namespace

GlyphClusters bound_glyph_clusters(const GlyphClusters& components, std::span<const Vec3> positions,
                                   std::span<const double> radii, double reach) {
  if (positions.size() != radii.size() || components.point_cluster.size() != positions.size())
    throw Error("bound_glyph_clusters: " + std::to_string(positions.size()) + " positions, " +
                std::to_string(radii.size()) + " radii and " + std::to_string(components.point_cluster.size()) +
                " cluster labels");
  if (!(reach > 0.0) || !std::isfinite(reach))
    throw Error("bound_glyph_clusters: the reach must be a positive number");
  const Index n = components.num_clusters();
  std::vector<std::vector<std::vector<Index>>> parts(static_cast<std::size_t>(n));
  tbb::parallel_for(tbb::blocked_range<Index>(0, n, 16), [&](const tbb::blocked_range<Index>& r) {
    for (Index c = r.begin(); c != r.end(); ++c) {
      const auto begin = components.offsets[static_cast<std::size_t>(c)];
      const auto end = components.offsets[static_cast<std::size_t>(c) + 1];
      const std::span<const Index> members(components.members.data() + begin, static_cast<std::size_t>(end - begin));
      if (members.size() == 1)
        parts[static_cast<std::size_t>(c)].push_back({members[0]});
      else
        parts[static_cast<std::size_t>(c)] = split_component(members, positions, radii, reach);
    }
  });

  // Number the clusters by their smallest member, as cluster_glyphs does.
  std::vector<const std::vector<Index>*> all;
  for (const auto& p : parts)
    for (const auto& cluster : p) all.push_back(&cluster);
  std::sort(all.begin(), all.end(), [](const auto* a, const auto* b) { return a->front() < b->front(); });
  GlyphClusters result;
  result.point_cluster.assign(positions.size(), kNoIndex);
  result.offsets.reserve(all.size() + 1);
  result.offsets.push_back(0);
  result.members.reserve(components.members.size());
  for (std::size_t c = 0; c < all.size(); ++c) {
    for (Index v : *all[c]) {
      result.point_cluster[static_cast<std::size_t>(v)] = static_cast<Index>(c);
      result.members.push_back(v);
    }
    result.offsets.push_back(static_cast<Index>(result.members.size()));
  }
  return result;
}

}  // namespace hq
