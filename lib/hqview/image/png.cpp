#include "hqview/image/png.h"

#include <png.h>

#include <algorithm>
#include <string>

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

// libpng reports errors through a callback that must not return: it longjmps
// back into encode_png, which throws from there (never through libpng).
[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  *static_cast<std::string*>(png_get_error_ptr(png)) = message;
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

void append_bytes(png_structp png, png_bytep data, png_size_t size) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), size);
}

void no_flush(png_structp) {}

bool is_opaque(const Image& image) {
  for (std::size_t i = 3; i < image.rgba.size(); i += 4)
    if (image.rgba[i] != 255) return false;
  return true;
}

}  // namespace

std::string encode_png(const Image& image) {
  check_image(image, "a PNG image");
  std::string bytes, error;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, on_png_error, on_png_warning);
  if (png == nullptr) throw Error("cannot encode a PNG image: libpng could not start");
  png_infop info = png_create_info_struct(png);
  // Nothing with a destructor is created between setjmp and the longjmp.
  if (info == nullptr || setjmp(png_jmpbuf(png)) != 0) {
    png_destroy_write_struct(&png, &info);
    throw Error("cannot encode a PNG image: " + (error.empty() ? std::string("libpng failed") : error));
  }
  png_set_write_fn(png, &bytes, append_bytes, no_flush);
  // Fast zlib level and the "up" filter alone: on rendered views about half
  // the encoding time of libpng's adaptive filter choice, files as small.
  png_set_compression_level(png, 1);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  // An opaque image (every view and chart is: figures have a background) is
  // written as RGB, libpng dropping each pixel's alpha byte: a quarter less
  // to filter and compress, and smaller files; it decodes to the same pixels.
  const bool opaque = is_opaque(image);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               opaque ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
               PNG_FILTER_TYPE_BASE);
  png_write_info(png, info);  // no time, text or gamma chunks: the same image gives the same bytes
  if (opaque) png_set_filler(png, 0, PNG_FILLER_AFTER);  // on writing: strip the 4th byte of each pixel
  const std::size_t row_bytes = 4 * static_cast<std::size_t>(image.width);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, image.rgba.data() + static_cast<std::size_t>(y) * row_bytes);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return bytes;
}

}  // namespace hq
