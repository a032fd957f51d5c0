#pragma once
// Hybrid meshes made by Debian's Gmsh 4.8.4 (built-in kernel) in the tests:
// the .geo texts, and one run of gmsh on one of them.
//   kHexTetGeo:   a 4x4x4 recombined transfinite box [0,1]^3 and an
//                 unstructured box [1,2]x[0,1]^2 extruded from its x=1 face
//                 without layers: 64 hexes, tets, and 16 pyramids Gmsh puts
//                 on the shared face's quads.
//   kExtrudedGeo: a 3x3 transfinite recombined square [0,1]^2 next to the
//                 triangle (1,0)-(2,0.5)-(1,1), extruded to z = 1 in 3 layers
//                 with Recombine: 27 hexes and wedges.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace hq::test {

inline constexpr const char* kHexTetGeo = R"(
Point(1) = {0, 0, 0, 0.25};
l[] = Extrude {0, 1, 0} { Point{1}; Layers{4}; };
s[] = Extrude {0, 0, 1} { Line{l[1]}; Layers{4}; Recombine; };
v[] = Extrude {1, 0, 0} { Surface{s[1]}; Layers{4}; Recombine; };
w[] = Extrude {1, 0, 0} { Surface{v[0]}; };
)";

inline constexpr const char* kExtrudedGeo = R"(
Point(1) = {0, 0, 0, 0.3}; Point(2) = {1, 0, 0, 0.3}; Point(3) = {1, 1, 0, 0.3};
Point(4) = {0, 1, 0, 0.3}; Point(5) = {2, 0.5, 0, 0.3};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1}; Line(5) = {2, 5}; Line(6) = {5, 3};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, -2}; Plane Surface(2) = {2};
Transfinite Curve{1, 2, 3, 4} = 4; Transfinite Surface{1}; Recombine Surface{1};
Extrude {0, 0, 1} { Surface{1, 2}; Layers{3}; Recombine; }
)";

// Runs `gmsh` (its path) on `geo` in `dir` (made if missing), writing
// dir/name in MSH 4.1; false when gmsh is missing or fails.
inline bool run_gmsh_geo(const std::string& gmsh, const std::filesystem::path& dir, const std::string& geo,
                         const std::string& name) {
  std::filesystem::create_directories(dir);
  const std::filesystem::path geo_path = dir / (name + ".geo");
  std::ofstream(geo_path) << geo;
  const std::string command = gmsh + " -3 -nt 1 " + geo_path.string() + " -format msh41 -o " + (dir / name).string() +
                              " > " + (dir / (name + ".log")).string() + " 2>&1";
  return std::system(command.c_str()) == 0 && std::filesystem::exists(dir / name);
}

}  // namespace hq::test
