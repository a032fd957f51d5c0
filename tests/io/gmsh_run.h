#pragma once
// Runs Debian's Gmsh (built-in kernel) on a .geo text in a test, and the
// hybrid .geo texts of support/gmsh_hybrid.h; shared by the io and overlap
// tests. The including test target defines HQ_GMSH (the gmsh executable,
// or a name that fails when gmsh is missing).

#include <cstdlib>
#include <string>
#include <vector>

#include "support/gmsh_hybrid.h"  // kHexTetGeo, kExtrudedGeo
#include "temp_dir.h"

namespace hq::test {

// Runs gmsh on a .geo text, writing each of `outputs` (by extension: *22.msh
// MSH 2.2, *.msh MSH 4.1, else Gmsh's choice) into dir; false when gmsh is
// missing or fails. `options` go before the output (e.g. "-order 2").
inline bool run_gmsh(const TempDir& dir, const std::string& geo, const std::vector<std::string>& outputs,
                     const std::string& options = "") {
  const auto geo_path = dir.write("m.geo", geo);
  for (const std::string& output : outputs) {
    const std::string format = output.ends_with("22.msh") ? " -format msh22" : output.ends_with(".msh") ? " -format msh41" : "";
    const std::string command = std::string(HQ_GMSH) + " -3 -nt 1 " + options + " " + geo_path.string() + format + " -o " +
                                (dir.path() / output).string() + " > " + (dir.path() / "gmsh.log").string() + " 2>&1";
    if (std::system(command.c_str()) != 0) return false;
  }
  return true;
}

}  // namespace hq::test
