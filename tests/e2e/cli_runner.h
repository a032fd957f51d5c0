#pragma once
// Runs the hqview binary and captures its exit code, stdout and stderr.

#include <array>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace hq::test {

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs hqview with `args` (each shell-quoted).
CliResult run_hqview(const std::vector<std::string>& args);

// True when stderr shows LeakSanitizer's stop-the-world tracer crashing at
// exit on its own ("Tracer caught signal", then "LeakSanitizer has
// encountered a fatal error", no leak report): a known fault of the
// sanitizer runtime (google/sanitizers#1353), seen under scripts/test
// --sanitize in e2e.BadInputs (7 of 48 runs of one row) and in
// e2e.SharedViews (bunny_in, 2026-12-06), and twice in a row in
// e2e.Cli.MesaIsLoadedOnlyWhenAViewIsDrawn. run_hqview makes such a run
// again, up to kLsanTracerRetries times; a leak report, an ASan error or a
// wrong result still fails.
bool lsan_tracer_crashed(const std::string& err);
// How many times a run whose stderr shows that signature is made again.
inline constexpr int kLsanTracerRetries = 3;

// A fresh, empty directory for one test's outputs under the build tree.
std::filesystem::path fresh_output_dir(const std::string& name);

std::string read_text(const std::filesystem::path& path);

// BUNDLE/report.json, parsed.
nlohmann::json read_report(const std::filesystem::path& bundle);

// A copy of an OFF surface with every vertex p -> move(p) (x, y, z in and out).
std::filesystem::path transformed_off_copy(const std::filesystem::path& off,
                                           const std::function<std::array<double, 3>(double, double, double)>& move,
                                           const std::filesystem::path& out);

// The rows of a CSV file (no quoting: HQView's CSVs hold numbers only).
std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path);

}  // namespace hq::test
