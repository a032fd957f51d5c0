#include "hqview/report/report_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <kainjow/mustache.hpp>

#include "hqview/core/error.h"
#include "hqview/report/cluster_color.h"

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
  if (model.overlap)
    headline.push_back(card("intersecting hexes", show_count(model.overlap->num_intersecting_cells), model.overlap->num_intersecting_cells > 0));
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
    // A chart's PNG twin (for Markdown) is left out when its SVG is listed.
    for (const std::string& f : v.files) {
      const bool is_png_twin = f.size() > 4 && f.ends_with(".png") &&
                               std::find(v.files.begin(), v.files.end(), f.substr(0, f.size() - 4) + ".svg") != v.files.end();
      if (!is_png_twin) files.push_back(f);
    }
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
    // Unbounded ends read as open intervals: [0, ∞).
    d.set("range", (std::isinf(metric.acceptable_min) ? "(−∞" : "[" + show(metric.acceptable_min)) + ", " +
                       (std::isinf(metric.acceptable_max) ? "∞)" : show(metric.acceptable_max) + "]"));
    d.set("fraction", show(100.0 * metric.fraction_acceptable) + " %");
    d.set("low_fraction", metric.stats.count > 0 && metric.fraction_acceptable < 0.9);
    d.set("count", show_count(metric.stats.count));
    d.set("min", show(metric.stats.min));
    d.set("p05", show(metric.stats.p05));
    d.set("p50", show(metric.stats.p50));
    d.set("mean", show(metric.stats.mean));
    d.set("p95", show(metric.stats.p95));
    d.set("max", show(metric.stats.max));
    d.set("num_degenerate", show_count(metric.stats.num_degenerate));
    metrics.push_back(d);
  }
  page.set("metrics", metrics);
  page.set("has_metrics", !q.metrics.empty());

  data gates{data::type::list};
  for (const GateResult& g : model.gates.results) {
    data d;
    d.set("rule", g.rule);
    d.set("value", show(g.value));
    d.set("passed", g.passed);
    gates.push_back(d);
  }
  page.set("gates", gates);
  page.set("has_gates", !model.gates.results.empty());
  page.set("gates_passed", model.gates.passed);

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

  // Glyph clusters: the worst kHtmlClusterRows, with their palette colour;
  // the first top_clusters are the ones later views show in detail.
  constexpr std::size_t kHtmlClusterRows = 20;
  page.set("has_glyphs", model.glyphs.has_value());
  if (model.glyphs) {
    const GlyphResult& g = *model.glyphs;
    const bool is_relative = g.options.rmax_unit == RmaxUnit::kMeanEdgeLength;
    page.set("glyph_summary",
             show_count(g.num_glyphs) + " vertices with quality below " + show(1.0 - g.options.threshold) +
                 " have a glyph, in " + show_count(static_cast<long long>(g.clusters.size())) +
                 " clusters of overlapping glyphs; rmax " + show(g.rmax) +
                 (is_relative ? " (" + show(g.options.rmax) + " × mean edge length)." : " (model units)."));
    data clusters{data::type::list};
    const std::size_t rows = std::min(g.clusters.size(), kHtmlClusterRows);
    for (std::size_t i = 0; i < rows; ++i) {
      const AggregatedGlyph& c = g.clusters[i];
      data d;
      d.set("id", std::to_string(c.id));
      d.set("color", cluster_color_hex(c.id));
      d.set("size", show_count(c.size));
      d.set("min_quality", show(c.min_quality));
      d.set("vertex", std::to_string(c.representative_vertex));
      d.set("position", show_vec(c.position));
      d.set("radius", show(c.radius));
      d.set("is_top", static_cast<int>(i) < g.options.top_clusters);
      clusters.push_back(d);
    }
    page.set("clusters", clusters);
    page.set("has_clusters", rows > 0);
    page.set("has_more_clusters", g.clusters.size() > rows);
    page.set("more_clusters", show_count(static_cast<long long>(g.clusters.size() - rows)));
  }

  // Overlap findings: the counts, then the first kHtmlOverlapRows pairs.
  constexpr std::size_t kHtmlOverlapRows = 20;
  page.set("has_overlap", model.overlap.has_value());
  if (model.overlap) {
    const OverlapReport& o = *model.overlap;
    const std::string mode(overlap_mode_name(o.mode));
    page.set("overlap_summary",
             o.certified_clean
                 ? "Certified: every hex is positively oriented (24 exact tets each) and the boundary is embedded and "
                   "unnested, so no two hexes overlap (Lipman's theorem)" +
                       std::string(o.mode == OverlapMode::exhaustive ? "; the exhaustive pair tests agree." : "; no pair tests were needed.")
                 : "Not certified: " + show_count(o.num_flagged_cells) + " hexes were tested against every hex near them (" +
                       show_count(o.num_candidate_pairs) + " pairs, " + mode + " mode). A pair intersects when a vertex of one lies inside the other.");
    data rows{data::type::list};
    auto row = [&](const std::string& key, std::size_t value) {
      data d = kv(key, show_count(static_cast<long long>(value)));
      d.set("alert", value > 0);
      rows.push_back(d);
    };
    row("intersecting hexes", static_cast<std::size_t>(o.num_intersecting_cells));
    row("intersecting pairs", o.intersecting_pairs.size());
    row("coincident vertices", static_cast<std::size_t>(o.num_coincident_vertices));
    row("zero-length edges", o.zero_length_edges.size());
    row("inverted hexes (a negative corner)", o.inverted_cells.size());
    row("degenerate hexes (a flat corner)", o.degenerate_cells.size());
    row("hexes with a non-positive tet (not certified)", o.nonpositive_tet_cells.size());
    row("faces shared by > 2 hexes", o.non_manifold_faces.size());
    row("duplicate hexes", o.duplicate_cells.size());
    row("interior faces with the same winding on both sides", o.same_winding_faces.size());
    row("intersecting boundary face pairs", o.boundary_self_intersections.size());
    row("nested boundary shells", static_cast<std::size_t>(o.num_nested_shells));
    page.set("overlap_rows", rows);
    data pairs{data::type::list};
    const std::size_t shown = std::min(o.intersecting_pairs.size(), kHtmlOverlapRows);
    for (std::size_t i = 0; i < shown; ++i) {
      const IntersectingPair& p = o.intersecting_pairs[i];
      data d;
      d.set("a", std::to_string(p.cells[0]));
      d.set("b", std::to_string(p.cells[1]));
      d.set("vertex", p.inside_vertex == kNoIndex ? "– (duplicates)" : std::to_string(p.inside_vertex));
      d.set("position", show_vec(p.position));
      pairs.push_back(d);
    }
    page.set("overlap_pairs", pairs);
    page.set("has_overlap_pairs", shown > 0);
    page.set("has_more_overlap_pairs", o.intersecting_pairs.size() > shown);
    page.set("more_overlap_pairs", show_count(static_cast<long long>(o.intersecting_pairs.size() - shown)));
  }

  mustache tmpl{std::string(detail::embedded_file("index.html.mustache"))};
  if (!tmpl.is_valid()) throw Error("internal: index.html template: " + tmpl.error_message());
  return tmpl.render(page);
}

}  // namespace hq
