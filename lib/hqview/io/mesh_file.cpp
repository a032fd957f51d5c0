#include "hqview/io/mesh_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <memory>
#include <string_view>
#include <system_error>

#include "hqview/core/error.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/io/text_scanner.h"
#include "hqview/io/vtk_legacy_reader.h"

namespace hq {
namespace detail {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

std::string errno_text(int error) { return std::error_code(error, std::generic_category()).message(); }

// Checks the file type before opening: opening a fifo would block.
FilePtr open_regular_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(path.string() + ": not a regular file");
  errno = 0;
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) throw InputError(path.string() + ": cannot open: " + errno_text(errno != 0 ? errno : ENOENT));
  return file;
}

}  // namespace

std::string lowercase_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c); });
  return ext;
}

void check_readable_file(const std::filesystem::path& path) { open_regular_file(path); }

}  // namespace detail

std::string read_file_bytes(const std::filesystem::path& path) {
  const detail::FilePtr file = detail::open_regular_file(path);
  std::string bytes;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) bytes.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  while (true) {
    const std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
    bytes.append(buffer, n);
    if (n < sizeof buffer) break;
  }
  if (std::ferror(file.get())) throw InputError(path.string() + ": read error: " + detail::errno_text(errno));
  return bytes;
}

namespace {

bool looks_like_vtk(std::string_view bytes) { return detail::istarts_with(bytes, "# vtk DataFile"); }

// MeshVersionFormatted after blanks and # comment lines.
bool looks_like_medit(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size()) {
    if (detail::is_space(bytes[i])) {
      ++i;
    } else if (bytes[i] == '#') {
      while (i < bytes.size() && bytes[i] != '\n') ++i;
    } else {
      return detail::istarts_with(bytes.substr(i), "MeshVersionFormatted");
    }
  }
  return false;
}

// Throws InputError unless path has a hex mesh extension.
void check_hex_mesh_extension(const std::filesystem::path& path) {
  const std::string ext = detail::lowercase_extension(path);
  if (ext == ".mesh" || ext == ".vtk") return;
  if (ext.empty()) throw InputError(path.string() + ": no file extension (expected .mesh or .vtk)");
  throw InputError(path.string() + ": unknown mesh format '" + path.extension().string() +
                   "' (expected .mesh or .vtk)");
}

}  // namespace

LoadedMesh read_hex_mesh(const std::filesystem::path& path) {
  check_hex_mesh_extension(path);
  return read_hex_mesh(path, read_file_bytes(path));
}

LoadedMesh read_hex_mesh(const std::filesystem::path& path, std::string_view bytes) {
  check_hex_mesh_extension(path);
  const std::string name = path.string();
  if (detail::lowercase_extension(path) == ".mesh") {
    if (looks_like_vtk(bytes)) throw ParseError(name, 1, "a .mesh file with legacy VTK content");
    return read_medit(bytes, name);
  }
  if (looks_like_medit(bytes)) throw ParseError(name, 0, "a .vtk file with MEDIT (.mesh) content");
  return read_vtk_legacy(bytes, name);
}

}  // namespace hq
