// The hostile-input corpus tests/bad_inputs/: every row of expected.tsv run
// through the built hqview, its exit code, exact standard error and run time
// checked; for a failing run, the bundle already in its -o directory must be
// byte-identical afterwards with nothing left beside it; for an accepted one,
// report.json numbers. Big, sparse, fifo, directory and permission cases are
// made here in the build tree, never committed.

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "support/fixtures.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

namespace fs = std::filesystem;

struct Case {
  int line = 0;  // in expected.tsv
  std::string input, command;
  int exit_code = 0;
  double seconds = 0;
  std::string stderr_text, checks;
};

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

std::vector<Case> read_cases(const fs::path& tsv) {
  std::vector<Case> cases;
  std::ifstream in(tsv);
  std::string row;
  int line = 0;
  while (std::getline(in, row)) {
    ++line;
    if (row.empty() || row[0] == '#') continue;
    const std::vector<std::string> f = split(row, '\t');
    EXPECT_GE(f.size(), 5u) << tsv.string() << ":" << line << ": expected 5 or 6 tab-separated columns";
    if (f.size() < 5) continue;
    cases.push_back({line, f[0], f[1], std::stoi(f[2]), std::stod(f[3]), f[4], f.size() > 5 ? f[5] : ""});
  }
  return cases;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

std::string shell_quote(const std::string& s) { return "'" + replace_all(s, "'", "'\\''") + "'"; }

// Every file under dir, by relative path, with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) files[fs::relative(entry.path(), dir).string()] = read_text(entry.path());
  return files;
}

constexpr std::uintmax_t kTwoGiB = std::uintmax_t{2} << 30;
constexpr const char* kMeditHeader = "MeshVersionFormatted 2\nDimension 3\nVertices 8\n";

// Makes the input gen:NAME in dir; false when it cannot be made meaningfully
// here (permissions as root).
bool generate(const std::string& name, const fs::path& path) {
  if (fs::exists(fs::symlink_status(path))) return true;  // made by an earlier row
  if (name.starts_with("sparse_2g_after_header")) {
    std::ofstream(path, std::ios::binary) << kMeditHeader;
    fs::resize_file(path, kTwoGiB + std::char_traits<char>::length(kMeditHeader));
  } else if (name.starts_with("sparse_2g")) {
    std::ofstream(path, std::ios::binary).flush();
    fs::resize_file(path, kTwoGiB);  // a hole: no disk space, no time
  } else if (name == "directory.mesh") {
    fs::create_directories(path);
  } else if (name.starts_with("fifo.")) {
    EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0);
  } else if (name == "unreadable.mesh") {
    if (::geteuid() == 0) return false;  // root reads anything
    std::ofstream(path) << kMeditHeader;
    fs::permissions(path, fs::perms::none);
  } else if (name != "missing.mesh") {
    ADD_FAILURE() << "unknown generated input gen:" << name;
  }
  return true;
}

// A report.json value by its dotted key.
const nlohmann::json* find_key(const nlohmann::json& report, const std::string& key) {
  const nlohmann::json* node = &report;
  for (const std::string& part : split(key, '.')) {
    if (!node->is_object() || !node->contains(part)) return nullptr;
    node = &(*node)[part];
  }
  return node;
}

TEST(BadInputs, EveryHostileInputGivesItsMessageAndKeepsThePreviousBundle) {
  const fs::path corpus = source_dir() / "tests/bad_inputs";
  const std::vector<Case> cases = read_cases(corpus / "expected.tsv");
  ASSERT_GE(cases.size(), 40u);
  const fs::path root = fresh_output_dir("bad_inputs");
  const fs::path generated = root / "generated", runs = root / "runs", bundle = runs / "bundle";
  fs::create_directories(generated);
  const std::string good = (source_dir() / "examples/twisted_bar.mesh").string();

  const CliResult first = run_hqview({"analyze", good, "-o", bundle.string(), "--no-render", "-q"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const std::map<std::string, std::string> before = snapshot(bundle);
  ASSERT_TRUE(before.contains("report.json"));

  int accepted = 0, refused = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE("expected.tsv:" + std::to_string(c.line) + ": " + c.input + " | " + c.command);
    fs::path input = corpus / c.input;
    if (c.input.starts_with("gen:")) {
      input = generated / c.input.substr(4);
      if (!generate(c.input.substr(4), input)) {
        std::cerr << "[ skipped ] expected.tsv:" << c.line << ": " << c.input << " (running as root)\n";
        continue;
      }
    }
    const fs::path out = c.exit_code == 0 ? root / "accepted" / std::to_string(c.line) : bundle;
    std::string command =
        "timeout -k 5 " + std::to_string(static_cast<int>(c.seconds) + 60) + " " + shell_quote(HQVIEW_BINARY);
    for (const std::string& arg : split(c.command, ' ')) {
      std::string value = replace_all(arg, "{input}", input.string());
      value = replace_all(value, "{good}", good);
      value = replace_all(value, "{examples}", (source_dir() / "examples").string());
      command += " " + shell_quote(value);
    }
    command += " -o " + shell_quote(out.string()) + " -q" + (c.exit_code == 0 ? "" : " --no-render");
    const fs::path err_file = root / "stderr.txt";
    command += " >/dev/null 2>" + shell_quote(err_file.string()) + " </dev/null";
    auto start = std::chrono::steady_clock::now();
    int status = std::system(command.c_str());
    std::string err = read_text(err_file);
    // LeakSanitizer's stop-the-world tracer sometimes crashes at exit on
    // its own ("Tracer caught signal 11", then "LeakSanitizer has
    // encountered a fatal error", no leak report: a known fault of the
    // sanitizer runtime, google/sanitizers#1353). Under scripts/test
    // --sanitize it hit the run of row 78 (every view, with a reference) in
    // 7 of 48 runs of this test on 2026-12-06 (cause not found: it stays
    // with one render thread and with the TBB workers joined before exit).
    // Such a run, and only on that signature, is made again (up to
    // kLsanTracerRetries times): a leak report, an ASan error or a wrong
    // result still fails.
    for (int retry = 0; retry < kLsanTracerRetries && lsan_tracer_crashed(err); ++retry) {
      std::cerr << "[ retried ] expected.tsv:" << c.line << ": LeakSanitizer's tracer crashed at exit\n";
      start = std::chrono::steady_clock::now();
      status = std::system(command.c_str());
      err = read_text(err_file);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;

    EXPECT_NE(exit_code, 124) << "hqview hung (killed by timeout)";
    EXPECT_EQ(exit_code, c.exit_code) << err;
    const std::string expected_err =
        c.stderr_text.empty() ? "" : replace_all(c.stderr_text, "{input}", input.string()) + "\n";
    EXPECT_EQ(err, expected_err);
    EXPECT_LE(seconds, c.seconds) << "took " << seconds << " s";
    if (c.exit_code == 0) {
      ++accepted;
      const nlohmann::json report = nlohmann::json::parse(read_text(out / "report.json"), nullptr, false);
      ASSERT_FALSE(report.is_discarded());
      for (const std::string& check : split(c.checks, ' ')) {
        if (check.empty()) continue;
        const auto eq = check.find('=');
        ASSERT_NE(eq, std::string::npos) << check;
        const nlohmann::json* value = find_key(report, check.substr(0, eq));
        ASSERT_NE(value, nullptr) << "no key " << check.substr(0, eq);
        ASSERT_TRUE(value->is_number()) << check;
        EXPECT_EQ(value->get<double>(), std::stod(check.substr(eq + 1))) << check;
      }
    } else {
      ++refused;
      // No refusal allocates much: the largest child so far (accepted runs
      // peak near 450 MiB) stays well below what reading a 2 GiB input takes.
      rusage usage{};
      ::getrusage(RUSAGE_CHILDREN, &usage);
      EXPECT_LT(usage.ru_maxrss, 1536L * 1024) << "peak RSS of the children so far, KiB";
      EXPECT_EQ(snapshot(bundle), before) << "the previous bundle changed";
      std::vector<std::string> beside;
      for (const auto& entry : fs::directory_iterator(runs)) beside.push_back(entry.path().filename().string());
      EXPECT_EQ(beside, std::vector<std::string>{"bundle"}) << "something was left beside the bundle";
    }
  }
  EXPECT_GE(accepted, 5);
  EXPECT_GE(refused, 40);
  // The generated 2 GiB files are holes, but remove them at once anyway.
  fs::remove_all(generated);
}

}  // namespace
}  // namespace hq::test
