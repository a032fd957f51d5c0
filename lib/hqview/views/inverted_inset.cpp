#include "hqview/views/inverted_inset.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "hqview/core/box3.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/cell_faces.h"

namespace hq {
namespace {

constexpr Rgba8 kInsetEdgeColor{30, 30, 40, 255};  // the inverted cells' edges

// The corner rectangles of `view` of size w x h, `margin` pixels in, in the
// tie order bottom right, bottom left, top right, top left.
std::array<PixelRect, 4> corner_rects(const PixelRect& view, int w, int h, int margin) {
  const int left = view.x + margin, right = view.x + view.width - margin - w;
  const int top = view.y + margin, bottom = view.y + view.height - margin - h;
  return {PixelRect{right, bottom, w, h}, PixelRect{left, bottom, w, h}, PixelRect{right, top, w, h},
          PixelRect{left, top, w, h}};
}

bool overlaps(const PixelRect& a, const PixelRect& b) {
  return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;
}

// Figure pixels in `rect` unlike the background (the model, its edges and rings).
long model_pixels(const Image& figure, const PixelRect& rect, Rgba8 background) {
  long n = 0;
  for (int y = std::max(0, rect.y); y < std::min(figure.height, rect.y + rect.height); ++y)
    for (int x = std::max(0, rect.x); x < std::min(figure.width, rect.x + rect.width); ++x) {
      const std::uint8_t* p = &figure.rgba[pixel_offset(figure, x, y)];
      n += p[0] != background.r || p[1] != background.g || p[2] != background.b;
    }
  return n;
}

// Whether the ring (with its halo) touches the rectangle.
bool ring_touches(const InvertedCallout& c, const PixelRect& r, double pad) {
  const double nx = std::clamp(c.x, static_cast<double>(r.x), static_cast<double>(r.x + r.width));
  const double ny = std::clamp(c.y, static_cast<double>(r.y), static_cast<double>(r.y + r.height));
  return std::hypot(nx - c.x, ny - c.y) <= c.radius + pad;
}

int caption_size(int text_size) { return std::max(9, static_cast<int>(std::lround(0.75 * text_size))); }

}  // namespace

std::vector<Index> cells_touching(const HexMesh& mesh, std::span<const Index> cells) {
  const Index num_cells = num_volume_cells(mesh);
  std::vector<char> is_cell(static_cast<std::size_t>(num_cells), 0);
  std::vector<char> is_vertex(mesh.points.size(), 0);
  for (Index c : cells) {
    if (c < 0 || c >= num_cells) continue;
    is_cell[static_cast<std::size_t>(c)] = 1;
    const CellRef ref = volume_cell(mesh, c);
    for (int k = 0; k < ref.num_corners; ++k) is_vertex[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])] = 1;
  }
  std::vector<Index> out;
  for (Index c = 0; c < num_cells; ++c) {
    if (is_cell[static_cast<std::size_t>(c)]) continue;
    const CellRef ref = volume_cell(mesh, c);
    for (int k = 0; k < ref.num_corners; ++k)
      if (is_vertex[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])]) {
        out.push_back(c);
        break;
      }
  }
  return out;
}

Scene inverted_inset_scene(const HexMesh& mesh, std::span<const Index> cells, std::span<const Index> neighbours) {
  const Index num_cells = num_volume_cells(mesh);
  Box3 box;
  bool any = false;
  auto each_corner = [&](std::span<const Index> ids, auto&& f) {
    for (Index c : ids) {
      if (c < 0 || c >= num_cells) continue;
      const CellRef ref = volume_cell(mesh, c);
      for (int k = 0; k < ref.num_corners; ++k) f(mesh.points[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])]);
    }
  };
  auto grow = [&](const Vec3& p) {
    if (!any) box.lo = box.hi = p;
    any = true;
    box.lo = {std::min(box.lo.x, p.x), std::min(box.lo.y, p.y), std::min(box.lo.z, p.z)};
    box.hi = {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y), std::max(box.hi.z, p.z)};
  };
  each_corner(cells, grow);
  each_corner(neighbours, grow);
  Scene scene;
  scene.origin = any ? 0.5 * (box.lo + box.hi) : Vec3{};
  const Vec3 origin = scene.origin;

  TriangleSet faces;  // the inverted cells, every face (two triangles per quad)
  LineSet edges;      // their edges
  edges.width = 2.0f;
  LineSet cage;       // the neighbours' edges
  cage.width = 1.0f;
  const Rgba8 blue = to_rgba8(kInvertedColor);
  for (Index c : cells) {
    if (c < 0 || c >= num_cells) continue;
    const CellRef ref = volume_cell(mesh, c);
    for_each_face_of(ref, [&](const std::array<Index, 4>& v, int size) {
      const auto base = static_cast<std::uint32_t>(faces.positions.size());
      for (int i = 0; i < size; ++i) {
        faces.positions.push_back(to_vec3f(mesh.points[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])] - origin));
        faces.colors.push_back(blue);
      }
      faces.indices.insert(faces.indices.end(), {base, base + 1, base + 2});
      if (size == 4) faces.indices.insert(faces.indices.end(), {base, base + 2, base + 3});
    });
    for_each_edge_of(ref, [&](Index a, Index b) {
      const auto base = static_cast<std::uint32_t>(edges.positions.size());
      for (Index v : {a, b}) {
        edges.positions.push_back(to_vec3f(mesh.points[static_cast<std::size_t>(v)] - origin));
        edges.colors.push_back(kInsetEdgeColor);
      }
      edges.indices.insert(edges.indices.end(), {base, base + 1});
    });
  }
  for (Index c : neighbours) {
    if (c < 0 || c >= num_cells) continue;
    for_each_edge_of(volume_cell(mesh, c), [&](Index a, Index b) {
      const auto base = static_cast<std::uint32_t>(cage.positions.size());
      for (Index v : {a, b}) {
        cage.positions.push_back(to_vec3f(mesh.points[static_cast<std::size_t>(v)] - origin));
        cage.colors.push_back(kInsetNeighbourColor);
      }
      cage.indices.insert(cage.indices.end(), {base, base + 1});
    });
  }
  scene.triangles.push_back(std::move(faces));
  scene.lines.push_back(std::move(cage));
  scene.lines.push_back(std::move(edges));
  return scene;
}

std::vector<InvertedInset> plan_inverted_insets(const HexMesh& mesh, std::vector<InvertedCallout>& callouts,
                                                const PixelRect& view, const Camera& view_camera, int text_size) {
  std::vector<InvertedInset> insets;
  const int w = static_cast<int>(std::lround(kInsetWidthFraction * view.width));
  const int h = static_cast<int>(std::lround(kInsetHeightFraction * view.height));
  const int caption_height = 2 * static_cast<int>(std::lround(1.3 * caption_size(text_size))) + 8;
  if (w < 40 || h < caption_height + 40) return insets;
  for (std::size_t i = 0; i < callouts.size() && static_cast<int>(insets.size()) < kMaxInvertedInsets; ++i) {
    if (callout_in_sight(callouts[i]) || callouts[i].cells.empty()) continue;
    InvertedInset inset;
    inset.callout = i;
    inset.letter = std::string(1, static_cast<char>('A' + insets.size()));
    inset.rect = {view.x, view.y, w, h};
    inset.picture = {view.x + 2, view.y + caption_height, w - 4, h - caption_height - 2};
    inset.cells = callouts[i].cells;
    std::sort(inset.cells.begin(), inset.cells.end());
    inset.neighbours = cells_touching(mesh, inset.cells);
    std::vector<Vec3> points;
    for (std::span<const Index> ids : {std::span<const Index>(inset.cells), std::span<const Index>(inset.neighbours)})
      for (Index c : ids) {
        const CellRef ref = volume_cell(mesh, c);
        for (int k = 0; k < ref.num_corners; ++k) points.push_back(mesh.points[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])]);
      }
    inset.camera = fit_camera_to_points(points, view_camera.target - view_camera.eye,
                                        static_cast<double>(inset.picture.width) / inset.picture.height,
                                        {.up = view_camera.up, .fov_y_degrees = view_camera.fov_y_degrees,
                                         .margin = 0.1, .is_perspective = view_camera.is_perspective});
    callouts[i].inset = inset.letter;
    insets.push_back(std::move(inset));
  }
  return insets;
}

std::vector<Image> render_inverted_insets(const HexMesh& mesh, std::span<const InvertedInset> insets,
                                          Renderer& renderer) {
  std::vector<Image> pictures;
  for (const InvertedInset& inset : insets)
    pictures.push_back(renderer.render(inverted_inset_scene(mesh, inset.cells, inset.neighbours), inset.camera,
                                       inset.picture.width, inset.picture.height));
  return pictures;
}

void place_inverted_insets(std::vector<InvertedInset>& insets, std::span<const InvertedCallout> callouts,
                           const Image& figure, const PixelRect& view, Rgba8 background, const AnnotationStyle& style) {
  const int margin = std::max(4, static_cast<int>(std::lround(12 * style.scale)));
  std::array<bool, 4> used{};
  std::vector<PixelRect> placed;
  for (InvertedInset& inset : insets) {
    const int w = inset.rect.width, h = inset.rect.height;
    const std::array<PixelRect, 4> corners = corner_rects(view, w, h, margin);
    // The free corner covering the fewest model pixels, ringless if it can.
    long best_cost = std::numeric_limits<long>::max();
    int best = -1;
    for (int k = 0; k < 4; ++k) {
      if (used[static_cast<std::size_t>(k)]) continue;
      const PixelRect& r = corners[static_cast<std::size_t>(k)];
      bool clash = false;
      for (const PixelRect& other : placed) clash = clash || overlaps(other, r);
      if (clash) continue;
      long cost = model_pixels(figure, r, background);
      for (const InvertedCallout& c : callouts)
        if (ring_touches(c, r, 4.0)) cost += static_cast<long>(w) * h;  // a ring under the inset: last resort
      if (cost < best_cost) best_cost = cost, best = k;
    }
    if (best < 0) best = 0;  // four corners, at most kMaxInvertedInsets insets: never reached
    used[static_cast<std::size_t>(best)] = true;
    const PixelRect r = corners[static_cast<std::size_t>(best)];
    const int dx = r.x - inset.rect.x, dy = r.y - inset.rect.y;
    inset.rect = r;
    inset.picture.x += dx;
    inset.picture.y += dy;
    placed.push_back(r);
  }
}

void draw_inverted_insets(Image& figure, std::span<const InvertedInset> insets, std::span<const Image> pictures,
                          std::span<const InvertedCallout> callouts, const std::string& noun, int text_size,
                          const AnnotationStyle& style) {
  const int caption = caption_size(text_size);
  const int pitch = static_cast<int>(std::lround(1.3 * caption));
  for (std::size_t i = 0; i < insets.size() && i < pictures.size(); ++i) {
    const InvertedInset& inset = insets[i];
    const PixelRect& r = inset.rect;
    fill_rect(figure, r, {255, 255, 255, 255});
    paste(figure, pictures[i], inset.picture.x, inset.picture.y);
    // The caption: what it shows and what the colours are.
    InvertedCallout named = callouts[inset.callout];
    named.inset.clear();
    named.num_more_cells = 0;
    const std::string line1 = inset.letter + ": " + inverted_callout_label(named, noun, 1.0);
    const std::string line2 = "blue: inverted · grey: their neighbours";
    const int max_width = r.width - 12;
    draw_text(figure, r.x + 6, r.y + 4 + pitch - caption / 4, ellipsize(line1, caption, max_width, style), caption, style);
    draw_text(figure, r.x + 6, r.y + 4 + 2 * pitch - caption / 4, ellipsize(line2, caption, max_width, style), caption,
              style);
    fill_rect(figure, {r.x, inset.picture.y - 2, r.width, 1}, kInsetFrameColor);
    for (int t = 0; t < 2; ++t) {
      fill_rect(figure, {r.x + t, r.y, 1, r.height}, kInsetFrameColor);
      fill_rect(figure, {r.x + r.width - 1 - t, r.y, 1, r.height}, kInsetFrameColor);
      fill_rect(figure, {r.x, r.y + t, r.width, 1}, kInsetFrameColor);
      fill_rect(figure, {r.x, r.y + r.height - 1 - t, r.width, 1}, kInsetFrameColor);
    }
  }
}

}  // namespace hq
