// The command line's flag parsers and exit codes (apps/hqview/flags.h).
#include "flags.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>

#include "hqview/core/stop.h"

#include <string>

#include "hqview/core/error.h"
#include "hqview/views/views.h"

namespace hqcli {
namespace HQ_TEST_UNIT {

template <class Fn>
std::string usage_error(Fn&& fn) {
  try {
    fn();
  } catch (const UsageError& e) {
    return e.what();
  }
  return "(no UsageError)";
}

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;

TEST(MemorySize, ParsesSizesWithBinaryUnits) {
  EXPECT_EQ(parse_memory_size("512M", "--max-memory"), 512 * kMiB);
  EXPECT_EQ(parse_memory_size("4G", "--max-memory"), 4096 * kMiB);
  EXPECT_EQ(parse_memory_size("0.5T", "--max-memory"), 512 * 1024 * kMiB);
  EXPECT_EQ(parse_memory_size("1.5g", "--max-memory"), 1536 * kMiB);
  EXPECT_EQ(parse_memory_size("64KB", "--max-memory"), 64 * 1024u);
  EXPECT_EQ(parse_memory_size("1000000", "--max-memory"), 1000000u);
  EXPECT_EQ(parse_memory_size("0", "--max-memory"), 0u);  // no limit
  for (const char* bad : {"", "G", "-1G", "4X", "4 G", "nan", "inf", "0.5", "1e30T", "4GG"})
    EXPECT_EQ(usage_error([&] { parse_memory_size(bad, "--max-memory"); }),
              "--max-memory: expected a size such as 512M, 4G or 0.5T (K, M, G, T: powers of 1024; 0: no limit), "
              "got '" +
                  std::string(bad) + "'")
        << bad;
}

TEST(MemorySize, TheBudgetTakesTheSameUnitsAndNamesItsFlag) {
  EXPECT_EQ(parse_memory_size("8G", "--memory-budget"), 8192 * kMiB);
  EXPECT_EQ(parse_memory_size("2T", "--memory-budget"), 2 * 1024 * 1024 * kMiB);
  EXPECT_EQ(usage_error([] { parse_memory_size("lots", "--memory-budget"); }).rfind("--memory-budget: ", 0), 0u);
}

TEST(Shard, ParseAndValidate) {
  const hq::Shard s = parse_shard("2/8");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 8);
  for (const char* bad : {"0/3", "4/3", "1/0", "a/3", "2", "2/3x", ""})
    EXPECT_EQ(usage_error([&] { parse_shard(bad); }),
              "--shard: expected I/N with 1 <= I <= N, e.g. 2/8, got '" + std::string(bad) + "'")
        << bad;
}

hq::BatchEntry entry(hq::BatchStatus status) {
  hq::BatchEntry e;
  e.status = status;
  return e;
}

TEST(BatchExitCode, FailedThenGateThenOk) {
  using hq::BatchStatus;
  EXPECT_EQ(batch_exit_code({}), kOk);
  EXPECT_EQ(batch_exit_code({entry(BatchStatus::ok)}), kOk);
  EXPECT_EQ(batch_exit_code({entry(BatchStatus::ok), entry(BatchStatus::gate_failed)}), kGateFailed);
  EXPECT_EQ(batch_exit_code({entry(BatchStatus::gate_failed), entry(BatchStatus::failed)}), kInput);
  // A mesh that failed because of the machine (disk full) wins: retry elsewhere.
  hq::BatchEntry full = entry(BatchStatus::failed);
  full.environment_failure = true;
  EXPECT_EQ(batch_exit_code({entry(BatchStatus::failed), full, entry(BatchStatus::gate_failed)}), kEnvironment);
}

TEST(ExitCode, EachErrorTypeHasItsCode) {
  auto code_of = [](auto&& thrower) -> int {
    try {
      thrower();
    } catch (const std::exception&) {
      return exit_code_of_current_exception();
    }
    return kOk;
  };
  EXPECT_EQ(code_of([] { throw UsageError("x"); }), kUsage);
  EXPECT_EQ(code_of([] { throw hq::ValueError("x"); }), kUsage);
  EXPECT_EQ(code_of([] { throw hq::InputError("x"); }), kInput);
  EXPECT_EQ(code_of([] { throw hq::ParseError("m.mesh", 3, "x"); }), kInput);
  EXPECT_EQ(code_of([] { throw hq::InvalidMeshError("x"); }), kInput);
  EXPECT_EQ(code_of([] { throw hq::RenderError("x"); }), kInternal);
  EXPECT_EQ(code_of([] { throw std::logic_error("x"); }), kInternal);
  EXPECT_EQ(code_of([] { throw hq::EnvironmentError("x"); }), kEnvironment);
  EXPECT_EQ(code_of([] {
              throw std::filesystem::filesystem_error("x", "/p", std::make_error_code(std::errc::no_space_on_device));
            }),
            kEnvironment);
  EXPECT_EQ(code_of([] { throw std::bad_alloc(); }), kEnvironment);
  EXPECT_EQ(code_of([] { throw hq::Interrupted(SIGINT); }), 130);
  EXPECT_EQ(code_of([] { throw hq::Interrupted(SIGTERM); }), 143);
}

TEST(ViewList, AllOrIdsInTableOrder) {
  std::vector<std::string> all;
  for (const hq::ViewSpec& spec : hq::kViews)
    if (spec.is_selectable) all.emplace_back(spec.id);
  EXPECT_EQ(parse_view_list("all"), all);
  EXPECT_EQ(parse_view_list("sorted_quality,main"), (std::vector<std::string>{"main", "sorted_quality"}));
  // histogram_log comes with histogram: not an id of its own.
  EXPECT_EQ(usage_error([] { parse_view_list("histogram_log"); }).rfind("--views: unknown view 'histogram_log'", 0),
            0u);
  EXPECT_EQ(usage_error([] {
              parse_view_list("main,nope");
            }).rfind("--views: unknown view 'nope' (known: all, overview, main,", 0),
            0u);
}

TEST(MetricList, NamesAllAndErrors) {
  const hq::HexMetricSet set = parse_metric_list("skew, volume");
  EXPECT_EQ(set.count(), 2u);
  EXPECT_TRUE(hq::contains(set, hq::HexMetric::skew));
  EXPECT_TRUE(hq::contains(set, hq::HexMetric::volume));
  EXPECT_EQ(parse_metric_list("all"), hq::all_hex_metrics());
  EXPECT_EQ(
      usage_error([] { parse_metric_list("skew,"); }).rfind("--metrics: empty entry in 'skew,'; choose from: all, ", 0),
      0u);
  EXPECT_EQ(usage_error([] { parse_metric_list("skw"); }).rfind("--metrics: unknown metric 'skw' in 'skw'", 0), 0u);
}

TEST(Size, WidthByHeightWithinBounds) {
  int w = 0, h = 0;
  parse_size("640x480", w, h);
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  EXPECT_EQ(usage_error([&] { parse_size("640", w, h); }), "--size: expected WIDTHxHEIGHT, e.g. 1600x1200, got '640'");
  EXPECT_EQ(usage_error([&] { parse_size("32x32", w, h); }),
            "--size: width and height must be between 64 and 8192, got '32x32'");
}

// Issue 48c: --error-density-reference, a positive density; not given: 0
// (the mesh's median).
TEST(ErrorDensityReference, PositiveOrNotGiven) {
  EXPECT_EQ(parse_error_density_reference(""), 0.0);
  EXPECT_EQ(parse_error_density_reference("0.05"), 0.05);
  EXPECT_EQ(parse_error_density_reference("2e-3"), 2e-3);
  for (const char* bad : {"0", "-1", "abc", "nan", "inf"})
    EXPECT_EQ(usage_error([&] { parse_error_density_reference(bad); }),
              std::string("--error-density-reference: expected a positive number (an error density), got '") + bad +
                  "'")
        << bad;
}

}  // namespace
}  // namespace hqcli
