#pragma once
// Shapes that views add to a Scene, and the depth sort of translucent
// triangles. Pure functions: tested without OpenGL.

#include <cstdint>
#include <vector>

#include "hqview/render/camera.h"
#include "hqview/render/scene.h"

namespace hq {

struct ArrowShape {
  float shaft_radius = 0.0f;  // model units
  float head_radius = 0.0f;   // cone base radius
  float head_length = 0.0f;   // cone height (clamped to the arrow's length)
  int segments = 16;          // around the axis, >= 3
};

// Appends an arrow from tail to tip (the cone's apex at tip) as triangles with
// smooth normals: a shaft cylinder, its end disc, the cone and its base disc.
// Nothing is added when tail == tip.
void append_arrow(TriangleSet& set, const Vec3f& tail, const Vec3f& tip, const ArrowShape& shape, Rgba8 color);

// The directions (unit vectors, in model space) of n arrows pointing at one
// place, spread every 360/n degrees in the image plane of the camera,
// starting at start_degrees measured counterclockwise from the image's +x
// (ALGORITHMS.md §4: a fixed start angle keeps output deterministic). Each
// direction points from the arrow's tail towards its tip.
std::vector<Vec3> arrow_directions(const Camera& camera, int n, double start_degrees = 45.0);

// The order in which to draw the triangles of set (triangle ids) so that the
// farthest from the eye comes first: sorted by the eye-space depth of the
// centroid, ties by id. model_view maps the set's positions to eye space.
std::vector<std::uint32_t> back_to_front_order(const TriangleSet& set, const Mat4& model_view);

// The 3 * #triangles indices of set reordered by back_to_front_order.
std::vector<std::uint32_t> sorted_indices(const TriangleSet& set, const std::vector<std::uint32_t>& order);

}  // namespace hq
