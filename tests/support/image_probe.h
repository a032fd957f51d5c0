#pragma once
// Pixel probes shared by the render tests.

#include "hqview/render/annotate.h"
#include "hqview/render/color.h"
#include "hqview/render/image.h"

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

}  // namespace hq::test
