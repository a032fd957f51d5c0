#include "cli_runner.h"


#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace hq::test {

namespace fs = std::filesystem;

namespace {
std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path fresh_output_dir(const std::string& name) {
  const fs::path dir = fs::path(HQVIEW_TEST_OUTPUT) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

nlohmann::json read_report(const fs::path& bundle) { return nlohmann::json::parse(read_text(bundle / "report.json")); }

bool lsan_tracer_crashed(const std::string& err) {
  return err.find("Tracer caught signal") != std::string::npos &&
         err.find("LeakSanitizer has encountered a fatal error") != std::string::npos;
}

CliResult run_hqview(const std::vector<std::string>& args) {
  static int counter = 0;
  const fs::path capture = fs::path(HQVIEW_TEST_OUTPUT) / "capture";
  fs::create_directories(capture);
  const std::string stem = std::to_string(::getpid()) + "-" + std::to_string(counter++);
  const fs::path out = capture / (stem + ".out"), err = capture / (stem + ".err");
  std::string command = quote(HQVIEW_BINARY);
  for (const std::string& a : args) command += " " + quote(a);
  command += " >" + quote(out.string()) + " 2>" + quote(err.string()) + " </dev/null";
  int status = std::system(command.c_str());
  CliResult r;
  r.err = read_text(err);
  // Under the sanitizers, LeakSanitizer's tracer may crash at exit on its
  // own (lsan_tracer_crashed): such a run is made again, up to three more
  // times (it crashed twice in a row once), on that signature only.
  for (int retry = 0; retry < kLsanTracerRetries && lsan_tracer_crashed(r.err); ++retry) {
    std::cerr << "[ retried ] hqview: LeakSanitizer's tracer crashed at exit\n";
    status = std::system(command.c_str());
    r.err = read_text(err);
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(out);
  fs::remove(out);
  fs::remove(err);
  return r;
}

std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> row;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) row.push_back(cell);
    if (!line.empty() && line.back() == ',') row.push_back("");
    rows.push_back(std::move(row));
  }
  return rows;
}

std::filesystem::path transformed_off_copy(const std::filesystem::path& off,
                                           const std::function<std::array<double, 3>(double, double, double)>& move,
                                           const std::filesystem::path& out) {
  std::istringstream in(read_text(off));
  std::ofstream o(out);
  std::string header;
  long nv = 0, nf = 0, ne = 0;
  in >> header >> nv >> nf >> ne;
  o << header << "\n" << nv << " " << nf << " " << ne << "\n" << std::setprecision(17);
  for (long i = 0; i < nv; ++i) {
    double x, y, z;
    in >> x >> y >> z;
    const auto p = move(x, y, z);
    o << p[0] << " " << p[1] << " " << p[2] << "\n";
  }
  o << in.rdbuf();
  return out;
}

}  // namespace hq::test
