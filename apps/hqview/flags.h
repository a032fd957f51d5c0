#pragma once
// Every flag's parser and its message: command-line text to the library's
// typed values. A bad value throws UsageError (exit code 2), whose message
// names the flag. The library never sees command-line text.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/glyph/glyphs.h"
#include "hqview/overlap/overlap.h"
#include "hqview/pipeline/batch.h"
#include "hqview/quality/hex_metrics.h"

namespace hqcli {

// A command line that cannot be run: a bad flag value, a flag that does
// not apply. Exit code 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The exit codes of docs/contract.md; a signal that stopped the run gives
// 128 + its number (130 SIGINT, 143 SIGTERM).
enum ExitCode { kOk = 0, kGateFailed = 1, kUsage = 2, kInput = 3, kInternal = 4, kEnvironment = 5 };

// The exit code of the exception being handled (call inside a catch block):
// UsageError and hq::ValueError 2, hq::InputError (ParseError,
// InvalidMeshError) 3, hq::EnvironmentError, std::filesystem::filesystem_error
// and std::bad_alloc 5, hq::Interrupted 128 + its signal, anything else 4.
int exit_code_of_current_exception();

// `batch` and `merge`: 5 if a mesh failed because of the machine (disk full,
// permission), else 3 if any mesh failed, else 1 if any gate failed, else 0.
ExitCode batch_exit_code(const std::vector<hq::BatchEntry>& entries);

// The whole of `text` as a finite number, or nullopt.
std::optional<double> parse_finite(std::string_view text);

// --size WIDTHxHEIGHT, each from 64 to 8192.
void parse_size(const std::string& text, int& width, int& height);

// --up AXIS: +x -x +y -y +z -z (x, y, z without a sign are +).
hq::Vec3 parse_up(const std::string& text);

// --rmax R (model units) or Rx (R times the mean edge length), R > 0.
void parse_rmax(const std::string& text, hq::GlyphOptions& glyphs);

// --glyph-threshold T: a ratio 1 - Jm, in [0, 2].
double parse_glyph_threshold(const std::string& text);
// --error-density-reference: a positive number; empty (not given): 0, the
// mesh's median. Throws UsageError.
double parse_error_density_reference(const std::string& text);

// --overlap certificate|exhaustive and --coincident-eps E (a fraction of the
// bounding-box diagonal, 0 = exact equality); nullopt with --no-overlap.
std::optional<hq::OverlapOptions> parse_overlap(const std::string& mode, const std::string& coincident_eps,
                                                bool no_overlap);

// --format: empty (detect) or one of hq::mesh_format_names().
std::string parse_mesh_format(const std::string& format);

// --metrics LIST: comma-separated Verdict names, or `all` (every Verdict
// metric), and fem_element (the Q1 element conditioning, not in `all`).
inline constexpr std::string_view kFemElementMetric = "fem_element";
hq::HexMetricSet parse_metric_list(std::string_view list);
// Whether LIST names fem_element.
bool lists_fem_element(std::string_view list);

// --views LIST: "all" or ids of hq::kViews (selectable ones) separated by
// commas; the result keeps the table's order.
std::vector<std::string> parse_view_list(const std::string& list);

// --max-memory and --memory-budget: a number (fractions allowed) with an
// optional unit K, M, G or T (binary, any case, optional trailing B):
// "512M", "4G", "0.5T", "1000000" (bytes); "0": no limit.
std::uint64_t parse_memory_size(std::string_view text, std::string_view flag);

// --shard I/N with 1 <= I <= N.
hq::Shard parse_shard(std::string_view text);

}  // namespace hqcli
