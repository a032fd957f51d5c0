#include "hqview/report/report_html.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <kainjow/mustache.hpp>

#include "hqview/core/error.h"

namespace hq {
namespace detail {
std::string_view embedded_file(std::string_view name);
}

namespace {

using kainjow::mustache::data;
using kainjow::mustache::mustache;

// Display text: 6 significant digits (report.json keeps full precision).
std::string show(double v) {
  if (!std::isfinite(v)) return "–";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

std::string show_count(long long v) {
  // Thousands separators make 6- and 7-digit counts readable at a glance.
  std::string digits = std::to_string(v < 0 ? -v : v), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return v < 0 ? "-" + out : out;
}

data card(const std::string& label, const std::string& value, bool alert = false) {
  data d;
  d.set("label", label);
  d.set("value", value);
  d.set("alert", alert);
  return d;
}

data stats_row(const std::string& name, const std::string& note, const Statistics& s) {
  data d;
  d.set("name", name);
  d.set("note", note);
  d.set("count", show_count(s.count));
  d.set("min", show(s.min));
  d.set("p01", show(s.p01));
  d.set("p05", show(s.p05));
  d.set("p50", show(s.p50));
  d.set("mean", show(s.mean));
  d.set("max", show(s.max));
  d.set("num_inverted", show_count(s.num_inverted));
  d.set("num_degenerate", show_count(s.num_degenerate));
  return d;
}

data kv(const std::string& key, const std::string& value) {
  data d;
  d.set("key", key);
  d.set("value", value);
  return d;
}

std::string show_vec(const Vec3& v) { return "(" + show(v.x) + ", " + show(v.y) + ", " + show(v.z) + ")"; }

}  // namespace

std::string_view report_stylesheet() { return detail::embedded_file("style.css"); }

std::string index_html(const ReportModel& model) {
  const MeshSummary& m = model.mesh_summary;
  const QualitySummary& q = model.quality;
  data page;
  page.set("mesh_name", std::filesystem::path(model.mesh_input.path).filename().string());
  page.set("format", model.mesh_input.format);
  page.set("sha256_short", model.mesh_input.sha256.substr(0, 12));
  page.set("version", model.tool_version);

  // The papers' headline: #V, #H, min and mean scaled Jacobian, #inverted.
  data headline{data::type::list};
  headline.push_back(card("vertices", show_count(m.num_vertices)));
  headline.push_back(card("hexahedra", show_count(m.num_hexes)));
  headline.push_back(card("min scaled Jacobian", show(q.scaled_jacobian.min), q.scaled_jacobian.min <= 0));
  headline.push_back(card("mean scaled Jacobian", show(q.scaled_jacobian.mean)));
  headline.push_back(card("inverted hexes", show_count(q.scaled_jacobian.num_inverted), q.scaled_jacobian.num_inverted > 0));
  headline.push_back(card("degenerate hexes", show_count(q.scaled_jacobian.num_degenerate), q.scaled_jacobian.num_degenerate > 0));
  headline.push_back(card("min vertex quality", show(q.vertex_quality.min), q.vertex_quality.min <= 0));
  page.set("headline", headline);

  data warnings{data::type::list};
  for (const std::string& w : model.warnings) warnings.push_back(w);
  page.set("warnings", warnings);
  page.set("has_warnings", !model.warnings.empty());

  data views{data::type::list};
  for (const ViewEntry& v : model.views) {
    data view;
    view.set("id", v.id);
    view.set("title", v.title);
    data files{data::type::list};
    for (const std::string& f : v.files) files.push_back(f);
    view.set("files", files);
    views.push_back(view);
  }
  page.set("views", views);

  data stats{data::type::list};
  stats.push_back(stats_row("cell scaled Jacobian", "Verdict: min over centre and 8 corner frames", q.scaled_jacobian));
  stats.push_back(stats_row("corner scaled Jacobian", "all 8 corners of every hex", q.corner_scaled_jacobian));
  stats.push_back(stats_row("vertex quality", "min corner value at the vertex", q.vertex_quality));
  page.set("stats", stats);

  data metrics{data::type::list};
  for (const MetricSummary& metric : q.metrics) {
    data d;
    d.set("name", metric.name);
    d.set("lo", show(metric.acceptable_min));
    d.set("hi", show(metric.acceptable_max));
    d.set("fraction", show(100.0 * metric.fraction_acceptable) + " %");
    metrics.push_back(d);
  }
  page.set("metrics", metrics);

  data worst_vertices{data::type::list};
  for (const WorstVertex& w : q.worst_vertices) {
    data d;
    d.set("vertex", std::to_string(w.vertex));
    d.set("quality", show(w.quality));
    d.set("position", show_vec(w.position));
    worst_vertices.push_back(d);
  }
  page.set("worst_vertices", worst_vertices);
  data worst_cells{data::type::list};
  for (const WorstCell& w : q.worst_cells) {
    data d;
    d.set("cell", std::to_string(w.cell));
    d.set("scaled_jacobian", w.scaled_jacobian >= 1e30 ? "degenerate" : show(w.scaled_jacobian));
    worst_cells.push_back(d);
  }
  page.set("worst_cells", worst_cells);

  data mesh_rows{data::type::list};
  mesh_rows.push_back(kv("boundary faces", show_count(m.num_boundary_faces)));
  mesh_rows.push_back(kv("boundary vertices", show_count(m.num_boundary_vertices)));
  mesh_rows.push_back(kv("unreferenced vertices", show_count(m.num_unreferenced_vertices)));
  mesh_rows.push_back(kv("faces shared by > 2 hexes", show_count(m.num_non_manifold_faces)));
  mesh_rows.push_back(kv("bounding box min", show_vec(m.bbox_min)));
  mesh_rows.push_back(kv("bounding box max", show_vec(m.bbox_max)));
  mesh_rows.push_back(kv("bounding box diagonal", show(m.bbox_diagonal)));
  mesh_rows.push_back(kv("edge length min / mean / max",
                         show(m.edge_length_min) + " / " + show(m.edge_length_mean) + " / " + show(m.edge_length_max)));
  page.set("mesh_rows", mesh_rows);

  mustache tmpl{std::string(detail::embedded_file("index.html.mustache"))};
  if (!tmpl.is_valid()) throw Error("internal: index.html template: " + tmpl.error_message());
  return tmpl.render(page);
}

}  // namespace hq
