#include "hqview/uv/uv_atlas.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <numbers>
#include <numeric>
#include <optional>
#include <queue>
#include <set>
#include <tuple>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "hqview/core/stop.h"
#include "hqview/uv/uv_cut.h"
#include "hqview/uv/uv_lscm.h"
#include "hqview/uv/uv_metrics.h"
#include "hqview/uv/uv_pack.h"

namespace hq {
namespace {

constexpr int kNumDirections = 26;

std::array<Vec3, kNumDirections> projection_directions() {
  std::array<Vec3, kNumDirections> d{};
  int n = 0;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x != 0 || y != 0 || z != 0) d[n++] = normalized(Vec3{double(x), double(y), double(z)});
  return d;
}

// A chart: its triangles and the direction it is projected along (a zero
// direction: each triangle laid out alone, in its own plane or canonically).
struct Chart {
  std::vector<Index> triangles;
  Vec3 direction{};
  bool lscm = false;  // laid out by LSCM (else projected along direction)
  // Edges inside the chart along which its layout is cut open (ascending
  // keys; set by merge_by_layout, which lays unions out again with them).
  std::vector<std::uint64_t> seams = {};
  bool own_plane() const { return direction == Vec3{}; }
};

// The largest charts tried halved in each round of the packing splits.
constexpr std::size_t kPackSplitCandidates = 5;
// The least share of a chart's area each piece of a packing cut holds.
constexpr double kPackCutMinShare = 0.2;

Index find_root(std::vector<Index>& parent, Index v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

class AtlasBuilder {
 public:
  AtlasBuilder(const TriSurface& s, const UvOptions& o) : s_(s), options_(o) {
    nt_ = static_cast<Index>(s.triangles.size());
    local_.assign(3 * static_cast<std::size_t>(nt_), Uv{0.0, 0.0});
    uvs_ = local_;
    fallback_length_ = typical_edge_length();
  }

  UvAtlas build() {
    UvAtlas atlas;
    if (nt_ == 0) return atlas;
    compute_triangles();
    if (options_.charts == UvCharts::grown) {
      grow_charts();
      merge_charts();
      smooth_borders();
    } else {
      make_projected_charts();
    }
    for (std::size_t c = 0; c < charts_.size(); ++c) lay_out(c);
    separate_flipped();
    atlas.num_splits += make_disks();
    if (options_.improve_with_lscm && nt_ <= options_.lscm_max_surface_triangles) {
      improve_with_lscm();
      if (options_.merge_by_layout) {
        atlas.num_splits += split_overlapping_layouts();
        merge_by_layout();
      }
    }
    equalise_scale();
    // Overlaps are searched once, on a first packing (charts apart);
    // splitting only separates triangles, so it never makes new ones.
    atlas.num_splits += split_for_packing();
    if (!packs_by_splitting()) pack();
    std::vector<std::array<Index, 2>> overlaps = uv_overlapping_pairs_by_part(uvs_, current_chart_of());
    const Index overlap_splits = split_overlapping_charts(overlaps);
    atlas.num_splits += overlap_splits;
    // The final exact check on the final UVs. Without splits the first
    // packing is final and its overlaps (if any, across charts) are known.
    for (int round = 0;; ++round) {
      if (round > 0 || overlap_splits > 0) {
        pack();
        overlaps = uv_overlapping_pairs_by_part(uvs_, current_chart_of());
      }
      const std::vector<std::uint8_t> flipped = uv_flipped_triangles(uvs_);
      std::vector<Index> bad;
      for (Index t = 0; t < nt_; ++t)
        if (flipped[t]) bad.push_back(t);
      for (const auto& p : overlaps) bad.insert(bad.end(), {p[0], p[1]});
      atlas.num_flipped = static_cast<Index>(std::count(flipped.begin(), flipped.end(), 1));
      atlas.num_overlaps = static_cast<Index>(overlaps.size());
      if (bad.empty() || round >= options_.max_repair_rounds) break;
      std::sort(bad.begin(), bad.end());
      bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
      make_singletons(bad, /*canonical=*/true);
      equalise_scale();
    }
    // Drop emptied charts, number the rest in order.
    atlas.triangle_chart.assign(static_cast<std::size_t>(nt_), kNoIndex);
    for (const Chart& c : charts_) {
      if (c.triangles.empty()) continue;
      for (Index t : c.triangles) atlas.triangle_chart[t] = atlas.num_charts;
      ++atlas.num_charts;
      atlas.num_lscm_charts += c.lscm ? 1 : 0;
    }
    atlas.uvs = std::move(uvs_);
    measure_uv_atlas(s_, atlas);
    return atlas;
  }

 private:
  const Vec3& point(Index t, int k) const { return s_.points[s_.triangles[t][k]]; }

  double typical_edge_length() const {
    std::vector<double> lengths;
    for (Index t = 0; t < nt_; t += std::max<Index>(1, nt_ / 4096))
      for (int k = 0; k < 3; ++k) {
        const double l = norm(point(t, (k + 1) % 3) - point(t, k));
        if (l > 0.0 && std::isfinite(l)) lengths.push_back(l);
      }
    if (lengths.empty()) return 1.0;
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    return lengths[lengths.size() / 2];
  }

  // Unit normals (zero for degenerate triangles), areas, centroids, and the
  // neighbour across each edge shared by exactly two triangles.
  void compute_triangles() {
    normal_.assign(static_cast<std::size_t>(nt_), Vec3{});
    area_.assign(static_cast<std::size_t>(nt_), 0.0);
    centroid_.assign(static_cast<std::size_t>(nt_), Vec3{});
    for (Index t = 0; t < nt_; ++t) {
      const Vec3 n = cross(point(t, 1) - point(t, 0), point(t, 2) - point(t, 0));
      const double l = norm(n);
      centroid_[t] = (point(t, 0) + point(t, 1) + point(t, 2)) / 3.0;
      if (!(l > 0.0) || !std::isfinite(l)) continue;
      const Vec3 u = n / l;
      if (!is_finite(u)) continue;
      normal_[t] = u;
      area_[t] = 0.5 * l;
    }
    std::vector<std::pair<std::uint64_t, Index>> edges(3 * static_cast<std::size_t>(nt_));
    for (Index t = 0; t < nt_; ++t)
      for (int k = 0; k < 3; ++k) {
        const auto a = static_cast<std::uint64_t>(static_cast<std::uint32_t>(s_.triangles[t][k]));
        const auto b = static_cast<std::uint64_t>(static_cast<std::uint32_t>(s_.triangles[t][(k + 1) % 3]));
        edges[3 * static_cast<std::size_t>(t) + k] = {std::min(a, b) << 32 | std::max(a, b), 3 * t + k};
      }
    std::sort(edges.begin(), edges.end());
    neighbour_.assign(3 * static_cast<std::size_t>(nt_), kNoIndex);
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j].first == edges[i].first) ++j;
      if (j - i == 2 && edges[i].second / 3 != edges[i + 1].second / 3 && (edges[i].first >> 32) !=
                                                                              (edges[i].first & 0xffffffffu)) {
        neighbour_[edges[i].second] = edges[i + 1].second / 3;
        neighbour_[edges[i + 1].second] = edges[i].second / 3;
      }
      i = j;
    }
  }

  double edge_length(Index t, int k) const { return norm(point(t, (k + 1) % 3) - point(t, k)); }

  // Charts grown from seeds over manifold edges (xatlas-like): a triangle
  // joins while its normal stays within the cone around the chart's
  // area-weighted mean normal; nearest-in-normal and nearest-in-space first,
  // so charts grow round. Degenerate triangles become charts of their own.
  void grow_charts() {
    const double cos_limit = std::cos(options_.grow_cone_degrees * std::numbers::pi / 180.0);
    chart_of_.assign(static_cast<std::size_t>(nt_), kNoIndex);
    using Entry = std::pair<double, Index>;
    for (Index seed = 0, sweep_from = 0; seed < nt_ || sweep_from < nt_; ++seed) {
      if (seed == nt_) {  // another sweep for the triangles sent back
        sweep_from = nt_;
        for (Index t = 0; t < nt_; ++t)
          if (chart_of_[t] == kNoIndex) sweep_from = std::min(sweep_from, t);
        if (sweep_from == nt_) break;
        seed = sweep_from;
      }
      if (chart_of_[seed] != kNoIndex) continue;
      const Index id = static_cast<Index>(charts_.size());
      charts_.push_back({{seed}, normal_[seed]});
      chart_of_[seed] = id;
      if (normal_[seed] == Vec3{}) continue;
      Vec3 sum = area_[seed] * normal_[seed];
      double chart_area = area_[seed];
      std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
      auto push_neighbours = [&](Index t) {
        for (int k = 0; k < 3; ++k) {
          const Index n = neighbour_[3 * static_cast<std::size_t>(t) + k];
          if (n == kNoIndex || chart_of_[n] != kNoIndex || normal_[n] == Vec3{}) continue;
          const Vec3 mean = normalized(sum);
          const double spread = norm(centroid_[n] - centroid_[seed]) / std::sqrt(chart_area);
          heap.push({(1.0 - dot(normal_[n], mean)) + 0.02 * spread, n});
        }
      };
      push_neighbours(seed);
      while (!heap.empty()) {
        const Index t = heap.top().second;
        heap.pop();
        if (chart_of_[t] != kNoIndex) continue;
        if (dot(normal_[t], normalized(sum)) < cos_limit) continue;
        chart_of_[t] = id;
        charts_[id].triangles.push_back(t);
        sum = sum + area_[t] * normal_[t];
        chart_area += area_[t];
        push_neighbours(t);
      }
      charts_[id].direction = normalized(sum);
      std::sort(charts_[id].triangles.begin(), charts_[id].triangles.end());
      // The mean moved while the chart grew: triangles left outside the cone
      // of the final mean go back to be grown again.
      std::erase_if(charts_[id].triangles, [&](Index t) {
        const bool out = t != seed && dot(normal_[t], charts_[id].direction) < cos_limit;
        if (out) chart_of_[t] = kNoIndex;
        return out;
      });
    }
  }

  // Merges neighbouring charts, longest shared border first, while every
  // triangle of the union stays within the merge cone of the union's mean
  // normal (so its projection stays one-sided and its area ratio bounded).
  // Small charts (below merge_small_area of the surface) may use the wider
  // absorb cone when they join a larger neighbour.
  void merge_charts() {
    double total = 0.0;
    for (Index t = 0; t < nt_; ++t) total += area_[t];
    const double cos_merge = std::cos(options_.merge_cone_degrees * std::numbers::pi / 180.0);
    const double cos_absorb = std::cos(options_.absorb_cone_degrees * std::numbers::pi / 180.0);
    // Each chart's triangles ascending (kept so by the merges below).
    tbb::parallel_for(std::size_t{0}, charts_.size(),
                      [&](std::size_t c) { std::sort(charts_[c].triangles.begin(), charts_[c].triangles.end()); });
    std::vector<double> area_of(charts_.size());
    std::vector<Vec3> normal_of(charts_.size());
    for (int pass = 0; pass < 64; ++pass) {
      // Each chart's area and area-weighted normal sum, as chart_area and
      // normal_sum compute them (a chart merged in this pass is not looked
      // at again in it).
      tbb::parallel_for(std::size_t{0}, charts_.size(), [&](std::size_t c) {
        area_of[c] = chart_area(static_cast<Index>(c));
        normal_of[c] = normal_sum(static_cast<Index>(c));
      });
      // Shared border lengths between chart pairs.
      std::vector<std::tuple<Index, Index, double>> borders;
      for (Index t = 0; t < nt_; ++t)
        for (int k = 0; k < 3; ++k) {
          const Index n = neighbour_[3 * static_cast<std::size_t>(t) + k];
          if (n == kNoIndex || n < t) continue;
          const Index a = chart_of_[t], b = chart_of_[n];
          if (a != b && !charts_[a].own_plane() && !charts_[b].own_plane())
            borders.emplace_back(std::min(a, b), std::max(a, b), edge_length(t, k));
        }
      std::sort(borders.begin(), borders.end());
      std::vector<std::tuple<double, Index, Index>> pairs;
      for (std::size_t i = 0; i < borders.size();) {
        std::size_t j = i;
        double length = 0.0;
        while (j < borders.size() && std::get<0>(borders[j]) == std::get<0>(borders[i]) &&
               std::get<1>(borders[j]) == std::get<1>(borders[i]))
          length += std::get<2>(borders[j++]);
        pairs.emplace_back(-length, std::get<0>(borders[i]), std::get<1>(borders[i]));
        i = j;
      }
      std::sort(pairs.begin(), pairs.end());
      std::vector<std::uint8_t> touched(charts_.size(), 0);
      bool merged = false;
      for (const auto& [neg_length, a, b] : pairs) {
        if (touched[a] || touched[b]) continue;
        const double area_a = area_of[a], area_b = area_of[b];
        const bool small = std::min(area_a, area_b) < options_.merge_small_area * total;
        // A small chart joining a large one keeps the large one's direction.
        const Vec3 direction = small ? (area_a >= area_b ? charts_[a].direction : charts_[b].direction)
                                     : normalized(normal_of[a] + normal_of[b]);
        const double limit = small ? cos_absorb : cos_merge;
        if (!(squared_norm(direction) > 0.5) || !within_cone(a, direction, limit) || !within_cone(b, direction, limit))
          continue;
        const Index keep = std::min(a, b), gone = std::max(a, b);
        for (Index t : charts_[gone].triangles) chart_of_[t] = keep;
        std::vector<Index>& kept = charts_[keep].triangles;
        const auto middle = static_cast<std::ptrdiff_t>(kept.size());
        kept.insert(kept.end(), charts_[gone].triangles.begin(), charts_[gone].triangles.end());
        std::inplace_merge(kept.begin(), kept.begin() + middle, kept.end());
        charts_[gone].triangles.clear();
        charts_[gone].direction = Vec3{};
        charts_[keep].direction = direction;
        touched[a] = touched[b] = 1;
        merged = true;
      }
      if (!merged) break;
    }
    std::erase_if(charts_, [](const Chart& c) { return c.triangles.empty(); });
  }

  // Straighter borders, fewer pinches: a triangle with two or three
  // neighbours in one other chart moves there when its normal is within the
  // absorb cone of that chart's direction (a few passes, in triangle order).
  void smooth_borders() {
    for (std::size_t c = 0; c < charts_.size(); ++c)
      for (Index t : charts_[c].triangles) chart_of_[t] = static_cast<Index>(c);
    const double cos_absorb = std::cos(options_.absorb_cone_degrees * std::numbers::pi / 180.0);
    std::vector<Index> size(charts_.size());
    for (std::size_t c = 0; c < charts_.size(); ++c) size[c] = static_cast<Index>(charts_[c].triangles.size());
    for (int pass = 0; pass < 4; ++pass) {
      bool moved = false;
      for (Index t = 0; t < nt_; ++t) {
        const Index own = chart_of_[t];
        if (charts_[own].own_plane() || size[own] <= 1) continue;
        Index n3[3];
        for (int k = 0; k < 3; ++k) n3[k] = neighbour_[3 * static_cast<std::size_t>(t) + k];
        for (int k = 0; k < 3; ++k) {
          if (n3[k] == kNoIndex) continue;
          const Index other = chart_of_[n3[k]];
          if (other == own || charts_[other].own_plane()) continue;
          int count = 0;
          for (int j = 0; j < 3; ++j) count += n3[j] != kNoIndex && chart_of_[n3[j]] == other;
          if (count < 2 || dot(normal_[t], charts_[other].direction) < cos_absorb) continue;
          chart_of_[t] = other;
          --size[own], ++size[other];
          moved = true;
          break;
        }
      }
      if (!moved) break;
    }
    for (Chart& c : charts_) c.triangles.clear();
    for (Index t = 0; t < nt_; ++t) charts_[chart_of_[t]].triangles.push_back(t);
    std::erase_if(charts_, [](const Chart& c) { return c.triangles.empty(); });
  }

  double chart_area(Index c) const {
    double a = 0.0;
    for (Index t : charts_[c].triangles) a += area_[t];
    return a;
  }

  Vec3 normal_sum(Index c) const {
    Vec3 sum{};
    for (Index t : charts_[c].triangles) sum = sum + area_[t] * normal_[t];
    return sum;
  }

  bool within_cone(Index c, const Vec3& direction, double cos_limit) const {
    for (Index t : charts_[c].triangles)
      if (dot(normal_[t], direction) < cos_limit) return false;
    return true;
  }

  // The fallback charting: each triangle labelled with the best of 26
  // projection directions; charts = components of equal labels.
  void make_projected_charts() {
    const auto dirs = projection_directions();
    std::vector<int> label(static_cast<std::size_t>(nt_), -1);
    for (Index t = 0; t < nt_; ++t) {
      if (normal_[t] == Vec3{}) continue;
      double best = -INFINITY;
      for (int d = 0; d < kNumDirections; ++d) {
        const double score = dot(normal_[t], dirs[d]);
        if (score > best) best = score, label[t] = d;
      }
    }
    std::vector<Index> parent(static_cast<std::size_t>(nt_));
    std::iota(parent.begin(), parent.end(), 0);
    for (Index t = 0; t < nt_; ++t)
      for (int k = 0; k < 3; ++k) {
        const Index n = neighbour_[3 * static_cast<std::size_t>(t) + k];
        if (n == kNoIndex || label[t] != label[n] || label[t] < 0) continue;
        const Index ra = find_root(parent, t), rb = find_root(parent, n);
        if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
      }
    std::vector<Index> chart_of_root(static_cast<std::size_t>(nt_), kNoIndex);
    for (Index t = 0; t < nt_; ++t) {
      const Index r = find_root(parent, t);
      if (chart_of_root[r] == kNoIndex) {
        chart_of_root[r] = static_cast<Index>(charts_.size());
        charts_.push_back({{}, label[t] < 0 ? Vec3{} : dirs[label[t]]});
      }
      charts_[chart_of_root[r]].triangles.push_back(t);
    }
  }

  // Local UVs of chart c: orthogonal projection on the plane of its
  // direction d (u x v = d, so front-facing triangles stay counter-clockwise),
  // with v along the model's up axis where the chart is not seen from above
  // or below; own-plane charts lay each triangle out alone.
  void lay_out(std::size_t c) {
    Chart& chart = charts_[c];
    if (chart.own_plane()) {
      for (Index t : chart.triangles) lay_out_alone(t, false);
      return;
    }
    const Vec3 d = chart.direction;
    Vec3 up = options_.up - dot(options_.up, d) * d;
    if (!(norm(up) > 0.3)) {
      const Vec3 axis = std::abs(d.x) <= std::abs(d.y) && std::abs(d.x) <= std::abs(d.z) ? Vec3{1, 0, 0}
                        : std::abs(d.y) <= std::abs(d.z)                                 ? Vec3{0, 1, 0}
                                                                                         : Vec3{0, 0, 1};
      up = cross(d, cross(axis, d));
    }
    const Vec3 v = normalized(up);
    const Vec3 u = cross(v, d);
    const Vec3 origin = point(chart.triangles.front(), 0);
    for (Index t : chart.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vec3 p = point(t, k) - origin;
        local_[3 * static_cast<std::size_t>(t) + k] = {dot(p, u), dot(p, v)};
      }
  }

  // Replaces a projected chart's layout by its LSCM layout when that is
  // one-to-one (exact checks) and distorts less (area-weighted |log area
  // ratio| + log conformal distortion); the LSCM layout is turned to match
  // the projection (so the model's up axis stays up).
  void improve_with_lscm(bool only_projected = false) {
    for (Chart& c : charts_) {
      if (c.own_plane() || c.triangles.size() < static_cast<std::size_t>(options_.lscm_min_triangles)) continue;
      if (only_projected && c.lscm) continue;
      if (c.triangles.size() >= 4096) stop::check();
      std::vector<Uv> uv;
      if (!lscm_chart_layout(s_, c.triangles, uv)) continue;
      const auto flipped = uv_flipped_triangles(uv);
      if (std::find(flipped.begin(), flipped.end(), 1) != flipped.end() || !uv_one_to_one(uv)) continue;
      std::vector<Uv> projected(uv.size());
      for (std::size_t i = 0; i < c.triangles.size(); ++i)
        for (int k = 0; k < 3; ++k) projected[3 * i + k] = local_[3 * static_cast<std::size_t>(c.triangles[i]) + k];
      if (chart_distortion(c.triangles, uv) >= chart_distortion(c.triangles, projected)) continue;
      turn_like(uv, projected);
      for (std::size_t i = 0; i < c.triangles.size(); ++i)
        for (int k = 0; k < 3; ++k) local_[3 * static_cast<std::size_t>(c.triangles[i]) + k] = uv[3 * i + k];
      c.lscm = true;
    }
  }

  // A projected chart whose layout LSCM could not replace and that overlaps
  // itself would be split after packing anyway, at its median, into pieces
  // that no union takes any more. Split before the merge, its pieces (laid
  // out by LSCM where that is one-to-one and distorts less than their
  // projection, as improve_with_lscm does) can join their neighbours.
  // Returns the splits made.
  Index split_overlapping_layouts() {
    Index splits = 0;
    for (int round = 0; round < 32; ++round) {
      std::vector<std::uint8_t> overlaps(charts_.size(), 0);
      tbb::parallel_for(std::size_t{0}, charts_.size(), [&](std::size_t c) {
        const Chart& chart = charts_[c];
        if (chart.lscm || chart.own_plane() || chart.triangles.size() < 2) return;
        std::vector<Uv> uv;
        uv.reserve(3 * chart.triangles.size());
        for (Index t : chart.triangles)
          for (int k = 0; k < 3; ++k) uv.push_back(local_[3 * static_cast<std::size_t>(t) + k]);
        overlaps[c] = !uv_one_to_one(uv);
      });
      const std::size_t before = charts_.size();
      for (std::size_t c = 0; c < before; ++c)
        if (overlaps[c]) split(c), ++splits;
      if (charts_.size() == before) break;
      splits += make_disks();
      improve_with_lscm(/*only_projected=*/true);
    }
    return splits;
  }

  // Neighbouring charts are merged, longest shared border first, while the
  // union's LSCM layout (or, when that fails, its ARAP layout) stays
  // one-to-one (exact checks) and within the distortion bound
  // (layout_acceptable). Two charts that share their border
  // in several arcs are glued along the longest and cut open along the
  // others (seams), so an open cylinder unrolls into one chart. A union
  // that still is no disk (a handle, two borders) is cut open along
  // shortest loops (disk_cut) once no other union passes, so a torus
  // becomes one disk. The merged layout is turned so that the model's up
  // axis points up where the chart allows it.
  void merge_by_layout() {
    std::size_t work = 0;  // triangles laid out so far: at most merge_work_surfaces surfaces' worth
    const auto budget = static_cast<std::size_t>(std::max(0.0, options_.merge_work_surfaces) * static_cast<double>(nt_));
    std::set<std::array<std::size_t, 4>> failed, not_a_disk;
    bool cut_loops = false;
    constexpr std::uint8_t kNotADisk = 2;
    while (work < budget) {
      // The merging can take seconds: a stop request (or this thread's
      // --mesh-timeout) is honoured between rounds and before each layout.
      stop::check();
      std::vector<Index> chart_of(static_cast<std::size_t>(nt_), kNoIndex);
      for (std::size_t c = 0; c < charts_.size(); ++c)
        for (Index t : charts_[c].triangles) chart_of[t] = static_cast<Index>(c);
      // Shared border edges per chart pair: (a, b, edge key, length).
      struct Border {
        Index a, b;
        std::uint64_t edge;
        double length;
      };
      std::vector<Border> borders;
      for (Index t = 0; t < nt_; ++t)
        for (int k = 0; k < 3; ++k) {
          const Index n = neighbour_[3 * static_cast<std::size_t>(t) + k];
          if (n == kNoIndex || n < t) continue;
          const Index a = chart_of[t], b = chart_of[n];
          if (a == b || charts_[a].own_plane() || charts_[b].own_plane()) continue;
          borders.push_back({std::min(a, b), std::max(a, b), edge_key(t, k), edge_length(t, k)});
        }
      std::sort(borders.begin(), borders.end(), [](const Border& x, const Border& y) {
        return std::tie(x.a, x.b, x.edge) < std::tie(y.a, y.b, y.edge);
      });
      struct Candidate {
        double length;
        std::size_t first, last;  // range of borders
      };
      std::vector<Candidate> candidates;
      for (std::size_t i = 0; i < borders.size();) {
        std::size_t j = i;
        double length = 0.0;
        while (j < borders.size() && borders[j].a == borders[i].a && borders[j].b == borders[i].b)
          length += borders[j++].length;
        candidates.push_back({length, i, j});
        i = j;
      }
      // Small charts join a neighbour first (the smaller chart of the pair
      // smallest first, then the longest shared border): their layouts are
      // cheap and they pass most often; two large charts are tried when
      // neither has a small neighbour left.
      auto smaller = [&](const Candidate& c) {
        return std::min(charts_[borders[c.first].a].triangles.size(), charts_[borders[c.first].b].triangles.size());
      };
      std::sort(candidates.begin(), candidates.end(), [&](const Candidate& x, const Candidate& y) {
        const std::size_t sx = smaller(x), sy = smaller(y);
        if (sx != sy) return sx < sy;
        return x.length != y.length ? x.length > y.length : x.first < y.first;
      });
      // A matching of untried pairs, best first; its layouts are computed in
      // parallel and the pairs that pass are merged (in matching order, so
      // the result is the same for any thread count). A pair that fails is
      // not tried again while both charts stay as they are (a chart is known
      // by its first triangle and its size: charts only grow).
      std::vector<std::uint8_t> touched(charts_.size(), 0);
      std::vector<const Candidate*> matching;
      for (const Candidate& cand : candidates) {
        const Index a = borders[cand.first].a, b = borders[cand.first].b;
        if (touched[a] || touched[b] || failed.count(pair_signature(a, b)) != 0) continue;
        touched[a] = touched[b] = 1;
        matching.push_back(&cand);
        work += charts_[a].triangles.size() + charts_[b].triangles.size();
        if (work >= budget) break;
      }
      if (matching.empty()) {
        // Unions that are no disk are tried again, cut open, once the
        // merge without cuts is done: cuts are longer seams, and an atlas
        // merged first without them keeps larger, rounder charts.
        if (cut_loops || not_a_disk.empty()) break;
        cut_loops = true;
        for (const auto& pair : not_a_disk) failed.erase(pair);
        not_a_disk.clear();
        continue;
      }
      std::vector<std::vector<Index>> merged_tris(matching.size());
      std::vector<std::vector<Uv>> merged_uv(matching.size());
      std::vector<std::vector<std::uint64_t>> merged_seams(matching.size());
      std::vector<std::uint8_t> ok(matching.size(), 0);
      tbb::parallel_for(std::size_t{0}, matching.size(), [&](std::size_t i) {
        stop::check();
        const Candidate& cand = *matching[i];
        const Index a = borders[cand.first].a, b = borders[cand.first].b;
        std::vector<Index>& tris = merged_tris[i];
        tris.reserve(charts_[a].triangles.size() + charts_[b].triangles.size());
        std::merge(charts_[a].triangles.begin(), charts_[a].triangles.end(), charts_[b].triangles.begin(),
                   charts_[b].triangles.end(), std::back_inserter(tris));
        // The new seams and both charts' own (else a chart cut open by an
        // earlier union would be glued shut again).
        const std::vector<std::uint64_t> cut =
            seams_but_the_longest_arc(std::span<const Border>(borders.data() + cand.first, cand.last - cand.first));
        std::vector<std::uint64_t>& seams = merged_seams[i];
        std::merge(charts_[a].seams.begin(), charts_[a].seams.end(), charts_[b].seams.begin(), charts_[b].seams.end(),
                   std::back_inserter(seams));
        add_seams(seams, cut);
        std::vector<Uv>& uv = merged_uv[i];
        // The exact checks and the distortion bound.
        bool accepted = false;
        const auto passes = [&](std::span<const Uv> layout) {
          const auto flipped = uv_flipped_triangles(layout);
          return accepted = std::find(flipped.begin(), flipped.end(), 1) == flipped.end() &&
                            layout_acceptable(tris, layout) && uv_one_to_one(layout);
        };
        // LSCM keeps angles and may shrink a limb's tip; when its layout does
        // not pass, ARAP (from it) evens areas out.
        const ChartLayout method = options_.merge_with_arap ? ChartLayout::arap : ChartLayout::lscm;
        if (!lscm_chart_layout(s_, tris, uv, seams, method, passes)) {
          // Not a disk (a handle, or borders that the glued arc joined into
          // an annulus): once no union without cuts is left, cut it open
          // along shortest loops and try again.
          if (!cut_loops) {
            ok[i] = kNotADisk;
            return;
          }
          const std::vector<std::uint64_t> loops = disk_cut(s_, tris, seams);
          if (loops.empty()) return;
          add_seams(seams, loops);
          if (!lscm_chart_layout(s_, tris, uv, seams, method, passes)) return;
        }
        if (!accepted && !passes(uv)) return;
        turn_up(tris, uv);
        ok[i] = 1;
      });
      for (std::size_t i = 0; i < matching.size(); ++i) {
        const Index a = borders[matching[i]->first].a, b = borders[matching[i]->first].b;
        if (ok[i] != 1) {
          failed.insert(pair_signature(a, b));
          if (ok[i] == kNotADisk) not_a_disk.insert(pair_signature(a, b));
          continue;
        }
        const std::vector<Index>& tris = merged_tris[i];
        for (std::size_t j = 0; j < tris.size(); ++j)
          for (int k = 0; k < 3; ++k) local_[3 * static_cast<std::size_t>(tris[j]) + k] = merged_uv[i][3 * j + k];
        const Vec3 direction = normalized(normal_sum(a) + normal_sum(b));
        charts_[a].triangles = std::move(merged_tris[i]);
        charts_[a].seams = std::move(merged_seams[i]);
        if (squared_norm(direction) > 0.5) charts_[a].direction = direction;
        charts_[a].lscm = true;
        charts_[b].triangles.clear();
      }
      std::erase_if(charts_, [](const Chart& c) { return c.triangles.empty(); });
    }
  }

  // Adds the ascending edge keys `extra` to the ascending `seams`.
  static void add_seams(std::vector<std::uint64_t>& seams, const std::vector<std::uint64_t>& extra) {
    const auto end = static_cast<std::ptrdiff_t>(seams.size());
    seams.insert(seams.end(), extra.begin(), extra.end());
    std::inplace_merge(seams.begin(), seams.begin() + end, seams.end());
  }

  // Each triangle's chart now (triangles of no chart share one more part).
  std::vector<Index> current_chart_of() const {
    std::vector<Index> part(static_cast<std::size_t>(nt_), static_cast<Index>(charts_.size()));
    for (std::size_t c = 0; c < charts_.size(); ++c)
      for (Index t : charts_[c].triangles) part[t] = static_cast<Index>(c);
    return part;
  }

  // Charts a and b as they are now (see merge_by_layout).
  std::array<std::size_t, 4> pair_signature(Index a, Index b) const {
    const Chart &x = charts_[a], &y = charts_[b];
    return {static_cast<std::size_t>(x.triangles.front()), x.triangles.size(), static_cast<std::size_t>(y.triangles.front()),
            y.triangles.size()};
  }

  // The shared edges of two charts fall into arcs (paths joined at
  // vertices); every edge but those of the longest arc becomes a seam.
  template <class Border>
  static std::vector<std::uint64_t> seams_but_the_longest_arc(std::span<const Border> shared) {
    if (shared.size() < 2) return {};
    std::vector<Index> ids;
    for (const Border& e : shared) ids.insert(ids.end(), {Index(e.edge >> 32), Index(e.edge & 0xffffffffu)});
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    auto id = [&](std::uint64_t v) {
      return static_cast<Index>(std::lower_bound(ids.begin(), ids.end(), Index(v)) - ids.begin());
    };
    std::vector<Index> parent(ids.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (const Border& e : shared) {
      const Index x = find_root(parent, id(e.edge >> 32)), y = find_root(parent, id(e.edge & 0xffffffffu));
      if (x != y) parent[std::max(x, y)] = std::min(x, y);
    }
    std::vector<double> arc_length(ids.size(), 0.0);
    for (const Border& e : shared) arc_length[find_root(parent, id(e.edge >> 32))] += e.length;
    const auto longest = static_cast<Index>(std::max_element(arc_length.begin(), arc_length.end()) - arc_length.begin());
    std::vector<std::uint64_t> seams;
    for (const Border& e : shared)
      if (find_root(parent, id(e.edge >> 32)) != longest) seams.push_back(e.edge);
    std::sort(seams.begin(), seams.end());
    return seams;
  }

  // The distortion bound of a merged chart, against its own scale: at least
  // merge_min_area_within_2 of its area with area ratio in [0.5, 2], and as
  // much with conformal distortion at most 2.
  bool layout_acceptable(std::span<const Index> tris, std::span<const Uv> uv) const {
    double within = 0.0, conformal = 0.0;
    const double area3 = for_each_distortion(tris, uv, [&](Index t, double ratio, double conf) {
      if (ratio >= 0.5 && ratio <= 2.0) within += area_[t];
      if (conf <= 2.0) conformal += area_[t];
      return true;
    });
    const double need = options_.merge_min_area_within_2 * area3;
    return area3 > 0.0 && within >= need && conformal >= need;
  }

  // Calls f(t, area ratio against the chart's own scale, conformal
  // distortion) for each triangle of positive area of a chart's layout, while
  // f returns true. Returns the chart's 3D area, or 0 when the layout has no
  // positive area or f stopped.
  template <class F>
  double for_each_distortion(std::span<const Index> tris, std::span<const Uv> uv, F&& f) const {
    double area3 = 0.0, area2 = 0.0;
    for (std::size_t i = 0; i < tris.size(); ++i) area3 += area_[tris[i]], area2 += uv_signed_area(&uv[3 * i]);
    if (!(area3 > 0.0) || !(area2 > 0.0)) return 0.0;
    const double k = area2 / area3;
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const Index t = tris[i];
      if (!(area_[t] > 0.0)) continue;
      const TriangleDistortion m = triangle_distortion(point(t, 0), point(t, 1), point(t, 2), &uv[3 * i]);
      if (!f(t, m.area_ratio / k, m.conformal)) return 0.0;
    }
    return area3;
  }

  // Turns a chart's layout about its centroid so that the model's up axis,
  // mapped into UV by each triangle's linear map (area-weighted, by how much
  // of the axis lies in the triangle's plane), points along +v. Charts seen
  // along the axis (little of it in their planes) keep their turn.
  void turn_up(std::span<const Index> tris, std::vector<Uv>& uv) const {
    double sx = 0.0, sy = 0.0, weight = 0.0;
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const Index t = tris[i];
      if (!(area_[t] > 0.0)) continue;
      const Vec3 e1 = point(t, 1) - point(t, 0), e2 = point(t, 2) - point(t, 0);
      const Vec3 w = options_.up - dot(options_.up, normal_[t]) * normal_[t];
      // w = x e1 + y e2 (w is in the plane): the 2x2 Gram system.
      const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
      const double det = g11 * g22 - g12 * g12;
      if (!(det > 0.0)) continue;
      const double r1 = dot(w, e1), r2 = dot(w, e2);
      const double x = (r1 * g22 - r2 * g12) / det, y = (g11 * r2 - g12 * r1) / det;
      const Uv* q = &uv[3 * i];
      const double dx = x * (q[1][0] - q[0][0]) + y * (q[2][0] - q[0][0]);
      const double dy = x * (q[1][1] - q[0][1]) + y * (q[2][1] - q[0][1]);
      const double l = std::hypot(dx, dy);
      if (!(l > 0.0) || !std::isfinite(l)) continue;
      const double wn = norm(w);
      sx += area_[t] * wn * dx / l, sy += area_[t] * wn * dy / l;
      weight += area_[t];
    }
    if (!(weight > 0.0) || std::hypot(sx, sy) < 0.3 * weight) return;
    const double angle = std::numbers::pi / 2 - std::atan2(sy, sx);
    const double c = std::cos(angle), sn = std::sin(angle);
    double mu[2] = {0.0, 0.0};
    for (const Uv& p : uv) mu[0] += p[0], mu[1] += p[1];
    mu[0] /= static_cast<double>(uv.size()), mu[1] /= static_cast<double>(uv.size());
    for (Uv& p : uv) {
      const double x = p[0] - mu[0], y = p[1] - mu[1];
      p = {c * x - sn * y, sn * x + c * y};
    }
  }

  std::uint64_t edge_key(Index t, int k) const {
    const auto a = static_cast<std::uint32_t>(s_.triangles[t][k]);
    const auto b = static_cast<std::uint32_t>(s_.triangles[t][(k + 1) % 3]);
    return static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
  }

  // Triangles t and n, neighbours across edge k of t, are glued in the
  // current layouts: the shared vertices have the same local UV in both
  // (false across a seam).
  bool glued(Index t, int k, Index n) const {
    for (int j = 0; j < 2; ++j) {
      const Index v = s_.triangles[t][(k + j) % 3];
      const Uv& p = local_[3 * static_cast<std::size_t>(t) + (k + j) % 3];
      int m = 0;
      while (m < 3 && s_.triangles[n][m] != v) ++m;
      if (m == 3 || local_[3 * static_cast<std::size_t>(n) + m] != p) return false;
    }
    return true;
  }

  // Area-weighted mean of |log area ratio| + log conformal distortion of a
  // chart's layout, the area ratio taken against the chart's own scale.
  double chart_distortion(std::span<const Index> tris, std::span<const Uv> uv) const {
    double sum = 0.0;
    const double area3 = for_each_distortion(tris, uv, [&](Index t, double ratio, double conformal) {
      if (!(ratio > 0.0) || !std::isfinite(conformal)) return false;
      sum += area_[t] * (std::abs(std::log(ratio)) + std::log(conformal));
      return true;
    });
    return area3 > 0.0 ? sum / area3 : INFINITY;
  }

  // Rotates `uv` about its centroid to best match `target` (2D Procrustes, no reflection).
  static void turn_like(std::vector<Uv>& uv, const std::vector<Uv>& target) {
    double mu[2] = {0, 0}, mt[2] = {0, 0};
    for (std::size_t i = 0; i < uv.size(); ++i)
      for (int a = 0; a < 2; ++a) mu[a] += uv[i][a], mt[a] += target[i][a];
    for (int a = 0; a < 2; ++a) mu[a] /= static_cast<double>(uv.size()), mt[a] /= static_cast<double>(uv.size());
    double sdot = 0.0, scross = 0.0;
    for (std::size_t i = 0; i < uv.size(); ++i) {
      const double qx = uv[i][0] - mu[0], qy = uv[i][1] - mu[1];
      const double px = target[i][0] - mt[0], py = target[i][1] - mt[1];
      sdot += qx * px + qy * py;
      scross += qx * py - qy * px;
    }
    const double angle = std::atan2(scross, sdot);
    const double c = std::cos(angle), sn = std::sin(angle);
    for (Uv& p : uv) {
      const double x = p[0] - mu[0], y = p[1] - mu[1];
      p = {c * x - sn * y, sn * x + c * y};
    }
  }

  void lay_out_alone(Index t, bool canonical) {
    const Vec3 a = point(t, 0), b = point(t, 1), c = point(t, 2);
    const double ab = norm(b - a);
    Uv* uv = &local_[3 * static_cast<std::size_t>(t)];
    if (!canonical && ab > 0.0) {
      const Vec3 x = (b - a) / ab;
      const Vec3 ac = c - a;
      const double cy = norm(cross(x, ac));
      uv[0] = {0.0, 0.0};
      uv[1] = {ab, 0.0};
      uv[2] = {dot(ac, x), cy};
      if (uv_flipped_triangles(std::span<const Uv>(uv, 3))[0] == 0) return;
    }
    const double length = std::max({ab, norm(c - b), norm(a - c)});
    const double l = length > 0.0 && std::isfinite(length) ? length : fallback_length_;
    uv[0] = {0.0, 0.0};
    uv[1] = {l, 0.0};
    uv[2] = {0.0, l};
  }

  // Moves each triangle in `triangles` (ascending) out of its chart into a chart of its own.
  void make_singletons(const std::vector<Index>& triangles, bool canonical) {
    std::vector<std::uint8_t> moving(static_cast<std::size_t>(nt_), 0);
    for (Index t : triangles) moving[t] = 1;
    for (Chart& c : charts_) std::erase_if(c.triangles, [&](Index t) { return moving[t] != 0; });
    for (Index t : triangles) {
      charts_.push_back({{t}, Vec3{}});
      lay_out_alone(t, canonical);
    }
  }

  void separate_flipped() {
    const std::vector<std::uint8_t> flipped = uv_flipped_triangles(local_);
    std::vector<Index> bad;
    for (Index t = 0; t < nt_; ++t)
      if (flipped[t]) bad.push_back(t);
    if (!bad.empty()) make_singletons(bad, false);
  }

  // Every chart a topological disk: a chart falling apart over its manifold
  // edges is separated into its pieces, and a connected chart whose Euler
  // characteristic is not 1 (an annulus, a handle, a pinched vertex) is split
  // at its median until the pieces are disks (one triangle always is).
  Index make_disks() {
    Index splits = 0;
    std::vector<Index> chart_of(static_cast<std::size_t>(nt_), kNoIndex);
    for (std::size_t c = 0; c < charts_.size(); ++c)
      for (Index t : charts_[c].triangles) chart_of[t] = static_cast<Index>(c);
    // The charts that already are one disk (most) are found in parallel and
    // left as they are; the others are cut below, one after the other, as
    // before (the same charts in the same order).
    const std::size_t num_first = charts_.size();
    std::vector<std::uint8_t> is_disk(num_first, 0);
    tbb::parallel_for(std::size_t{0}, num_first, [&](std::size_t c) {
      is_disk[c] = components(c, chart_of).size() == 1 && euler_characteristic(charts_[c].triangles) == 1;
    });
    for (std::size_t c = 0; c < charts_.size(); ++c) {
      if (c < num_first && is_disk[c]) continue;
      std::vector<std::size_t> todo = {c};
      while (!todo.empty()) {
        const std::size_t k = todo.back();
        todo.pop_back();
        for (Index t : charts_[k].triangles) chart_of[t] = static_cast<Index>(k);
        std::vector<std::vector<Index>> pieces = components(k, chart_of);
        if (pieces.size() > 1) {
          charts_[k].triangles = std::move(pieces[0]);
          for (std::size_t i = 1; i < pieces.size(); ++i) {
            for (Index t : pieces[i]) chart_of[t] = static_cast<Index>(charts_.size());
            charts_.push_back({std::move(pieces[i]), charts_[k].direction, charts_[k].lscm});
            todo.push_back(charts_.size() - 1);
          }
          todo.push_back(k);
          continue;
        }
        if (euler_characteristic(charts_[k].triangles) == 1) continue;
        if (!split_through_a_hole(k)) split(k);
        ++splits;
        todo.push_back(k);
        todo.push_back(charts_.size() - 1);
      }
    }
    return splits;
  }

  // A chart with a hole (a second border loop: an island of another chart,
  // or a hole of the surface) is cut in two by the vertical line through
  // the hole's centre, so both halves have a notch where the hole was and
  // the model's up axis stays up in both. False when it has one border loop
  // or the line leaves one side empty.
  bool split_through_a_hole(std::size_t c) {
    std::vector<Index>& tris = charts_[c].triangles;
    // in_chart_ is all 0 between calls: set for this chart, cleared on return.
    in_chart_.resize(static_cast<std::size_t>(nt_), 0);
    std::vector<std::uint8_t>& in_chart = in_chart_;
    for (Index t : tris) in_chart[t] = 1;
    struct Clear {
      std::vector<std::uint8_t>& marks;
      const std::vector<Index> triangles;
      ~Clear() {
        for (Index t : triangles) marks[static_cast<std::size_t>(t)] = 0;
      }
    } clear{in_chart, tris};
    // Border edges (no neighbour in this chart), their loops by shared vertices.
    std::vector<std::array<Index, 2>> border;
    std::vector<std::array<Uv, 2>> border_uv;
    for (Index t : tris)
      for (int k = 0; k < 3; ++k) {
        const Index n = neighbour_[3 * static_cast<std::size_t>(t) + k];
        if (n != kNoIndex && in_chart[n] && glued(t, k, n)) continue;
        border.push_back({s_.triangles[t][k], s_.triangles[t][(k + 1) % 3]});
        border_uv.push_back({local_[3 * static_cast<std::size_t>(t) + k], local_[3 * static_cast<std::size_t>(t) + (k + 1) % 3]});
      }
    std::vector<Index> ids;
    for (const auto& e : border) ids.insert(ids.end(), {e[0], e[1]});
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    auto id = [&](Index v) { return static_cast<Index>(std::lower_bound(ids.begin(), ids.end(), v) - ids.begin()); };
    std::vector<Index> parent(ids.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (const auto& e : border) {
      const Index a = find_root(parent, id(e[0])), b = find_root(parent, id(e[1]));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
    // Per loop: its UV box and centre.
    std::vector<std::array<double, 6>> loop(ids.size(), {INFINITY, INFINITY, -INFINITY, -INFINITY, 0.0, 0.0});
    for (std::size_t i = 0; i < border.size(); ++i) {
      auto& l = loop[static_cast<std::size_t>(find_root(parent, id(border[i][0])))];
      for (const Uv& p : border_uv[i])
        l = {std::min(l[0], p[0]), std::min(l[1], p[1]), std::max(l[2], p[0]), std::max(l[3], p[1]), l[4] + p[0], l[5] + 1.0};
    }
    std::size_t outer = ids.size(), hole = ids.size();
    for (std::size_t r = 0; r < ids.size(); ++r) {
      if (loop[r][5] == 0.0) continue;
      auto extent = [&](std::size_t q) { return (loop[q][2] - loop[q][0]) + (loop[q][3] - loop[q][1]); };
      if (outer == ids.size() || extent(r) > extent(outer)) hole = outer, outer = r;
      else if (hole == ids.size() || extent(r) > extent(hole)) hole = r;
    }
    if (hole == ids.size()) return false;
    const double cut = loop[hole][4] / loop[hole][5];
    std::vector<Index> left, right;
    for (Index t : tris) {
      const std::size_t i = 3 * static_cast<std::size_t>(t);
      (local_[i][0] + local_[i + 1][0] + local_[i + 2][0] < 3.0 * cut ? left : right).push_back(t);
    }
    if (left.empty() || right.empty()) return false;
    tris = std::move(left);
    charts_.push_back({std::move(right), charts_[c].direction});
    return true;
  }

  std::vector<std::vector<Index>> components(std::size_t c, const std::vector<Index>& chart_of) const {
    std::vector<std::vector<Index>> out;
    // This thread's marks, one per surface triangle: all 0 between calls.
    std::vector<std::uint8_t>& mark = marks_.local();
    mark.resize(static_cast<std::size_t>(nt_), 0);
    for (Index t0 : charts_[c].triangles) {
      if (mark[t0]) continue;
      std::vector<Index> piece = {t0};
      mark[t0] = 1;
      for (std::size_t j = 0; j < piece.size(); ++j)
        for (int k = 0; k < 3; ++k) {
          const Index n = neighbour_[3 * static_cast<std::size_t>(piece[j]) + k];
          if (n == kNoIndex || chart_of[n] != static_cast<Index>(c) || !glued(piece[j], k, n)) continue;
          if (!mark[n]) mark[n] = 1, piece.push_back(n);
        }
      std::sort(piece.begin(), piece.end());
      out.push_back(std::move(piece));
    }
    for (Index t : charts_[c].triangles) mark[t] = 0;
    return out;
  }

  // V - E + F over the chart's own vertices and edges, a vertex being a
  // surface vertex at one position of the chart's layout (so a seam, where
  // the layout cuts the chart open, counts as border).
  long euler_characteristic(const std::vector<Index>& tris) const {
    const std::size_t n = 3 * tris.size();
    if (n == 0) return 0;
    // Corners by surface vertex (key vertex << 32 | position 3 i + k).
    // Ascending: by a count of each vertex's corners when the chart has
    // corners enough to pay for a table of all surface vertices, else sorted.
    std::vector<std::uint64_t> keys(n);
    const auto key_of = [&](std::size_t corner) {
      return static_cast<std::uint64_t>(static_cast<std::uint32_t>(s_.triangles[tris[corner / 3]][corner % 3])) << 32 |
             corner;
    };
    const std::size_t num_vertices = s_.points.size();
    if (4 * n >= num_vertices) {
      std::vector<std::size_t> next(num_vertices + 1, 0);
      for (std::size_t c = 0; c < n; ++c) ++next[(key_of(c) >> 32) + 1];
      for (std::size_t v = 0; v < num_vertices; ++v) next[v + 1] += next[v];
      for (std::size_t c = 0; c < n; ++c) {
        const std::uint64_t key = key_of(c);
        keys[next[key >> 32]++] = key;
      }
    } else {
      for (std::size_t c = 0; c < n; ++c) keys[c] = key_of(c);
      std::sort(keys.begin(), keys.end());
    }
    const auto at = [&](std::size_t p) { return static_cast<std::size_t>(keys[p] & 0xffffffffu); };
    const auto uv_at = [&](std::size_t corner) { return local_[3 * static_cast<std::size_t>(tris[corner / 3]) + corner % 3]; };
    // Chart vertices: the corners of one surface vertex at one position.
    std::vector<std::uint32_t> vertex_of(n);
    std::uint32_t v = 0;
    std::vector<std::size_t> runs{0};
    for (std::size_t p = 0; p < n; ++p) {
      if (p > 0 && keys[p] >> 32 != keys[p - 1] >> 32) runs.push_back(p);
      const Uv uv = uv_at(at(p));
      std::size_t q = runs.back();
      while (q < p && uv_at(at(q)) != uv) ++q;
      vertex_of[at(p)] = q < p ? vertex_of[at(q)] : v++;
    }
    runs.push_back(n);
    // Edges: each chart vertex's distinct neighbours, an edge seen from both
    // ends (a degenerate edge from a vertex to itself once).
    std::size_t ends = 0, loops = 0;
    std::vector<std::uint64_t> pairs;
    for (std::size_t r = 0; r + 1 < runs.size(); ++r) {
      pairs.clear();
      for (std::size_t p = runs[r]; p < runs[r + 1]; ++p) {
        const std::size_t c = at(p), base = c / 3 * 3;
        const std::uint64_t a = vertex_of[c];
        pairs.push_back(a << 32 | vertex_of[base + (c + 1) % 3]);
        pairs.push_back(a << 32 | vertex_of[base + (c + 2) % 3]);
      }
      std::sort(pairs.begin(), pairs.end());
      pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
      for (std::uint64_t e : pairs) (e >> 32 == (e & 0xffffffffu) ? loops : ends) += 1;
    }
    return static_cast<long>(v) - static_cast<long>(ends / 2 + loops) + static_cast<long>(tris.size());
  }

  // One global scale: each chart's layout is scaled so that its UV area is its
  // 3D area (UV area / 3D area = 1 for the whole atlas before packing).
  // Degenerate charts keep their layout.
  void equalise_scale() {
    for (const Chart& c : charts_) {
      double area3 = 0.0, area2 = 0.0;
      for (Index t : c.triangles) area3 += area_[t], area2 += uv_signed_area(&local_[3 * static_cast<std::size_t>(t)]);
      if (!(area3 > 0.0) || !(area2 > 0.0) || !std::isfinite(area3 / area2)) continue;
      const double f = std::sqrt(area3 / area2);
      if (!std::isfinite(f) || std::abs(f - 1.0) < 1e-12) continue;
      for (Index t : c.triangles)
        for (int k = 0; k < 3; ++k) {
          Uv& p = local_[3 * static_cast<std::size_t>(t) + k];
          p = {p[0] * f, p[1] * f};
        }
    }
  }

  // A chart holding an overlapping pair is split in two at the median of its
  // triangles' centroids along its longer extent, until no chart holds one.
  Index split_overlapping_charts(const std::vector<std::array<Index, 2>>& pairs) {
    std::vector<Index> chart_of(static_cast<std::size_t>(nt_), kNoIndex);
    for (std::size_t c = 0; c < charts_.size(); ++c)
      for (Index t : charts_[c].triangles) chart_of[t] = static_cast<Index>(c);
    Index splits = 0;
    while (true) {
      std::vector<Index> failing;
      for (const auto& p : pairs)
        if (chart_of[p[0]] == chart_of[p[1]]) failing.push_back(chart_of[p[0]]);
      if (failing.empty()) break;
      std::sort(failing.begin(), failing.end());
      failing.erase(std::unique(failing.begin(), failing.end()), failing.end());
      for (Index c : failing) {
        split(static_cast<std::size_t>(c));
        ++splits;
        for (Index t : charts_.back().triangles) chart_of[t] = static_cast<Index>(charts_.size() - 1);
      }
    }
    // Halves may fall apart: keep every chart connected (and a disk).
    return splits + make_disks();
  }

  // Three times the centroid of triangle t along the layout's axis.
  double layout_centroid(Index t, int axis) const {
    const std::size_t i = 3 * static_cast<std::size_t>(t);
    return local_[i][axis] + local_[i + 1][axis] + local_[i + 2][axis];
  }

  // Orders triangles along a layout axis (ties by index: deterministic).
  auto along(int axis) const {
    return [this, axis](Index a, Index b) {
      const double ca = layout_centroid(a, axis), cb = layout_centroid(b, axis);
      return ca != cb ? ca < cb : a < b;
    };
  }

  // A cut of a chart: its first `count` triangles along `axis` stay, the
  // rest become a new chart.
  struct Cut {
    int axis = 0;
    std::size_t count = 0;
  };

  // Halves chart c at the median of its triangles along the layout's longer
  // axis (the split of a chart whose layout is not one-to-one).
  void split(std::size_t c) { split_at(c, median_cut(c)); }

  Cut median_cut(std::size_t c) const {
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (Index t : charts_[c].triangles)
      for (int a = 0; a < 2; ++a)
        lo[a] = std::min(lo[a], layout_centroid(t, a)), hi[a] = std::max(hi[a], layout_centroid(t, a));
    return Cut{hi[0] - lo[0] >= hi[1] - lo[1] ? 0 : 1, charts_[c].triangles.size() / 2};
  }

  void split_at(std::size_t c, Cut cut) {
    std::vector<Index> tris = std::move(charts_[c].triangles);
    const auto first = tris.begin() + static_cast<std::ptrdiff_t>(cut.count);
    std::nth_element(tris.begin(), first, tris.end(), along(cut.axis));
    // A piece keeps the chart's layout, hence how it was made (lscm).
    Chart second{std::vector<Index>(first, tris.end()), charts_[c].direction, charts_[c].lscm};
    tris.erase(first, tris.end());
    std::sort(tris.begin(), tris.end());
    std::sort(second.triangles.begin(), second.triangles.end());
    charts_[c].triangles = std::move(tris);
    charts_.push_back(std::move(second));
  }

  // The cut of chart c, along either layout axis, whose two pieces' layout
  // bounding boxes have the least summed area, each piece holding at least
  // kPackCutMinShare of the chart's area (an L is cut at its corner into two
  // bars, a half ring about its middle): two sorts and sweeps of prefix and
  // suffix boxes.
  Cut tightest_box_cut(std::size_t c) const {
    std::vector<Index> tris = charts_[c].triangles;
    const std::size_t n = tris.size();
    const double total = chart_area(charts_[c]);
    Cut best{0, n / 2};
    double best_cost = INFINITY;
    std::vector<std::array<double, 4>> suffix(n + 1);
    for (int axis = 0; axis < 2; ++axis) {
      std::sort(tris.begin(), tris.end(), along(axis));
      const auto grown = [&](std::array<double, 4> b, Index t) {
        for (int k = 0; k < 3; ++k) {
          const Uv& p = local_[3 * static_cast<std::size_t>(t) + k];
          b = {std::min(b[0], p[0]), std::min(b[1], p[1]), std::max(b[2], p[0]), std::max(b[3], p[1])};
        }
        return b;
      };
      const std::array<double, 4> empty{INFINITY, INFINITY, -INFINITY, -INFINITY};
      suffix[n] = empty;
      for (std::size_t i = n; i-- > 0;) suffix[i] = grown(suffix[i + 1], tris[i]);
      const auto box_area = [](const std::array<double, 4>& b) { return (b[2] - b[0]) * (b[3] - b[1]); };
      std::array<double, 4> prefix = empty;
      double held = 0.0;
      for (std::size_t k = 1; k < n; ++k) {
        prefix = grown(prefix, tris[k - 1]);
        held += area_[tris[k - 1]];
        if (held < kPackCutMinShare * total || held > (1.0 - kPackCutMinShare) * total) continue;
        const double cost = box_area(prefix) + box_area(suffix[k]);
        if (cost < best_cost) best_cost = cost, best = {axis, k};
      }
    }
    return best;
  }

  // A chart that fills its bounding box poorly (a long strip, an L, a hand)
  // leaves the square around it empty. While the packed charts fill less
  // than pack_target, each of the kPackSplitCandidates largest charts that
  // fills less than pack_split_max_box_fill of its box is tried halved at
  // its median (split(), pieces kept disks by make_disks()): each piece
  // keeps its part of the chart's layout, so no flip, no overlap within a
  // piece and the same distortion. The try that packs best is kept when it
  // packs better than before and at most pack_max_charts_95 charts still
  // hold 95 % of the area; else the charts stay as they were. The tries are
  // packed on a coarser grid (a third of the cells a side: a ninth of the
  // places to look at), the result again on the full one. Leaves the charts
  // packed. Returns the splits kept.
  Index split_for_packing() {
    if (!packs_by_splitting()) return 0;
    const int coarse = std::max(32, options_.pack_resolution / 3);
    pack(coarse);
    Index kept = 0;
    double filled = packed_area();
    for (int round = 0; round < options_.pack_max_splits && filled < options_.pack_target; ++round) {
      std::vector<std::size_t> order(charts_.size());
      std::iota(order.begin(), order.end(), std::size_t{0});
      std::vector<double> area(charts_.size());
      for (std::size_t c = 0; c < charts_.size(); ++c) area[c] = chart_area(charts_[c]);
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return area[a] != area[b] ? area[a] > area[b] : a < b;
      });
      const std::vector<Chart> before = charts_;
      std::optional<std::vector<Chart>> best;
      double best_filled = filled;
      Index best_splits = 0;
      for (std::size_t i = 0; i < std::min(kPackSplitCandidates, order.size()); ++i) {
        if (charts_[order[i]].triangles.size() < 2) continue;
        if (box_fill(charts_[order[i]]) >= options_.pack_split_max_box_fill) continue;
        // The median cut and the one with the tightest boxes (when not the same).
        const std::array<Cut, 2> cuts = {median_cut(order[i]), tightest_box_cut(order[i])};
        const bool same = cuts[1].axis == cuts[0].axis && cuts[1].count == cuts[0].count;
        for (const Cut cut : std::span(cuts).first(same ? 1 : 2)) {
          split_at(order[i], cut);
          straighten_cut(order[i], charts_.size() - 1);
          const Index splits = 1 + make_disks();
          if (charts_holding(0.95) <= static_cast<std::size_t>(options_.pack_max_charts_95)) {
            pack(coarse);
            const double f = packed_area();
            if (f > best_filled) best = charts_, best_filled = f, best_splits = splits;
          }
          charts_ = before;
        }
      }
      if (!best) break;
      charts_ = std::move(*best);
      filled = best_filled;
      kept += best_splits;
    }
    pack();
    pack_cache_.clear();
    return kept;
  }

  // Only surfaces of up to pack_split_max_triangles: each try rasterises
  // every triangle again, which on a 10^6-triangle surface costs more than
  // the rest of the atlas.
  bool packs_by_splitting() const {
    return options_.pack_max_splits > 0 && nt_ <= options_.pack_split_max_triangles;
  }

  // The median cut of split() runs along triangle borders and so zigzags:
  // a triangle of one half with two glued neighbours in the other half moves
  // there (a few passes). Both halves keep their layout (a part of one
  // one-to-one layout), so this changes only where the seam runs.
  void straighten_cut(std::size_t a, std::size_t b) {
    std::vector<std::uint8_t> side(static_cast<std::size_t>(nt_), 0);  // 1: in a, 2: in b
    for (Index t : charts_[a].triangles) side[t] = 1;
    for (Index t : charts_[b].triangles) side[t] = 2;
    std::vector<Index> order = charts_[a].triangles;
    order.insert(order.end(), charts_[b].triangles.begin(), charts_[b].triangles.end());
    straighten_two_way_cut(order, neighbour_, side, [this](Index t, int k, Index n) { return glued(t, k, n); });
    std::vector<Index> all = std::move(charts_[a].triangles);
    all.insert(all.end(), charts_[b].triangles.begin(), charts_[b].triangles.end());
    std::sort(all.begin(), all.end());
    charts_[a].triangles.clear();
    charts_[b].triangles.clear();
    for (Index t : all) charts_[side[t] == 1 ? a : b].triangles.push_back(t);
  }

  // How much of its layout's bounding box a chart covers.
  double box_fill(const Chart& c) const {
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, area = 0.0;
    for (Index t : c.triangles) {
      const Uv* p = &local_[3 * static_cast<std::size_t>(t)];
      area += std::abs(uv_signed_area(p));
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], p[k][a]), hi[a] = std::max(hi[a], p[k][a]);
    }
    const double box = (hi[0] - lo[0]) * (hi[1] - lo[1]);
    return box > 0.0 ? area / box : 1.0;
  }

  // The packed UV area of all charts (the packing efficiency).
  double packed_area() const {
    double sum = 0.0;
    for (const Chart& c : charts_)
      for (Index t : c.triangles) {
        sum += std::abs(uv_signed_area(&uvs_[3 * static_cast<std::size_t>(t)]));
      }
    return sum;
  }

  double chart_area(const Chart& c) const {
    double a = 0.0;
    for (Index t : c.triangles) a += area_[t];
    return a;
  }

  // How many of the largest charts hold `fraction` of the surface's area.
  std::size_t charts_holding(double fraction) const {
    std::vector<double> area;
    double total = 0.0;
    for (const Chart& c : charts_)
      if (const double a = chart_area(c); a > 0.0) area.push_back(a), total += a;
    std::sort(area.begin(), area.end(), std::greater<>());
    double held = 0.0;
    std::size_t n = 0;
    while (n < area.size() && held < fraction * total) held += area[n++];
    return n;
  }

  void pack() { pack(options_.pack_resolution); }
  void pack(int resolution) {
    std::vector<std::vector<Index>> lists;
    lists.reserve(charts_.size());
    for (const Chart& c : charts_) lists.push_back(c.triangles);
    pack_charts(local_, lists, uvs_, PackOptions{.resolution = resolution}, &pack_cache_);
  }

  const TriSurface& s_;
  const UvOptions& options_;
  Index nt_ = 0;
  double fallback_length_ = 1.0;
  std::vector<Chart> charts_;
  std::vector<Index> chart_of_;  // while growing and merging
  std::vector<Vec3> normal_, centroid_;
  std::vector<double> area_;
  std::vector<std::uint8_t> in_chart_;  // scratch of split_through_a_hole
  std::vector<Index> neighbour_;  // 3 per triangle: across each manifold edge, or kNoIndex
  std::vector<Uv> local_;  // each chart's own layout (model units)
  std::vector<Uv> uvs_;    // packed into [0,1]² by pack()
  // The shapes of the charts packed by split_for_packing's tries (most
  // charts are the same from one try to the next); emptied after it.
  PackShapeCache pack_cache_;
  mutable tbb::enumerable_thread_specific<std::vector<std::uint8_t>> marks_;  // components()' scratch
};

}  // namespace

UvAtlas build_uv_atlas(const TriSurface& surface, const UvOptions& options) {
  return AtlasBuilder(surface, options).build();
}

std::vector<double> uv_corner_values(const TriSurface& surface, std::span<const double> point_field) {
  std::vector<double> out(3 * surface.triangles.size());
  for (std::size_t t = 0; t < surface.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) out[3 * t + k] = point_field[static_cast<std::size_t>(surface.triangles[t][k])];
  return out;
}

}  // namespace hq
