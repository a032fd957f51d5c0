#include "hqview/report/report_csv.h"

#include <cmath>
#include <string>
#include <vector>

#include "hqview/core/number_format.h"
#include "hqview/quality/corner_jacobian.h"

namespace hq {
namespace {

// Rows are formatted into one buffer and flushed in blocks: formatting, not
// the stream, dominates.
constexpr std::size_t kFlushBytes = 1 << 20;

void flush_if_full(std::string& buffer, std::ostream& out, bool force = false) {
  if (force || buffer.size() >= kFlushBytes) {
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
  }
}

}  // namespace

void write_cells_csv(const ReportModel& model, std::ostream& out) {
  std::string buffer = "cell,scaled_jacobian";
  for (int i = 0; i < 8; ++i) buffer += ",corner_sj_" + std::to_string(i);
  // Then every Verdict metric but scaled_jacobian (already the second
  // column), in HexMetric order; a metric left out by --metrics keeps its
  // column, empty, so the header never changes.
  std::vector<const std::vector<double>*> metric_columns;
  for (int m = 0; m < kNumHexMetrics; ++m) {
    if (static_cast<HexMetric>(m) == HexMetric::scaled_jacobian) continue;
    buffer += ',';
    buffer += hex_metric_name(static_cast<HexMetric>(m));
    metric_columns.push_back(&model.analysis.metrics.of(static_cast<HexMetric>(m)));
  }
  buffer += ",inverted,degenerate,intersecting,size_gradation\n";
  const QualityField& q = model.analysis.field;
  for (std::size_t h = 0; h < model.analysis.mesh.hexes.size(); ++h) {
    append_int(buffer, static_cast<long long>(h));
    buffer += ',';
    const double sj = q.cell_scaled_jacobian[h];
    append_double(buffer, sj);
    for (int i = 0; i < 8; ++i) {
      buffer += ',';
      append_double(buffer, q.corner_scaled_jacobian[8 * h + static_cast<std::size_t>(i)]);
    }
    for (const std::vector<double>* column : metric_columns) {
      buffer += ',';
      if (!column->empty()) append_double(buffer, (*column)[h]);
    }
    buffer += cell_is_inverted(q, h) ? ",1" : ",0";
    buffer += cell_is_degenerate(q, h) ? ",1" : ",0";
    // intersecting: 0/1 from the overlap stage, empty with --no-overlap.
    buffer += ',';
    if (model.analysis.overlap) buffer += model.analysis.overlap->cell_intersecting[h] ? '1' : '0';
    // size_gradation: empty for a hex without a positive volume or a face
    // neighbour of positive volume.
    buffer += ',';
    append_double(buffer, model.analysis.structure.cell_gradation[h]);
    buffer += '\n';
    flush_if_full(buffer, out);
  }
  flush_if_full(buffer, out, true);
}

void write_vertices_csv(const ReportModel& model, std::ostream& out) {
  std::string buffer = "vertex,x,y,z,quality,glyph_radius,cluster,coincident_group,boundary,boundary_error,singular\n";
  for (std::size_t v = 0; v < model.analysis.mesh.points.size(); ++v) {
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
    if (model.analysis.boundary_error) append_double(buffer, model.analysis.boundary_error->vertex_error[v]);
    buffer += model.analysis.structure.vertex_singular[v] ? ",1\n" : ",0\n";
    flush_if_full(buffer, out);
  }
  flush_if_full(buffer, out, true);
}

const char* edge_kind_name(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::interior: return "interior";
    case EdgeKind::boundary: return "boundary";
    case EdgeKind::nonmanifold: return "nonmanifold";
  }
  return "";
}

void write_edges_csv(const ReportModel& model, std::ostream& out) {
  std::string buffer = "edge,v0,v1,valence,kind,singular,ideal_valence,irregular,curve\n";
  const HexStructure& s = model.analysis.structure;
  for (std::size_t i = 0; i < s.edges.size(); ++i) {
    const StructureEdge& e = s.edges[i];
    append_int(buffer, static_cast<long long>(i));
    for (Index v : {e.vertices[0], e.vertices[1], e.valence}) {
      buffer += ',';
      append_int(buffer, v);
    }
    buffer += ',';
    buffer += edge_kind_name(e.kind);
    buffer += e.singular ? ",1," : ",0,";
    // ideal_valence and irregular: boundary edges only.
    if (e.kind == EdgeKind::boundary) {
      append_int(buffer, e.ideal_valence);
      buffer += e.irregular ? ",1" : ",0";
    } else {
      buffer += ',';
    }
    buffer += ',';
    append_int(buffer, e.curve == kNoIndex ? -1 : e.curve);
    buffer += '\n';
    flush_if_full(buffer, out);
  }
  flush_if_full(buffer, out, true);
}

}  // namespace hq
