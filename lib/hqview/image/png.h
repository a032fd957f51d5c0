#pragma once
// PNG encoding of rendered images (libpng, in memory: the bundle
// writer puts the bytes on disk).

#include <string>

#include "hqview/image/image.h"

namespace hq {

// The 8-bit RGBA PNG of image (zlib level 1 and the "up" filter: far faster
// than libpng's defaults, files about as small). Thread-safe: views are
// encoded on worker threads while the next frame renders. Throws Error when
// the image is malformed (rgba.size() != 4 * width * height, or empty).
std::string encode_png(const Image& image);

}  // namespace hq
