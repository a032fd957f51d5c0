#include "hqview/report/compare_table.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>

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

// Two values that differ by rounding only (a relative 1e-12: the same mesh
// turned or renumbered sums its means in another order) are equal here.
constexpr double kRoundoff = 1e-12;

bool roundoff_equal(double mine, double theirs) {
  return std::abs(theirs - mine) <= kRoundoff * std::max(std::abs(mine), std::abs(theirs));
}

bool worse(double mine, double theirs, Better better) {
  if (!std::isfinite(mine) || !std::isfinite(theirs) || roundoff_equal(mine, theirs)) return false;
  return better == Better::lower ? theirs > mine : better == Better::higher ? theirs < mine : false;
}

CompareTableRow number_row(const std::string& label, double mine, double theirs, Better better) {
  const double difference = std::isfinite(mine) && std::isfinite(theirs) && roundoff_equal(mine, theirs) ? 0.0 : theirs - mine;
  return {label, display_number(mine), display_number(theirs), signed_number(difference), worse(mine, theirs, better)};
}

CompareTableRow count_row(const std::string& label, double mine, double theirs, Better better) {
  const auto count = [](double v) { return std::isfinite(v) ? display_count(std::llround(v)) : std::string("–"); };
  const bool known = std::isfinite(mine) && std::isfinite(theirs);
  return {label, count(mine), count(theirs), known ? signed_count(std::llround(theirs) - std::llround(mine)) : "–",
          worse(mine, theirs, better)};
}

// A number of a report.json object by path; NaN when missing or null.
double number_at(const nlohmann::json& j, std::initializer_list<const char*> path) {
  const nlohmann::json* node = &j;
  for (const char* key : path) {
    if (!node->is_object() || !node->contains(key)) return std::nan("");
    node = &(*node)[key];
  }
  return node->is_number() ? node->get<double>() : std::nan("");
}

bool has_non_hex_cells(const CompareNumbers& n) {
  return n.num_tets > 0 || n.num_wedges > 0 || n.num_pyramids > 0;  // false on NaN
}

bool is_surface(const CompareNumbers& n) { return n.num_quads > 0 || n.num_triangles > 0; }  // false on NaN

}  // namespace

CompareNumbers compare_numbers(const MeshSummary& m, const QualitySummary& q, const CellComposition& c) {
  const auto count = [](auto v) { return static_cast<double>(v); };
  const auto fraction = [](const std::optional<double>& f) { return f ? *f : std::nan(""); };
  return {count(m.num_vertices),
          count(m.num_hexes),
          count(c.num_cells),
          count(c.count[1]),
          count(c.count[2]),
          count(c.count[3]),
          fraction(c.hex_fraction),
          fraction(c.hex_volume_fraction),
          q.scaled_jacobian.min,
          q.scaled_jacobian.mean,
          q.scaled_jacobian.p05,
          count(q.scaled_jacobian.num_inverted),
          count(q.scaled_jacobian.num_degenerate),
          q.vertex_quality.min,
          count(m.num_boundary_faces),
          m.bbox_diagonal,
          m.edge_length_mean,
          count(c.num_quads),
          count(c.num_triangles),
          count(m.num_boundary_edges)};
}

CompareNumbers compare_numbers(const nlohmann::json& headline, const nlohmann::json& mesh,
                               const nlohmann::json& quality) {
  return {number_at(mesh, {"num_vertices"}),
          number_at(mesh, {"num_hexes"}),
          number_at(headline, {"num_cells"}),
          number_at(headline, {"num_cells_by_kind", "tet"}),
          number_at(headline, {"num_cells_by_kind", "wedge"}),
          number_at(headline, {"num_cells_by_kind", "pyramid"}),
          number_at(headline, {"hex_fraction"}),
          number_at(headline, {"hex_volume_fraction"}),
          number_at(quality, {"scaled_jacobian", "min"}),
          number_at(quality, {"scaled_jacobian", "mean"}),
          number_at(quality, {"scaled_jacobian", "p05"}),
          number_at(quality, {"scaled_jacobian", "num_inverted"}),
          number_at(quality, {"scaled_jacobian", "num_degenerate"}),
          number_at(quality, {"vertex_quality", "min"}),
          number_at(mesh, {"num_boundary_faces"}),
          number_at(mesh, {"bbox", "diagonal"}),
          number_at(mesh, {"edge_length", "mean"}),
          number_at(headline, {"num_cells_by_kind", "quad"}),
          number_at(headline, {"num_cells_by_kind", "triangle"}),
          number_at(mesh, {"num_boundary_edges"})};
}

MeshCells mesh_cells(const CompareNumbers& m, const CompareNumbers& n) {
  if (is_surface(m) && is_surface(n)) return MeshCells::surface;
  if (is_surface(m) || is_surface(n) || has_non_hex_cells(m) || has_non_hex_cells(n)) return MeshCells::volume;
  return MeshCells::hex;
}

std::vector<CompareTableRow> compare_rows(const CompareNumbers& m, const CompareNumbers& n) {
  const MeshCells cells = mesh_cells(m, n);
  const bool any_surface = is_surface(m) || is_surface(n);
  std::vector<CompareTableRow> rows = {count_row("vertices", m.num_vertices, n.num_vertices, Better::neither)};
  if (cells != MeshCells::surface) rows.push_back(count_row("hexahedra", m.num_hexes, n.num_hexes, Better::neither));
  if (has_non_hex_cells(m) || has_non_hex_cells(n)) {
    rows.push_back(count_row("cells (every kind)", m.num_cells, n.num_cells, Better::neither));
    rows.push_back(count_row("tetrahedra", m.num_tets, n.num_tets, Better::neither));
    rows.push_back(count_row("wedges", m.num_wedges, n.num_wedges, Better::neither));
    rows.push_back(count_row("pyramids", m.num_pyramids, n.num_pyramids, Better::neither));
    rows.push_back(number_row("hex fraction (by count)", m.hex_fraction, n.hex_fraction, Better::higher));
    rows.push_back(number_row("hex fraction (by volume)", m.hex_volume_fraction, n.hex_volume_fraction, Better::higher));
  }
  if (any_surface) {
    rows.push_back(count_row("quadrilaterals", m.num_quads, n.num_quads, Better::neither));
    if (m.num_triangles > 0 || n.num_triangles > 0)
      rows.push_back(count_row("triangles", m.num_triangles, n.num_triangles, Better::neither));
  }
  // The scaled Jacobian's statistics run over every cell of every kind.
  const std::string plural = cells_plural(cells);
  const std::vector<CompareTableRow> quality_rows = {
      number_row("min scaled Jacobian", m.sj_min, n.sj_min, Better::higher),
      number_row("mean scaled Jacobian", m.sj_mean, n.sj_mean, Better::higher),
      number_row("p05 scaled Jacobian", m.sj_p05, n.sj_p05, Better::higher),
      count_row("inverted " + plural, m.num_inverted, n.num_inverted, Better::lower),
      count_row("degenerate " + plural, m.num_degenerate, n.num_degenerate, Better::lower),
      number_row("min vertex quality", m.vertex_quality_min, n.vertex_quality_min, Better::higher),
  };
  rows.insert(rows.end(), quality_rows.begin(), quality_rows.end());
  if (cells != MeshCells::surface)
    rows.push_back(count_row("boundary faces", m.num_boundary_faces, n.num_boundary_faces, Better::neither));
  if (any_surface)
    rows.push_back(count_row("boundary edges", m.num_boundary_edges, n.num_boundary_edges, Better::neither));
  rows.push_back(number_row("bounding box diagonal", m.bbox_diagonal, n.bbox_diagonal, Better::neither));
  rows.push_back(number_row("mean edge length", m.edge_length_mean, n.edge_length_mean, Better::neither));
  return rows;
}

CompareTable compare_table(const Analysis& a) {
  const Analysis::Compared& c = *a.compare;
  CompareTable t;
  t.mine_name = std::filesystem::path(a.mesh_input.path).filename().string();
  t.theirs_name = std::filesystem::path(c.input.path).filename().string();
  t.rows = compare_rows(compare_numbers(a.mesh_summary, a.quality, a.composition),
                        compare_numbers(c.mesh_summary, c.quality, c.composition));
  t.alignment = alignment_description(c.alignment);
  return t;
}

}  // namespace hq
