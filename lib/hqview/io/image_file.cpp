#include "hqview/io/image_file.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>
#include <string>

#include "hqview/core/error.h"

namespace hq {

void write_png(const Image& image, const std::filesystem::path& path) {
  const std::size_t expected = 4 * static_cast<std::size_t>(std::max(image.width, 0)) *
                               static_cast<std::size_t>(std::max(image.height, 0));
  if (image.width <= 0 || image.height <= 0 || image.rgba.size() != expected)
    throw Error("cannot write " + path.string() + ": malformed image (" + std::to_string(image.width) + "x" +
                std::to_string(image.height) + ", " + std::to_string(image.rgba.size()) + " bytes)");
  std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create("png");
  if (!output) throw Error("cannot write " + path.string() + ": no PNG support in OpenImageIO: " + OIIO::geterror());
  OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("png:compressionLevel", 1);
  if (!output->open(path.string(), spec) || !output->write_image(OIIO::TypeDesc::UINT8, image.rgba.data()) ||
      !output->close())
    throw Error("cannot write " + path.string() + ": " + output->geterror());
}

}  // namespace hq
