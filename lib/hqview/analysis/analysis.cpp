#include "hqview/analysis/analysis.h"

#include <filesystem>

namespace hq {

std::string Analysis::mesh_name() const { return std::filesystem::path(mesh_input.path).filename().string(); }

}  // namespace hq
