#include "hqview/render/scene_shapes.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hq {
namespace {

Vec3 to_vec3(const Vec3f& v) { return {v.x, v.y, v.z}; }

// Two unit vectors completing the unit vector w to an orthonormal basis.
void basis(const Vec3& w, Vec3& u, Vec3& v) {
  const Vec3 helper = std::abs(w.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  u = normalized(cross(w, helper));
  v = cross(w, u);
}

}  // namespace

void append_arrow(TriangleSet& set, const Vec3f& tail_f, const Vec3f& tip_f, const ArrowShape& shape, Rgba8 color) {
  const Vec3 tail = to_vec3(tail_f), tip = to_vec3(tip_f);
  const double length = norm(tip - tail);
  if (!(length > 0.0)) return;
  const Vec3 w = (1.0 / length) * (tip - tail);
  Vec3 u, v;
  basis(w, u, v);
  const int n = std::max(3, shape.segments);
  const double head = std::min<double>(shape.head_length, length);
  const Vec3 neck = tip - head * w;
  // Keep normals consistent when set had no normals so far.
  if (set.normals.size() != set.positions.size()) set.normals.resize(set.positions.size(), Vec3f{0.0f, 0.0f, 1.0f});
  auto add = [&](const Vec3& p, const Vec3& normal) {
    set.positions.push_back(to_vec3f(p));
    set.normals.push_back(to_vec3f(normal));
    set.colors.push_back(color);
    return static_cast<std::uint32_t>(set.positions.size() - 1);
  };
  auto ring = [&](int i) {
    const double a = 2.0 * M_PI * i / n;
    return std::cos(a) * u + std::sin(a) * v;
  };
  // Shaft: a cylinder from tail to neck, closed at the tail.
  const std::uint32_t tail_centre = add(tail, -1.0 * w);
  std::vector<std::uint32_t> side(2 * n), cap(n), cone(2 * n), base(n);
  for (int i = 0; i < n; ++i) {
    const Vec3 r = ring(i);
    side[2 * i] = add(tail + shape.shaft_radius * r, r);
    side[2 * i + 1] = add(neck + shape.shaft_radius * r, r);
    cap[i] = add(tail + shape.shaft_radius * r, -1.0 * w);
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    set.indices.insert(set.indices.end(), {side[2 * i], side[2 * j], side[2 * j + 1], side[2 * i], side[2 * j + 1],
                                           side[2 * i + 1], tail_centre, cap[j], cap[i]});
  }
  // Head: a cone from the neck to the tip, closed by its base disc.
  const std::uint32_t base_centre = add(neck, -1.0 * w);
  const double slope = shape.head_radius / std::max(head, 1e-30);
  for (int i = 0; i < n; ++i) {
    const Vec3 r = ring(i);
    const Vec3 normal = normalized(r + slope * w);
    cone[2 * i] = add(neck + shape.head_radius * r, normal);
    cone[2 * i + 1] = add(tip, normal);
    base[i] = add(neck + shape.head_radius * r, -1.0 * w);
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    set.indices.insert(set.indices.end(), {cone[2 * i], cone[2 * j], cone[2 * i + 1], base_centre, base[j], base[i]});
  }
}

std::vector<Vec3> arrow_directions(const Camera& camera, int n, double start_degrees) {
  std::vector<Vec3> directions;
  if (n <= 0) return directions;
  const Vec3 forward = normalized(camera.target - camera.eye);
  Vec3 right = cross(forward, camera.up);
  if (!(norm(right) > 0.0)) {
    Vec3 v;
    basis(forward, right, v);
  }
  right = normalized(right);
  const Vec3 up = cross(right, forward);
  for (int k = 0; k < n; ++k) {
    const double a = (start_degrees + 360.0 * k / n) * M_PI / 180.0;
    // The arrow sits at angle a around its target and points inwards.
    directions.push_back(-1.0 * (std::cos(a) * right + std::sin(a) * up));
  }
  return directions;
}

std::vector<std::uint32_t> back_to_front_order(const TriangleSet& set, const Mat4& model_view) {
  const std::size_t n = set.indices.size() / 3;
  std::vector<float> depth(n);
  for (std::size_t t = 0; t < n; ++t) {
    Vec3 c{0.0, 0.0, 0.0};
    for (std::size_t k = 0; k < 3; ++k) c = c + to_vec3(set.positions[set.indices[3 * t + k]]);
    c = (1.0 / 3.0) * c;
    // Eye space looks down -z: larger z is nearer.
    depth[t] = static_cast<float>(model_view(2, 0) * c.x + model_view(2, 1) * c.y + model_view(2, 2) * c.z +
                                  model_view(2, 3));
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return depth[a] < depth[b]; });
  return order;
}

std::vector<std::uint32_t> sorted_indices(const TriangleSet& set, const std::vector<std::uint32_t>& order) {
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * order.size());
  for (std::uint32_t t : order)
    for (std::size_t k = 0; k < 3; ++k) indices.push_back(set.indices[3 * static_cast<std::size_t>(t) + k]);
  return indices;
}

}  // namespace hq
