#include "hqview/io/read_limits.h"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "hqview/core/error.h"

namespace hq {
namespace {

constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();

// Peak RSS of `hqview analyze -j2` measured with /usr/bin/time -v (README,
// "Resource limits"): a 14 KB mesh 183 MB (libraries, TBB, OSMesa); grids of
// 50^3 and 100^3 hexes without rendering 277 MB and 938 MB, i.e. 183 MB +
// the file + about 690 bytes per hex and vertex pair; rendering adds 110 MB
// (grid 50^3) to 240 MB (Dolphin_padded, 45,440 hexes: 456 MB in all). The
// constants below are those numbers with about 30 % to spare.
constexpr std::uint64_t kBaseBytes = std::uint64_t{448} << 20;  // process, libraries, rendering framebuffers
constexpr std::uint64_t kBytesPerVertex = 250;
constexpr std::uint64_t kBytesPerHex = 650;

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  return a != 0 && b > kSaturated / a ? kSaturated : a * b;
}
std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) { return b > kSaturated - a ? kSaturated : a + b; }

// The first line of a file as a number of bytes; 0 when absent, "max" or unreadable.
std::uint64_t read_limit_file(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!in || !std::getline(in, text)) return 0;
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() ? value : 0;
}

// The memory limit of this process's cgroup (v2, else v1); 0 when none.
std::uint64_t cgroup_memory_limit() {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  std::uint64_t limit = 0;
  while (std::getline(in, line)) {
    // "0::/path" (v2) or "4:memory:/path" (v1).
    const auto first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string group = line.substr(second + 1);
    std::uint64_t found = 0;
    if (controllers.empty())
      found = read_limit_file("/sys/fs/cgroup" + group + "/memory.max");
    else if (controllers == "memory" || controllers.find("memory,") != std::string::npos ||
             controllers.ends_with(",memory"))
      found = read_limit_file("/sys/fs/cgroup/memory" + group + "/memory.limit_in_bytes");
    // v1 writes "no limit" as a huge number rounded to the page size.
    if (found > 0 && found < (std::uint64_t{1} << 62) && (limit == 0 || found < limit)) limit = found;
  }
  return limit;
}

std::uint64_t compute_default_max_memory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  std::uint64_t physical =
      pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) : 0;
  const std::uint64_t cgroup = cgroup_memory_limit();
  if (cgroup > 0 && (physical == 0 || cgroup < physical)) physical = cgroup;
  return physical / 4 * 3;
}

}  // namespace

std::uint64_t default_max_memory() {
  static const std::uint64_t bytes = compute_default_max_memory();
  return bytes;
}

std::uint64_t estimate_analysis_memory(std::uint64_t file_bytes, std::uint64_t num_vertices, std::uint64_t num_hexes) {
  std::uint64_t bytes = saturating_add(kBaseBytes, file_bytes);
  bytes = saturating_add(bytes, saturating_mul(num_vertices, kBytesPerVertex));
  return saturating_add(bytes, saturating_mul(num_hexes, kBytesPerHex));
}

namespace {
std::uint64_t analysis_peak_estimate(std::uint64_t file_bytes, bool is_rendering) {
  // Measured with /usr/bin/time on ../shared/data (Dolphin_padded, bunny_in,
  // warrior: 3-4 MB text files; hex_cube_coarse, 7 KB), one render thread
  // as in a batch of several workers: about 9-11 bytes of peak RSS per file
  // byte above a 12 MB baseline without rendering (33-45 MB); rendering
  // at 1600x1200 adds 245 MB for the smallest mesh (the 2x2-supersampled
  // framebuffer, its read-back, llvmpipe, the figures and their PNGs) and
  // about 50 bytes per file byte more (the views' scenes): 257 MB and
  // 428-441 MB in all. Doubled for safety.
  if (!is_rendering) return saturating_add(saturating_mul(file_bytes, 20), std::uint64_t{16} << 20);
  return saturating_add(saturating_mul(file_bytes, 120), std::uint64_t{512} << 20);
}
}  // namespace

std::uint64_t estimate_mesh_memory(std::uint64_t file_bytes, bool is_rendering, bool is_simulating) {
  // --simulate: measured on Dolphin_padded refined once and twice (32.7 MB
  // and about 260 MB of MEDIT text; 363,520 and 2,908,160 hexes), the check
  // raises the peak by 5-6 bytes per file byte (the CSR matrix of 27
  // non-zeros per free vertex, 12 bytes each, CG's vectors of three
  // solutions, and per hex the error integrals, shares and density).
  // Doubled for safety.
  const std::uint64_t fem = is_simulating ? saturating_mul(file_bytes, 12) : 0;
  return saturating_add(analysis_peak_estimate(file_bytes, is_rendering), fem);
}

std::string format_memory_size(std::uint64_t bytes) {
  constexpr const char* kUnits[] = {"bytes", "KB", "MB", "GB", "TB", "PB", "EB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 6) {
    value /= 1024.0;
    ++unit;
  }
  if (unit == 0) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  char text[32];
  // Three significant digits: 1.23 GB, 12.3 GB, 123 GB.
  std::snprintf(text, sizeof text, value < 10 ? "%.2f" : value < 100 ? "%.1f" : "%.0f", value);
  std::string number = text;
  if (number.find('.') != std::string::npos) {
    while (number.back() == '0') number.pop_back();
    if (number.back() == '.') number.pop_back();
  }
  return number + " " + kUnits[unit];
}

void check_mesh_memory(const ReadLimits& limits, const std::string& name, std::int64_t line, std::uint64_t file_bytes,
                       std::int64_t num_vertices, std::int64_t num_hexes, std::string_view cell_noun) {
  if (limits.max_memory == 0) return;
  const std::uint64_t vertices = num_vertices > 0 ? static_cast<std::uint64_t>(num_vertices) : 0;
  const std::uint64_t hexes = num_hexes > 0 ? static_cast<std::uint64_t>(num_hexes) : 0;
  const std::uint64_t needed = estimate_analysis_memory(file_bytes, vertices, hexes);
  if (needed <= limits.max_memory) return;
  const std::string noun(cell_noun);
  const std::string what = num_hexes >= 0
                               ? std::to_string(num_hexes) + " " +
                                     (num_hexes == 1  ? noun
                                      : noun == "hex" ? "hexes"
                                                      : noun + "s")
                               : std::to_string(num_vertices) + (num_vertices == 1 ? " vertex" : " vertices");
  std::string needed_text = format_memory_size(needed), limit_text = format_memory_size(limits.max_memory);
  if (needed_text == limit_text) {  // rounded alike: say which is larger
    needed_text += " (" + std::to_string(needed) + " bytes)";
    limit_text += " (" + std::to_string(limits.max_memory) + " bytes)";
  }
  throw ParseError(
      name, line,
      "the file declares " + what + ", which needs about " + needed_text + "; --max-memory is " + limit_text);
}

void check_coordinate_magnitudes(const HexMesh& mesh, const std::string& name) {
  double smallest = INFINITY, largest = 0.0;
  for (const Vec3& p : mesh.points)
    for (const double c : {p.x, p.y, p.z}) {
      const double m = std::abs(c);
      largest = std::max(largest, m);
      if (m > 0.0) smallest = std::min(smallest, m);
    }
  if (!(largest > kMaxCoordinateMagnitude)) return;
  char text[160];
  std::snprintf(text, sizeof text, "node coordinates span %.3g to %.3g in magnitude", smallest, largest);
  throw ParseError(name, 0,
                   std::string(text) +
                       "; HQView analyses magnitudes up to 1e+100 (beyond, squared lengths overflow and exact "
                       "geometry slows down): rescale the mesh");
}

}  // namespace hq
