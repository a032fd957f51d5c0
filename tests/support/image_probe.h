#pragma once
// Pixel probes shared by the render tests.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "hqview/image/color.h"
#include "hqview/image/image.h"
#include "hqview/image/png.h"
#include "hqview/render/annotate.h"

namespace hq::test {

inline const Rgba8 kWhite{255, 255, 255, 255};

inline Rgba8 pixel_at(const Image& image, int x, int y) {
  const std::uint8_t* p = image.rgba.data() + pixel_offset(image, x, y);
  return {p[0], p[1], p[2], p[3]};
}

// Pixels of rectangle r whose colour differs from `background`.
inline int count_differing(const Image& image, const PixelRect& r, Rgba8 background) {
  int n = 0;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) n += pixel_at(image, x, y) != background;
  return n;
}

// The pixels of rectangle r that have exactly `color` (alpha aside) and lie
// within `within` pixels of (x, y) (anywhere in r by default): how many, and
// their centre.
struct ColorPixels {
  int count = 0;
  double cx = 0, cy = 0;
};
inline ColorPixels pixels_of_color(const Image& image, const PixelRect& r, Rgba8 color, double x = 0, double y = 0,
                                   double within = std::numeric_limits<double>::infinity()) {
  ColorPixels found;
  for (int py = r.y; py < r.y + r.height; ++py)
    for (int px = r.x; px < r.x + r.width; ++px) {
      const Rgba8 p = pixel_at(image, px, py);
      if (p.r != color.r || p.g != color.g || p.b != color.b) continue;
      if (std::isfinite(within) && std::hypot(px + 0.5 - x, py + 0.5 - y) > within) continue;
      ++found.count;
      found.cx += px + 0.5;
      found.cy += py + 0.5;
    }
  if (found.count > 0) found.cx /= found.count, found.cy /= found.count;
  return found;
}

// Writes image as PNG for a person to look at (or as a golden image).
inline void write_png_file(const Image& image, const std::filesystem::path& path) {
  const std::string bytes = encode_png(image);
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace hq::test
