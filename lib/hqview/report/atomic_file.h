#pragma once
// One file written atomically: the text goes to a temporary sibling
// (".NAME.hqview-tmp-PID"), which is renamed over the file only once it is
// complete, so a reader sees the old file or the new one, never half of one.
// (A bundle is made atomic as a whole directory: bundle_writer.h.)

#include <filesystem>
#include <string_view>

namespace hq {

// Throws EnvironmentError when the temporary file cannot be written or renamed (it is
// removed then; `path` is untouched).
void write_file_atomically(const std::filesystem::path& path, std::string_view text);

}  // namespace hq
