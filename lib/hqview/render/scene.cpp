#include "hqview/render/scene.h"

#include <algorithm>
#include <cmath>

namespace hq {

Color map_fragment_color(const ScalarColorMap& map, float scalar, float below_weight, float undefined_weight) {
  if (undefined_weight > 0.5f) return map.undefined;
  if (below_weight > 0.5f) return map.below;
  const std::size_t n = map.samples.size();
  if (n == 0) return map.undefined;
  if (n == 1) return map.samples[0];
  const float x = std::clamp(std::isnan(scalar) ? 1.0f : scalar, 0.0f, 1.0f) * static_cast<float>(n - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), n - 2);
  const float f = x - static_cast<float>(i);
  const Color& p = map.samples[i];
  const Color& q = map.samples[i + 1];
  return {p.r + (q.r - p.r) * f, p.g + (q.g - p.g) * f, p.b + (q.b - p.b) * f, 1.0f};
}

}  // namespace hq
