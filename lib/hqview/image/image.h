#pragma once
// Image: an 8-bit RGBA raster, the output of every renderer and the input of
// annotate and io/image_file.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hq {

// width x height pixels, rows top-down, 4 bytes per pixel (R, G, B, A, sRGB,
// straight alpha): pixel (x, y) starts at rgba[4 * (y * width + x)].
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};

// Byte offset of pixel (x, y) in Image::rgba. No bounds check.
inline std::size_t pixel_offset(const Image& image, int x, int y) {
  return 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x));
}

}  // namespace hq
