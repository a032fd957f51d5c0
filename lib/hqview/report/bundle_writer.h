#pragma once
// Writes an analysis bundle atomically: every file goes to a temporary
// sibling directory, which replaces DIR by rename only once it is complete.
// A failed run leaves DIR as it was (an older bundle is never lost).

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hqview/core/stage_times.h"
#include "hqview/image/image.h"
#include "hqview/report/report_json.h"
#include "hqview/report/report_model.h"
#include "hqview/report/single_file.h"

namespace hq {

struct BundleImage {
  std::string relative_path;  // e.g. "views/overview.png"
  Image image;
  std::string text;  // non-empty: written as is instead of the image (an SVG chart, an encoded PNG)
};

struct BundleOptions {
  bool force = false;  // replace a file, or a non-empty directory that is not an HQView bundle
  std::string link_base;  // --link-base (normalize_link_base): pages with absolute links; empty: relative
  SingleFile single_file = SingleFile::none;  // --single-file: also report.html (single_file.h)
  StageSink on_stage;  // called as each file is written (--verbose); may be empty
  // When the process started: timings.json's wall_seconds runs from it to
  // the last file (unset: from the first stage's start).
  std::optional<std::chrono::steady_clock::time_point> started;
};

// Throws ValueError, unless force, when `dir` is an existing non-directory
// (a file: --force replaces it) or a non-empty directory without report.json
// (not an HQView bundle). Call it before the analysis, so a doomed run fails fast.
void check_output_dir(const std::filesystem::path& dir, const BundleOptions& options);

// timings.json: {note, stages[{name, seconds, peak_rss_mb}], total_seconds,
// wall_seconds}, in stage order.
std::string timings_json(const std::vector<StageTime>& timings, double wall_seconds);

// report.json (document's text), timings.json (model.analysis.timings and the
// writing of each file: wall seconds, the one file that differs run to run), index.html, boundary.html (with a boundary error), summary.md, style.css,
// data/cells.csv, data/vertices.csv, data/annotated.vtu (when model.has_annotated_vtu) and the images (relative paths
// without "..": anything else is an internal error, nothing is written outside DIR). Throws EnvironmentError on an I/O
// failure (the temporary directory is removed, DIR untouched), Interrupted when a stop is requested while writing.
// Stale temporaries of killed runs next to DIR are cleaned first (remove_stale_temporaries).
void write_bundle(const ReportModel& model, const ReportDocument& document, const std::vector<BundleImage>& images,
                  const std::filesystem::path& dir, const BundleOptions& options);

// Puts the complete directory `tmp` at `dir`: exchanged atomically with an
// existing bundle where the file system allows (renameat2), else by two
// renames with the old bundle kept aside until the new one is in place.
void swap_into_place(const std::filesystem::path& tmp, const std::filesystem::path& dir);

// Removes what killed runs left in `dir` (and, when recursive, in its
// subdirectories that are not bundles): `.NAME.hqview-tmp-PID` entries whose
// process is gone; a `.NAME.hqview-old-PID` (a bundle moved aside by a swap
// that was killed) goes back to NAME when NAME is missing, else is removed.
// Returns how many entries it removed or restored.
int remove_stale_temporaries(const std::filesystem::path& dir, bool recursive);

}  // namespace hq
