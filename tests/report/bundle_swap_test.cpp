#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "hqview/report/atomic_file.h"
#include "hqview/report/bundle_writer.h"

namespace HQ_TEST_UNIT {
namespace fs = std::filesystem;

// A process id no process has (above any pid_max): a killed run's.
constexpr const char* kDeadPid = "999999999";

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("hqview-swap-test-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

std::string read(const fs::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(BundleSwap, TheNewBundleReplacesTheOldAndNothingIsLeftBeside) {
  const fs::path root = fresh_dir("swap");
  write(root / "b" / "report.json", "old");
  write(root / "b" / "only-old.txt", "x");
  const fs::path tmp = hq::temporary_sibling(root / "b", hq::kTemporaryTag);
  EXPECT_EQ(tmp.filename().string(), ".b.hqview-tmp-" + std::to_string(::getpid()));
  write(tmp / "report.json", "new");
  hq::swap_into_place(tmp, root / "b");
  EXPECT_EQ(read(root / "b" / "report.json"), "new");
  EXPECT_FALSE(fs::exists(root / "b" / "only-old.txt"));  // the whole old bundle went, not a mix
  EXPECT_FALSE(fs::exists(tmp));
  // Into a place where nothing was.
  write(tmp / "report.json", "first");
  hq::swap_into_place(tmp, root / "c");
  EXPECT_EQ(read(root / "c" / "report.json"), "first");
  EXPECT_EQ(std::distance(fs::directory_iterator(root), fs::directory_iterator()), 2);
}

TEST(BundleSwap, KilledRunsLeftoversGoAndASetAsideBundleComesBack) {
  const fs::path root = fresh_dir("stale");
  const std::string dead = kDeadPid;
  const std::string alive = std::to_string(::getpid());
  write(root / (".a.mesh.hqview-tmp-" + dead) / "report.json", "half");   // a killed write: removed
  write(root / (".index.json.hqview-tmp-" + dead), "{");                  // a killed index write: removed
  write(root / (".b.hqview-old-" + dead) / "report.json", "kept");        // b missing: put back
  write(root / "c" / "report.json", "current");
  write(root / (".c.hqview-old-" + dead) / "report.json", "older");      // c present: removed
  write(root / (".d.hqview-tmp-" + alive) / "report.json", "running");  // a live process's: kept
  write(root / ".hidden.hqview-tmp-x", "not a pid");                     // not ours: kept
  write(root / "sub" / (".e.hqview-tmp-" + dead) / "report.json", "deep");
  write(root / "c" / (".f.hqview-tmp-" + dead), "inside a bundle");      // bundles are not entered
  EXPECT_EQ(hq::remove_stale_temporaries(root, false), 4);
  EXPECT_FALSE(fs::exists(root / (".a.mesh.hqview-tmp-" + dead)));
  EXPECT_FALSE(fs::exists(root / (".index.json.hqview-tmp-" + dead)));
  EXPECT_EQ(read(root / "b" / "report.json"), "kept");
  EXPECT_EQ(read(root / "c" / "report.json"), "current");
  EXPECT_FALSE(fs::exists(root / (".c.hqview-old-" + dead)));
  EXPECT_TRUE(fs::exists(root / (".d.hqview-tmp-" + alive)));
  EXPECT_TRUE(fs::exists(root / ".hidden.hqview-tmp-x"));
  EXPECT_TRUE(fs::exists(root / "sub" / (".e.hqview-tmp-" + dead)));  // not recursive
  EXPECT_EQ(hq::remove_stale_temporaries(root, true), 1);
  EXPECT_FALSE(fs::exists(root / "sub" / (".e.hqview-tmp-" + dead)));
  EXPECT_TRUE(fs::exists(root / "c" / (".f.hqview-tmp-" + dead)));
}

}  // namespace
