#include "bench_data.h"

#include <cstdlib>

namespace hq::bench {

std::filesystem::path largest_mesh() {
  namespace fs = std::filesystem;
  fs::path data = fs::path(HQVIEW_SOURCE_DIR) / ".." / "shared" / "data";
  if (const char* env = std::getenv("HQVIEW_DATA"); env && *env) data = env;
  const fs::path dolphin = data / "meshes" / "gao2016_sweeping" / "Dolphin_padded.mesh";
  if (fs::exists(dolphin)) return dolphin;
  return fs::path(HQVIEW_SOURCE_DIR) / "examples" / "ball.mesh";
}

}  // namespace hq::bench
