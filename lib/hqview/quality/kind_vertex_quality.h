#pragma once
// Vertex quality by cell kind (issue 46, 46q review Q-M2): the paper's
// one-ring rule restricted to the cells of one kind, so that a view
// colouring a hex's boundary face blends the hexes' corner values only and
// a perfect hex next to poor tets stays the colour of its own corners.
// Unitless, in [-1, 1] like the corner scaled Jacobians it is made of.

#include <array>
#include <vector>

#include "hqview/core/cell_kinds.h"
#include "hqview/mesh/mesh.h"
#include "hqview/quality/quality_field.h"

namespace hq {

// by_kind[k][v]: the min corner scaled Jacobian over the corners at v of
// the cells of volume kind k; a pyramid apex (no corner value) takes the
// lowest base corner of its pyramids; NaN where no cell of kind k uses v.
// by_kind[k] is empty for a kind the mesh has no cell of, and every entry
// is empty for a mesh of one kind only (whose field.vertex_quality is
// already that kind's). Surface kinds are never filled.
struct KindVertexQuality {
  std::array<std::vector<double>, kNumCellKinds> by_kind;
  bool empty() const {
    for (const auto& v : by_kind)
      if (!v.empty()) return false;
    return true;
  }
};
KindVertexQuality kind_vertex_quality(const Mesh& mesh, const QualityField& field);

}  // namespace hq
