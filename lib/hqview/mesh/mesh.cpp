#include "hqview/mesh/mesh.h"

namespace hq {

std::int64_t num_cells_of(const Mesh& mesh, CellKind kind) {
  std::int64_t n = 0;
  for_each_block(mesh, [&](auto k, const auto& cells) {
    if (k() == kind) n = static_cast<std::int64_t>(cells.size());
  });
  return n;
}

std::int64_t num_cells(const Mesh& mesh) {
  std::int64_t n = 0;
  for_each_block(mesh, [&](auto, const auto& cells) { n += static_cast<std::int64_t>(cells.size()); });
  return n;
}

}  // namespace hq
