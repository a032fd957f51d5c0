#include "hqview/report/report_csv.h"

#include <string>

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
  buffer += ",inverted,degenerate,intersecting\n";
  const QualityField& q = model.field;
  for (std::size_t h = 0; h < model.mesh.hexes.size(); ++h) {
    append_int(buffer, static_cast<long long>(h));
    buffer += ',';
    const double sj = q.cell_scaled_jacobian[h];
    append_double(buffer, sj);
    for (int i = 0; i < 8; ++i) {
      buffer += ',';
      append_double(buffer, q.corner_scaled_jacobian[8 * h + static_cast<std::size_t>(i)]);
    }
    const bool degenerate = sj >= kVerdictDegenerate || q.corner_degenerate_mask[h] != 0;
    const bool inverted = !degenerate && sj <= 0.0;
    buffer += inverted ? ",1" : ",0";
    buffer += degenerate ? ",1" : ",0";
    buffer += ",\n";  // intersecting: the overlap stage is not part of this release
    flush_if_full(buffer, out);
  }
  flush_if_full(buffer, out, true);
}

void write_vertices_csv(const ReportModel& model, std::ostream& out) {
  std::string buffer = "vertex,x,y,z,quality,glyph_radius,cluster,coincident_group,boundary,boundary_error\n";
  for (std::size_t v = 0; v < model.mesh.points.size(); ++v) {
    const Vec3& p = model.mesh.points[v];
    append_int(buffer, static_cast<long long>(v));
    for (double c : {p.x, p.y, p.z}) {
      buffer += ',';
      append_double(buffer, c);
    }
    buffer += ',';
    append_double(buffer, model.field.vertex_quality[v]);  // empty for an unreferenced vertex
    // glyph_radius, cluster, coincident_group: stages not part of this release.
    buffer += ",,,,";
    buffer += model.topology.is_boundary_vertex[v] ? '1' : '0';
    buffer += ",\n";  // boundary_error: needs --reference (not part of this release)
    flush_if_full(buffer, out);
  }
  flush_if_full(buffer, out, true);
}

}  // namespace hq
