#include "hqview/render/osmesa_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <span>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/core/stop.h"
#include "hqview/render/gl_api.h"
#include "hqview/render/scene_shapes.h"

namespace hq {
namespace {

// Each axis is drawn at this many times the output resolution, then each
// output pixel is the rounded mean of its 2x2 block (box_filter_2x2): on
// llvmpipe this is as fast as 4x MSAA and also smooths the discarded edges
// of the sphere impostors (ALGORITHMS.md §6).
constexpr int kSupersampling = 2;

// Every shader is compiled from three strings: the version line, the
// colour-space functions below, and its own source.
constexpr const char* kShaderVersion = "#version 450 core\n";

// sRGB <-> linear RGB without pow: llvmpipe evaluates pow as exp2(log2)
// polynomials per channel and per fragment, which made these conversions the
// largest part of a frame's cost (at 2x2 supersampling a 1600x1200 frame
// shades 7.7 million samples). Both curves are fitted (minimax) as sums of
// nested square roots, one SIMD instruction each on llvmpipe:
// - to_srgb: 1.055 c^(1/2.4) - 0.055 for c >= 0.0031308, within 0.0008/255
//   of the exact curve, evaluated in float32;
// - to_linear: y^2.4 = y^2 y^0.4 with y = (c + 0.055) / 1.055 for
//   c >= 0.04045, within a relative 1.3e-6.
// Both are far below half a step of an 8-bit channel: a pixel can move by
// one only where the exact value lies that close to a rounding boundary
// (test OsmesaRenderer.ShadingFollowsTheSrgbCurves).
constexpr const char* kColorSpaceFunctions = R"(
vec3 to_linear(vec3 c) {
  vec3 y = (c + 0.055) / 1.055;
  vec3 r1 = sqrt(y), r2 = sqrt(r1), r3 = sqrt(r2);
  vec3 y04 = 0.475850085 * r1 + 0.938860991 * r2 - 0.501297324 * r3 - 0.0100050836 * y + 0.0965900537;
  return mix(c / 12.92, y * y * y04, step(0.04045, c));
}
vec3 to_srgb(vec3 c) {
  vec3 r1 = sqrt(c), r2 = sqrt(r1), r3 = sqrt(r2), r4 = sqrt(r3);
  vec3 s = 0.532354054 * r1 + 1.29197461 * r2 - 1.79019805 * r3 + 1.31596827 * r4 - 0.0081068418 * c - 0.341994753;
  return mix(c * 12.92, s, step(0.0031308, c));
}
)";

constexpr GLuint kPositionAttribute = 0;
constexpr GLuint kNormalAttribute = 1;
constexpr GLuint kColorAttribute = 2;
constexpr GLuint kCornerAttribute = 3;  // sphere impostors: quad corner (xy) and radius (z)
constexpr GLuint kScalarAttribute = 3;  // triangles: (scalar, below weight, undefined weight)

// Shading: a directional light fixed to the camera (a headlight tilted up by
// 20 degrees, so that the sides of a box seen obliquely get three distinct
// brightnesses, lit from above as people expect)
// plus ambient. Two-sided: |n . l|, since boundary quads of a broken mesh
// can face either way and clipped views show inner sides.
// Sets with scalars (TriangleSet::scalars) interpolate (scalar, below weight,
// undefined weight) and map them per fragment (scene.h's map_fragment_color,
// the same steps): every fragment shows a colour of the map.
constexpr const char* kTriangleVertexShader = R"(layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec4 color;
layout(location = 3) in vec3 scalar;
uniform mat4 model_view;
uniform mat4 projection;
out vec3 eye_position;
out vec3 eye_normal;
out vec4 vertex_color;
out vec3 vertex_scalar;
void main() {
  vec4 p = model_view * vec4(position, 1.0);
  eye_position = p.xyz;
  eye_normal = mat3(model_view) * normal;  // model_view is rigid
  vertex_color = color;
  vertex_scalar = scalar;
  gl_Position = projection * p;
}
)";

constexpr const char* kTriangleFragmentShader = R"(in vec3 eye_position;
in vec3 eye_normal;
in vec4 vertex_color;
in vec3 vertex_scalar;
uniform bool use_vertex_normals;
uniform bool is_lit;
uniform bool has_set_color;     // every vertex has one colour: set_linear_color
uniform vec3 set_linear_color;  // that colour in linear RGB (saves a to_linear per fragment)
uniform bool has_scalars;       // colour = the map of vertex_scalar (sRGB samples)
uniform int map_size;
uniform vec3 map_samples[64];
uniform vec3 map_below;
uniform vec3 map_undefined;
uniform vec3 light_direction;
uniform float ambient;
out vec4 fragment_color;
vec3 mapped_color() {
  if (vertex_scalar.z > 0.5) return map_undefined;
  if (vertex_scalar.y > 0.5) return map_below;
  float x = clamp(vertex_scalar.x, 0.0, 1.0) * float(map_size - 1);
  int i = min(int(x), map_size - 2);
  return mix(map_samples[i], map_samples[i + 1], x - float(i));
}
void main() {
  if (!is_lit) {
    fragment_color = has_scalars ? vec4(mapped_color(), vertex_color.a) : vertex_color;
    return;
  }
  vec3 n = use_vertex_normals ? eye_normal : cross(dFdx(eye_position), dFdy(eye_position));
  float len = length(n);
  float diffuse = len > 0.0 ? abs(dot(n / len, light_direction)) : 1.0;
  float shade = ambient + (1.0 - ambient) * diffuse;
  // Light in linear RGB: shading in sRGB would muddy the pale end of the map.
  vec3 base = has_scalars ? to_linear(mapped_color()) : has_set_color ? set_linear_color : to_linear(vertex_color.rgb);
  fragment_color = vec4(to_srgb(base * shade), vertex_color.a);
}
)";

constexpr const char* kLineVertexShader = R"(layout(location = 0) in vec3 position;
layout(location = 2) in vec4 color;
uniform mat4 model_view;
uniform mat4 projection;
out vec4 vertex_color;
void main() {
  vertex_color = color;
  gl_Position = projection * (model_view * vec4(position, 1.0));
}
)";

constexpr const char* kLineFragmentShader = R"(in vec4 vertex_color;
out vec4 fragment_color;
void main() { fragment_color = vertex_color; }
)";

// Sphere impostors: each sphere is a quad facing the eye, just large enough
// to cover the sphere's silhouette (for a perspective camera, the tangent
// cone's cross-section through the centre: r d / sqrt(d^2 - r^2)). Each
// fragment casts its eye ray against the sphere, discards misses, shades the
// hit with the triangles' light and writes the hit's depth, so spheres
// intersect each other and the mesh correctly. (Point sprites would do the
// same but llvmpipe caps their size at 255 pixels, too small for large
// glyphs at 2x2 supersampling.)
constexpr const char* kSphereVertexShader = R"(layout(location = 0) in vec3 center;
layout(location = 2) in vec4 color;
layout(location = 3) in vec3 corner_radius;
uniform mat4 model_view;
uniform mat4 projection;
uniform bool is_perspective;
out vec3 eye_point;
flat out vec3 eye_center;
flat out float radius;
flat out vec3 linear_color;
flat out vec4 flat_color;
void main() {
  flat_color = color;
  vec3 c = (model_view * vec4(center, 1.0)).xyz;
  float r = corner_radius.z;
  vec3 axis = is_perspective ? normalize(-c) : vec3(0.0, 0.0, 1.0);
  float d = length(c);
  float half_size = is_perspective ? r * d / sqrt(max(d * d - r * r, 1e-6 * d * d)) : r;
  half_size *= 1.02;
  vec3 u = normalize(cross(abs(axis.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), axis));
  vec3 v = cross(axis, u);
  vec3 p = c + half_size * (corner_radius.x * u + corner_radius.y * v);
  eye_point = p;
  eye_center = c;
  radius = r;
  // One colour per sphere: linearised once here, not for every fragment.
  linear_color = to_linear(color.rgb);
  gl_Position = projection * vec4(p, 1.0);
}
)";

constexpr const char* kSphereFragmentShader = R"(in vec3 eye_point;
flat in vec3 eye_center;
flat in float radius;
flat in vec3 linear_color;
flat in vec4 flat_color;
uniform mat4 projection;
uniform bool is_perspective;
uniform bool is_flat;  // id images: the colour as given, unlit
uniform float pale;    // SphereSet::pale: the lit colour mixed this far towards white
uniform vec3 light_direction;
uniform float ambient;
out vec4 fragment_color;
void main() {
  vec3 origin = is_perspective ? vec3(0.0) : vec3(eye_point.xy, 0.0);
  vec3 direction = is_perspective ? normalize(eye_point) : vec3(0.0, 0.0, -1.0);
  vec3 oc = origin - eye_center;
  float b = dot(direction, oc);
  float disc = b * b - (dot(oc, oc) - radius * radius);
  if (disc < 0.0) discard;
  float t = -b - sqrt(disc);
  vec3 hit = origin + t * direction;
  vec3 n = (hit - eye_center) / radius;
  vec4 clip = projection * vec4(hit, 1.0);
  gl_FragDepth = clamp(0.5 * clip.z / clip.w + 0.5, 0.0, 1.0);
  if (is_flat) {
    fragment_color = vec4(flat_color.rgb, 1.0);
    return;
  }
  float diffuse = max(dot(n, light_direction), 0.0);
  float shade = ambient + (1.0 - ambient) * diffuse;
  // A small highlight makes spheres read as round at a glance.
  vec3 h = normalize(light_direction + vec3(0.0, 0.0, 1.0));
  // x^40 as x^32 x^8 by squaring (pow would be exp2(log2) on llvmpipe).
  float x = max(dot(n, h), 0.0);
  float x2 = x * x, x4 = x2 * x2, x8 = x4 * x4, x32 = (x8 * x8) * (x8 * x8);
  float specular = 0.25 * x32 * x8;
  vec3 lit = mix(min(linear_color * shade + vec3(specular), vec3(1.0)), vec3(1.0), pale);
  fragment_color = vec4(to_srgb(lit), 1.0);
}
)";

std::string gl_error_name(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "GL error 0x" + [&] {
        char buffer[16];
        std::snprintf(buffer, sizeof buffer, "%04x", error);
        return std::string(buffer);
      }();
  }
}

void check_gl(const char* what) {
  const GlApi& gl = gl_api();
  const GLenum error = gl.GetError();
  if (error != GL_NO_ERROR) throw RenderError(std::string("OpenGL error during ") + what + ": " + gl_error_name(error));
}

GLuint compile_shader(GLenum type, const char* source, const char* name) {
  const GlApi& gl = gl_api();
  const GLuint shader = gl.CreateShader(type);
  const char* sources[] = {kShaderVersion, kColorSpaceFunctions, source};
  gl.ShaderSource(shader, 3, sources, nullptr);
  gl.CompileShader(shader);
  GLint ok = GL_FALSE;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    std::array<char, 4096> log{};
    gl.GetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    gl.DeleteShader(shader);
    throw RenderError(std::string("cannot compile the ") + name + " shader: " + log.data());
  }
  return shader;
}

GLuint link_program(const char* vertex_source, const char* fragment_source, const char* name) {
  const GlApi& gl = gl_api();
  const GLuint vertex = compile_shader(GL_VERTEX_SHADER, vertex_source, name);
  const GLuint fragment = compile_shader(GL_FRAGMENT_SHADER, fragment_source, name);
  const GLuint program = gl.CreateProgram();
  gl.AttachShader(program, vertex);
  gl.AttachShader(program, fragment);
  gl.LinkProgram(program);
  gl.DeleteShader(vertex);
  gl.DeleteShader(fragment);
  GLint ok = GL_FALSE;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    std::array<char, 4096> log{};
    gl.GetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    gl.DeleteProgram(program);
    throw RenderError(std::string("cannot link the ") + name + " shader program: " + log.data());
  }
  return program;
}

std::array<float, 16> to_float(const Mat4& a) {
  std::array<float, 16> f;
  for (std::size_t i = 0; i < 16; ++i) f[i] = static_cast<float>(a.m[i]);
  return f;
}

// A scene comes from code, not from users, but a bad index would make the
// rasterizer read outside the vertex buffers: refuse it here.
template <class Set>
void check_indices(const Set& set, std::size_t per_primitive, const char* kind) {
  const std::size_t n = set.positions.size();
  if (set.colors.size() != n) throw RenderError(std::string(kind) + ": colours and positions differ in count");
  if (set.indices.size() % per_primitive != 0)
    throw RenderError(std::string(kind) + ": index count is not a multiple of " + std::to_string(per_primitive));
  for (std::uint32_t i : set.indices)
    if (i >= n) throw RenderError(std::string(kind) + ": vertex index " + std::to_string(i) + " out of range");
}

// Scalars: one per vertex and a map of 2 to kMaxColorMapSamples samples.
void check_scalars(const TriangleSet& set) {
  if (set.scalars.empty()) return;
  if (set.scalars.size() != set.positions.size())
    throw RenderError("triangle set: scalars and positions differ in count");
  const std::size_t n = set.color_map.samples.size();
  if (n < 2 || n > kMaxColorMapSamples)
    throw RenderError("triangle set: a colour map needs 2 to " + std::to_string(kMaxColorMapSamples) +
                      " samples, got " + std::to_string(n));
}

// The output image of a 2x2-supersampled frame read back bottom-up
// (OpenGL's row order): each output pixel, rows top-down, is the rounded
// mean of its 2x2 block in every channel, in integers, so the result is
// exact and the same on every machine.
Image box_filter_2x2(const std::vector<std::uint8_t>& bottom_up, int width, int height) {
  static_assert(kSupersampling == 2);
  Image image{width, height,
              std::vector<std::uint8_t>(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
  const std::size_t ss_row = 8 * static_cast<std::size_t>(width);
  for (int y = 0; y < height; ++y) {
    // Output row y (top-down) is resolved row height - 1 - y (bottom-up),
    // i.e. supersampled rows 2 (height - 1 - y) and the one above it.
    const std::uint8_t* r0 = bottom_up.data() + ss_row * (2 * static_cast<std::size_t>(height - 1 - y));
    const std::uint8_t* r1 = r0 + ss_row;
    std::uint8_t* out = image.rgba.data() + 4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(y);
    for (int x = 0; x < width; ++x) {
      const std::size_t i = 8 * static_cast<std::size_t>(x);
      for (std::size_t c = 0; c < 4; ++c)
        out[4 * static_cast<std::size_t>(x) + c] = static_cast<std::uint8_t>(
            (static_cast<unsigned>(r0[i + c]) + r0[i + 4 + c] + r1[i + c] + r1[i + 4 + c] + 2u) >> 2);
    }
  }
  return image;
}

class OsmesaRenderer final : public Renderer {
 public:
  OsmesaRenderer() {
    const int attributes[] = {OSMESA_FORMAT,         OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,     24,
                              OSMESA_STENCIL_BITS,   0,
                              OSMESA_ACCUM_BITS,     0,
                              OSMESA_PROFILE,        OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION, 4,
                              OSMESA_CONTEXT_MINOR_VERSION, 5,
                              0};
    context_ = gl.CreateContextAttribs(attributes, nullptr);
    if (!context_)
      throw RenderError(
          "cannot create an OSMesa OpenGL 4.5 core-profile context (is libOSMesa from Mesa >= 20 with "
          "llvmpipe installed? package libosmesa6)");
    try {
      make_current();
      triangle_program_ = link_program(kTriangleVertexShader, kTriangleFragmentShader, "triangle");
      line_program_ = link_program(kLineVertexShader, kLineFragmentShader, "line");
      sphere_program_ = link_program(kSphereVertexShader, kSphereFragmentShader, "sphere");
      gl.GenVertexArrays(1, &vertex_array_);
      gl.GenBuffers(1, &position_buffer_);
      gl.GenBuffers(1, &normal_buffer_);
      gl.GenBuffers(1, &color_buffer_);
      gl.GenBuffers(1, &index_buffer_);
      gl.GenBuffers(1, &scalar_buffer_);
      gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_renderbuffer_size_);
      GLfloat widths[2] = {1.0f, 1.0f};
      gl.GetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, widths);
      max_line_width_ = std::max(1.0f, widths[1]);
      check_gl("renderer set-up");
    } catch (...) {
      release();
      throw;
    }
  }

  ~OsmesaRenderer() override { release(); }

  // Its own context: llvmpipe draws two contexts' frames at once, and
  // their images are the same bit for bit (one JIT, one rasteriser).
  std::unique_ptr<Renderer> sibling() const override { return std::make_unique<OsmesaRenderer>(); }

  OsmesaRenderer(const OsmesaRenderer&) = delete;
  OsmesaRenderer& operator=(const OsmesaRenderer&) = delete;

  Image render(const Scene& scene, const Camera& camera, int width, int height) override {
    id_mode_ = false;
    draw_frame(scene, camera, width, height);
    Image image = resolve(width, height);
    check_gl("reading the image back");
    return image;
  }

  IdImage render_ids(const Scene& scene, const Camera& camera, int width, int height) override {
    id_mode_ = true;
    try {
      draw_frame(scene, camera, width, height);
    } catch (...) {
      id_mode_ = false;
      throw;
    }
    id_mode_ = false;
    IdImage ids = resolve_ids(width, height);
    check_gl("reading the id image back");
    return ids;
  }

 private:
  // Draws the frame into the supersampled framebuffer (id_mode_: unlit,
  // unblended, translucent sets left out).
  void draw_frame(const Scene& scene, const Camera& camera, int width, int height) {
    stop::check();
    if (width <= 0 || height <= 0)
      throw RenderError("image size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
    for (const auto* sets : {&scene.triangles, &scene.translucent, &scene.overlay})
      for (const TriangleSet& set : *sets) check_scalars(set);
    for (const TriangleSet& set : scene.triangles) {
      check_indices(set, 3, "triangle set");
      if (!set.normals.empty() && set.normals.size() != set.positions.size())
        throw RenderError("triangle set: normals and positions differ in count");
    }
    for (const TriangleSet& set : scene.translucent) {
      check_indices(set, 3, "translucent triangle set");
      if (!set.normals.empty() && set.normals.size() != set.positions.size())
        throw RenderError("translucent triangle set: normals and positions differ in count");
    }
    for (const TriangleSet& set : scene.overlay) {
      check_indices(set, 3, "overlay triangle set");
      if (!set.normals.empty() && set.normals.size() != set.positions.size())
        throw RenderError("overlay triangle set: normals and positions differ in count");
    }
    for (const LineSet& set : scene.lines) check_indices(set, 2, "line set");
    for (const SphereSet& set : scene.spheres)
      if (set.radii.size() != set.centers.size() || set.colors.size() != set.centers.size())
        throw RenderError("sphere set: centres, radii and colours differ in count");

    make_current();
    prepare_framebuffers(width, height);
    const int ss_width = kSupersampling * width, ss_height = kSupersampling * height;

    gl.BindFramebuffer(GL_FRAMEBUFFER, supersampled_framebuffer_);
    gl.Viewport(0, 0, ss_width, ss_height);
    const Color background = to_color(scene.background);
    gl.ClearColor(background.r, background.g, background.b, background.a);
    gl.ClearDepth(1.0);
    gl.DepthMask(GL_TRUE);  // glClear obeys the depth mask
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LEQUAL);
    gl.Disable(GL_CULL_FACE);
    gl.BindVertexArray(vertex_array_);

    const double aspect = static_cast<double>(width) / static_cast<double>(height);
    const Mat4 model_view_matrix = view_matrix(camera) * translation_matrix(scene.origin);
    const auto model_view = to_float(model_view_matrix);
    const auto projection = to_float(projection_matrix(camera, aspect));

    draw_triangles(scene.triangles, model_view, projection, nullptr);
    // Spheres, the lines under the ranked spheres, the ranked (over other)
    // spheres, the other lines (scene.h, draw order).
    draw_spheres(scene, model_view, projection, camera.is_perspective, false);
    draw_lines(scene, model_view, projection, true);
    draw_spheres(scene, model_view, projection, camera.is_perspective, true);
    draw_lines(scene, model_view, projection, false);
    if (!scene.translucent.empty() && !id_mode_) {
      // Blended over everything, without depth writes, back to front.
      gl.Enable(GL_BLEND);
      gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      gl.DepthMask(GL_FALSE);
      for (const TriangleSet& set : scene.translucent) {
        const std::span<const TriangleSet> one(&set, 1);
        if (set.single_layer) {
          // The first fragment a pixel blends, the others fail the stencil
          // test (a depth pass and then GL_EQUAL blended several faces
          // that the depth buffer could not tell apart: a stack of
          // overlapping cubes).
          gl.Clear(GL_STENCIL_BUFFER_BIT);
          gl.Enable(GL_STENCIL_TEST);
          gl.StencilFunc(GL_EQUAL, 0, 0xff);
          gl.StencilOp(GL_KEEP, GL_KEEP, GL_INCR);
        }
        draw_triangles(one, model_view, projection, &model_view_matrix);
        gl.Disable(GL_STENCIL_TEST);
      }
      gl.DepthMask(GL_TRUE);
      gl.Disable(GL_BLEND);
      if (std::any_of(scene.translucent.begin(), scene.translucent.end(),
                      [](const TriangleSet& set) { return !set.indices.empty(); })) {
        draw_spheres(scene, model_view, projection, camera.is_perspective, false, true);
        draw_spheres(scene, model_view, projection, camera.is_perspective, true, true);
      }
    }
    // Overlay lines alone (the overview's inverted-face outlines) are drawn
    // over everything too.
    if (std::any_of(scene.overlay.begin(), scene.overlay.end(),
                    [](const TriangleSet& set) { return !set.indices.empty(); }) ||
        std::any_of(scene.lines.begin(), scene.lines.end(),
                    [](const LineSet& set) { return set.in_overlay && !set.indices.empty(); })) {
      gl.Clear(GL_DEPTH_BUFFER_BIT);  // the depth mask is on again
      draw_triangles(scene.overlay, model_view, projection, nullptr);
      draw_lines(scene, model_view, projection, false, true);
    }
    check_gl("drawing");
  }

  void make_current() {
    if (!gl.MakeCurrent(context_, default_buffer_.data(), GL_UNSIGNED_BYTE, kDefaultSize, kDefaultSize))
      throw RenderError("cannot make the OSMesa context current");
  }

  void release() {
    if (!context_) return;
    if (gl.MakeCurrent(context_, default_buffer_.data(), GL_UNSIGNED_BYTE, kDefaultSize, kDefaultSize)) {
      delete_framebuffers();
      const GLuint buffers[] = {position_buffer_, normal_buffer_, color_buffer_, index_buffer_, scalar_buffer_};
      gl.DeleteBuffers(5, buffers);
      gl.DeleteVertexArrays(1, &vertex_array_);
      gl.DeleteProgram(triangle_program_);
      gl.DeleteProgram(line_program_);
      gl.DeleteProgram(sphere_program_);
    }
    gl.DestroyContext(context_);
    context_ = nullptr;
  }

  void delete_framebuffers() {
    const GLuint renderbuffers[] = {supersampled_color_, supersampled_depth_};
    gl.DeleteFramebuffers(1, &supersampled_framebuffer_);
    gl.DeleteRenderbuffers(2, renderbuffers);
    supersampled_framebuffer_ = 0;
    supersampled_color_ = supersampled_depth_ = 0;
    framebuffer_width_ = framebuffer_height_ = 0;
  }

  // (Re)creates the supersampled framebuffer when the image size changes;
  // frames of one size reuse it.
  void prepare_framebuffers(int width, int height) {
    if (width == framebuffer_width_ && height == framebuffer_height_) return;
    const int ss_width = kSupersampling * width, ss_height = kSupersampling * height;
    if (ss_width > max_renderbuffer_size_ || ss_height > max_renderbuffer_size_)
      throw RenderError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                        " exceeds the renderer's limit of " + std::to_string(max_renderbuffer_size_ / kSupersampling) +
                        " pixels per side");
    delete_framebuffers();
    auto make_renderbuffer = [this](GLenum format, int w, int h) {
      GLuint id = 0;
      gl.GenRenderbuffers(1, &id);
      gl.BindRenderbuffer(GL_RENDERBUFFER, id);
      gl.RenderbufferStorage(GL_RENDERBUFFER, format, w, h);
      return id;
    };
    supersampled_color_ = make_renderbuffer(GL_RGBA8, ss_width, ss_height);
    supersampled_depth_ = make_renderbuffer(GL_DEPTH24_STENCIL8, ss_width, ss_height);  // stencil: single_layer

    gl.GenFramebuffers(1, &supersampled_framebuffer_);
    gl.BindFramebuffer(GL_FRAMEBUFFER, supersampled_framebuffer_);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, supersampled_color_);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, supersampled_depth_);
    const GLenum supersampled_status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    check_gl("framebuffer set-up");
    if (supersampled_status != GL_FRAMEBUFFER_COMPLETE) {
      delete_framebuffers();
      throw RenderError("cannot create an offscreen framebuffer of " + std::to_string(ss_width) + "x" +
                        std::to_string(ss_height) + " pixels");
    }
    framebuffer_width_ = width;
    framebuffer_height_ = height;
  }

  template <class T>
  void upload(GLenum target, GLuint buffer, const std::vector<T>& data) {
    gl.BindBuffer(target, buffer);
    gl.BufferData(target, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(), GL_STREAM_DRAW);
  }

  void bind_positions_and_colors(const std::vector<Vec3f>& positions, const std::vector<Rgba8>& colors) {
    upload(GL_ARRAY_BUFFER, position_buffer_, positions);
    gl.VertexAttribPointer(kPositionAttribute, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3f), nullptr);
    gl.EnableVertexAttribArray(kPositionAttribute);
    upload(GL_ARRAY_BUFFER, color_buffer_, colors);
    gl.VertexAttribPointer(kColorAttribute, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(Rgba8), nullptr);
    gl.EnableVertexAttribArray(kColorAttribute);
  }

  void set_matrices(GLuint program, const std::array<float, 16>& model_view, const std::array<float, 16>& projection) {
    gl.UniformMatrix4fv(gl.GetUniformLocation(program, "model_view"), 1, GL_FALSE, model_view.data());
    gl.UniformMatrix4fv(gl.GetUniformLocation(program, "projection"), 1, GL_FALSE, projection.data());
  }

  void set_light(GLuint program) {
    // Above the view direction, in eye space.
    const float light[3] = {0.0f, 0.35f, 0.94f};
    const float length = std::sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
    gl.Uniform3f(gl.GetUniformLocation(program, "light_direction"), light[0] / length, light[1] / length,
                light[2] / length);
    gl.Uniform1f(gl.GetUniformLocation(program, "ambient"), 0.25f);
  }

  void draw_spheres(const Scene& scene, const std::array<float, 16>& model_view,
                    const std::array<float, 16>& projection, bool is_perspective, bool over,
                    bool over_translucent = false) {
    if (std::none_of(scene.spheres.begin(), scene.spheres.end(), [&](const SphereSet& set) {
          return set.over_other_spheres == over && (!over_translucent || set.over_translucent) &&
                 !set.centers.empty();
        }))
      return;
    gl.UseProgram(sphere_program_);
    set_matrices(sphere_program_, model_view, projection);
    gl.Uniform1i(gl.GetUniformLocation(sphere_program_, "is_perspective"), is_perspective ? 1 : 0);
    gl.Uniform1i(gl.GetUniformLocation(sphere_program_, "is_flat"), id_mode_ ? 1 : 0);
    set_light(sphere_program_);
    gl.Disable(GL_BLEND);
    static constexpr float kCorners[4][2] = {{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}};
    // Sets over the others (over == true): back to front (eye z ascending)
    // or first on top, depth test off.
    std::vector<const SphereSet*> order;
    for (const SphereSet& set : scene.spheres)
      if (set.over_other_spheres == over && (!over_translucent || set.over_translucent)) order.push_back(&set);
    auto eye_z = [&](const Vec3f& c) { return model_view[2] * c.x + model_view[6] * c.y + model_view[10] * c.z; };
    for (const SphereSet* set_pointer : order) {
      const SphereSet& set = *set_pointer;
      stop::check();  // a stop request lands between draws (hq::stop)
      if (set.centers.empty()) continue;
      gl.Uniform1f(gl.GetUniformLocation(sphere_program_, "pale"), std::clamp(set.pale, 0.0f, 0.95f));
      const std::size_t n = set.centers.size();
      std::vector<std::size_t> sphere_order(n);
      for (std::size_t i = 0; i < n; ++i) sphere_order[i] = i;
      if (set.over_other_spheres) {
        if (set.first_on_top)
          std::reverse(sphere_order.begin(), sphere_order.end());
        else
          std::stable_sort(sphere_order.begin(), sphere_order.end(), [&](std::size_t a, std::size_t b) {
            return eye_z(set.centers[a]) < eye_z(set.centers[b]);
          });
        gl.DepthFunc(GL_ALWAYS);
      }
      std::vector<Vec3f> centers(4 * n), corners(4 * n);
      std::vector<Rgba8> colors(4 * n);
      std::vector<std::uint32_t> indices(6 * n);
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t s = sphere_order[i];
        for (std::size_t k = 0; k < 4; ++k) {
          centers[4 * i + k] = set.centers[s];
          corners[4 * i + k] = {kCorners[k][0], kCorners[k][1], set.radii[s]};
          colors[4 * i + k] = set.colors[s];
        }
        const auto base = static_cast<std::uint32_t>(4 * i);
        const std::uint32_t quad[6] = {base, base + 1, base + 2, base, base + 2, base + 3};
        std::copy(quad, quad + 6, indices.begin() + static_cast<std::ptrdiff_t>(6 * i));
      }
      bind_positions_and_colors(centers, colors);
      upload(GL_ARRAY_BUFFER, normal_buffer_, corners);
      gl.VertexAttribPointer(kCornerAttribute, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3f), nullptr);
      gl.EnableVertexAttribArray(kCornerAttribute);
      upload(GL_ELEMENT_ARRAY_BUFFER, index_buffer_, indices);
      gl.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices.size()), GL_UNSIGNED_INT, nullptr);
      gl.DepthFunc(GL_LEQUAL);
    }
    gl.DisableVertexAttribArray(kCornerAttribute);
  }

  // Opaque sets (sort_by == nullptr) or translucent ones, whose triangles are
  // drawn back to front for the eye-space transform *sort_by.
  void draw_triangles(std::span<const TriangleSet> sets, const std::array<float, 16>& model_view,
                      const std::array<float, 16>& projection, const Mat4* sort_by) {
    gl.UseProgram(triangle_program_);
    set_matrices(triangle_program_, model_view, projection);
    set_light(triangle_program_);
    if (!sort_by) gl.Disable(GL_BLEND);
    // Push filled triangles back so that lines on them pass the depth test.
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(1.0f, 1.0f);
    for (const TriangleSet& set : sets) {
      stop::check();
      if (set.indices.empty()) continue;
      bind_positions_and_colors(set.positions, set.colors);
      const bool use_normals = !set.normals.empty();
      if (use_normals) {
        upload(GL_ARRAY_BUFFER, normal_buffer_, set.normals);
        gl.VertexAttribPointer(kNormalAttribute, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3f), nullptr);
        gl.EnableVertexAttribArray(kNormalAttribute);
      } else {
        gl.DisableVertexAttribArray(kNormalAttribute);
      }
      gl.Uniform1i(gl.GetUniformLocation(triangle_program_, "use_vertex_normals"), use_normals ? 1 : 0);
      gl.Uniform1i(gl.GetUniformLocation(triangle_program_, "is_lit"), set.is_lit && !id_mode_ ? 1 : 0);
      gl.Uniform1f(gl.GetUniformLocation(triangle_program_, "ambient"), set.ambient);
      set_scalars(set);
      // One colour for the whole set (translucent hulls, arrows, the grey
      // boundary of view F): linearised once here instead of per fragment.
      const Rgba8 first = set.colors.front();
      const bool one_color =
          std::all_of(set.colors.begin(), set.colors.end(), [&](const Rgba8& c) { return c == first; });
      gl.Uniform1i(gl.GetUniformLocation(triangle_program_, "has_set_color"), one_color ? 1 : 0);
      if (one_color) {
        auto to_linear = [](std::uint8_t byte) {
          const float c = static_cast<float>(byte) / 255.0f;
          return c >= 0.04045f ? std::pow((c + 0.055f) / 1.055f, 2.4f) : c / 12.92f;
        };
        gl.Uniform3f(gl.GetUniformLocation(triangle_program_, "set_linear_color"), to_linear(first.r), to_linear(first.g),
                    to_linear(first.b));
      }
      if (sort_by)
        upload(GL_ELEMENT_ARRAY_BUFFER, index_buffer_, sorted_indices(set, back_to_front_order(set, *sort_by)));
      else
        upload(GL_ELEMENT_ARRAY_BUFFER, index_buffer_, set.indices);
      gl.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(set.indices.size()), GL_UNSIGNED_INT, nullptr);
    }
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    gl.DisableVertexAttribArray(kNormalAttribute);
    gl.DisableVertexAttribArray(kScalarAttribute);
  }

  // The per-fragment colour map of a set with scalars (has_scalars off
  // otherwise): per vertex (scalar, below weight, undefined weight) as
  // map_fragment_color (scene.h) reads them, the samples as uniforms.
  void set_scalars(const TriangleSet& set) {
    const bool has_scalars = !set.scalars.empty() && !id_mode_;
    gl.Uniform1i(gl.GetUniformLocation(triangle_program_, "has_scalars"), has_scalars ? 1 : 0);
    if (!has_scalars) {
      gl.DisableVertexAttribArray(kScalarAttribute);
      return;
    }
    std::vector<Vec3f> weights(set.scalars.size());
    for (std::size_t i = 0; i < weights.size(); ++i) {
      const float s = set.scalars[i];
      weights[i] = std::isnan(s) ? Vec3f{1.0f, 0.0f, 1.0f} : s < 0.0f ? Vec3f{0.0f, 1.0f, 0.0f} : Vec3f{s, 0.0f, 0.0f};
    }
    upload(GL_ARRAY_BUFFER, scalar_buffer_, weights);
    gl.VertexAttribPointer(kScalarAttribute, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3f), nullptr);
    gl.EnableVertexAttribArray(kScalarAttribute);
    const std::vector<Color>& samples = set.color_map.samples;
    std::vector<float> rgb;
    for (const Color& c : samples) rgb.insert(rgb.end(), {c.r, c.g, c.b});
    gl.Uniform1i(gl.GetUniformLocation(triangle_program_, "map_size"), static_cast<GLint>(samples.size()));
    gl.Uniform3fv(gl.GetUniformLocation(triangle_program_, "map_samples"), static_cast<GLsizei>(samples.size()),
                  rgb.data());
    const Color& below = set.color_map.below;
    const Color& undefined = set.color_map.undefined;
    gl.Uniform3f(gl.GetUniformLocation(triangle_program_, "map_below"), below.r, below.g, below.b);
    gl.Uniform3f(gl.GetUniformLocation(triangle_program_, "map_undefined"), undefined.r, undefined.g, undefined.b);
  }

  // The line sets with under_ranked_spheres == under.
  void draw_lines(const Scene& scene, const std::array<float, 16>& model_view,
                  const std::array<float, 16>& projection, bool under, bool overlay = false) {
    const auto drawn = [&](const LineSet& set) {
      return !set.indices.empty() && set.in_overlay == overlay && (overlay || set.under_ranked_spheres == under);
    };
    if (std::none_of(scene.lines.begin(), scene.lines.end(), drawn))
      return;
    gl.UseProgram(line_program_);
    set_matrices(line_program_, model_view, projection);
    if (id_mode_) gl.Disable(GL_BLEND);
    else gl.Enable(GL_BLEND);
    gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    for (const LineSet& set : scene.lines) {
      stop::check();
      if (!drawn(set)) continue;
      bind_positions_and_colors(set.positions, set.colors);
      gl.LineWidth(std::clamp(set.width * static_cast<float>(kSupersampling), 1.0f, max_line_width_));
      upload(GL_ELEMENT_ARRAY_BUFFER, index_buffer_, set.indices);
      if (set.over_all) gl.Disable(GL_DEPTH_TEST);
      gl.DrawElements(GL_LINES, static_cast<GLsizei>(set.indices.size()), GL_UNSIGNED_INT, nullptr);
      if (set.over_all) gl.Enable(GL_DEPTH_TEST);
    }
    gl.Disable(GL_BLEND);
  }

  // Reads the supersampled frame back into supersampled_pixels_ (on
  // llvmpipe a plain copy, far cheaper than a GPU-side downsampling blit).
  void read_back(int width, int height) {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, supersampled_framebuffer_);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    const int ss_width = kSupersampling * width, ss_height = kSupersampling * height;
    supersampled_pixels_.resize(4 * static_cast<std::size_t>(ss_width) * static_cast<std::size_t>(ss_height));
    gl.ReadPixels(0, 0, ss_width, ss_height, GL_RGBA, GL_UNSIGNED_BYTE, supersampled_pixels_.data());
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  // The frame read back and box-filtered down.
  Image resolve(int width, int height) {
    read_back(width, height);
    return box_filter_2x2(supersampled_pixels_, width, height);
  }

  // The id frame read back: each output pixel (rows top-down) the id of
  // most of its 2x2 samples, the first sample's on a tie.
  IdImage resolve_ids(int width, int height) {
    read_back(width, height);
    static_assert(kSupersampling == 2);
    IdImage ids{width, height, 0, 0,
                std::vector<std::uint32_t>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
    const std::size_t ss_row = 8 * static_cast<std::size_t>(width);
    auto sample = [&](const std::uint8_t* p) { return id_of(Rgba8{p[0], p[1], p[2], 255}); };
    for (int y = 0; y < height; ++y) {
      const std::uint8_t* r0 = supersampled_pixels_.data() + ss_row * (2 * static_cast<std::size_t>(height - 1 - y));
      const std::uint8_t* r1 = r0 + ss_row;
      for (int x = 0; x < width; ++x) {
        const std::size_t i = 8 * static_cast<std::size_t>(x);
        const std::uint32_t s[4] = {sample(r1 + i), sample(r1 + i + 4), sample(r0 + i), sample(r0 + i + 4)};
        std::uint32_t best = s[0];
        int best_count = 0;
        for (int a = 0; a < 4; ++a) {
          const int count = static_cast<int>(std::count(s, s + 4, s[a]));
          if (count > best_count) best = s[a], best_count = count;
        }
        ids.ids[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] = best;
      }
    }
    return ids;
  }

  // OSMesa needs a client buffer to make a context current; every frame is
  // drawn into framebuffer objects instead, so this one stays tiny.
  static constexpr int kDefaultSize = 4;
  std::array<std::uint8_t, 4 * kDefaultSize * kDefaultSize> default_buffer_{};

  // Loaded before anything else (the first renderer loads libOSMesa).
  const GlApi& gl = gl_api();
  OSMesaContext context_ = nullptr;
  GLuint triangle_program_ = 0, line_program_ = 0, sphere_program_ = 0;
  GLuint vertex_array_ = 0;
  GLuint position_buffer_ = 0, normal_buffer_ = 0, color_buffer_ = 0, index_buffer_ = 0, scalar_buffer_ = 0;
  GLuint supersampled_framebuffer_ = 0;
  GLuint supersampled_color_ = 0, supersampled_depth_ = 0;
  std::vector<std::uint8_t> supersampled_pixels_;  // read-back buffer, reused by every frame
  int framebuffer_width_ = 0, framebuffer_height_ = 0;
  GLint max_renderbuffer_size_ = 0;
  float max_line_width_ = 1.0f;
  bool id_mode_ = false;  // the frame being drawn is an id image (render_ids)
};

}  // namespace

std::unique_ptr<Renderer> make_osmesa_renderer() { return std::make_unique<OsmesaRenderer>(); }

}  // namespace hq
