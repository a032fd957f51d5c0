#pragma once
// How well a UV atlas reads: per-triangle distortion of the map from the
// surface to the UV square, and the atlas's chart and packing statistics
// (definitions in docs/analysis.md, "UV atlas").

#include "hqview/core/vec3.h"
#include "hqview/uv/uv_validation.h"

namespace hq {

struct TriangleDistortion {
  double area_ratio = 0;  // UV area / 3D area (not normalised)
  double conformal = 1;   // sigma_max / sigma_min of the map's Jacobian (>= 1; inf when degenerate)
};

// The linear map from triangle (a, b, c) to uv[0..2].
TriangleDistortion triangle_distortion(const Vec3& a, const Vec3& b, const Vec3& c, const Uv* uv);

struct UvAtlas;
struct TriSurface;

// Fills the atlas's statistics from its UVs and chart labels.
void measure_uv_atlas(const TriSurface& surface, UvAtlas& atlas);

}  // namespace hq
