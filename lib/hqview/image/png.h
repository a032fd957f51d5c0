#pragma once
// Writing rendered images to disk (PNG through OpenImageIO).

#include <filesystem>
#include <string>

#include "hqview/render/image.h"

namespace hq {

// Writes image as an 8-bit RGBA PNG (zlib level 1 and the "up" filter: far
// faster than libpng's defaults, files about as small). Throws Error when
// the image is malformed
// (rgba.size() != 4 * width * height, or empty) or the file cannot be written.
void write_png(const Image& image, const std::filesystem::path& path);

// The bytes write_png would write (thread-safe: views are encoded on worker
// threads while the next frame renders). Throws Error as write_png.
std::string encode_png(const Image& image);

}  // namespace hq
