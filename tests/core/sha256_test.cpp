#include "hqview/core/sha256.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace hq {
namespace HQ_TEST_UNIT {

// FIPS 180-4 examples and the padding boundaries (55, 56, 64 bytes).
TEST(Sha256, KnownDigests) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// Any split of the input into update() calls gives the one-shot digest.
TEST(Sha256, IncrementalEqualsOneShot) {
  std::string text;
  for (int i = 0; i < 300; ++i) text += static_cast<char>('a' + (i * 7) % 26);
  for (std::size_t first : {0u, 1u, 55u, 56u, 63u, 64u, 65u, 128u, 299u}) {
    for (std::size_t step : {1u, 3u, 64u, 100u}) {
      Sha256 sha;
      sha.update(std::string_view(text).substr(0, first));
      for (std::size_t at = first; at < text.size(); at += step) sha.update(std::string_view(text).substr(at, step));
      EXPECT_EQ(sha.hex(), sha256_hex(text)) << first << " " << step;
    }
  }
  Sha256 million;
  const std::string block(1000, 'a');
  for (int i = 0; i < 1000; ++i) million.update(block);
  EXPECT_EQ(million.hex(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// Files are hashed in 1 MiB chunks: a file over two chunks gives the FIPS digest.
TEST(Sha256, FileInChunks) {
  const auto path = std::filesystem::temp_directory_path() / ("hq_sha256_" + std::to_string(::getpid()));
  {
    std::ofstream out(path, std::ios::binary);
    out << std::string(1000000, 'a') << std::string(1000000, 'a') << std::string(500000, 'a');
  }
  Sha256 expected;
  for (int i = 0; i < 5; ++i) expected.update(std::string(500000, 'a'));
  EXPECT_EQ(sha256_file_hex(path), expected.hex());
  std::filesystem::remove(path);
  EXPECT_FALSE(sha256_file_hex(path).has_value());
  {
    std::ofstream out(path, std::ios::binary);
    out << "abc";
  }
  EXPECT_EQ(sha256_file_hex(path), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace hq
