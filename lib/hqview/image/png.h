#pragma once
// PNG encoding of rendered images (the chunks written here, the zlib
// stream by libdeflate; in memory: the bundle writer puts the bytes on disk).

#include <string>

#include "hqview/image/image.h"

namespace hq {

// The 8-bit PNG of image, RGB when every alpha is 255, else RGBA (the "up"
// filter, libdeflate level 2: far faster than libpng's defaults, files about
// as small). The same image gives the same bytes. Thread-safe: views are
// encoded on worker threads while the next frame renders. Throws Error when
// the image is malformed (rgba.size() != 4 * width * height, or empty).
std::string encode_png(const Image& image);

}  // namespace hq
