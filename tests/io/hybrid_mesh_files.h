#pragma once
// One small conforming hybrid mesh built by hand (2 hexahedra, 2 wedges, 1
// pyramid, 2 tetrahedra), written here in every text format HQView reads, in
// each format's own corner order, and a signed volume computed by splitting
// each cell into tetrahedra. Written for the tests alone: nothing here calls
// HQView's tables or readers, so a wrong corner order in a reader (or in
// core/cell_kinds.h) shows as a mismatch or a negative volume.
//
//        y=2  13 ---- 12            points 0-11: two unit cubes side by side
//             | W2 / |              (x in [0,2], y in [0,1], z in [0,1]);
//             |  / W1|              12-15: the box y in [1,2] over cube A,
//        y=1  3 ---- 4 ---- 5       split into wedges W1, W2 along 3-12;
//             | hex A| hex B|       16: apex of the pyramid on hex B's top;
//        y=0  0 ---- 1 ---- 2       17, 18: tetrahedra T1 (on the pyramid's
//            x=0    x=1    x=2      x=2 face) and T2 (on T1's face 8-11-17).

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace hq::test {

struct HybridCell {
  int vtk_type;            // 12 hexahedron, 10 tetra, 13 wedge, 14 pyramid
  std::vector<int> vtk;    // 0-based point ids, VTK corner order
};

struct HybridMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<HybridCell> cells;  // interleaved kinds, as a file may list them
};

inline HybridMesh hybrid_mesh() {
  HybridMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0},        // z = 0
              {0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {0, 1, 1}, {1, 1, 1}, {2, 1, 1},        // z = 1
              {1, 2, 0}, {0, 2, 0}, {1, 2, 1}, {0, 2, 1},                              // y = 2
              {1.5, 0.5, 1.6}, {2.6, 0.5, 1.4}, {2.5, 0.5, 0.6}};
  m.cells = {
      {10, {8, 11, 16, 17}},                // T1
      {12, {0, 1, 4, 3, 6, 7, 10, 9}},      // hex A
      {13, {3, 12, 4, 9, 14, 10}},          // W1: (3,12,4) faces away from (9,14,10)
      {14, {7, 8, 11, 10, 16}},             // pyramid on hex B's top
      {12, {1, 2, 5, 4, 7, 8, 11, 10}},     // hex B
      {13, {3, 13, 12, 9, 15, 14}},         // W2
      {10, {8, 11, 17, 18}},                // T2
  };
  return m;
}

// Corners of each cell kind for the split into tetrahedra (positive for a
// valid cell in VTK order): a hex around its diagonal 0-6, a wedge in 3, a
// pyramid across its base diagonal 0-2.
inline std::vector<std::array<int, 4>> tet_split(int vtk_type) {
  switch (vtk_type) {
    case 12:
      return {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
    case 13:
      return {{0, 2, 1, 3}, {1, 2, 5, 3}, {1, 5, 4, 3}};
    case 14:
      return {{0, 1, 2, 4}, {0, 2, 3, 4}};
    default:
      return {{0, 1, 2, 3}};
  }
}

// The smallest signed volume of the tetrahedra of a cell's split (all must
// be > 0 for a valid cell in VTK order) and their sum.
struct SplitVolume {
  double min_tet = 0;
  double total = 0;
};
inline SplitVolume split_volume(const std::vector<std::array<double, 3>>& p, int vtk_type,
                                const std::vector<int>& corners) {
  SplitVolume v{1e300, 0};
  for (const auto& t : tet_split(vtk_type)) {
    const auto& a = p[static_cast<std::size_t>(corners[static_cast<std::size_t>(t[0])])];
    double e[3][3];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) e[k][c] = p[static_cast<std::size_t>(corners[static_cast<std::size_t>(t[k + 1])])][c] - a[c];
    const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                       e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                       e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    v.min_tet = std::min(v.min_tet, det / 6);
    v.total += det / 6;
  }
  return v;
}

// A VTK-order wedge in the order of Gmsh, Exodus, Abaqus and MEDIT (first
// triangle's normal towards the second): swap corners 1-2 and 4-5.
inline std::vector<int> flipped_wedge(const std::vector<int>& vtk) {
  return {vtk[0], vtk[2], vtk[1], vtk[3], vtk[5], vtk[4]};
}
inline std::vector<int> file_order(const HybridCell& c, bool wedge_flipped) {
  return c.vtk_type == 13 && wedge_flipped ? flipped_wedge(c.vtk) : c.vtk;
}

inline std::string coordinates(const std::array<double, 3>& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g", p[0], p[1], p[2]);
  return buffer;
}

inline std::string ids(const std::vector<int>& corners, int base, const char* separator = " ") {
  std::string s;
  for (std::size_t i = 0; i < corners.size(); ++i) s += (i ? separator : "") + std::to_string(corners[i] + base);
  return s;
}

// MEDIT: sections by kind, 1-based, wedges as Prisms in the flipped order.
inline std::string write_medit(const HybridMesh& m) {
  std::string s = "MeshVersionFormatted 2\nDimension 3\nVertices\n" + std::to_string(m.points.size()) + "\n";
  for (const auto& p : m.points) s += coordinates(p) + " 0\n";
  for (const auto& [type, keyword] : std::vector<std::pair<int, std::string>>{
           {12, "Hexahedra"}, {10, "Tetrahedra"}, {13, "Prisms"}, {14, "Pyramids"}}) {
    std::string lines;
    int n = 0;
    for (const HybridCell& c : m.cells)
      if (c.vtk_type == type) lines += ids(file_order(c, true), 1) + " " + std::to_string(++n) + "\n";
    s += keyword + "\n" + std::to_string(n) + "\n" + lines;
  }
  return s + "End\n";
}

inline std::string write_vtk_legacy(const HybridMesh& m) {
  std::string s = "# vtk DataFile Version 4.2\nhybrid\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS " +
                  std::to_string(m.points.size()) + " double\n";
  for (const auto& p : m.points) s += coordinates(p) + "\n";
  std::size_t size = 0;
  for (const HybridCell& c : m.cells) size += 1 + c.vtk.size();
  s += "CELLS " + std::to_string(m.cells.size()) + " " + std::to_string(size) + "\n";
  for (const HybridCell& c : m.cells) s += std::to_string(c.vtk.size()) + " " + ids(c.vtk, 0) + "\n";
  s += "CELL_TYPES " + std::to_string(m.cells.size()) + "\n";
  for (const HybridCell& c : m.cells) s += std::to_string(c.vtk_type) + "\n";
  return s;
}

// A one-piece ASCII .vtu from its arrays' texts.
inline std::string vtu_text(std::size_t num_points, std::size_t num_cells, const std::string& points,
                            const std::string& connectivity, const std::string& offsets, const std::string& types) {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
         "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" +
         std::to_string(num_points) + "\" NumberOfCells=\"" + std::to_string(num_cells) +
         "\">\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">" + points +
         "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" +
         connectivity + "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + offsets +
         "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" + types +
         "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

inline std::string write_vtu(const HybridMesh& m) {
  std::string points, connectivity, offsets, types;
  for (const auto& p : m.points) points += coordinates(p) + " ";
  std::size_t offset = 0;
  for (const HybridCell& c : m.cells) {
    connectivity += ids(c.vtk, 0) + " ";
    offset += c.vtk.size();
    offsets += std::to_string(offset) + " ";
    types += std::to_string(c.vtk_type) + " ";
  }
  return vtu_text(m.points.size(), m.cells.size(), points, connectivity, offsets, types);
}

inline int gmsh_type(int vtk_type) {
  switch (vtk_type) {
    case 12:
      return 5;
    case 13:
      return 6;
    case 14:
      return 7;
    default:
      return 4;
  }
}

// Gmsh 2.2: element tags 101, 102, ... in file order, node tags 1-based.
inline std::string write_gmsh22(const HybridMesh& m) {
  std::string s = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(m.points.size()) + "\n";
  for (std::size_t i = 0; i < m.points.size(); ++i) s += std::to_string(i + 1) + " " + coordinates(m.points[i]) + "\n";
  s += "$EndNodes\n$Elements\n" + std::to_string(m.cells.size()) + "\n";
  for (std::size_t e = 0; e < m.cells.size(); ++e)
    s += std::to_string(101 + e) + " " + std::to_string(gmsh_type(m.cells[e].vtk_type)) + " 2 0 1 " +
         ids(file_order(m.cells[e], true), 1) + "\n";
  return s + "$EndElements\n";
}

// Gmsh 4.1: one element block per cell (so the file order is kept), tags as 2.2.
inline std::string write_gmsh41(const HybridMesh& m) {
  const std::size_t n = m.points.size();
  std::string s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 " + std::to_string(n) + " 1 " +
                  std::to_string(n) + "\n3 1 0 " + std::to_string(n) + "\n";
  for (std::size_t i = 0; i < n; ++i) s += std::to_string(i + 1) + "\n";
  for (const auto& p : m.points) s += coordinates(p) + "\n";
  s += "$EndNodes\n$Elements\n" + std::to_string(m.cells.size()) + " " + std::to_string(m.cells.size()) + " 101 " +
       std::to_string(100 + m.cells.size()) + "\n";
  for (std::size_t e = 0; e < m.cells.size(); ++e)
    s += "3 1 " + std::to_string(gmsh_type(m.cells[e].vtk_type)) + " 1\n" + std::to_string(101 + e) + " " +
         ids(file_order(m.cells[e], true), 1) + "\n";
  return s + "$EndElements\n";
}

// Abaqus: one *ELEMENT block per cell, labels 11, 12, ... in file order.
inline std::string write_abaqus(const HybridMesh& m) {
  std::string s = "*HEADING\nhybrid\n*NODE\n";
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const auto& p = m.points[i];
    char buffer[128];
    std::snprintf(buffer, sizeof buffer, "%zu, %.17g, %.17g, %.17g\n", i + 1, p[0], p[1], p[2]);
    s += buffer;
  }
  for (std::size_t e = 0; e < m.cells.size(); ++e) {
    const int type = m.cells[e].vtk_type;
    s += std::string("*ELEMENT, TYPE=") + (type == 12 ? "C3D8R" : type == 13 ? "C3D6" : type == 14 ? "C3D5" : "C3D4") +
         ", ELSET=E" + std::to_string(e) + "\n" + std::to_string(11 + e) + ", " +
         ids(file_order(m.cells[e], true), 1, ", ") + "\n";
  }
  return s;
}

// The outward faces of each kind in VTK order (counter-clockwise seen from
// outside), from VTK's cell definitions.
inline std::vector<std::vector<int>> outward_faces(int vtk_type) {
  switch (vtk_type) {
    case 12:
      return {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    case 13:
      return {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}};
    case 14:
      return {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    default:
      return {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  }
}

// OpenVolumeMesh ASCII: shared edges and faces, each cell's half-faces
// outward (2f as the face was first listed, 2f+1 reversed).
inline std::string write_ovm(const HybridMesh& m) {
  std::map<std::pair<int, int>, int> edge_of;
  std::vector<std::array<int, 2>> edges;
  std::map<std::set<int>, std::pair<int, std::vector<int>>> face_of;  // vertex set -> (id, first cycle)
  std::vector<std::vector<int>> faces;                                // as half-edge ids
  std::vector<std::vector<int>> cells;
  const auto halfedge = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = edge_of.find({key.first, key.second});
    if (it == edge_of.end()) {
      it = edge_of.emplace(std::pair{key.first, key.second}, static_cast<int>(edges.size())).first;
      edges.push_back({key.first, key.second});
    }
    return 2 * it->second + (a == key.first ? 0 : 1);
  };
  for (const HybridCell& c : m.cells) {
    std::vector<int> halffaces;
    for (const auto& local : outward_faces(c.vtk_type)) {
      std::vector<int> cycle;
      for (const int k : local) cycle.push_back(c.vtk[static_cast<std::size_t>(k)]);
      const std::set<int> key(cycle.begin(), cycle.end());
      auto it = face_of.find(key);
      if (it == face_of.end()) {
        std::vector<int> hes;
        for (std::size_t k = 0; k < cycle.size(); ++k) hes.push_back(halfedge(cycle[k], cycle[(k + 1) % cycle.size()]));
        it = face_of.emplace(key, std::pair{static_cast<int>(faces.size()), cycle}).first;
        faces.push_back(hes);
        halffaces.push_back(2 * it->second.first);
      } else {
        halffaces.push_back(2 * it->second.first + 1);  // a shared face is seen reversed from the other side
      }
    }
    cells.push_back(halffaces);
  }
  std::string s = "OVM ASCII\nVertices\n" + std::to_string(m.points.size()) + "\n";
  for (const auto& p : m.points) s += coordinates(p) + "\n";
  s += "Edges\n" + std::to_string(edges.size()) + "\n";
  for (const auto& e : edges) s += std::to_string(e[0]) + " " + std::to_string(e[1]) + "\n";
  s += "Faces\n" + std::to_string(faces.size()) + "\n";
  for (const auto& f : faces) s += std::to_string(f.size()) + " " + ids(f, 0) + "\n";
  s += "Polyhedra\n" + std::to_string(cells.size()) + "\n";
  for (const auto& c : cells) s += std::to_string(c.size()) + " " + ids(c, 0) + "\n";
  return s;
}

}  // namespace hq::test
