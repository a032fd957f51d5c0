#include "hqview/report/compare_table.h"

#include <cmath>
#include <filesystem>

#include "hqview/core/number_format.h"

namespace hq {
namespace {

enum class Better { lower, higher, neither };

std::string signed_number(double d) {
  if (!std::isfinite(d)) return "–";
  if (d == 0.0) return "0";
  return (d > 0 ? "+" : "") + display_number(d);
}

std::string signed_count(long long d) { return d == 0 ? "0" : (d > 0 ? "+" : "") + display_count(d); }

bool worse(double mine, double theirs, Better better) {
  if (!std::isfinite(mine) || !std::isfinite(theirs)) return false;
  return better == Better::lower ? theirs > mine : better == Better::higher ? theirs < mine : false;
}

CompareTableRow number_row(const std::string& label, double mine, double theirs, Better better) {
  return {label, display_number(mine), display_number(theirs), signed_number(theirs - mine), worse(mine, theirs, better)};
}

CompareTableRow count_row(const std::string& label, long long mine, long long theirs, Better better) {
  return {label, display_count(mine), display_count(theirs), signed_count(theirs - mine),
          worse(static_cast<double>(mine), static_cast<double>(theirs), better)};
}

}  // namespace

CompareTable compare_table(const Analysis& a) {
  const Analysis::Compared& c = *a.compare;
  const MeshSummary &m = a.mesh_summary, &n = c.mesh_summary;
  const QualitySummary &q = a.quality, &r = c.quality;
  CompareTable t;
  t.mine_name = std::filesystem::path(a.mesh_input.path).filename().string();
  t.theirs_name = std::filesystem::path(c.input.path).filename().string();
  t.rows = {
      count_row("vertices", m.num_vertices, n.num_vertices, Better::neither),
      count_row("hexahedra", m.num_hexes, n.num_hexes, Better::neither),
      number_row("min scaled Jacobian", q.scaled_jacobian.min, r.scaled_jacobian.min, Better::higher),
      number_row("mean scaled Jacobian", q.scaled_jacobian.mean, r.scaled_jacobian.mean, Better::higher),
      number_row("p05 scaled Jacobian", q.scaled_jacobian.p05, r.scaled_jacobian.p05, Better::higher),
      count_row("inverted hexes", q.scaled_jacobian.num_inverted, r.scaled_jacobian.num_inverted, Better::lower),
      count_row("degenerate hexes", q.scaled_jacobian.num_degenerate, r.scaled_jacobian.num_degenerate, Better::lower),
      number_row("min vertex quality", q.vertex_quality.min, r.vertex_quality.min, Better::higher),
      count_row("boundary faces", m.num_boundary_faces, n.num_boundary_faces, Better::neither),
      number_row("bounding box diagonal", m.bbox_diagonal, n.bbox_diagonal, Better::neither),
      number_row("mean edge length", m.edge_length_mean, n.edge_length_mean, Better::neither),
  };
  t.alignment = alignment_description(c.alignment);
  return t;
}

}  // namespace hq
