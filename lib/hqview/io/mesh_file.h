#pragma once
// File access shared by the readers that open files (internal to io/).

#include <filesystem>
#include <string>

namespace hq::detail {

// The extension of path, lower-cased (".vtk"); empty when it has none.
std::string lowercase_extension(const std::filesystem::path& path);

// Throws InputError "path: not a regular file" for a directory, fifo,
// device, ..., and "path: cannot open: <reason>" when it cannot be opened
// for reading. Never blocks on a fifo.
void check_readable_file(const std::filesystem::path& path);

}  // namespace hq::detail
