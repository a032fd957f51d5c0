#pragma once
// Writing rendered images to disk (PNG through OpenImageIO).

#include <filesystem>

#include "hqview/render/image.h"

namespace hq {

// Writes image as an 8-bit RGBA PNG (zlib level 1: 2-3x faster than the
// default for ~20% larger files). Throws Error when the image is malformed
// (rgba.size() != 4 * width * height, or empty) or the file cannot be written.
void write_png(const Image& image, const std::filesystem::path& path);

}  // namespace hq
