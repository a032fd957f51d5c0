#include "support/surface_fixtures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace hq::test {

TriSurface triangulated_box(Vec3 lo, Vec3 hi, int n) {
  TriSurface s;
  std::map<std::array<int, 3>, Index> ids;
  auto point = [&](std::array<int, 3> g) {
    auto [it, inserted] = ids.emplace(g, static_cast<Index>(s.points.size()));
    if (inserted)
      s.points.push_back(
          {lo.x + (hi.x - lo.x) * g[0] / n, lo.y + (hi.y - lo.y) * g[1] / n, lo.z + (hi.z - lo.z) * g[2] / n});
    return it->second;
  };
  // For each axis and side: the face's two in-plane axes in counter-clockwise order seen from outside.
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      int a = (axis + 1) % 3, b = (axis + 2) % 3;
      if (side == 0) std::swap(a, b);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto g = [&](int di, int dj) {
            std::array<int, 3> c{};
            c[axis] = side * n;
            c[a] = i + di;
            c[b] = j + dj;
            return point(c);
          };
          const Index p00 = g(0, 0), p10 = g(1, 0), p11 = g(1, 1), p01 = g(0, 1);
          s.triangles.push_back({p00, p10, p11});
          s.triangles.push_back({p00, p11, p01});
        }
    }
  return s;
}

TriSurface icosphere(int level, double radius, Vec3 centre) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> p = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<Index, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (Vec3& q : p) q = normalized(q);
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<Index, Index>, Index> mid;
    auto midpoint = [&](Index a, Index b) {
      auto key = std::minmax(a, b);
      auto [it, inserted] = mid.emplace(key, static_cast<Index>(p.size()));
      if (inserted) p.push_back(normalized(p[a] + p[b]));
      return it->second;
    };
    std::vector<std::array<Index, 3>> next;
    for (const auto& tri : f) {
      const Index a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    f = std::move(next);
  }
  TriSurface s;
  for (const Vec3& q : p) s.points.push_back(centre + radius * q);
  s.triangles = std::move(f);
  return s;
}

TriSurface remove_triangles(const TriSurface& s, const std::function<bool(const Vec3&)>& remove) {
  TriSurface out;
  out.points = s.points;
  for (const auto& t : s.triangles)
    if (!remove((s.points[t[0]] + s.points[t[1]] + s.points[t[2]]) / 3.0)) out.triangles.push_back(t);
  return out;
}

TriSurface append(const TriSurface& a, const TriSurface& b) {
  TriSurface out = a;
  const Index shift = static_cast<Index>(a.points.size());
  out.points.insert(out.points.end(), b.points.begin(), b.points.end());
  for (const auto& t : b.triangles) out.triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
  return out;
}

HexMesh hex_ball(int n, const std::function<double(const Vec3&)>& radius) {
  HexMesh mesh;
  const int m = n + 1;
  auto id = [m](int i, int j, int k) { return static_cast<Index>(i + m * (j + m * k)); };
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const Vec3 c{-1.0 + 2.0 * i / n, -1.0 + 2.0 * j / n, -1.0 + 2.0 * k / n};
        const double inf_norm = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)});
        if (inf_norm == 0.0) {
          mesh.points.push_back({});
          continue;
        }
        const Vec3 u = normalized(c);
        mesh.points.push_back(inf_norm * radius(u) * u);
      }
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        mesh.hexes.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                              id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
  return mesh;
}

TriSurface genus3_slab() {
  // Voxels (i, 0..2, 0) for i in 0..6, without (1,1), (3,1), (5,1).
  auto filled = [](int i, int j, int k) {
    if (i < 0 || i > 6 || j < 0 || j > 2 || k != 0) return false;
    return !(j == 1 && (i == 1 || i == 3 || i == 5));
  };
  TriSurface s;
  std::map<std::array<int, 3>, Index> ids;
  auto point = [&](std::array<int, 3> g) {
    auto [it, inserted] = ids.emplace(g, static_cast<Index>(s.points.size()));
    if (inserted) s.points.push_back({double(g[0]), double(g[1]), double(g[2])});
    return it->second;
  };
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 3; ++j) {
      if (!filled(i, j, 0)) continue;
      for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
          std::array<int, 3> nb{i, j, 0};
          nb[axis] += side ? 1 : -1;
          if (filled(nb[0], nb[1], nb[2])) continue;
          int a = (axis + 1) % 3, b = (axis + 2) % 3;
          if (side == 0) std::swap(a, b);
          auto g = [&](int da, int db) {
            std::array<int, 3> c{i, j, 0};
            c[axis] += side;
            c[a] += da;
            c[b] += db;
            return point(c);
          };
          const Index p00 = g(0, 0), p10 = g(1, 0), p11 = g(1, 1), p01 = g(0, 1);
          s.triangles.push_back({p00, p10, p11});
          s.triangles.push_back({p00, p11, p01});
        }
    }
  return s;
}

Mesh quad_cube_sphere(int n, double radius) {
  Mesh mesh;
  std::map<std::array<int, 3>, Index> ids;
  for (int axis = 0; axis < 3; ++axis)
    for (const int sign : {-1, 1}) {
      // (u, v, normal) right-handed with the normal outward.
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto id = [&](int i, int j) {
        std::array<int, 3> k{};
        k[static_cast<std::size_t>(axis)] = sign * n;
        k[static_cast<std::size_t>(u)] = (2 * i - n) * sign;
        k[static_cast<std::size_t>(v)] = 2 * j - n;
        const auto [it, is_new] = ids.emplace(k, static_cast<Index>(mesh.points.size()));
        if (is_new) {
          const Vec3 p{k[0] / double(n), k[1] / double(n), k[2] / double(n)};
          mesh.points.push_back(p * (radius / norm(p)));
        }
        return it->second;
      };
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) mesh.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return mesh;
}

}  // namespace hq::test
