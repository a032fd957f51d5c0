#include "hqview/report/report_csv.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "hqview/core/number_format.h"
#include "hqview/quality/corner_jacobian.h"
#include "hqview/report/cell_rows.h"
#include "hqview/report/deflate.h"
#include "hqview/report/ordered_chunks.h"

namespace hq {
namespace {

// Rows per chunk: chunks are formatted (and gzip'ed) in parallel, then
// written in order. Fixed, so a .csv.gz has the same gzip members, hence the
// same bytes, for any thread count.
constexpr std::size_t kRowsPerChunk = 4096;

// Writes `header` then rows [0, num_rows) in chunks, each chunk's rows
// appended by append_rows(first, last, text); gzip: each chunk is one gzip
// member (the header in the first).
template <class AppendRows>
void write_table(std::ostream& out, TextEncoding encoding, const std::string& header, std::size_t num_rows,
                 AppendRows&& append_rows) {
  const std::size_t num_chunks = std::max<std::size_t>(1, (num_rows + kRowsPerChunk - 1) / kRowsPerChunk);
  write_ordered_chunks(out, num_chunks, [&](std::size_t i, std::string& chunk) {
    std::string text = i == 0 ? header : std::string();
    append_rows(i * kRowsPerChunk, std::min(num_rows, (i + 1) * kRowsPerChunk), text);
    if (encoding == TextEncoding::gzip)
      append_gzip_member(text, chunk);
    else
      chunk = std::move(text);
  });
}

}  // namespace

void write_cells_csv(const ReportModel& model, std::ostream& out, TextEncoding encoding) {
  std::string header = "cell,scaled_jacobian";
  for (int i = 0; i < 8; ++i) header += ",corner_sj_" + std::to_string(i);
  // Then every Verdict metric but scaled_jacobian (already the second
  // column), in HexMetric order; a metric left out by --metrics keeps its
  // column, empty, so the header never changes.
  // A non-hex cell fills the columns its kind shares a Verdict name with.
  for (int m = 0; m < kNumHexMetrics; ++m) {
    if (static_cast<HexMetric>(m) == HexMetric::scaled_jacobian) continue;
    header += ',';
    header += hex_metric_name(static_cast<HexMetric>(m));
  }
  header += ",inverted,degenerate,intersecting,size_gradation";
  // The finite-element check's columns, empty when it did not run (element
  // conditioning: --simulate or --metrics fem_element; the rest: --simulate).
  header += ",fem_kappa,fem_lambda_max,fem_det_j_min,fem_det_j_max,fem_l2_error_share,fem_h1_error_share,"
            "fem_error_density\n";
  // Then where the cell is: its kind and its index in its file.
  header.back() = ',';
  header += "cell_type,source_index\n";
  const std::optional<FemElementField>& fem = model.analysis.fem_elements;
  const bool has_poisson = model.analysis.poisson && model.analysis.poisson->skipped.empty();
  const QualityField& q = model.analysis.field;
  const CellRows rows(model.analysis);
  const std::size_t nh = rows.num_hexes();
  write_table(out, encoding, header, rows.num_cells(), [&](std::size_t first, std::size_t last, std::string& buffer) {
    for (std::size_t c = first; c < last; ++c) {
      append_int(buffer, static_cast<long long>(c));
      buffer += ',';
      append_double(buffer, q.cell_scaled_jacobian[c]);
      // corner_sj_i: the kind's corners in its corner_frames order, empty past them.
      for (int i = 0; i < 8; ++i) {
        buffer += ',';
        append_double(buffer, rows.corner(c, i));
      }
      for (int m = 0; m < kNumHexMetrics; ++m) {
        if (static_cast<HexMetric>(m) == HexMetric::scaled_jacobian) continue;
        buffer += ',';
        append_double(buffer, rows.metric(m, c));
      }
      buffer += cell_is_inverted(q, c) ? ",1" : ",0";
      buffer += cell_is_degenerate(q, c) ? ",1" : ",0";
      // intersecting: 0/1 from the overlap stage, empty with --no-overlap and
      // for a non-hex cell of a volume mesh; every face of a surface mesh.
      buffer += ',';
      if (model.analysis.overlap && (c < nh || model.analysis.overlap->is_surface))
        buffer += model.analysis.overlap->cell_intersecting[c] ? '1' : '0';
      // size_gradation: every kind; empty for a cell without a positive
      // volume or a face neighbour of positive volume.
      buffer += ',';
      const std::vector<double>& gradation = model.analysis.structure.cell_gradation;
      append_double(buffer, c < gradation.size() ? gradation[c] : std::numeric_limits<double>::quiet_NaN());
      for (const std::vector<double>* column :
           {fem ? &fem->kappa : nullptr, fem ? &fem->lambda_max : nullptr, fem ? &fem->det_j_min : nullptr,
            fem ? &fem->det_j_max : nullptr, has_poisson ? &model.analysis.poisson->cell_l2_share : nullptr,
            has_poisson ? &model.analysis.poisson->cell_h1_share : nullptr,
            has_poisson ? &model.analysis.poisson->cell_error_density : nullptr}) {
        buffer += ',';
        if (column) append_double(buffer, CellRows::hex_only(*column, c, nh));
      }
      buffer += ',';
      buffer += cell_kind_name(rows.ref(c).kind);
      buffer += ',';
      append_int(buffer, static_cast<long long>(rows.source_index(c)));
      buffer += '\n';
    }
  });
}

void write_vertices_csv(const ReportModel& model, std::ostream& out, TextEncoding encoding) {
  const std::string header =
      "vertex,x,y,z,quality,glyph_radius,cluster,coincident_group,boundary,boundary_error,singular\n";
  write_table(out, encoding, header, model.analysis.mesh.points.size(),
              [&](std::size_t first, std::size_t last, std::string& buffer) {
                for (std::size_t v = first; v < last; ++v) {
                  const Vec3& p = model.analysis.mesh.points[v];
                  append_int(buffer, static_cast<long long>(v));
                  for (double c : {p.x, p.y, p.z}) {
                    buffer += ',';
                    append_double(buffer, c);
                  }
                  buffer += ',';
                  append_double(buffer, model.analysis.field.vertex_quality[v]);  // empty for an unreferenced vertex
                  // glyph_radius: 0 without a glyph, empty for an unreferenced vertex;
                  // cluster: the cluster's rank id, -1 without a glyph.
                  buffer += ',';
                  if (model.analysis.glyphs && !std::isnan(model.analysis.field.vertex_quality[v]))
                    append_double(buffer, model.analysis.glyphs->vertex_radius[v]);
                  buffer += ',';
                  if (model.analysis.glyphs) append_int(buffer, model.analysis.glyphs->vertex_cluster[v]);
                  // coincident_group: the group's index in report.json, -1 for none;
                  // empty with --no-overlap.
                  buffer += ',';
                  if (model.analysis.overlap) append_int(buffer, model.analysis.overlap->vertex_coincident_group[v]);
                  buffer += ',';
                  buffer += model.analysis.topology.is_boundary_vertex[v] ? '1' : '0';
                  buffer += ',';
                  // boundary_error: signed distance for boundary vertices with --reference, else empty.
                  if (model.analysis.boundary_error)
                    append_double(buffer, model.analysis.boundary_error->vertex_error[v]);
                  buffer += model.analysis.structure.vertex_singular[v] ? ",1\n" : ",0\n";
                }
              });
}

const char* edge_kind_name(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::interior:
      return "interior";
    case EdgeKind::boundary:
      return "boundary";
    case EdgeKind::nonmanifold:
      return "nonmanifold";
  }
  return "";
}

void write_edges_csv(const ReportModel& model, std::ostream& out) {
  const HexStructure& s = model.analysis.structure;
  write_table(out, TextEncoding::plain, "edge,v0,v1,valence,kind,singular,ideal_valence,irregular,curve,touches_non_hex\n",
              s.edges.size(), [&](std::size_t first, std::size_t last, std::string& buffer) {
                for (std::size_t i = first; i < last; ++i) {
                  const StructureEdge& e = s.edges[i];
                  append_int(buffer, static_cast<long long>(i));
                  for (Index v : {e.vertices[0], e.vertices[1], e.valence}) {
                    buffer += ',';
                    append_int(buffer, v);
                  }
                  buffer += ',';
                  buffer += edge_kind_name(e.kind);
                  buffer += e.singular ? ",1," : ",0,";
                  // ideal_valence and irregular: boundary edges of the hex part only.
                  if (e.kind == EdgeKind::boundary && !e.touches_non_hex) {
                    append_int(buffer, e.ideal_valence);
                    buffer += e.irregular ? ",1" : ",0";
                  } else {
                    buffer += ',';
                  }
                  buffer += ',';
                  append_int(buffer, e.curve == kNoIndex ? -1 : e.curve);
                  buffer += e.touches_non_hex ? ",1\n" : ",0\n";
                }
              });
}

void write_non_conforming_faces_csv(const ReportModel& model, std::ostream& out) {
  const std::vector<NonConformingFace>& faces = model.analysis.topology.non_conforming_faces;
  write_table(out, TextEncoding::plain,
              "face,v0,v1,v2,v3,split_v0,split_v1,quad_cell,quad_cell_type,triangle_cell_a,triangle_cell_a_type,"
              "triangle_cell_b,triangle_cell_b_type\n",
              faces.size(), [&](std::size_t first, std::size_t last, std::string& buffer) {
                for (std::size_t i = first; i < last; ++i) {
                  const NonConformingFace& f = faces[i];
                  append_int(buffer, static_cast<long long>(i));
                  for (Index v : f.quad) {
                    buffer += ',';
                    append_int(buffer, v);
                  }
                  // The diagonal the triangles share: the two ids in both, ascending.
                  Tri a = f.triangles[0];
                  std::sort(a.begin(), a.end());
                  for (Index v : a)
                    if (std::find(f.triangles[1].begin(), f.triangles[1].end(), v) != f.triangles[1].end()) {
                      buffer += ',';
                      append_int(buffer, v);
                    }
                  const auto cell = [&](Index id, CellKind kind) {
                    buffer += ',';
                    append_int(buffer, id);
                    buffer += ',';
                    buffer += cell_kind_name(kind);
                  };
                  cell(f.quad_cell, f.quad_kind);
                  cell(f.triangle_cells[0], f.triangle_kinds[0]);
                  cell(f.triangle_cells[1], f.triangle_kinds[1]);
                  buffer += '\n';
                }
              });
}

}  // namespace hq
