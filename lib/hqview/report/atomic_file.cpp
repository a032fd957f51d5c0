#include "hqview/report/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "hqview/core/error.h"

namespace hq {
namespace fs = std::filesystem;

fs::path temporary_sibling(const fs::path& path, std::string_view tag) {
  // Built with += : GCC 12 warns falsely (-Wrestrict) on chained operator+.
  std::string name = ".";
  name += path.filename().string();
  name += '.';
  name += tag;
  name += '-';
  name += std::to_string(::getpid());
  return path.parent_path() / name;
}

void write_file_atomically(const fs::path& path, std::string_view text) {
  const fs::path tmp = temporary_sibling(path, kTemporaryTag);
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw EnvironmentError(tmp.string() + ": cannot create: " + std::strerror(errno));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) {
      std::error_code ignored;
      fs::remove(tmp, ignored);
      throw EnvironmentError(tmp.string() + ": write failed: " + std::strerror(errno));
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw EnvironmentError(path.string() + ": cannot rename into place: " + ec.message());
  }
}

}  // namespace hq
