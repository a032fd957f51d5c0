#pragma once
// SHA-256 (FIPS 180-4) of a byte string, as lowercase hex: the input
// fingerprint of report.json (`input.mesh.sha256`) and of batch --resume.

#include <string>
#include <string_view>

namespace hq {

std::string sha256_hex(std::string_view bytes);

}  // namespace hq
