#pragma once
// The viewer's data.js read back in tests: the JSON object and its base64
// arrays (report/viewer.h writes them).

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "hqview/report/viewer.h"

namespace hq::test {

inline std::vector<unsigned char> decode_base64(const std::string& s) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::vector<unsigned char> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    const int v = value(c);
    if (v < 0) break;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((acc >> bits) & 0xff));
    }
  }
  return out;
}

// A base64 array of data.js as values of type T.
template <class T>
std::vector<T> array_of(const nlohmann::json& b64) {
  const auto bytes = decode_base64(b64.get<std::string>());
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
  return v;
}

// data.js's object (window.HQ_VIEWER_DATA).
inline nlohmann::json data_of(const ReportModel& model) {
  for (const ViewerFile& f : viewer_files(model))
    if (f.relative_path == "viewer/data.js") {
      const std::string prefix = "window.HQ_VIEWER_DATA = ";
      EXPECT_EQ(f.text.rfind(prefix, 0), 0u);
      return nlohmann::json::parse(f.text.substr(prefix.size(), f.text.size() - prefix.size() - 2));
    }
  ADD_FAILURE() << "no data.js";
  return {};
}

}  // namespace hq::test
