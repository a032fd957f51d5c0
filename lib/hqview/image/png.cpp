#include "hqview/image/png.h"

#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hqview/core/error.h"

namespace hq {
namespace {

void check_image(const Image& image, const std::string& what) {
  const std::size_t expected =
      4 * static_cast<std::size_t>(std::max(image.width, 0)) * static_cast<std::size_t>(std::max(image.height, 0));
  if (image.width <= 0 || image.height <= 0 || image.rgba.size() != expected)
    throw Error("cannot write " + what + ": malformed image (" + std::to_string(image.width) + "x" +
                std::to_string(image.height) + ", " + std::to_string(image.rgba.size()) + " bytes)");
}

bool is_opaque(const Image& image) {
  for (std::size_t i = 3; i < image.rgba.size(); i += 4)
    if (image.rgba[i] != 255) return false;
  return true;
}

void put_u32(std::string& out, std::uint32_t v) {
  const char bytes[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                         static_cast<char>(v)};
  out.append(bytes, 4);
}

// One chunk: length, type, data, and the CRC-32 of type and data.
void put_chunk(std::string& out, const char (&type)[5], const unsigned char* data, std::size_t size) {
  put_u32(out, static_cast<std::uint32_t>(size));
  const std::size_t type_at = out.size();
  out.append(type, 4);
  out.append(reinterpret_cast<const char*>(data), size);
  put_u32(out, libdeflate_crc32(0, out.data() + type_at, 4 + size));
}

// libdeflate's compressor, made for each image (a few hundred kilobytes,
// far cheaper than the image's compression): no state per thread.
struct FreeCompressor {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};
using Compressor = std::unique_ptr<libdeflate_compressor, FreeCompressor>;

}  // namespace

std::string encode_png(const Image& image) {
  check_image(image, "a PNG image");
  // An opaque image (every view and chart is: figures have a background) is
  // written as RGB: a quarter less to filter and compress, smaller files,
  // and it decodes to the same pixels.
  const bool opaque = is_opaque(image);
  const std::size_t channels = opaque ? 3 : 4;
  const auto width = static_cast<std::size_t>(image.width), height = static_cast<std::size_t>(image.height);
  const std::size_t row_bytes = channels * width;
  // Every row with the "up" filter (type 2: each byte minus the one above
  // it, the row above the first being zeros): on rendered views as small as
  // an adaptive choice of filter, at a fraction of its cost.
  std::vector<unsigned char> filtered((row_bytes + 1) * height);
  for (std::size_t y = 0; y < height; ++y) {
    unsigned char* out = filtered.data() + y * (row_bytes + 1);
    *out++ = 2;
    const std::uint8_t* row = image.rgba.data() + 4 * width * y;
    const std::uint8_t* above = y == 0 ? nullptr : row - 4 * width;
    for (std::size_t x = 0; x < width; ++x)
      for (std::size_t c = 0; c < channels; ++c)
        *out++ = static_cast<unsigned char>(row[4 * x + c] - (above ? above[4 * x + c] : 0));
  }
  // Level 2: on the rendered views 20 % faster than zlib's level 1 and
  // files 10 % smaller (docs/performance.md).
  const Compressor c(libdeflate_alloc_compressor(2));
  if (!c) throw Error("cannot encode a PNG image: out of memory for the compressor");
  std::vector<unsigned char> zlib(libdeflate_zlib_compress_bound(c.get(), filtered.size()));
  const std::size_t zlib_size =
      libdeflate_zlib_compress(c.get(), filtered.data(), filtered.size(), zlib.data(), zlib.size());
  if (zlib_size == 0) throw Error("cannot encode a PNG image: compression failed");

  std::string png;
  png.reserve(zlib_size + 64);
  png.append("\x89PNG\r\n\x1a\n", 8);
  std::array<unsigned char, 13> header{};
  for (int k = 0; k < 4; ++k) {
    header[static_cast<std::size_t>(k)] = static_cast<unsigned char>(width >> (24 - 8 * k));
    header[static_cast<std::size_t>(4 + k)] = static_cast<unsigned char>(height >> (24 - 8 * k));
  }
  header[8] = 8;                 // bits per channel
  header[9] = opaque ? 2 : 6;    // colour type: RGB or RGBA
  // header[10..12]: deflate, adaptive filtering (filter method 0), no interlace
  put_chunk(png, "IHDR", header.data(), header.size());
  // No time, text or gamma chunks: the same image gives the same bytes. The
  // zlib stream in IDAT chunks of at most 1 GiB (a chunk holds < 2^31 bytes).
  constexpr std::size_t kMaxChunk = std::size_t{1} << 30;
  for (std::size_t at = 0; at < zlib_size; at += kMaxChunk)
    put_chunk(png, "IDAT", zlib.data() + at, std::min(kMaxChunk, zlib_size - at));
  put_chunk(png, "IEND", nullptr, 0);
  return png;
}

}  // namespace hq
