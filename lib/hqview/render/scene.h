#pragma once
// Scene: what a view draws, as plain data (ARCHITECTURE.md, "Rendering").
// View builders (views_*.cpp) fill it; a Renderer draws it with a Camera.
// Nothing here touches OpenGL, so scenes are unit-tested without a context.
//
// Positions are single-precision offsets from Scene::origin (model units):
// builders put the origin at the centre of what they draw, which keeps full
// float precision for meshes far from the model origin and halves memory.
//
// Draw order (each layer depth-tested against the ones before it):
//   1. triangles   opaque, shaded, pushed back by a small polygon offset so
//                  that lines lying on them win the depth test; arrows are
//                  triangles too (append_arrow, scene_shapes.h);
//   2. spheres     ray-cast impostors (vertex glyphs): one camera-facing
//                  quad per sphere, each fragment intersects its ray with
//                  the sphere, shades it and writes the sphere's true depth;
//   3. lines       on top of coincident triangles (a set with
//                  under_ranked_spheres is drawn before the spheres with
//                  over_other_spheres, which cover it);
//   4. translucent triangles blended over everything else without depth
//                  writes, all triangles of a set sorted back to front for
//                  the camera (back_to_front_order, scene_shapes.h); then
//                  the sphere sets with over_translucent again, over them;
//   5. overlay     opaque triangles over everything else: drawn last, after
//                  the depth buffer is cleared, so they hide only each other
//                  (markers that must stay visible, e.g. overlap arrows
//                  whose target lies inside a glyph);
//   6. overlay lines line sets with in_overlay, after the overlay triangles
//                  and depth-tested against them only (the overlay's edges).

#include <cstdint>
#include <vector>

#include "hqview/core/vec3.h"
#include "hqview/image/color.h"

namespace hq {

// A position or direction in single precision, relative to Scene::origin.
struct Vec3f {
  float x = 0.0f, y = 0.0f, z = 0.0f;
};

inline Vec3f to_vec3f(const Vec3& v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

// A colour map applied to each fragment's interpolated scalar (colour after
// interpolation): interpolating colours mapped at the vertices would paint
// faces in blends that are in no legend (the purple between an inverted
// vertex's blue and its neighbour's orange).
//   samples:   2 to kMaxColorMapSamples colours evenly spaced over the scalar
//              range [0, 1] (sRGB), interpolated linearly between samples as
//              the CPU-side maps do (colormap.h); scalars clamped to [0, 1];
//   below:     the colour where the vertices with a scalar < 0 weigh more
//              than half (barycentrically), so that such a vertex keeps
//              this colour in the part of each face nearest to it however
//              little below 0 it is; there the map takes its scalar as 0;
//   undefined: likewise for NaN scalars (there the map takes them as 1).
inline constexpr std::size_t kMaxColorMapSamples = 64;
struct ScalarColorMap {
  std::vector<Color> samples;
  Color below;
  Color undefined;
};

// Indexed triangles (3 indices per triangle into the vertex arrays).
struct TriangleSet {
  std::vector<Vec3f> positions;        // #V, relative to Scene::origin
  std::vector<Vec3f> normals;          // #V unit normals, or empty: each triangle flat-shaded by its own plane
  std::vector<Rgba8> colors;           // #V, interpolated across triangles (with scalars: only their alpha)
  std::vector<std::uint32_t> indices;  // 3 * #triangles, ids in [0, #V)
  bool is_lit = true;                  // false: colours shown as given (2D maps)
  // A translucent set only: each pixel blended once, by the first of the
  // set's faces drawn there (a stencil test), so that unlit it shows its
  // colour blended once over what is behind however many of its faces stack
  // (view A's intersecting cells).
  bool single_layer = false;
  // Lit: the share of the colour kept facing away from the light (shade =
  // ambient + (1 - ambient) * |n . l|). A surface mesh's binned fill keeps
  // 0.7 so a shaded face keeps its legend colour's hue and near its value.
  float ambient = 0.25f;
  // #V values, or empty. When set, each fragment's colour is color_map of the
  // interpolated scalar (ScalarColorMap) instead of the interpolated colour.
  std::vector<float> scalars;
  ScalarColorMap color_map;
};

// The colour a renderer draws for a fragment of a TriangleSet with scalars:
//   scalar:          interpolated scalar, vertices below 0 counted as 0 and
//                    NaN ones as 1;
//   below_weight:    interpolated 1 for vertices below 0, else 0;
//   undefined_weight interpolated 1 for NaN vertices, else 0.
// (The GL backend runs the same steps in its fragment shader.)
Color map_fragment_color(const ScalarColorMap& map, float scalar, float below_weight, float undefined_weight);

// Indexed line segments (2 indices per segment into the vertex arrays).
struct LineSet {
  std::vector<Vec3f> positions;        // #V, relative to Scene::origin
  std::vector<Rgba8> colors;           // #V, alpha < 255 blends over what is behind
  std::vector<std::uint32_t> indices;  // 2 * #segments, ids in [0, #V)
  float width = 1.0f;                  // in output pixels
  // Drawn after the other spheres but before the over_other_spheres sets,
  // which then cover it (view A's boundary wireframe: no veil over the
  // ranked glyphs).
  bool under_ranked_spheres = false;
  // Drawn in the overlay layer (6. above), not with the other lines.
  bool in_overlay = false;
  // Drawn with no depth test, over everything drawn before it (the cells
  // figure's max hex: its whole wireframe stays visible behind nearer cells).
  bool over_all = false;
};

// Spheres (glyphs): centre, radius (model units, > 0) and colour each.
struct SphereSet {
  std::vector<Vec3f> centers;  // relative to Scene::origin
  std::vector<float> radii;    // #spheres
  std::vector<Rgba8> colors;   // #spheres (alpha ignored: spheres are opaque)
  // Drawn after the other sphere sets, back to front, over the opaque
  // triangles and the other sets' spheres (depth test off), still writing
  // their depth (lines and translucent faces in front of them show): view
  // A's ranked glyphs, which the many grey ones must not hide.
  bool over_other_spheres = false;
  // With over_other_spheres: drawn in the reverse of the set's order, so its
  // first sphere is on top of the others whatever their depth (view A: the
  // worst cluster's glyph is never hidden by a less severe one), instead of
  // back to front.
  bool first_on_top = false;
  // With over_other_spheres: drawn once more after the translucent layer
  // (4.), depth test off, so that no translucent face blends over these
  // spheres (issue 44 part U, round 2: view A's intersecting-cell boxes
  // turned the worst glyph magenta); the overlay layer still covers them.
  bool over_translucent = false;
  // In [0, 1): the lit colour is mixed this far towards white (issue 44
  // part T: view A's grey glyphs are de-emphasised by lightness, not size).
  // Id images ignore it.
  float pale = 0.0f;
};

struct Scene {
  Vec3 origin;  // model position that vertex offsets are relative to
  Rgba8 background{255, 255, 255, 255};
  std::vector<TriangleSet> triangles;
  std::vector<SphereSet> spheres;
  std::vector<LineSet> lines;
  std::vector<TriangleSet> translucent;  // colours' alpha is the opacity
  std::vector<TriangleSet> overlay;      // opaque, on top of all the rest
};

inline std::size_t sphere_count(const Scene& scene) {
  std::size_t n = 0;
  for (const SphereSet& set : scene.spheres) n += set.centers.size();
  return n;
}

// Number of triangles / segments over all sets (for tests and statistics).
inline std::size_t triangle_count(const Scene& scene) {
  std::size_t n = 0;
  for (const TriangleSet& set : scene.triangles) n += set.indices.size() / 3;
  return n;
}
inline std::size_t segment_count(const Scene& scene) {
  std::size_t n = 0;
  for (const LineSet& set : scene.lines) n += set.indices.size() / 2;
  return n;
}

}  // namespace hq
