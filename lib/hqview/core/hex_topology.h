#pragma once
// Reference-hexahedron tables (VTK_HEXAHEDRON = Exodus HEX8 = Verdict =
// Gmsh type 5 = MEDIT Hexahedra corner order; ALGORITHMS.md §1).
//
//          7 -------- 6
//         /|         /|
//        / |        / |
//       4 -------- 5  |        z
//       |  3 ------|- 2        |  y
//       | /        | /         | /
//       |/         |/          |/
//       0 -------- 1           +---- x
//
// 0-1-2-3 is the bottom face, counter-clockwise seen from the top; corner
// i+4 lies above corner i. A valid hex has det[P1-P0, P3-P0, P4-P0] > 0.

#include <array>

namespace hq {

// The 12 edges, bottom ring, top ring, then the verticals.
inline constexpr std::array<std::array<int, 2>, 12> kHexEdges = {{
    {0, 1}, {1, 2}, {2, 3}, {3, 0},  //
    {4, 5}, {5, 6}, {6, 7}, {7, 4},  //
    {0, 4}, {1, 5}, {2, 6}, {3, 7},
}};

// The 6 faces, each listed counter-clockwise seen from outside the hex
// (outward normal by the right-hand rule).
inline constexpr std::array<std::array<int, 4>, 6> kHexFaces = {{
    {0, 3, 2, 1},  // bottom (-z)
    {4, 5, 6, 7},  // top (+z)
    {0, 1, 5, 4},  // front (-y)
    {2, 3, 7, 6},  // back (+y)
    {1, 2, 6, 5},  // right (+x)
    {3, 0, 4, 7},  // left (-x)
}};

// Corner frames: for corner i, the three neighbours a, b, c such that
// (Pa-Pi, Pb-Pi, Pc-Pi) is right-handed in a valid hex.
inline constexpr std::array<std::array<int, 3>, 8> kCornerFrames = {{
    {1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
    {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3},
}};

// For corner i and frame slot k, the edge (index into kHexEdges) joining
// i to kCornerFrames[i][k]. Lets kernels compute each edge length once.
inline constexpr std::array<std::array<int, 3>, 8> kCornerFrameEdges = {{
    {0, 3, 8}, {1, 0, 9}, {2, 1, 10}, {3, 2, 11},
    {7, 4, 8}, {4, 5, 9}, {5, 6, 10}, {6, 7, 11},
}};

}  // namespace hq
