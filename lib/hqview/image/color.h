#pragma once
// Colours: Color (float sRGB, what colour maps return) and Rgba8 (packed, what
// scenes and images store).

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace hq {

// A colour with sRGB-encoded components and straight alpha, each in [0, 1].
struct Color {
  float r = 0.0f, g = 0.0f, b = 0.0f, a = 1.0f;
};

// A colour packed as 4 bytes (sRGB, straight alpha).
struct Rgba8 {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
};

constexpr bool operator==(const Rgba8& p, const Rgba8& q) { return p.r == q.r && p.g == q.g && p.b == q.b && p.a == q.a; }
constexpr bool operator!=(const Rgba8& p, const Rgba8& q) { return !(p == q); }

// Rounds each component to the nearest byte; values outside [0, 1] (and NaN,
// as 0) are clamped.
inline Rgba8 to_rgba8(const Color& c) {
  auto byte = [](float v) {
    if (!(v > 0.0f)) return std::uint8_t{0};
    return static_cast<std::uint8_t>(std::lround(std::min(v, 1.0f) * 255.0f));
  };
  return {byte(c.r), byte(c.g), byte(c.b), byte(c.a)};
}

inline Color to_color(const Rgba8& p) {
  return {p.r / 255.0f, p.g / 255.0f, p.b / 255.0f, p.a / 255.0f};
}

}  // namespace hq
