#include "hqview/quality/quality_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hqview/quality/corner_jacobian.h"
#include "hqview/quality/pyramid_metrics.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/wedge_metrics.h"

namespace hq {
namespace {

// The kernels of one non-hex volume kind: corner values, Verdict's scaled
// Jacobian, validity.
template <CellKind K>
struct VolumeKernels;
template <>
struct VolumeKernels<CellKind::tet> {
  static auto corners(const std::array<Vec3, 4>& p) { return tet_corner_scaled_jacobians(p); }
  static double scaled_jacobian(const std::array<Vec3, 4>& p) { return tet_scaled_jacobian(p); }
  static CellValidity validity(const std::array<Vec3, 4>& p) { return tet_validity(p); }
};
template <>
struct VolumeKernels<CellKind::wedge> {
  static auto corners(const std::array<Vec3, 6>& p) { return wedge_corner_scaled_jacobians(p); }
  static double scaled_jacobian(const std::array<Vec3, 6>& p) { return wedge_metric(WedgeMetric::scaled_jacobian, p); }
  static CellValidity validity(const std::array<Vec3, 6>& p) { return wedge_validity(p); }
};
template <>
struct VolumeKernels<CellKind::pyramid> {
  static auto corners(const std::array<Vec3, 5>& p) { return pyramid_corner_scaled_jacobians(p); }
  static double scaled_jacobian(const std::array<Vec3, 5>& p) {
    return pyramid_metric(PyramidMetric::scaled_jacobian, p);
  }
  static CellValidity validity(const std::array<Vec3, 5>& p) { return pyramid_validity(p); }
};

// Surface kinds: corners signed against the surface's normal (a planar
// mesh's plane) or each cell's own; the cell's value is its lowest corner
// (Verdict's scaled Jacobian when the cell is measured against its own
// normal; negative for a cell reversed against the plane); validity by the
// same normal (a surface that is not planar: SurfaceOrientation decides
// inverted).
template <>
struct VolumeKernels<CellKind::quad> {
  static auto corners(const std::array<Vec3, 4>& p, const std::optional<Vec3>& n) { return quad_corner_scaled_jacobians(p, n); }
  static CellValidity validity(const std::array<Vec3, 4>& p, const std::optional<Vec3>& n) { return quad_validity(p, n); }
};
template <>
struct VolumeKernels<CellKind::triangle> {
  static auto corners(const std::array<Vec3, 3>& p, const std::optional<Vec3>& n) {
    return triangle_corner_scaled_jacobians(p, n);
  }
  static CellValidity validity(const std::array<Vec3, 3>& p, const std::optional<Vec3>& n) {
    return triangle_validity(p, n);
  }
};

// Every kind with cells (a mesh holds volume or surface cells, never both
// in the analysis: io/cell_reading.h keep_dimension).
template <class F>
void for_each_analysed_kind(F&& f) {
  for_each_cell_kind([&](auto kind) { f(kind); });
}

// The corners, scaled Jacobian and validity of every cell of the non-hex
// block of kind K, cell ids from first_cell.
template <CellKind K>
void compute_block(const Mesh& mesh, std::size_t first_cell, QualityField& q, const SurfaceOrientation& surface) {
  const auto& cells = cell_block<K>(mesh);
  constexpr int N = CellKindTable<K>::num_corners;
  constexpr int C = kCornerValuesPerCell<K>;
  const std::size_t corner0 = q.corner_begin[static_cast<std::size_t>(K)];
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      std::array<Vec3, N> p;
      for (int i = 0; i < N; ++i) p[i] = mesh.points[static_cast<std::size_t>(cells[c][i])];
      if constexpr (CellKindTable<K>::dimension == 3) {
        const auto k = VolumeKernels<K>::corners(p);
        for (int i = 0; i < C; ++i) q.corner_scaled_jacobian[corner0 + C * c + static_cast<std::size_t>(i)] = k.value[i];
        q.corner_degenerate_mask[first_cell + c] = k.degenerate_mask;
        q.cell_scaled_jacobian[first_cell + c] = VolumeKernels<K>::scaled_jacobian(p);
        q.non_hex_validity[first_cell + c - q.num_hexes] = VolumeKernels<K>::validity(p);
      } else {
        auto k = VolumeKernels<K>::corners(p, surface.plane_normal);
        CellValidity validity = VolumeKernels<K>::validity(p, surface.plane_normal);
        if (!surface.plane_normal) {
          // Not planar: inverted = reversed against the neighbours, its
          // corners then measured against the orientation they agree on
          // (its own normal turned over: every value negated, 0 stays +0);
          // a folded (concave) cell is bad, not inverted.
          const bool reversed = first_cell + c < surface.is_reversed.size() && surface.is_reversed[first_cell + c];
          if (reversed)
            for (double& v : k.value) v = 0.0 - v;
          validity = reversed ? CellValidity::inverted
                              : (validity == CellValidity::inverted ? CellValidity::valid : validity);
        }
        for (int i = 0; i < C; ++i) q.corner_scaled_jacobian[corner0 + C * c + static_cast<std::size_t>(i)] = k.value[i];
        q.corner_degenerate_mask[first_cell + c] = k.degenerate_mask;
        q.cell_scaled_jacobian[first_cell + c] = *std::min_element(k.value.begin(), k.value.end());
        q.non_hex_validity[first_cell + c - q.num_hexes] = validity;
      }
    }
  });
}

// The non-hex corners into vertex quality (a min, in any order the same).
// A pyramid apex that has no corner value from any cell takes the lowest
// base corner of its pyramids.
void add_non_hex_vertex_quality(const Mesh& mesh, QualityField& q) {
  auto lower = [&](Index v, double value) {
    double& w = q.vertex_quality[static_cast<std::size_t>(v)];
    if (std::isnan(w) || value < w) w = value;
  };
  for_each_analysed_kind([&](auto kind) {
    if constexpr (kind() != CellKind::hex) {
      constexpr int C = kCornerValuesPerCell<kind()>;
      const std::size_t corner0 = q.corner_begin[static_cast<std::size_t>(kind())];
      const auto& cells = cell_block<kind()>(mesh);
      for (std::size_t c = 0; c < cells.size(); ++c)
        for (int i = 0; i < C; ++i) lower(cells[c][i], q.corner_scaled_jacobian[corner0 + C * c + static_cast<std::size_t>(i)]);
    }
  });
  std::vector<double> apex(mesh.pyramids.empty() ? 0 : mesh.points.size(), std::numeric_limits<double>::quiet_NaN());
  const std::size_t corner0 = q.corner_begin[static_cast<std::size_t>(CellKind::pyramid)];
  for (std::size_t c = 0; c < mesh.pyramids.size(); ++c) {
    const double* base = q.corner_scaled_jacobian.data() + corner0 + 4 * c;
    const double lowest = *std::min_element(base, base + 4);
    double& a = apex[static_cast<std::size_t>(mesh.pyramids[c][4])];
    if (std::isnan(a) || lowest < a) a = lowest;
  }
  for (std::size_t v = 0; v < apex.size(); ++v)
    if (!std::isnan(apex[v]) && std::isnan(q.vertex_quality[v])) q.vertex_quality[v] = apex[v];
}

}  // namespace

void compute_corner_scaled_jacobians(const HexMesh& mesh, std::span<double> out, std::span<std::uint8_t> mask) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.hexes.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t h = r.begin(); h != r.end(); ++h) {
      const CornerJacobians cj = corner_scaled_jacobians(hex_corners(mesh, static_cast<Index>(h)));
      std::copy(cj.value.begin(), cj.value.end(), out.begin() + static_cast<std::ptrdiff_t>(8 * h));
      mask[h] = cj.degenerate_mask;
    }
  });
}


QualityField compute_quality(const Mesh& mesh, const Topology& topo, const SurfaceOrientation& surface) {
  const std::size_t nh = mesh.hexes.size();
  const std::size_t nv = mesh.points.size();
  const auto nc = static_cast<std::size_t>(num_cells(mesh));
  QualityField q;
  q.num_hexes = nh;
  std::size_t corners = 0;
  for_each_cell_kind([&](auto kind) {
    q.corner_begin[static_cast<std::size_t>(kind())] = corners;
    corners += kCornerValuesPerCell<kind()> * cell_block<kind()>(mesh).size();
  });
  q.corner_begin[kNumCellKinds] = corners;
  q.corner_scaled_jacobian.resize(corners);
  q.corner_degenerate_mask.resize(nc);
  q.cell_scaled_jacobian.resize(nc);
  q.non_hex_validity.resize(nc - nh);
  compute_corner_scaled_jacobians(mesh, std::span<double>(q.corner_scaled_jacobian).first(8 * nh),
                                  std::span<std::uint8_t>(q.corner_degenerate_mask).first(nh));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nh, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t h = r.begin(); h != r.end(); ++h) q.cell_scaled_jacobian[h] = hex_scaled_jacobian(hex_corners(mesh, static_cast<Index>(h)));
  });
  std::size_t first_cell = nh;
  for_each_analysed_kind([&](auto kind) {
    if constexpr (kind() != CellKind::hex) {
      compute_block<kind()>(mesh, first_cell, q, surface);
      first_cell += cell_block<kind()>(mesh).size();
    }
  });

  q.vertex_quality.assign(nv, std::numeric_limits<double>::quiet_NaN());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      double quality = std::numeric_limits<double>::infinity();
      for (Index k = topo.vertex_hex_offsets[v]; k < topo.vertex_hex_offsets[v + 1]; ++k) {
        const std::size_t h = static_cast<std::size_t>(topo.vertex_hexes[static_cast<std::size_t>(k)]);
        const Hex& hex = mesh.hexes[h];
        for (int i = 0; i < 8; ++i)
          if (hex[i] == static_cast<Index>(v)) quality = std::min(quality, q.corner_scaled_jacobian[8 * h + i]);
      }
      if (std::isfinite(quality)) q.vertex_quality[v] = quality;
    }
  });
  if (nc > nh) add_non_hex_vertex_quality(mesh, q);
  return q;
}

}  // namespace hq
