#pragma once
// Meshes built in code for tests, and the location of ../shared/data.

#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"

namespace hq::test {

// The unit cube [0,1]^3 as one hex.
HexMesh unit_cube();
// An n x n x n grid of unit hexes, (n+1)^3 points, x fastest.
HexMesh grid(int n);
// An nx x ny x nz grid of unit hexes, x fastest.
HexMesh box_grid(int nx, int ny, int nz);
// The 8 corners of the unit cube with the top face rotated by theta radians
// about the vertical axis through its centre.
std::array<Vec3, 8> twisted_hex(double theta);
// The unit cube with its top and bottom faces swapped: every corner frame
// is left-handed.
std::array<Vec3, 8> inverted_hex();
// The unit cube's corners.
std::array<Vec3, 8> cube_corners();

// ../shared/data (or $HQVIEW_DATA) when it exists, else nullopt; tests that
// need it GTEST_SKIP() with a message.
std::optional<std::filesystem::path> shared_data_dir();
// The project's source directory (for examples/).
std::filesystem::path source_dir();
// The hex meshes (.mesh, .vtk) under data/meshes, sorted by path.
std::vector<std::filesystem::path> shared_hex_meshes(const std::filesystem::path& data);
// The mean length of the mesh's unique edges (the unit of --rmax Rx).
double mean_edge_length(const HexMesh& mesh, const Topology& topology);

// p turned by `angle` (radians) about the unit `axis` (Rodrigues' formula),
// then moved by `shift`: a placement a mesh's numbers must not depend on.
Vec3 turned(const Vec3& p, const Vec3& axis, double angle, const Vec3& shift = {});

}  // namespace hq::test
