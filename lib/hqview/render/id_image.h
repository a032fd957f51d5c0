#pragma once
// Id images (issue 44: "a label must point at a visible part of its own
// glyph"): per pixel, which object is visible there. A renderer draws an
// id-coded scene (every colour an id, id_color) with the view's camera and
// depth test but no lighting, blending or anti-aliasing
// (Renderer::render_ids); views turn ids back into glyphs, markers, edges.

#include <cstdint>
#include <vector>

#include "hqview/image/color.h"

namespace hq {

// Ids of 24 bits, coded in a colour's red (low byte), green and blue.
inline constexpr std::uint32_t kMaxId = 0xffffffu;
inline constexpr Rgba8 id_color(std::uint32_t id) {
  return {static_cast<std::uint8_t>(id & 0xffu), static_cast<std::uint8_t>((id >> 8) & 0xffu),
          static_cast<std::uint8_t>((id >> 16) & 0xffu), 255};
}
inline constexpr std::uint32_t id_of(const Rgba8& c) {
  return static_cast<std::uint32_t>(c.r) | (static_cast<std::uint32_t>(c.g) << 8) |
         (static_cast<std::uint32_t>(c.b) << 16);
}

// width x height ids, rows top-down; pixel (x, y) of the image is pixel
// (x + x0, y + y0) of the figure it belongs to (figure pixels, as labels use).
struct IdImage {
  int width = 0, height = 0;
  int x0 = 0, y0 = 0;
  std::vector<std::uint32_t> ids;
  bool empty() const { return ids.empty(); }
  // The id at figure pixel (x, y); outside the image: outside.
  std::uint32_t at(int x, int y, std::uint32_t outside = 0) const {
    const int u = x - x0, v = y - y0;
    if (u < 0 || v < 0 || u >= width || v >= height) return outside;
    return ids[static_cast<std::size_t>(v) * static_cast<std::size_t>(width) + static_cast<std::size_t>(u)];
  }
};

}  // namespace hq
