#pragma once
// Runs Debian's Gmsh (built-in kernel) on a .geo text in a test, and the
// .geo of a conforming hex-pyramid-tet mesh; shared by the io and overlap
// tests. The including test target defines HQ_GMSH (the gmsh executable,
// or a name that fails when gmsh is missing).

#include <cstdlib>
#include <string>
#include <vector>

#include "temp_dir.h"

namespace hq::test {

// Runs gmsh on a .geo text, writing each of `outputs` (by extension: *22.msh
// MSH 2.2, *.msh MSH 4.1, else Gmsh's choice) into dir; false when gmsh is
// missing or fails.
inline bool run_gmsh(const TempDir& dir, const std::string& geo, const std::vector<std::string>& outputs) {
  const auto geo_path = dir.write("m.geo", geo);
  for (const std::string& output : outputs) {
    const std::string format = output.ends_with("22.msh") ? " -format msh22" : output.ends_with(".msh") ? " -format msh41" : "";
    const std::string command = std::string(HQ_GMSH) + " -3 -nt 1 " + geo_path.string() + format + " -o " +
                                (dir.path() / output).string() + " > " + (dir.path() / "gmsh.log").string() + " 2>&1";
    if (std::system(command.c_str()) != 0) return false;
  }
  return true;
}

// A 4x4x4 recombined transfinite box [0,1]^3 and an unstructured box
// [1,2]x[0,1]^2 extruded from its x=1 face without layers: 64 hexes, 16
// pyramids on the shared face, tets.
inline constexpr const char* kHexTetGeo = R"(
Point(1) = {0, 0, 0, 0.25};
l[] = Extrude {0, 1, 0} { Point{1}; Layers{4}; };
s[] = Extrude {0, 0, 1} { Line{l[1]}; Layers{4}; Recombine; };
v[] = Extrude {1, 0, 0} { Surface{s[1]}; Layers{4}; Recombine; };
w[] = Extrude {1, 0, 0} { Surface{v[0]}; };
)";

}  // namespace hq::test
