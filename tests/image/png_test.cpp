// PNG encoding: the bytes decode back to the same straight-alpha pixels.
#include "hqview/image/png.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "hqview/core/error.h"

namespace hq {
namespace {

TEST(EncodePng, RejectsMalformedImages) {
  EXPECT_THROW(encode_png(Image{2, 2, std::vector<std::uint8_t>(15)}), Error);
  EXPECT_THROW(encode_png(Image{0, 2, {}}), Error);
}

TEST(EncodePng, DecodesToTheSamePixels) {
  // Half-transparent pixels catch a premultiplication on the way.
  Image image{3, 2, {}};
  for (int i = 0; i < 6; ++i) {
    const auto v = static_cast<std::uint8_t>(40 * i);
    image.rgba.insert(image.rgba.end(),
                      {v, static_cast<std::uint8_t>(255 - v), 7, static_cast<std::uint8_t>(30 + 40 * i)});
  }
  const std::string bytes = encode_png(image);
  ASSERT_EQ(bytes.substr(1, 3), "PNG");
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "hqview_png_test.png";
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(path.string(), &config);
  ASSERT_TRUE(input) << OIIO::geterror();
  const OIIO::ImageSpec& spec = input->spec();
  EXPECT_EQ(spec.width, 3);
  EXPECT_EQ(spec.height, 2);
  std::vector<std::uint8_t> decoded(4 * 6);
  ASSERT_TRUE(input->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, decoded.data()));
  EXPECT_EQ(decoded, image.rgba);
}

// An opaque image is written as RGB (colour type 2 in IHDR) and decodes to
// the same pixels with alpha 255; one translucent pixel keeps RGBA (type 6).
TEST(EncodePng, OpaqueImagesAreWrittenAsRgb) {
  Image image{5, 3, {}};
  for (int i = 0; i < 15; ++i)
    image.rgba.insert(image.rgba.end(), {static_cast<std::uint8_t>(17 * i), static_cast<std::uint8_t>(250 - 9 * i),
                                         static_cast<std::uint8_t>(i), 255});
  const std::string bytes = encode_png(image);
  ASSERT_GT(bytes.size(), 26u);
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(static_cast<int>(bytes[25]), 2) << "colour type RGB";
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "hqview_png_rgb_test.png";
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  auto input = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(input) << OIIO::geterror();
  EXPECT_EQ(input->spec().nchannels, 3);
  std::vector<std::uint8_t> rgb(3 * 15);
  ASSERT_TRUE(input->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
  for (std::size_t p = 0; p < 15; ++p)
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(rgb[3 * p + c], image.rgba[4 * p + c]);
  image.rgba[4 * 7 + 3] = 254;
  EXPECT_EQ(static_cast<int>(encode_png(image)[25]), 6) << "colour type RGBA";
}

}  // namespace
}  // namespace hq
