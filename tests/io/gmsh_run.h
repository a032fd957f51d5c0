#pragma once
// Debian's Gmsh (built-in kernel) run from a test: a .geo text meshed into
// files of a TempDir, the element counts of an ASCII MSH 2.2 file by a parse
// of its own (not HQView's reader), and the hybrid .geo texts of
// support/gmsh_hybrid.h. Shared by the io, mesh, overlap and pipeline tests.
// A test target that defines HQ_GMSH (the gmsh executable, or a name that
// fails when gmsh is missing) also gets run_gmsh without the executable.

#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "io/temp_dir.h"
#include "support/gmsh_hybrid.h"  // kHexTetGeo, kExtrudedGeo

namespace hq::test {

// Two unit squares side by side in z = 0: surface 1 [0,1]^2, surface 2
// [1,2] x [0,1], sharing line 2 (x = 1); points with the size lc.
inline constexpr const char* kTwoSquares = R"(
Point(1)={0,0,0,lc}; Point(2)={1,0,0,lc}; Point(3)={1,1,0,lc}; Point(4)={0,1,0,lc};
Point(5)={2,0,0,lc}; Point(6)={2,1,0,lc};
Line(1)={1,2}; Line(2)={2,3}; Line(3)={3,4}; Line(4)={4,1};
Line(5)={2,5}; Line(6)={5,6}; Line(7)={6,3};
Curve Loop(1)={1,2,3,4}; Plane Surface(1)={1};
Curve Loop(2)={5,6,7,-2}; Plane Surface(2)={2};
)";

// Element counts by Gmsh type of an ASCII MSH 2.2 file ("tag type ntags ...").
inline std::map<int, int> msh22_type_counts(const std::string& text) {
  std::map<int, int> counts;
  std::istringstream in(text.substr(text.find("$Elements")));
  std::string keyword;
  int n = 0;
  in >> keyword >> n;
  std::string line;
  std::getline(in, line);
  for (int e = 0; e < n && std::getline(in, line); ++e) {
    std::istringstream fields(line);
    int tag = 0, type = 0;
    fields >> tag >> type;
    ++counts[type];
  }
  return counts;
}

// Runs `gmsh` on a .geo text, writing each of `outputs` (by extension: *22.msh
// MSH 2.2, *.msh MSH 4.1, else Gmsh's choice) into dir; false when gmsh is
// missing or fails. `options` go before the output (e.g. "-order 2").
inline bool run_gmsh(const std::string& gmsh, const TempDir& dir, const std::string& geo,
                     const std::vector<std::string>& outputs, const std::string& options = "") {
  const auto geo_path = dir.write("m.geo", geo);
  for (const std::string& output : outputs) {
    const std::string format = output.ends_with("22.msh") ? " -format msh22" : output.ends_with(".msh") ? " -format msh41" : "";
    const std::string command = gmsh + " -3 -nt 1 " + options + " " + geo_path.string() + format + " -o " +
                                (dir.path() / output).string() + " > " + (dir.path() / "gmsh.log").string() + " 2>&1";
    if (std::system(command.c_str()) != 0) return false;
  }
  return true;
}

#ifdef HQ_GMSH
// The same with the target's HQ_GMSH.
inline bool run_gmsh(const TempDir& dir, const std::string& geo, const std::vector<std::string>& outputs,
                     const std::string& options = "") {
  return run_gmsh(HQ_GMSH, dir, geo, outputs, options);
}
#endif

}  // namespace hq::test
