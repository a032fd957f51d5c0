#pragma once
// SHA-256 (FIPS 180-4) as lowercase hex: the input fingerprint of report.json
// (`input.mesh.sha256`) and of batch --resume. Incremental, so a file is
// hashed in chunks without being read whole.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace hq {

class Sha256 {
 public:
  Sha256();
  void update(std::string_view bytes);
  std::string hex() const;  // of everything given so far; the object stays usable

 private:
  std::array<std::uint32_t, 8> state_;
  std::array<unsigned char, 64> block_{};
  std::size_t pending_ = 0;  // bytes in block_
  std::uint64_t total_ = 0;  // bytes given
};

std::string sha256_hex(std::string_view bytes);

// Hashes a file in 1 MiB chunks; nullopt when it cannot be opened or read.
std::optional<std::string> sha256_file_hex(const std::filesystem::path& file);

}  // namespace hq
