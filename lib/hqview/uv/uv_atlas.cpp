#include "hqview/uv/uv_atlas.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "hqview/uv/uv_lscm.h"

namespace hq {
namespace {

constexpr int kNumDirections = 26;
constexpr int kOwnPlane = -1;  // a singleton chart laid out in its own plane (or canonically)

std::array<Vec3, kNumDirections> projection_directions() {
  std::array<Vec3, kNumDirections> d{};
  int n = 0;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x != 0 || y != 0 || z != 0) d[n++] = normalized(Vec3{double(x), double(y), double(z)});
  return d;
}

struct Chart {
  std::vector<Index> triangles;
  int direction = kOwnPlane;
};

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
    make_initial_charts();
    for (std::size_t c = 0; c < charts_.size(); ++c) lay_out(c);
    if (options_.improve_with_lscm && nt_ <= options_.lscm_max_surface_triangles)
      atlas.num_lscm_charts = improve_with_lscm();
    separate_flipped();
    split_dominant_charts();
    // Overlaps are searched once, on a first packing (charts apart, plain 2D
    // boxes); splitting only separates triangles, so it never makes new ones.
    pack();
    std::vector<std::array<Index, 2>> overlaps = uv_overlapping_pairs(uvs_);
    atlas.num_splits = split_overlapping_charts(overlaps);
    // The final exact check on the final UVs. Without splits the first
    // packing is final and its overlaps (if any, across charts) are known.
    for (int round = 0;; ++round) {
      if (round > 0 || atlas.num_splits > 0) {
        pack();
        overlaps = uv_overlapping_pairs(uvs_);
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
    }
    // Drop emptied charts, number the rest in order.
    atlas.triangle_chart.assign(static_cast<std::size_t>(nt_), kNoIndex);
    for (const Chart& c : charts_) {
      if (c.triangles.empty()) continue;
      for (Index t : c.triangles) atlas.triangle_chart[t] = atlas.num_charts;
      ++atlas.num_charts;
    }
    double area = 0.0;
    for (Index t = 0; t < nt_; ++t) {
      const Uv &a = uvs_[3 * t], &b = uvs_[3 * t + 1], &c = uvs_[3 * t + 2];
      area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    atlas.packing_efficiency = area;
    atlas.uvs = std::move(uvs_);
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

  // Label = best of the 26 directions; charts = components of equal labels
  // across edges shared by exactly two triangles. Zero-area triangles are singletons.
  void make_initial_charts() {
    const auto dirs = projection_directions();
    std::vector<int> label(static_cast<std::size_t>(nt_), kOwnPlane);
    for (Index t = 0; t < nt_; ++t) {
      const Vec3 n = cross(point(t, 1) - point(t, 0), point(t, 2) - point(t, 0));
      if (!(squared_norm(n) > 0.0)) continue;
      double best = -INFINITY;
      for (int d = 0; d < kNumDirections; ++d) {
        const double score = dot(n, dirs[d]);
        if (score > best) best = score, label[t] = d;
      }
    }
    std::vector<std::pair<std::uint64_t, Index>> edges(3 * static_cast<std::size_t>(nt_));
    for (Index t = 0; t < nt_; ++t)
      for (int k = 0; k < 3; ++k) {
        const auto a = static_cast<std::uint64_t>(static_cast<std::uint32_t>(s_.triangles[t][k]));
        const auto b = static_cast<std::uint64_t>(static_cast<std::uint32_t>(s_.triangles[t][(k + 1) % 3]));
        edges[3 * static_cast<std::size_t>(t) + k] = {std::min(a, b) << 32 | std::max(a, b), t};
      }
    std::sort(edges.begin(), edges.end());
    std::vector<Index> parent(static_cast<std::size_t>(nt_));
    std::iota(parent.begin(), parent.end(), 0);
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j].first == edges[i].first) ++j;
      if (j - i == 2) {
        const Index a = edges[i].second, b = edges[i + 1].second;
        if (a != b && label[a] == label[b] && label[a] != kOwnPlane) {
          const Index ra = find_root(parent, a), rb = find_root(parent, b);
          if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
        }
      }
      i = j;
    }
    std::vector<Index> chart_of_root(static_cast<std::size_t>(nt_), kNoIndex);
    for (Index t = 0; t < nt_; ++t) {
      const Index r = find_root(parent, t);
      if (chart_of_root[r] == kNoIndex) {
        chart_of_root[r] = static_cast<Index>(charts_.size());
        charts_.push_back({{}, label[t]});
      }
      charts_[chart_of_root[r]].triangles.push_back(t);
    }
  }

  // Local UVs of chart c: orthogonal projection on the plane of its direction
  // (u × v = direction, so front-facing triangles stay counter-clockwise), or
  // for a singleton its own plane, or a canonical right triangle.
  void lay_out(std::size_t c) {
    Chart& chart = charts_[c];
    if (chart.direction == kOwnPlane) {
      for (Index t : chart.triangles) lay_out_alone(t, false);
      return;
    }
    static const auto dirs = projection_directions();
    const Vec3 d = dirs[chart.direction];
    const Vec3 axis = std::abs(d.x) <= std::abs(d.y) && std::abs(d.x) <= std::abs(d.z) ? Vec3{1, 0, 0}
                      : std::abs(d.y) <= std::abs(d.z)                                 ? Vec3{0, 1, 0}
                                                                                       : Vec3{0, 0, 1};
    const Vec3 u = normalized(cross(axis, d));
    const Vec3 v = cross(d, u);
    const Vec3 origin = point(chart.triangles.front(), 0);
    // In-plane rotation to the principal axes of the chart's corners: tighter
    // bounding boxes, better packing (a rotation keeps orientations; the
    // exact flip check that follows catches rounding).
    Vec3 mean{};
    for (Index t : chart.triangles)
      for (int k = 0; k < 3; ++k) mean = mean + (point(t, k) - origin);
    mean = mean / (3.0 * static_cast<double>(chart.triangles.size()));
    double sxx = 0, syy = 0, sxy = 0;
    for (Index t : chart.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vec3 p = point(t, k) - origin - mean;
        const double x = dot(p, u), y = dot(p, v);
        sxx += x * x, syy += y * y, sxy += x * y;
      }
    const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
    const Vec3 pu = std::cos(angle) * u + std::sin(angle) * v;
    // Keep the principal axes only when their bounding box is smaller (not for a square, say).
    auto box_size = [&](const Vec3& a) {
      const Vec3 b = cross(d, a);
      double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
      for (Index t : chart.triangles)
        for (int k = 0; k < 3; ++k) {
          const Vec3 p = point(t, k) - origin;
          const double x = dot(p, a), y = dot(p, b);
          lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x), lo[1] = std::min(lo[1], y),
          hi[1] = std::max(hi[1], y);
        }
      return std::array<double, 2>{hi[0] - lo[0], hi[1] - lo[1]};
    };
    const auto principal = box_size(pu), plain = box_size(u);
    const bool use_principal = principal[0] * principal[1] < plain[0] * plain[1];
    Vec3 ru = use_principal ? pu : u;
    const auto size = use_principal ? principal : plain;
    // Stand every chart upright (height >= width) for the shelf packer.
    if (size[0] > size[1]) ru = cross(d, ru);
    const Vec3 rv = cross(d, ru);
    for (Index t : chart.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vec3 p = point(t, k) - origin;
        local_[3 * static_cast<std::size_t>(t) + k] = {dot(p, ru), dot(p, rv)};
      }
  }

  // Rotates a 2D layout to the principal axes of its corners when that
  // shrinks its bounding box, then stands it upright (height >= width). A
  // rotation keeps orientations up to rounding; the exact checks that follow
  // catch the rest.
  static void turn_for_packing(std::vector<Uv>& uv) {
    double mean[2] = {0, 0};
    for (const Uv& p : uv) mean[0] += p[0], mean[1] += p[1];
    mean[0] /= static_cast<double>(uv.size()), mean[1] /= static_cast<double>(uv.size());
    double sxx = 0, syy = 0, sxy = 0;
    for (const Uv& p : uv) {
      const double x = p[0] - mean[0], y = p[1] - mean[1];
      sxx += x * x, syy += y * y, sxy += x * y;
    }
    const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
    const double c = std::cos(angle), sn = std::sin(angle);
    auto size = [&](double cs, double sc) {
      double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
      for (const Uv& p : uv) {
        const double x = cs * p[0] + sc * p[1], y = -sc * p[0] + cs * p[1];
        lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x), lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
      }
      return std::array<double, 2>{hi[0] - lo[0], hi[1] - lo[1]};
    };
    const auto turned = size(c, sn), plain = size(1.0, 0.0);
    if (turned[0] * turned[1] < plain[0] * plain[1])
      for (Uv& p : uv) p = {c * p[0] + sn * p[1], -sn * p[0] + c * p[1]};
    const auto now = turned[0] * turned[1] < plain[0] * plain[1] ? turned : plain;
    if (now[0] > now[1])
      for (Uv& p : uv) p = {p[1], -p[0]};  // exact quarter turn
  }

  Index improve_with_lscm() {
    Index improved = 0;
    for (const Chart& c : charts_) {
      if (c.direction == kOwnPlane || c.triangles.size() < static_cast<std::size_t>(options_.lscm_min_triangles))
        continue;
      std::vector<Uv> uv;
      if (!lscm_chart_layout(s_, c.triangles, uv)) continue;
      const auto flipped = uv_flipped_triangles(uv);
      if (std::find(flipped.begin(), flipped.end(), 1) != flipped.end() || !uv_overlapping_pairs(uv).empty()) continue;
      turn_for_packing(uv);
      for (std::size_t i = 0; i < c.triangles.size(); ++i)
        for (int k = 0; k < 3; ++k) local_[3 * static_cast<std::size_t>(c.triangles[i]) + k] = uv[3 * i + k];
      ++improved;
    }
    return improved;
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
      charts_.push_back({{t}, kOwnPlane});
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
    return splits;
  }

  // A chart longer than half the side of the ideal square atlas would leave
  // most of the square empty: split it at its median until none is.
  void split_dominant_charts() {
    auto box = [&](const Chart& c) {
      double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
      for (Index t : c.triangles)
        for (int k = 0; k < 3; ++k)
          for (int a = 0; a < 2; ++a) {
            const double x = local_[3 * static_cast<std::size_t>(t) + k][a];
            lo[a] = std::min(lo[a], x), hi[a] = std::max(hi[a], x);
          }
      return std::array<double, 2>{hi[0] - lo[0], hi[1] - lo[1]};
    };
    double total = 0.0;
    for (const Chart& c : charts_) {
      const auto size = box(c);
      total += size[0] * size[1];
    }
    const double limit = 0.5 * std::sqrt(total);
    for (std::size_t c = 0; c < charts_.size(); ++c) {
      while (charts_[c].triangles.size() > 1) {
        const auto size = box(charts_[c]);
        if (std::max(size[0], size[1]) <= limit) break;
        split(c);
      }
    }
  }

  void split(std::size_t c) {
    std::vector<Index> tris = std::move(charts_[c].triangles);
    auto centroid = [&](Index t, int axis) {
      const std::size_t i = 3 * static_cast<std::size_t>(t);
      return local_[i][axis] + local_[i + 1][axis] + local_[i + 2][axis];
    };
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (Index t : tris)
      for (int a = 0; a < 2; ++a) lo[a] = std::min(lo[a], centroid(t, a)), hi[a] = std::max(hi[a], centroid(t, a));
    const int axis = hi[0] - lo[0] >= hi[1] - lo[1] ? 0 : 1;
    const auto half = tris.begin() + static_cast<std::ptrdiff_t>(tris.size() / 2);
    std::nth_element(tris.begin(), half, tris.end(), [&](Index a, Index b) {
      const double ca = centroid(a, axis), cb = centroid(b, axis);
      return ca != cb ? ca < cb : a < b;
    });
    Chart second{std::vector<Index>(half, tris.end()), charts_[c].direction};
    tris.erase(half, tris.end());
    std::sort(tris.begin(), tris.end());
    std::sort(second.triangles.begin(), second.triangles.end());
    charts_[c].triangles = std::move(tris);
    charts_.push_back(std::move(second));
  }

  // Shelf packing of the charts' bounding boxes (tallest first), then one
  // uniform scale into [0,1]². Local UVs are read from local_, written to uvs_.
  void pack() {
    const std::size_t nc = charts_.size();
    std::vector<std::array<double, 4>> box(nc, {INFINITY, INFINITY, -INFINITY, -INFINITY});
    double total = 0.0, widest = 0.0;
    for (std::size_t c = 0; c < nc; ++c) {
      for (Index t : charts_[c].triangles)
        for (int k = 0; k < 3; ++k) {
          const Uv& p = local_[3 * static_cast<std::size_t>(t) + k];
          box[c] = {std::min(box[c][0], p[0]), std::min(box[c][1], p[1]), std::max(box[c][2], p[0]),
                    std::max(box[c][3], p[1])};
        }
      if (charts_[c].triangles.empty()) continue;
      total += (box[c][2] - box[c][0]) * (box[c][3] - box[c][1]);
      widest = std::max(widest, box[c][2] - box[c][0]);
    }
    const double pad = options_.padding * std::sqrt(std::max(total, 1e-300));
    std::vector<Index> order;
    for (std::size_t c = 0; c < nc; ++c)
      if (!charts_[c].triangles.empty()) order.push_back(static_cast<Index>(c));
    std::sort(order.begin(), order.end(), [&](Index a, Index b) {
      const double ha = box[a][3] - box[a][1], hb = box[b][3] - box[b][1];
      return ha != hb ? ha > hb : a < b;
    });
    double packed_area = 0.0;
    for (Index c : order) packed_area += (box[c][2] - box[c][0] + pad) * (box[c][3] - box[c][1] + pad);
    const double row_width = std::max(widest + pad, std::sqrt(packed_area));
    std::vector<std::array<double, 2>> offset(nc);
    double x = 0.0, y = 0.0, shelf = 0.0, used_width = 0.0;
    for (Index c : order) {
      const double w = box[c][2] - box[c][0] + pad, h = box[c][3] - box[c][1] + pad;
      if (x > 0.0 && x + w > row_width) y += shelf, x = 0.0, shelf = 0.0;
      offset[c] = {x + 0.5 * pad, y + 0.5 * pad};
      x += w;
      shelf = std::max(shelf, h);
      used_width = std::max(used_width, x);
    }
    const double side = std::max(used_width, y + shelf);
    for (Index c : order)
      for (Index t : charts_[c].triangles)
        for (int k = 0; k < 3; ++k) {
          const std::size_t i = 3 * static_cast<std::size_t>(t) + k;
          uvs_[i] = {std::clamp((local_[i][0] - box[c][0] + offset[c][0]) / side, 0.0, 1.0),
                     std::clamp((local_[i][1] - box[c][1] + offset[c][1]) / side, 0.0, 1.0)};
        }
  }

  const TriSurface& s_;
  const UvOptions& options_;
  Index nt_ = 0;
  double fallback_length_ = 1.0;
  std::vector<Chart> charts_;
  std::vector<Uv> local_;  // each chart's own layout (model units)
  std::vector<Uv> uvs_;    // packed into [0,1]² by pack()
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
