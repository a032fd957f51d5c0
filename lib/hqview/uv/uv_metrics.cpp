#include "hqview/uv/uv_metrics.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "hqview/uv/uv_atlas.h"

namespace hq {
namespace {

// The value below which `weight` of the total weight lies (values sorted by the caller).
double weighted_quantile(const std::vector<std::pair<double, double>>& sorted, double total, double q) {
  double acc = 0.0;
  for (const auto& [value, weight] : sorted) {
    acc += weight;
    if (acc >= q * total) return value;
  }
  return sorted.empty() ? 0.0 : sorted.back().first;
}

UvDistortionStats stats_of(std::vector<std::pair<double, double>> v) {
  UvDistortionStats s;
  std::sort(v.begin(), v.end());
  double total = 0.0;
  for (const auto& p : v) total += p.second;
  if (v.empty() || !(total > 0.0)) return s;
  s.p5 = weighted_quantile(v, total, 0.05);
  s.p50 = weighted_quantile(v, total, 0.50);
  s.p95 = weighted_quantile(v, total, 0.95);
  s.min = v.front().first;
  s.max = v.back().first;
  return s;
}

}  // namespace

TriangleDistortion triangle_distortion(const Vec3& a, const Vec3& b, const Vec3& c, const Uv* uv) {
  TriangleDistortion d;
  // The triangle in its own plane: a at the origin, b on the x axis.
  const Vec3 e1 = b - a, e2 = c - a;
  const double l1 = norm(e1);
  const double area3 = 0.5 * norm(cross(e1, e2));
  const double area2 = uv_signed_area(uv);
  if (!(area3 > 0.0) || !(l1 > 0.0)) {
    d.conformal = INFINITY;
    return d;
  }
  d.area_ratio = area2 / area3;
  const double x2 = dot(e2, e1) / l1, y2 = 2.0 * area3 / l1;
  // J maps (l1, 0) -> q1 and (x2, y2) -> q2.
  const double q1x = uv[1][0] - uv[0][0], q1y = uv[1][1] - uv[0][1];
  const double q2x = uv[2][0] - uv[0][0], q2y = uv[2][1] - uv[0][1];
  const double j00 = q1x / l1, j10 = q1y / l1;
  const double j01 = (q2x - j00 * x2) / y2, j11 = (q2y - j10 * x2) / y2;
  // Singular values of the 2x2 Jacobian.
  const double e = 0.5 * (j00 + j11), f = 0.5 * (j00 - j11), g = 0.5 * (j10 + j01), h = 0.5 * (j10 - j01);
  const double qv = std::hypot(e, h), rv = std::hypot(f, g);
  const double smax = qv + rv, smin = std::abs(qv - rv);
  d.conformal = smin > 0.0 ? smax / smin : INFINITY;
  return d;
}

void measure_uv_atlas(const TriSurface& surface, UvAtlas& atlas) {
  const std::size_t nt = surface.triangles.size();
  double area3 = 0.0, area2 = 0.0;
  std::vector<double> a3(nt), a2(nt), chart_area(static_cast<std::size_t>(atlas.num_charts), 0.0);
  std::vector<TriangleDistortion> d(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = surface.triangles[t];
    const Vec3 &a = surface.points[tri[0]], &b = surface.points[tri[1]], &c = surface.points[tri[2]];
    a3[t] = 0.5 * norm(cross(b - a, c - a));
    if (!std::isfinite(a3[t])) a3[t] = 0.0;
    d[t] = triangle_distortion(a, b, c, &atlas.uvs[3 * t]);
    a2[t] = uv_signed_area(&atlas.uvs[3 * t]);
    area3 += a3[t];
    area2 += a2[t];
    if (atlas.triangle_chart[t] >= 0) chart_area[static_cast<std::size_t>(atlas.triangle_chart[t])] += a3[t];
  }
  atlas.packing_efficiency = area2;
  std::sort(chart_area.begin(), chart_area.end(), std::greater<>());
  if (area3 > 0.0) {
    double top4 = 0.0, top8 = 0.0;
    for (std::size_t i = 0; i < chart_area.size(); ++i) {
      if (i < 4) top4 += chart_area[i];
      if (i < 8) top8 += chart_area[i];
    }
    atlas.area_fraction_largest_chart = chart_area.empty() ? 0.0 : chart_area.front() / area3;
    atlas.area_fraction_top_4_charts = top4 / area3;
    atlas.area_fraction_top_8_charts = top8 / area3;
  }
  // Area ratio normalised by the atlas's one scale (UV area / 3D area overall).
  const double k = area3 > 0.0 ? area2 / area3 : 0.0;
  std::vector<std::pair<double, double>> ratio, conformal;
  double within = 0.0;
  for (std::size_t t = 0; t < nt; ++t) {
    if (!(a3[t] > 0.0)) continue;
    const double r = k > 0.0 ? d[t].area_ratio / k : 0.0;
    ratio.emplace_back(r, a3[t]);
    conformal.emplace_back(d[t].conformal, a3[t]);
    if (r >= 0.5 && r <= 2.0) within += a3[t];
  }
  atlas.area_ratio = stats_of(std::move(ratio));
  atlas.conformal_distortion = stats_of(std::move(conformal));
  atlas.area_fraction_area_ratio_within_2 = area3 > 0.0 ? within / area3 : 0.0;
}

}  // namespace hq
