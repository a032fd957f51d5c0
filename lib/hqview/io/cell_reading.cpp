#include "hqview/io/cell_reading.h"

namespace hq::detail {

void append_cell(Mesh& mesh, CellKind kind, const Index* corners, const int* to_vtk, std::int64_t source_index) {
  for_each_cell_kind([&](auto k) {
    if (k() != kind) return;
    CellCorners<k()> cell;
    for (std::size_t i = 0; i < cell.size(); ++i) cell[i] = corners[to_vtk != nullptr ? to_vtk[i] : i];
    append_cell<k()>(mesh, cell, source_index);
  });
}

int first_repeated(const Index* ids, int n) {
  for (int j = 1; j < n; ++j)
    for (int i = 0; i < j; ++i)
      if (ids[i] == ids[j]) return j;
  return -1;
}

std::string cell_kind_noun(CellKind kind, std::int64_t count) {
  const bool one = count == 1;
  switch (kind) {
    case CellKind::hex:
      return one ? "hexahedron" : "hexahedra";
    case CellKind::tet:
      return one ? "tetrahedron" : "tetrahedra";
    case CellKind::wedge:
      return one ? "wedge" : "wedges";
    case CellKind::pyramid:
      return one ? "pyramid" : "pyramids";
    case CellKind::quad:
      return one ? "quadrilateral" : "quadrilaterals";
    case CellKind::triangle:
      return one ? "triangle" : "triangles";
  }
  return {};
}

std::string non_hex_volume_counts(const Mesh& mesh) {
  std::string text;
  for (const CellKind kind : {CellKind::tet, CellKind::wedge, CellKind::pyramid}) {
    const std::int64_t n = num_cells_of(mesh, kind);
    if (n == 0) continue;
    if (!text.empty()) text += ", ";
    text += std::to_string(n) + " " + cell_kind_noun(kind, n);
  }
  return text;
}

std::int64_t num_volume_cells(const Mesh& mesh) {
  return static_cast<std::int64_t>(mesh.hexes.size() + mesh.tets.size() + mesh.wedges.size() + mesh.pyramids.size());
}

}  // namespace hq::detail
