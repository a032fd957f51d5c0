// PNG encoding: the bytes decode back to the same straight-alpha pixels.
#include "hqview/image/png.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "hqview/core/error.h"

namespace hq {
namespace HQ_TEST_UNIT {

// PNG bytes written to a file and opened with OIIO (libpng underneath, which
// checks every chunk's CRC), alpha kept straight.
std::unique_ptr<OIIO::ImageInput> open_png(const std::string& bytes, const std::string& name) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  return OIIO::ImageInput::open(path.string(), &config);
}

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
  const auto input = open_png(bytes, "hqview_png_test.png");
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

// A larger image (rows of noise, runs and gradients, so that the "up"
// filter and the compressor see every kind of row) decodes to the same
// pixels through libpng (via OIIO), which checks every chunk's CRC; the
// bytes are the same on every call and on another thread.
TEST(EncodePng, LargeImagesRoundTripAndGiveTheSameBytes) {
  for (const bool opaque : {true, false}) {
    Image image{301, 77, {}};
    std::uint32_t state = 12345;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        state = state * 1664525u + 1013904223u;
        const auto noise = static_cast<std::uint8_t>(state >> 24);
        const auto r = static_cast<std::uint8_t>(y % 3 == 0 ? noise : x);
        const auto g = static_cast<std::uint8_t>(y % 3 == 1 ? noise : 255 - x);
        const auto b = static_cast<std::uint8_t>(y % 3 == 2 ? noise : x + y);
        const auto a = static_cast<std::uint8_t>(opaque ? 255 : (x * 7 + y) % 256);
        image.rgba.insert(image.rgba.end(), {r, g, b, a});
      }
    const std::string bytes = encode_png(image);
    EXPECT_EQ(static_cast<int>(bytes[25]), opaque ? 2 : 6);
    std::string other;
    std::thread([&] { other = encode_png(image); }).join();
    EXPECT_EQ(bytes, other) << "the same bytes on another thread";
    EXPECT_EQ(bytes, encode_png(image));
    const auto input = open_png(bytes, "hqview_png_large_test.png");
    ASSERT_TRUE(input) << OIIO::geterror();
    EXPECT_EQ(input->spec().width, 301);
    EXPECT_EQ(input->spec().height, 77);
    const int channels = opaque ? 3 : 4;
    ASSERT_EQ(input->spec().nchannels, channels);
    std::vector<std::uint8_t> decoded(static_cast<std::size_t>(channels) * 301 * 77), expected;
    ASSERT_TRUE(input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, decoded.data())) << input->geterror();
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
      if (i % 4 < static_cast<std::size_t>(channels)) expected.push_back(image.rgba[i]);
    EXPECT_EQ(decoded, expected) << (opaque ? "RGB" : "RGBA");
  }
}

}  // namespace
}  // namespace hq
