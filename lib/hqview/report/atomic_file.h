#pragma once
// One file written atomically: the text goes to a temporary sibling
// (".NAME.hqview-tmp-PID"), which is renamed over the file only once it is
// complete, so a reader sees the old file or the new one, never half of one.
// (A bundle is made atomic as a whole directory: bundle_writer.h.)

#include <filesystem>
#include <string_view>

namespace hq {

// The temporaries of a write in progress: `.NAME.TAG-PID` beside NAME, so
// that the next run can tell a killed run's leftovers (its PID is gone)
// from a running one's (bundle_writer.h, remove_stale_temporaries).
inline constexpr std::string_view kTemporaryTag = "hqview-tmp";
inline constexpr std::string_view kSetAsideTag = "hqview-old";  // an old bundle moved aside by a swap
std::filesystem::path temporary_sibling(const std::filesystem::path& path, std::string_view tag);

// Throws EnvironmentError when the temporary file cannot be written or renamed (it is
// removed then; `path` is untouched).
void write_file_atomically(const std::filesystem::path& path, std::string_view text);

}  // namespace hq
