#include "hqview/core/cell_kinds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "hqview/core/vec3.h"

namespace HQ_TEST_UNIT {

using hq::CellKind;
using hq::CellKindTable;
using hq::Vec3;

// A valid reference cell of each kind in VTK's corner order, written out by
// hand from VTK's cell documentation (not from the tables under test).
std::vector<Vec3> reference_cell(CellKind kind) {
  switch (kind) {
    case CellKind::hex:
      return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    case CellKind::tet:
      return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case CellKind::wedge:  // (0,1,2)'s right-hand normal points to -z, away from the top
      return {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 0, 1}};
    case CellKind::pyramid:
      return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
    case CellKind::quad:
      return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    case CellKind::triangle:
      return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  }
  return {};
}

double det3(const Vec3& a, const Vec3& b, const Vec3& c) { return dot(a, cross(b, c)); }

template <CellKind K>
void check_kind() {
  using T = CellKindTable<K>;
  SCOPED_TRACE(std::string(T::name));
  const std::vector<Vec3> p = reference_cell(K);
  ASSERT_EQ(static_cast<int>(p.size()), T::num_corners);
  EXPECT_EQ(hq::cell_kind_num_corners(K), T::num_corners);
  EXPECT_EQ(hq::cell_kind_name(K), T::name);

  // Edges: distinct, in range; every corner reached.
  std::set<std::pair<int, int>> edges;
  for (const auto& e : T::edges) {
    ASSERT_TRUE(e[0] >= 0 && e[0] < T::num_corners && e[1] >= 0 && e[1] < T::num_corners);
    EXPECT_TRUE(edges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])}).second);
  }

  // Corner frames: neighbours along edges, right-handed in the valid cell.
  for (std::size_t i = 0; i < T::corner_frames.size(); ++i) {
    const auto& f = T::corner_frames[i];
    const int n = T::dimension == 3 ? 3 : 2;
    for (int k = 0; k < n; ++k)
      EXPECT_TRUE(edges.count({std::min<int>(static_cast<int>(i), f[k]), std::max<int>(static_cast<int>(i), f[k])}))
          << "corner " << i << " neighbour " << f[k] << " is not along an edge";
    if (T::dimension == 3)
      EXPECT_GT(det3(p[f[0]] - p[i], p[f[1]] - p[i], p[f[2]] - p[i]), 0.0) << "corner " << i;
    else
      EXPECT_EQ(f[2], -1);
  }

  if constexpr (T::dimension == 3) {
    // Faces: outward (normal away from the centroid), each edge in exactly
    // two faces, and Euler's V - E + F = 2 for a closed polyhedron.
    Vec3 centroid{0, 0, 0};
    for (const Vec3& q : p) centroid = centroid + q;
    centroid = centroid * (1.0 / static_cast<double>(p.size()));
    std::map<std::pair<int, int>, int> uses;
    for (const auto& face : T::faces) {
      ASSERT_TRUE(face.size == 3 || face.size == 4);
      Vec3 normal{0, 0, 0};
      Vec3 mid{0, 0, 0};
      for (int k = 0; k < face.size; ++k) {
        const Vec3& a = p[face.v[k]];
        const Vec3& b = p[face.v[(k + 1) % face.size]];
        normal = normal + cross(a, b);  // Newell's normal
        mid = mid + a;
        const int u = face.v[k], w = face.v[(k + 1) % face.size];
        ++uses[{std::min(u, w), std::max(u, w)}];
      }
      mid = mid * (1.0 / face.size);
      EXPECT_GT(dot(normal, mid - centroid), 0.0) << "face " << face.v[0] << face.v[1] << face.v[2];
      if (face.size == 3) {
        EXPECT_EQ(face.v[3], -1);
      }
    }
    EXPECT_EQ(uses.size(), edges.size());
    for (const auto& [edge, n] : uses) EXPECT_EQ(n, 2) << edge.first << "-" << edge.second;
    EXPECT_EQ(T::num_corners - static_cast<int>(T::edges.size()) + static_cast<int>(T::faces.size()), 2);
  } else {
    // A surface cell's edges form one cycle through every corner.
    EXPECT_EQ(static_cast<int>(T::edges.size()), T::num_corners);
  }
}

TEST(CellKinds, TablesAgreeWithValidReferenceCells) {
  hq::for_each_cell_kind([](auto k) { check_kind<k()>(); });
}

TEST(CellKinds, VtkTypesAndBlockOrder) {
  EXPECT_EQ(hq::cell_kind_vtk_type(CellKind::hex), 12);
  EXPECT_EQ(hq::cell_kind_vtk_type(CellKind::tet), 10);
  EXPECT_EQ(hq::cell_kind_vtk_type(CellKind::wedge), 13);
  EXPECT_EQ(hq::cell_kind_vtk_type(CellKind::pyramid), 14);
  EXPECT_EQ(hq::cell_kind_vtk_type(CellKind::quad), 9);
  EXPECT_EQ(hq::cell_kind_vtk_type(CellKind::triangle), 5);
  EXPECT_EQ(hq::kCellKinds.front(), CellKind::hex);
}

// The wedge permutation turns a valid VTK wedge into one whose first
// triangle's normal points towards the second (Verdict's order).
TEST(CellKinds, WedgePermutationFlipsTheFirstTriangle) {
  const std::vector<Vec3> vtk = reference_cell(CellKind::wedge);
  std::vector<Vec3> v(6);
  for (int i = 0; i < 6; ++i) v[i] = vtk[hq::kWedgeVtkToVerdict[i]];
  const Vec3 n = cross(v[1] - v[0], v[2] - v[0]);
  EXPECT_GT(dot(n, v[3] - v[0]), 0.0);
  const Vec3 n_vtk = cross(vtk[1] - vtk[0], vtk[2] - vtk[0]);
  EXPECT_LT(dot(n_vtk, vtk[3] - vtk[0]), 0.0);
}

}  // namespace
