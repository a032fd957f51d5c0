#include "hqview/report/json_path.h"

namespace hq {

std::vector<std::string> split_json_path(std::string_view dotted) {
  std::vector<std::string> keys;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = dotted.find('.', start);
    keys.emplace_back(dotted.substr(start, dot == std::string_view::npos ? std::string_view::npos : dot - start));
    if (dot == std::string_view::npos) return keys;
    start = dot + 1;
  }
}

}  // namespace hq
