#include "hqview/image/png.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
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

// Writes image through output (opened on name, a proxy's).
void write_with(OIIO::ImageOutput& output, const Image& image, const std::string& name, const std::string& what) {
  OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
  // Fast zlib level and libpng's "up" filter alone: on rendered views
  // about half the encoding time of the adaptive filter choice, files as
  // small or smaller.
  spec.attribute("png:compressionLevel", 1);
  spec.attribute("png:filter", 0x20);  // PNG_FILTER_UP
  // Image holds straight alpha: without this OpenImageIO would divide every
  // pixel by its alpha, taking the data for premultiplied.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!output.open(name, spec) || !output.write_image(OIIO::TypeDesc::UINT8, image.rgba.data()) || !output.close())
    throw Error("cannot write " + what + ": " + output.geterror());
}

}  // namespace

std::string encode_png(const Image& image) {
  check_image(image, "a PNG image");
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create("image.png", &proxy);
  if (!output) throw Error("cannot encode a PNG image: no PNG support in OpenImageIO: " + OIIO::geterror());
  if (!output->set_ioproxy(&proxy)) throw Error("cannot encode a PNG image in memory: " + output->geterror());
  write_with(*output, image, "image.png", "a PNG image");
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace hq
