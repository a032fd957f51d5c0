#pragma once
// The one path lookup into report.json and index.json values: gates, batch
// rows and diff name a value by its dotted path ("quality.scaled_jacobian.min";
// a number indexes an array: "quality.worst_cells.0.cell").

#include <charconv>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hq {

// "a.b.c" -> {"a", "b", "c"} (no validation: empty keys stay empty).
std::vector<std::string> split_json_path(std::string_view dotted);

// The node at `keys` under `root`, or nullptr. `depth`, when given, is set
// to the number of keys found before the lookup stopped (keys.size() when
// found), for messages that say where the path went wrong. Works for
// nlohmann::json and nlohmann::ordered_json.
template <class Json>
const Json* find_json_path(const Json& root, std::span<const std::string> keys, std::size_t* depth = nullptr) {
  const Json* node = &root;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string& key = keys[i];
    const Json* next = nullptr;
    if (node->is_object()) {
      if (const auto it = node->find(key); it != node->end()) next = &*it;
    } else if (node->is_array()) {
      std::size_t index = 0;
      const auto [end, error] = std::from_chars(key.data(), key.data() + key.size(), index);
      if (error == std::errc() && end == key.data() + key.size() && index < node->size()) next = &(*node)[index];
    }
    if (next == nullptr) {
      if (depth) *depth = i;
      return nullptr;
    }
    node = next;
  }
  if (depth) *depth = keys.size();
  return node;
}

// The number at a dotted path, or nullopt (missing, null, not a number).
template <class Json>
std::optional<double> json_number_at(const Json& root, std::string_view dotted) {
  const std::vector<std::string> keys = split_json_path(dotted);
  const Json* node = find_json_path(root, std::span<const std::string>(keys));
  if (node == nullptr || !node->is_number()) return std::nullopt;
  return node->template get<double>();
}

}  // namespace hq
