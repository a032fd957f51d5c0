#pragma once
// Pixel probes shared by the render tests.

#include <filesystem>
#include <fstream>

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

// Writes image as PNG for a person to look at (or as a golden image).
inline void write_png_file(const Image& image, const std::filesystem::path& path) {
  const std::string bytes = encode_png(image);
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace hq::test
