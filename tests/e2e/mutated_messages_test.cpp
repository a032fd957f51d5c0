// Byte mutation of mesh files (issue 46, "Messages are text"): the one-hex
// files of tests/bad_inputs/ in every format with bytes that are not UTF-8,
// C0 and C1 control characters and random bytes put in at random places
// (fixed seed), 40 of each, run through one `hqview batch`. Whatever each
// reader says about its file, standard error is valid UTF-8 with no control
// character but '\n', and so are index.json, junit.xml (well-formed XML),
// index.html and summary.md, which repeat every error.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "cli_runner.h"
#include "support/fixtures.h"
#include "support/text_checks.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

namespace fs = std::filesystem;

// Puts 1 to 3 hostile bytes or sequences into bytes.
std::string mutate(std::string bytes, std::mt19937_64& rng) {
  static const std::string kHostile[] = {"\xa6",     "\x1b", "\x1b[2J", "\x07",     "\x08",         "\r",       "\x7f",
                                         "\xc2\x9b", "\xff", "\xc3",    "\xe2\x82", "\xed\xa0\x80", "\xc0\xaf", "\x00"};
  const int count = 1 + static_cast<int>(rng() % 3);
  for (int m = 0; m < count; ++m) {
    const std::size_t at = rng() % (bytes.size() + 1);
    switch (rng() % 3) {
      case 0: {  // inserted
        const std::string& h = kHostile[rng() % std::size(kHostile)];
        bytes.insert(at, h.data(), h == std::string("\x00") ? 1 : h.size());
        break;
      }
      case 1:  // a byte replaced by a hostile one
        if (at < bytes.size()) bytes[at] = kHostile[rng() % 9][0];
        break;
      default:  // a byte replaced by any byte
        if (at < bytes.size()) bytes[at] = static_cast<char>(rng());
    }
  }
  return bytes;
}

TEST(MessagesAreText, MutatedMeshFilesGiveTextOnEveryOutput) {
  const fs::path root = fresh_output_dir("mutated_messages");
  const fs::path in = root / "in", out = root / "out";
  fs::create_directories(in);
  std::mt19937_64 rng(46);
  int written = 0;
  for (const char* seed : {"medit_one_hex.mesh", "vtk_one_hex.vtk", "vtu_one_hex.vtu", "gmsh_one_hex.msh",
                           "abaqus_one_hex.inp", "exodus_one_hex.e"}) {
    const fs::path file = source_dir() / "tests/bad_inputs" / seed;
    const std::string valid = read_text(file);
    for (int i = 0; i < 40; ++i) {
      std::ofstream(in / (file.stem().string() + "_" + std::to_string(i) + file.extension().string()), std::ios::binary)
          << mutate(valid, rng);
      ++written;
    }
  }
  const CliResult b =
      run_hqview({"batch", in.string(), "-o", out.string(), "--no-render", "--no-viewer", "--data", "none"});
  EXPECT_TRUE(b.exit_code == 0 || b.exit_code == 3) << b.exit_code << "\n" << b.err;
  EXPECT_TRUE(is_valid_utf8(b.err)) << "stderr is not UTF-8";
  const std::size_t at = find_control_character(b.err, "\n");
  EXPECT_EQ(at, std::string::npos) << "control character in stderr: " << b.err.substr(at > 80 ? at - 80 : 0, 160);
  // The mutations reach the messages: many meshes are refused, and some
  // messages show escaped bytes.
  int failed = 0;
  for (std::size_t p = b.err.find("] failed "); p != std::string::npos; p = b.err.find("] failed ", p + 1)) ++failed;
  EXPECT_GT(failed, written / 4) << b.err;
  EXPECT_NE(b.err.find("\\x"), std::string::npos) << b.err;

  for (const char* name : {"index.json", "junit.xml", "index.html", "summary.md"}) {
    const std::string text = read_text(out / name);
    EXPECT_TRUE(is_valid_utf8(text)) << name << " is not UTF-8";
    EXPECT_EQ(find_control_character(text, "\n\t"), std::string::npos) << name;
  }
  const nlohmann::json index = nlohmann::json::parse(read_text(out / "index.json"));
  EXPECT_EQ(index["meshes"].size(), static_cast<std::size_t>(written));
  const std::string parse_junit = "python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' '" +
                                  (out / "junit.xml").string() + "'";
  EXPECT_EQ(std::system(parse_junit.c_str()), 0) << "junit.xml is not well-formed XML";
}

}  // namespace
}  // namespace hq::test
