#include "hqview/boundary/surface_sign.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace hq {
namespace {

// A closest point this close (in barycentric terms) to an edge or a vertex is
// on that feature: CGAL's closest point is rounded, never exactly on it.
constexpr double kFeatureTolerance = 1e-9;
// |cos| between the offset and the pseudo-normal below which the sign is uncertain.
constexpr double kTangentCosine = 1e-9;
constexpr Index kLeafSize = 8;

double corner_angle(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 u = a - p, v = b - p;
  return std::atan2(norm(cross(u, v)), dot(u, v));
}

}  // namespace

PseudoNormals compute_pseudo_normals(const TriSurface& s) {
  PseudoNormals pn;
  const std::size_t nt = s.triangles.size();
  pn.face.resize(nt);
  pn.edge.assign(3 * nt, Vec3{});
  pn.vertex.assign(s.points.size(), Vec3{});
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = s.triangles[t];
    const Vec3 &a = s.points[tri[0]], &b = s.points[tri[1]], &c = s.points[tri[2]];
    pn.face[t] = normalized(cross(b - a, c - a));
    pn.vertex[tri[0]] = pn.vertex[tri[0]] + corner_angle(a, b, c) * pn.face[t];
    pn.vertex[tri[1]] = pn.vertex[tri[1]] + corner_angle(b, c, a) * pn.face[t];
    pn.vertex[tri[2]] = pn.vertex[tri[2]] + corner_angle(c, a, b) * pn.face[t];
  }
  // Edges: sort the 3·nt directed edges by their undirected key; each
  // manifold edge has two entries, whose face normals are summed.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint64_t>(s.triangles[t][k]);
      const auto b = static_cast<std::uint64_t>(s.triangles[t][(k + 1) % 3]);
      keys[3 * t + k] = {std::min(a, b) << 32 | std::max(a, b), static_cast<std::uint32_t>(3 * t + k)};
    }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    Vec3 sum{};
    while (j < keys.size() && keys[j].first == keys[i].first) sum = sum + pn.face[keys[j++].second / 3];
    for (std::size_t k = i; k < j; ++k) pn.edge[keys[k].second] = sum;
    i = j;
  }
  return pn;
}

int pseudo_normal_sign(const TriSurface& s, const PseudoNormals& pn, const Vec3& query, const ClosestPoint& closest,
                       bool& uncertain) {
  uncertain = false;
  const Vec3 offset = query - closest.point;
  if (closest.triangle == kNoIndex || squared_norm(offset) == 0.0) return 0;
  const auto& tri = s.triangles[closest.triangle];
  const Vec3 &a = s.points[tri[0]], &b = s.points[tri[1]], &c = s.points[tri[2]];
  // Barycentric coordinates of the closest point.
  const Vec3 n = cross(b - a, c - a);
  const double nn = squared_norm(n);
  const Vec3 p = closest.point;
  const double w0 = dot(cross(c - b, p - b), n) / nn;
  const double w1 = dot(cross(a - c, p - c), n) / nn;
  const double w2 = 1.0 - w0 - w1;
  const double w[3] = {w0, w1, w2};
  Vec3 normal = pn.face[closest.triangle];
  int small = 0, last_small = -1, big = -1;
  for (int k = 0; k < 3; ++k) {
    if (w[k] <= kFeatureTolerance) ++small, last_small = k;
    if (w[k] >= 1.0 - kFeatureTolerance) big = k;
  }
  if (big >= 0) {
    normal = pn.vertex[tri[big]];
  } else if (small == 1) {
    // On the edge opposite corner k: the edge (t[k+1], t[k+2]) is corner slot k+1.
    normal = pn.edge[3 * static_cast<std::size_t>(closest.triangle) + static_cast<std::size_t>((last_small + 1) % 3)];
  }
  const double d = dot(offset, normal);
  const double scale = norm(offset) * norm(normal);
  if (!(scale > 0.0) || std::abs(d) <= kTangentCosine * scale) uncertain = true;
  return d > 0.0 ? 1 : (d < 0.0 ? -1 : 0);
}

WindingTree build_winding_tree(const TriSurface& s) {
  WindingTree tree;
  const Index nt = static_cast<Index>(s.triangles.size());
  tree.order.resize(static_cast<std::size_t>(nt));
  for (Index t = 0; t < nt; ++t) tree.order[t] = t;
  std::vector<Vec3> centroid(static_cast<std::size_t>(nt));
  for (Index t = 0; t < nt; ++t) {
    const auto& tri = s.triangles[t];
    centroid[t] = (s.points[tri[0]] + s.points[tri[1]] + s.points[tri[2]]) / 3.0;
  }
  if (nt == 0) return tree;
  tree.nodes.reserve(2 * static_cast<std::size_t>(nt / kLeafSize + 1));
  // Iterative build: (node, first, count), median split on the longest axis of the centroids.
  struct Task {
    Index node, first, count;
  };
  std::vector<Task> stack;
  tree.nodes.push_back({});
  stack.push_back({0, 0, nt});
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    auto begin = tree.order.begin() + task.first, end = begin + task.count;
    Vec3 area_vector{}, weighted{}, lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    double area = 0.0;
    for (auto it = begin; it != end; ++it) {
      const auto& tri = s.triangles[*it];
      const Vec3 n = 0.5 * cross(s.points[tri[1]] - s.points[tri[0]], s.points[tri[2]] - s.points[tri[0]]);
      const double a = norm(n);
      area_vector = area_vector + n;
      weighted = weighted + a * centroid[*it];
      area += a;
      const Vec3& c = centroid[*it];
      lo = {std::min(lo.x, c.x), std::min(lo.y, c.y), std::min(lo.z, c.z)};
      hi = {std::max(hi.x, c.x), std::max(hi.y, c.y), std::max(hi.z, c.z)};
    }
    WindingTree::Node node;
    node.centre = area > 0.0 ? weighted / area : (lo + hi) / 2.0;
    node.area_vector = area_vector;
    for (auto it = begin; it != end; ++it) {
      const auto& tri = s.triangles[*it];
      for (Index v : tri) node.radius = std::max(node.radius, norm(s.points[v] - node.centre));
      const Vec3 n = 0.5 * cross(s.points[tri[1]] - s.points[tri[0]], s.points[tri[2]] - s.points[tri[0]]);
      const Vec3 delta = centroid[*it] - node.centre;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) node.moment[3 * i + j] += n[i] * delta[j];
    }
    node.first = task.first;
    node.count = task.count;
    if (task.count > kLeafSize) {
      const Vec3 extent = hi - lo;
      const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      const Index half = task.count / 2;
      std::nth_element(begin, begin + half, end, [&](Index a, Index b) {
        const double ca = centroid[a][axis], cb = centroid[b][axis];
        return ca != cb ? ca < cb : a < b;
      });
      node.left = static_cast<Index>(tree.nodes.size());
      node.right = node.left + 1;
      tree.nodes.push_back({});
      tree.nodes.push_back({});
      stack.push_back({node.left, task.first, half});
      stack.push_back({node.right, task.first + half, task.count - half});
    }
    tree.nodes[task.node] = node;
  }
  return tree;
}

double winding_number(const TriSurface& s, const WindingTree& tree, const Vec3& q, double beta) {
  if (tree.nodes.empty()) return 0.0;
  double solid_angle = 0.0;
  Index stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const WindingTree::Node& node = tree.nodes[stack[--top]];
    const Vec3 r = node.centre - q;
    const double dist = norm(r);
    if (dist > beta * node.radius && dist > 0.0) {
      // g(r) = r / |r|^3 and its Jacobian J = I / |r|^3 - 3 r r^T / |r|^5, contracted with the moment.
      const double inv3 = 1.0 / (dist * dist * dist), inv5 = inv3 / (dist * dist);
      const auto& m = node.moment;
      double r_m_r = 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r_m_r += r[i] * m[3 * i + j] * r[j];
      solid_angle += dot(r, node.area_vector) * inv3 + (m[0] + m[4] + m[8]) * inv3 - 3.0 * r_m_r * inv5;
      continue;
    }
    if (node.left == kNoIndex || top + 2 > 128) {
      for (Index i = node.first; i < node.first + node.count; ++i) {
        const auto& tri = s.triangles[tree.order[i]];
        const Vec3 a = s.points[tri[0]] - q, b = s.points[tri[1]] - q, c = s.points[tri[2]] - q;
        const double la = norm(a), lb = norm(b), lc = norm(c);
        const double numerator = det(a, b, c);
        const double denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
        solid_angle += 2.0 * std::atan2(numerator, denominator);
      }
      continue;
    }
    stack[top++] = node.left;
    stack[top++] = node.right;
  }
  return solid_angle / (4.0 * std::numbers::pi);
}

double winding_number_for_sign(const TriSurface& surface, const WindingTree& tree, const Vec3& query) {
  const double w = winding_number(surface, tree, query, 2.0);
  return std::abs(w - 0.5) < 0.25 ? winding_number(surface, tree, query, 4.0) : w;
}

}  // namespace hq
