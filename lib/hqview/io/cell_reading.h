#pragma once
// What every mesh reader shares to put a file's volume cells into a Mesh's
// blocks (mesh/mesh.h): appending a cell of a kind with its source index,
// the corner permutation of the formats that list a wedge the other way
// round, the check for repeated corners, and the words of the messages
// ("2 tetrahedra, 1 wedge"), the reading of hexahedra with repeated corners
// in a collapse pattern as their collapsed kind, and the one warning per
// file about such cells and about higher-order cells read by their corners
// (CellNotes).
//
// Wedge orders (docs/formats.md): VTK (legacy, VTU), MEDIT and OVM's
// reconstruction use VTK_WEDGE's order (the right-hand normal of the first
// triangle points away from the second); Gmsh (prism, type 6), Exodus
// (WEDGE6) and Abaqus (C3D6) point it towards the second, as Verdict does.
// Those three are read through kWedgeFlippedToVtk.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "hqview/core/cell_kinds.h"
#include "hqview/core/types.h"
#include "hqview/io/read_limits.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/mesh/mesh.h"

namespace hq::detail {

// A wedge in Gmsh/Exodus/Abaqus/Verdict order -> VTK order:
// vtk_corner[i] = file_corner[kWedgeFlippedToVtk[i]] (its own inverse).
inline constexpr std::array<int, 6> kWedgeFlippedToVtk = {0, 2, 1, 3, 5, 4};

// Appends one cell, its corners already in VTK order, and its source index.
template <CellKind K>
void append_cell(Mesh& mesh, const CellCorners<K>& corners, std::int64_t source_index) {
  cell_block<K>(mesh).push_back(corners);
  mesh.source_index[static_cast<std::size_t>(K)].push_back(source_index);
}

// Appends one volume cell of `kind` from the num_corners(kind) ids at
// `corners`, in the file's order; `to_vtk` (nullptr: none) permutes them:
// vtk_corner[i] = corners[to_vtk[i]].
void append_cell(Mesh& mesh, CellKind kind, const Index* corners, const int* to_vtk, std::int64_t source_index);

// The position j of the first id among ids[0..n) equal to an earlier one, -1
// when all are distinct.
int first_repeated(const Index* ids, int n);

// A hexahedron (corners in VTK order) whose repeated corners follow one of
// the collapse patterns that ANSYS, Abaqus, Exodus and HyperMesh writers use
// for other kinds in an 8-node hexahedron, as that kind, corners in VTK
// order; none for any other hexahedron (all corners distinct, or repeated
// otherwise). With 1-based corners, the documented patterns are
//   wedge:   3=4 and 7=8 (ANSYS "K,L and O,P"), or 2=3 and 6=7 (HyperMesh):
//            two parallel edges of one face collapse, that face becoming an
//            edge; 6 distinct corners;
//   pyramid: 5=6=7=8, one face collapsed to the apex; 5 distinct corners;
//   tet:     3=4 and 5=6=7=8 (ANSYS "K,L and M,N,O,P"); 4 distinct corners;
// and each of them on any face: every rotation of the hexahedron (the 24
// that keep its orientation) of those three. A rotation keeps the sign of
// the volume, so a valid collapsed hexahedron gives a valid cell.
struct CollapsedHex {
  CellKind kind;
  std::array<Index, 8> corners;  // the first num_corners(kind), VTK order
};
std::optional<CollapsedHex> collapse_hex(const std::array<Index, 8>& hex);

// What a reader tells once per file about the cells it read in a way the
// user should know of: higher-order cells (second-order, Lagrange, Bezier)
// read by their corner nodes, counted by the format's type name, and
// hexahedra with repeated corners read as their collapsed kind, counted by
// kind with the first few of their source indices.
class CellNotes {
 public:
  // Type names in their natural order: numbers by value ("9" before "24"),
  // names alphabetically.
  struct TypeOrder {
    bool operator()(const std::string& a, const std::string& b) const {
      const bool numbers = is_number(a) && is_number(b);
      return numbers && a.size() != b.size() ? a.size() < b.size() : a < b;
    }
    static bool is_number(const std::string& s) {
      return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
    }
  };

  void add_higher_order(const std::string& type, std::int64_t count = 1) { higher_order_[type] += count; }
  void add_collapsed(CellKind kind, std::int64_t source_index);

  // The warnings ("" none), `noun` the format's word ("cell", "element"):
  //   "NAME: 12 second-order cells read by their corner nodes only (10 of type 24, 2 of type 25):
  //    their other nodes are ignored, so curved cells are measured straight"
  //   "NAME: 3 hexahedra with repeated corners read as the cells they collapse to (2 wedges,
  //    1 tetrahedron): cells 4, 7, 9"
  void append_warnings(const std::string& file, const char* noun, std::vector<std::string>& warnings) const;

 private:
  std::map<std::string, std::int64_t, TypeOrder> higher_order_;
  std::array<std::int64_t, kNumCellKinds> collapsed_by_kind_{};
  std::vector<std::int64_t> collapsed_sources_;  // the first kShownCollapsed
  std::int64_t num_collapsed_ = 0;
};

// A hexahedron whose corners repeat: appends it as its collapsed kind
// (collapse_hex), noted in `notes`, and returns true; false (nothing
// appended) when the repetition is not a collapse pattern. `corners` in the
// file's order, `to_vtk` (nullptr: none) as for append_cell.
bool append_collapsed_hex(Mesh& mesh, const Index* corners, const int* to_vtk, std::int64_t source_index,
                          CellNotes& notes);

// The surface cells (quadrilaterals, triangles) of a file, and how the ones
// with repeated corners were read: a quadrilateral with one collapsed edge
// (two neighbouring corners equal, 3 distinct) is read as its triangle; any
// other repetition (a triangle with two equal corners, a quadrilateral with
// opposite corners equal or 2 distinct) leaves the cell out. Told once per
// file (append_warnings), only when the mesh is read as a surface.
class SurfaceNotes {
 public:
  // Appends a surface cell of `kind` (quad or triangle) from its corners in
  // VTK order; returns false when it was left out.
  bool append(Mesh& mesh, CellKind kind, const Index* corners, std::int64_t source_index);

  //   "NAME: 2 quadrilaterals with a repeated corner read as triangles: cells 4, 7"
  //   "NAME: 1 surface cell with repeated corners left out (no area): cell 9"
  void append_warnings(const std::string& file, const char* noun, std::vector<std::string>& warnings) const;

  std::int64_t num_left_out() const { return num_left_out_; }

  // The reason of a surface mesh without cells: "no surface cells
  // (quadrilaterals or triangles)", or, when every one was left out, "no
  // surface cells with an area (every quadrilateral and triangle repeats a
  // corner)".
  std::string no_cells_message() const;

 private:
  std::vector<std::int64_t> collapsed_sources_, left_out_sources_;  // the first few
  std::int64_t num_collapsed_ = 0, num_left_out_ = 0;
};

// What a reader keeps about the surface cells of a file while it reads the
// volume cells (both go into the mesh's blocks; keep_dimension decides which
// stay): their count by the format's type, how repeated corners and
// higher-order cells were read, and the first malformed one (a node
// undefined or out of range, a point count its type cannot have), which
// fails the read only when the mesh is a surface (a volume mesh skips
// surface cells unread, as before surface meshes were read). `where` is the
// reader's location of the bad cell (a line, a byte offset, ...).
template <class Type>
struct SurfaceCells {
  std::map<Type, std::int64_t> types;
  SurfaceNotes notes;
  CellNotes higher_order;
  std::int64_t bad_where = -1, bad_detail = 0;
  std::string bad_message;

  bool has_bad() const { return !bad_message.empty(); }
  void set_bad(std::int64_t where, std::int64_t detail, std::string message) {
    if (has_bad()) return;
    bad_where = where;
    bad_detail = detail;
    bad_message = std::move(message);
  }
  // The warnings of a surface mesh: higher-order cells, repeated corners.
  void append_warnings(const std::string& file, const char* noun, std::vector<std::string>& warnings) const {
    higher_order.append_warnings(file, noun, warnings);
    notes.append_warnings(file, noun, warnings);
  }
};

// After a reader has read every cell: keeps the blocks of the dimension the
// mesh is read as (`dimension`, ReadLimits) and returns true for a surface
// mesh. `surface_types` counts the file's surface cells by the format's type
// (read or left out by SurfaceNotes). A volume mesh drops the surface blocks
// and counts their types into `skipped` (the "cells of unread types skipped"
// warning, as before surface meshes were read); a surface mesh drops the
// volume blocks, and `num_volume_dropped` is how many (with --dimension
// surface on a file that has them).
template <class Type>
bool keep_dimension(Mesh& mesh, MeshDimension dimension, std::map<Type, std::int64_t>& skipped,
                    const std::map<Type, std::int64_t>& surface_types, std::int64_t& num_volume_dropped);

// The word for a kind's cells, singular or plural: "hexahedron",
// "tetrahedra", "wedges", "pyramid", ...
std::string cell_kind_noun(CellKind kind, std::int64_t count);

// "2 tetrahedra, 1 wedge, 3 pyramids": the non-empty volume blocks other
// than hexahedra, "" when there are none.
std::string non_hex_volume_counts(const Mesh& mesh);

// The number of surface cells (quadrilaterals, triangles).
inline std::int64_t num_surface_cells(const Mesh& mesh) {
  return static_cast<std::int64_t>(mesh.quads.size() + mesh.triangles.size());
}

// "36 quadrilaterals, 4 triangles": the non-empty surface blocks.
std::string surface_counts(const Mesh& mesh);

// The warning of --dimension surface on a file with volume cells:
// "NAME: 12 volume cells left out (--dimension surface)".
std::string volume_dropped_warning(const std::string& file, std::int64_t count, const char* noun);

template <class Type>
bool keep_dimension(Mesh& mesh, MeshDimension dimension, std::map<Type, std::int64_t>& skipped,
                    const std::map<Type, std::int64_t>& surface_types, std::int64_t& num_volume_dropped) {
  const bool is_surface = dimension == MeshDimension::surface ||
                          (dimension == MeshDimension::automatic && num_volume_cells(mesh) == 0 && !surface_types.empty());
  num_volume_dropped = 0;
  if (is_surface) {
    num_volume_dropped = num_volume_cells(mesh);
    for (const CellKind kind : {CellKind::hex, CellKind::tet, CellKind::wedge, CellKind::pyramid})
      mesh.source_index[static_cast<std::size_t>(kind)].clear();
    mesh.hexes.clear();
    mesh.tets.clear();
    mesh.wedges.clear();
    mesh.pyramids.clear();
  } else {
    for (const CellKind kind : {CellKind::quad, CellKind::triangle})
      mesh.source_index[static_cast<std::size_t>(kind)].clear();
    mesh.quads.clear();
    mesh.triangles.clear();
    for (const auto& [type, n] : surface_types) skipped[type] += n;
  }
  return is_surface;
}

}  // namespace hq::detail
