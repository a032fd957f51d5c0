#include "hqview/io/cell_reading.h"

#include <algorithm>

namespace hq::detail {

namespace {

// The 24 rotations of the reference cube as corner permutations of a VTK
// hexahedron: the rotated hexahedron's corner i is the original's
// corner r[i]. Built from the signed permutation matrices of determinant +1
// acting on the corners' coordinates in {-1, 1}^3.
using HexRotation = std::array<int, 8>;

std::array<HexRotation, 24> hex_rotations() {
  constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const auto corner_at = [&](const int xyz[3]) {
    for (int c = 0; c < 8; ++c)
      if (kCorner[c][0] == xyz[0] && kCorner[c][1] == xyz[1] && kCorner[c][2] == xyz[2]) return c;
    return -1;
  };
  std::array<HexRotation, 24> rotations{};
  std::size_t n = 0;
  std::array<int, 3> axes = {0, 1, 2};
  do {
    // The permutation's sign times the signs' product must be +1.
    const int inversions = (axes[0] > axes[1]) + (axes[0] > axes[2]) + (axes[1] > axes[2]);
    for (int signs = 0; signs < 8; ++signs) {
      const int flips = (signs & 1) + ((signs >> 1) & 1) + ((signs >> 2) & 1);
      if ((inversions + flips) % 2 != 0) continue;
      HexRotation r{};
      for (int i = 0; i < 8; ++i) {
        int xyz[3];
        for (int k = 0; k < 3; ++k) {
          const int v = kCorner[i][axes[static_cast<std::size_t>(k)]];
          xyz[k] = ((signs >> k) & 1) != 0 ? 1 - v : v;
        }
        r[static_cast<std::size_t>(i)] = corner_at(xyz);
      }
      rotations[n++] = r;
    }
  } while (std::next_permutation(axes.begin(), axes.end()));
  return rotations;
}

int num_distinct(const std::array<Index, 8>& ids) {
  int n = 0;
  for (std::size_t j = 0; j < 8; ++j)
    if (std::find(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(j), ids[j]) == ids.begin() + static_cast<std::ptrdiff_t>(j)) ++n;
  return n;
}

constexpr std::size_t kShownCollapsed = 5;

}  // namespace

std::optional<CollapsedHex> collapse_hex(const std::array<Index, 8>& hex) {
  static const std::array<HexRotation, 24> kRotations = hex_rotations();
  const int distinct = num_distinct(hex);
  if (distinct < 4 || distinct > 6) return std::nullopt;
  for (const HexRotation& r : kRotations) {
    std::array<Index, 8> h;
    for (std::size_t i = 0; i < 8; ++i) h[i] = hex[static_cast<std::size_t>(r[i])];
    // In each pattern the bottom face (0,1,2,3) turns its right-hand normal
    // towards the top (4,5,6,7), as in every valid hexahedron.
    if (distinct == 6 && h[2] == h[3] && h[6] == h[7]) {
      // Triangles (0,1,2) below (4,5,6), normal towards it: VTK's wedge
      // turns it away, so the triangles are listed (0,2,1) and (4,6,5).
      return CollapsedHex{CellKind::wedge, {h[0], h[2], h[1], h[4], h[6], h[5], 0, 0}};
    }
    if (distinct == 5 && h[4] == h[5] && h[4] == h[6] && h[4] == h[7])
      return CollapsedHex{CellKind::pyramid, {h[0], h[1], h[2], h[3], h[4], 0, 0, 0}};
    if (distinct == 4 && h[2] == h[3] && h[4] == h[5] && h[4] == h[6] && h[4] == h[7])
      return CollapsedHex{CellKind::tet, {h[0], h[1], h[2], h[4], 0, 0, 0, 0}};
  }
  return std::nullopt;
}

void CellNotes::add_collapsed(CellKind kind, std::int64_t source_index) {
  ++collapsed_by_kind_[static_cast<std::size_t>(kind)];
  if (collapsed_sources_.size() < kShownCollapsed) collapsed_sources_.push_back(source_index);
  ++num_collapsed_;
}

void CellNotes::append_warnings(const std::string& file, const char* noun, std::vector<std::string>& warnings) const {
  const auto plural = [&](std::int64_t n) { return std::string(noun) + (n > 1 ? "s" : ""); };
  if (!higher_order_.empty()) {
    std::int64_t total = 0;
    std::string types;
    for (const auto& [type, n] : higher_order_) {
      total += n;
      types += (types.empty() ? "" : ", ") + std::to_string(n) + " of type " + type;
    }
    const std::string its = total > 1 ? "their" : "its";
    warnings.push_back(file + ": " + std::to_string(total) + " higher-order " + plural(total) + " read by " + its +
                       " corner nodes only (" + types + "): " + its +
                       " other nodes are ignored, so curved cells are measured as straight-sided ones");
  }
  if (num_collapsed_ > 0) {
    std::string kinds;
    for (const CellKind kind : {CellKind::wedge, CellKind::pyramid, CellKind::tet}) {
      const std::int64_t n = collapsed_by_kind_[static_cast<std::size_t>(kind)];
      if (n > 0) kinds += (kinds.empty() ? "" : ", ") + std::to_string(n) + " " + cell_kind_noun(kind, n);
    }
    std::string sources;
    for (const std::int64_t s : collapsed_sources_) sources += (sources.empty() ? "" : ", ") + std::to_string(s);
    if (num_collapsed_ > static_cast<std::int64_t>(collapsed_sources_.size()))
      sources += " and " + std::to_string(num_collapsed_ - static_cast<std::int64_t>(collapsed_sources_.size())) +
                 " more";
    warnings.push_back(file + ": " + std::to_string(num_collapsed_) + " " + cell_kind_noun(CellKind::hex, num_collapsed_) +
                       " with repeated corners read as the cells they collapse to (" + kinds + "): " +
                       plural(num_collapsed_) + " " + sources);
  }
}

bool append_collapsed_hex(Mesh& mesh, const Index* corners, const int* to_vtk, std::int64_t source_index,
                          CellNotes& notes) {
  std::array<Index, 8> hex;
  for (std::size_t i = 0; i < 8; ++i) hex[i] = corners[to_vtk != nullptr ? to_vtk[i] : i];
  const std::optional<CollapsedHex> collapsed = collapse_hex(hex);
  if (!collapsed) return false;
  append_cell(mesh, collapsed->kind, collapsed->corners.data(), nullptr, source_index);
  notes.add_collapsed(collapsed->kind, source_index);
  return true;
}

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

std::string surface_counts(const Mesh& mesh) {
  std::string text;
  for (const CellKind kind : {CellKind::quad, CellKind::triangle}) {
    const std::int64_t n = num_cells_of(mesh, kind);
    if (n == 0) continue;
    if (!text.empty()) text += ", ";
    text += std::to_string(n) + " " + cell_kind_noun(kind, n);
  }
  return text;
}

std::string volume_dropped_warning(const std::string& file, std::int64_t count, const char* noun) {
  return file + ": " + std::to_string(count) + " volume " + noun + (count > 1 ? "s" : "") +
         " left out (--dimension surface)";
}

bool SurfaceNotes::append(Mesh& mesh, CellKind kind, const Index* corners, std::int64_t source_index) {
  const int n = cell_kind_num_corners(kind);
  if (first_repeated(corners, n) < 0) {
    append_cell(mesh, kind, corners, nullptr, source_index);
    return true;
  }
  if (kind == CellKind::quad) {
    // One collapsed edge (i, i+1): the other three corners, in their order.
    for (int i = 0; i < 4; ++i) {
      const Index t[3] = {corners[(i + 1) % 4], corners[(i + 2) % 4], corners[(i + 3) % 4]};
      if (corners[i] == t[0] && first_repeated(t, 3) < 0) {
        append_cell(mesh, CellKind::triangle, t, nullptr, source_index);
        if (collapsed_sources_.size() < kShownCollapsed) collapsed_sources_.push_back(source_index);
        ++num_collapsed_;
        return true;
      }
    }
  }
  if (left_out_sources_.size() < kShownCollapsed) left_out_sources_.push_back(source_index);
  ++num_left_out_;
  return false;
}

void SurfaceNotes::append_warnings(const std::string& file, const char* noun, std::vector<std::string>& warnings) const {
  const auto listed = [&](const std::vector<std::int64_t>& sources, std::int64_t total) {
    std::string text = std::string(noun) + (total > 1 ? "s " : " ");
    for (std::size_t i = 0; i < sources.size(); ++i) text += (i ? ", " : "") + std::to_string(sources[i]);
    if (total > static_cast<std::int64_t>(sources.size()))
      text += " and " + std::to_string(total - static_cast<std::int64_t>(sources.size())) + " more";
    return text;
  };
  if (num_collapsed_ > 0)
    warnings.push_back(file + ": " + std::to_string(num_collapsed_) + " " + cell_kind_noun(CellKind::quad, num_collapsed_) +
                       " with a repeated corner read as " + (num_collapsed_ > 1 ? "" : "a ") +
                       cell_kind_noun(CellKind::triangle, num_collapsed_) + ": " +
                       listed(collapsed_sources_, num_collapsed_));
  if (num_left_out_ > 0)
    warnings.push_back(file + ": " + std::to_string(num_left_out_) + " surface " + noun + (num_left_out_ > 1 ? "s" : "") +
                       " with repeated corners left out (no area): " + listed(left_out_sources_, num_left_out_));
}

std::string SurfaceNotes::no_cells_message() const {
  return num_left_out_ > 0 ? "no surface cells with an area (every quadrilateral and triangle repeats a corner)"
                           : "no surface cells (quadrilaterals or triangles)";
}

}  // namespace hq::detail
