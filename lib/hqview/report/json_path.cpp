#include "hqview/report/json_path.h"

#include "hqview/core/text.h"

namespace hq {

std::vector<std::string> split_json_path(std::string_view dotted) {
  std::vector<std::string> keys;
  for (const std::string_view key : split(dotted, '.')) keys.emplace_back(key);
  return keys;
}

}  // namespace hq
