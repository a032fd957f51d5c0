#include "hqview/report/report_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <kainjow/mustache.hpp>
#include <map>
#include <set>

#include "hqview/analysis/limitations.h"
#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/render/upright.h"
#include "hqview/glyph/glyph_ties.h"
#include "hqview/report/cluster_color.h"
#include "hqview/report/compare_table.h"
#include "hqview/report/escape.h"
#include "hqview/report/report_templates.h"
#include "hqview/views/views.h"

namespace hq {

namespace {

using kainjow::mustache::data;
using kainjow::mustache::mustache;

// Display text (report.json keeps full precision).
std::string show(double v) { return display_number(v); }
std::string show_count(long long v) { return display_count(v); }
// A share in percent with one decimal (the three boundary area shares).
std::string one_decimal(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", v);
  return buffer;
}
// A boundary-error distance in % of the reference's diagonal.
double sampled_relative(const BoundaryError& e, double v) {
  return e.reference_bbox_diagonal > 0 ? 100.0 * v / e.reference_bbox_diagonal : 0.0;
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

// ---- panels A–F and S: figures and the links between them ----

// The paper's six linked views (A–F) of index.html and the structure panel
// (S, after A), in page order, and the views each shows; the boundary views
// have their own page.
struct PanelSpec {
  const char* anchor;
  const char* nav;  // short title for the navigation bar
  const char* title;
  const char* intro;
  char letter;  // its views: those of kViews with this panel
};

const std::vector<PanelSpec>& index_panels() {
  static const std::vector<PanelSpec> panels{
      {"panel-a", "A main", "A · Overview and main view: vertex quality, glyphs, clusters and intersecting hexes",
       "",  // panel_intro: from the views drawn
       'A'},
      {"panel-s", "S structure", "S · Structure: singularity graph and size gradation",
       "",  // panel_intro: from the views drawn
       'S'},
      {"panel-b", "B sorted quality", "B · Sorted vertex quality",
       "Each bar of the sorted chart is one of the worst vertices, worst on the left. Click a bar to go to its "
       "cluster's sub-region (C), or to its local view (D) when its cluster has no sub-region view.",
       'B'},
      {"panel-c", "C clusters", "C · Sub-regions of the worst clusters",
       "One view per top cluster (the table's bold rows): its glyphs (reduced: half size, at most 0.35 of the mean "
       "edge) and the hexes around them. Each "
       "links to the local view (D) and corner chart (E) of the cluster's worst vertex, and back to its table row.",
       'C'},
      {"panel-d", "D local", "D · Local views: one-ring hexes of a vertex",
       "The hexes around a chosen vertex (the worst of each top cluster, then any --focus-vertex), with the scaled "
       "Jacobian of every corner at the vertex.",
       'D'},
      {"panel-e", "E corners", "E · Corner charts",
       "The corner scaled Jacobians at each chosen vertex, one bar per incident hex.", 'E'},
      {"panel-f", "F reference", "F · Reference",
       "The hex boundary against the reference surface (--reference), and the compared mesh (--compare).", 'F'},
      {"panel-p", "P simulation", "P · Simulation: where the finite-element error is",
       "With --simulate: the Poisson check's error density per hex (its H1 error over the a-priori factor h\u00b2 "
       "|D\u00b2u|\u00b2, h = the cube root of the hex's volume, so it shows where the mesh is bad rather than where u curves). First, each metric's "
       "Spearman \u03c1 with that density over the hexes, strongest first: the metrics that say where the error "
       "is. Then every hex's density against its scaled Jacobian on log axes. Numbers: report.json fem.poisson; per "
       "hex: data/cells.csv fem_error_density.",
       'P'},
  };
  return panels;
}

// The ids of a panel's views (kViews), in its order; panel 0: boundary.html
// (the order of the paper's figure: 3D error views, UV error map, sorted
// error chart, area percentages).
std::vector<std::string_view> panel_view_ids(char panel) {
  std::vector<std::string_view> ids;
  for (const ViewSpec* spec : views_of_panel(panel)) ids.push_back(spec->id);
  return ids;
}

std::string stem_of(const std::string& file) { return std::filesystem::path(file).stem().string(); }

// A chart's PNG twin (for Markdown) is left out of the pages when its SVG is listed.
bool is_png_twin(const ViewEntry& v, const std::string& f) {
  return f.size() > 4 && f.ends_with(".png") &&
         std::find(v.files.begin(), v.files.end(), f.substr(0, f.size() - 4) + ".svg") != v.files.end();
}

std::string percent_style(const ChartRect& r) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "left:%.4f%%;top:%.4f%%;width:%.4f%%;height:%.4f%%", 100.0 * r.x, 100.0 * r.y,
                100.0 * r.width, 100.0 * r.height);
  return buffer;
}

data link(const std::string& href, const std::string& label) {
  data d;
  d.set("href", href);
  d.set("label", label);
  return d;
}

// Which panels exist, for the links between them.
struct PanelIndex {
  std::set<Index> cluster_views;                  // clusters with a C view
  std::set<Index> local_views, corner_views;      // vertices with a D / E view
  std::map<Index, std::vector<Index>> detail_of;  // cluster -> its vertices with a D or E view
  std::set<Index> table_clusters;                 // clusters with a row in the table
  std::set<Index> worst_vertices;                 // vertices with a row in the worst vertex table
  const ReportModel* model = nullptr;

  Index cluster_of(Index v) const {
    if (!model->analysis.glyphs || v < 0 ||
        static_cast<std::size_t>(v) >= model->analysis.glyphs->vertex_cluster.size())
      return kNoIndex;
    return model->analysis.glyphs->vertex_cluster[static_cast<std::size_t>(v)];
  }
  const AggregatedGlyph* glyph_cluster(Index c) const {
    if (!model->analysis.glyphs || c < 0 || static_cast<std::size_t>(c) >= model->analysis.glyphs->clusters.size())
      return nullptr;
    return &model->analysis.glyphs->clusters[static_cast<std::size_t>(c)];
  }
  double quality_of(Index v) const {
    const auto& q = model->analysis.field.vertex_quality;
    return v >= 0 && static_cast<std::size_t>(v) < q.size() ? q[static_cast<std::size_t>(v)] : NAN;
  }
  // Where a click on vertex v leads: its cluster's C view, else its D view,
  // else its cluster's table row, else its worst-vertex row ("" when none).
  std::string target_of_vertex(Index v) const {
    const Index c = cluster_of(v);
    if (c != kNoIndex && cluster_views.count(c)) return "#cluster-" + std::to_string(c);
    if (local_views.count(v)) return "#vertex-" + std::to_string(v);
    if (c != kNoIndex && table_clusters.count(c)) return "#cluster-row-" + std::to_string(c);
    if (worst_vertices.count(v)) return "#worst-vertex-" + std::to_string(v);
    return "";
  }
  // Links from a cluster to its D and E panels (short labels for a table cell).
  void push_detail_links(Index c, data& links, bool is_short) const {
    const auto it = detail_of.find(c);
    if (it == detail_of.end()) return;
    for (Index v : it->second) {
      const std::string vs = std::to_string(v);
      if (local_views.count(v))
        links.push_back(link("#vertex-" + vs, is_short ? "D: " + vs : "D: local view of vertex " + vs));
      if (corner_views.count(v))
        links.push_back(link("#corners-" + vs, is_short ? "E: " + vs : "E: corner chart of vertex " + vs));
    }
  }
};

PanelIndex index_panels_of(const ReportModel& model, std::size_t table_rows) {
  PanelIndex index;
  index.model = &model;
  for (const ViewEntry& v : model.views)
    for (const ViewFileLinks& l : v.links) {
      if (v.id == "clusters" && l.cluster != kNoIndex) index.cluster_views.insert(l.cluster);
      if (l.vertex == kNoIndex) continue;
      if (v.id == "local") index.local_views.insert(l.vertex);
      if (v.id == "corners") index.corner_views.insert(l.vertex);
      if (l.cluster != kNoIndex) {
        std::vector<Index>& d = index.detail_of[l.cluster];
        if (std::find(d.begin(), d.end(), l.vertex) == d.end()) d.push_back(l.vertex);
      }
    }
  for (std::size_t i = 0; i < table_rows; ++i) index.table_clusters.insert(static_cast<Index>(i));
  for (const WorstVertex& w : model.analysis.quality.worst_vertices) index.worst_vertices.insert(w.vertex);
  return index;
}

// One <figure> of a view file: anchor id, caption and the links it carries.
data figure(const ViewEntry& v, std::size_t i, const PanelIndex& index) {
  const std::string& file = v.files[i];
  const ViewFileLinks no_links;
  const ViewFileLinks& l = i < v.links.size() ? v.links[i] : no_links;
  data d;
  d.set("file", file);
  d.set("alt", v.title);
  d.set("is_chart", file.ends_with(".svg"));
  d.set("is_overview", v.id == "overview");  // fitted above the fold (style.css figure.overview)
  data links{data::type::list};
  std::string id = "view-" + stem_of(file), caption = v.title;
  if (v.id == "clusters" && l.cluster != kNoIndex) {
    const std::string c = std::to_string(l.cluster);
    id = "cluster-" + c;
    caption = "Cluster " + c;
    if (const AggregatedGlyph* g = index.glyph_cluster(l.cluster))
      caption += ": " + show_count(g->size) + " glyphs, min quality " + show(g->min_quality);
    index.push_detail_links(l.cluster, links, false);
    if (index.table_clusters.count(l.cluster)) links.push_back(link("#cluster-row-" + c, "↑ table row"));
  } else if ((v.id == "local" || v.id == "corners") && l.vertex != kNoIndex) {
    const std::string vs = std::to_string(l.vertex);
    const bool is_local = v.id == "local";
    id = (is_local ? "vertex-" : "corners-") + vs;
    caption = std::string(is_local ? "Vertex " : "Corners at vertex ") + vs + " (quality " +
              show(index.quality_of(l.vertex)) + ")";
    if (is_local && index.corner_views.count(l.vertex)) links.push_back(link("#corners-" + vs, "E: corner chart"));
    if (!is_local && index.local_views.count(l.vertex)) links.push_back(link("#vertex-" + vs, "D: local view"));
    const std::string c = std::to_string(l.cluster);
    if (l.cluster != kNoIndex && index.cluster_views.count(l.cluster))
      links.push_back(link("#cluster-" + c, "C: cluster " + c));
    if (l.cluster != kNoIndex && index.table_clusters.count(l.cluster))
      links.push_back(link("#cluster-row-" + c, "↑ table row"));
  }
  d.set("id", id);
  d.set("caption", caption);
  d.set("links", links);
  d.set("has_links", !links.is_empty_list());
  data hotspots{data::type::list};
  for (std::size_t rank = 0; rank < l.hotspots.size(); ++rank) {
    const ChartHotspot& h = l.hotspots[rank];
    const std::string target = index.target_of_vertex(h.key);
    if (target.empty()) continue;
    data spot;
    spot.set("href", target);
    spot.set("style", percent_style(h.rect));
    spot.set("label", "rank " + std::to_string(rank + 1) + ": vertex " + std::to_string(h.key) + ", quality " +
                          show(index.quality_of(h.key)));
    hotspots.push_back(spot);
  }
  d.set("hotspots", hotspots);
  d.set("has_hotspots", !hotspots.is_empty_list());
  return d;
}

data figures_of(const ReportModel& model, const std::vector<std::string_view>& ids, const PanelIndex& index) {
  data figures{data::type::list};
  for (std::string_view id : ids)
    for (const ViewEntry& v : model.views)
      if (v.id == id)
        for (std::size_t i = 0; i < v.files.size(); ++i)
          if (!is_png_twin(v, v.files[i])) figures.push_back(figure(v, i, index));
  return figures;
}

data input_rows(const ReportModel& model) {
  data rows{data::type::list};
  auto add = [&](const std::string& role, const InputFile& f) {
    rows.push_back(kv(role, f.path));
    rows.push_back(kv(role + " format", f.format));
    rows.push_back(kv(role + " sha256", f.sha256));
  };
  add("mesh", model.analysis.mesh_input);
  if (model.analysis.reference_input) add("reference", *model.analysis.reference_input);
  if (model.analysis.compare) add("compared mesh", model.analysis.compare->input);
  // The views' up axis, and why (issue 45: --up auto picks it per mesh).
  if (!model.views.empty())
    rows.push_back(kv("up axis of the views", up_axis_name(model.viewer_up) +
                                                  (model.analysis.resting_up
                                                       ? (model.analysis.resting_up->from_data
                                                              ? " (--up auto: the pose it would rest in)"
                                                              : " (--up auto: no resting pose, the default)")
                                                       : model.up_auto && is_surface_mesh(model.analysis.mesh)
                                                           ? (model.viewer_up == Vec3{0.0, 0.0, 1.0}
                                                                  ? " (--up auto: no axis of revolution, the default)"
                                                                  : " (--up auto: the surface's axis of revolution)")
                                                           : " (--up)")));
  rows.push_back(kv("HQView", model.tool_version));
  rows.push_back(kv("metric definitions", "Verdict 1.4.5 (hex), Si and Chen (IEEE VIS 2023) vertex quality"));
  return rows;
}

// ---- index.html, section by section ----

// The data files and where the per-cell and per-vertex values are.
void set_data_files(data& page, const ReportModel& model) {
  data files{data::type::list};
  for (const DataFile& f : data_files(model.data)) {
    data file;
    file.set("path", f.path);
    file.set("what", f.what);
    files.push_back(file);
  }
  page.set("data_files", files);
  const std::string cells = cell_data_path(model.data);
  page.set("has_cell_data", !cells.empty());
  page.set("has_csv", model.data.csv || model.data.csv_gz);
  page.set("cell_data", cells.empty() ? "a bundle written with --data csv" : cells);
  page.set("vertex_data", cells.empty() ? "a bundle written with --data csv" : vertex_data_path(model.data));
}

// The mesh, its inputs and the tool.
void set_header(data& page, const ReportModel& model) {
  page.set("mesh_name", std::filesystem::path(model.analysis.mesh_input.path).filename().string());
  page.set("format", model.analysis.mesh_input.format);
  page.set("sha256_short", model.analysis.mesh_input.sha256.substr(0, 12));
  page.set("version", model.tool_version);
  page.set("has_boundary_page", model.analysis.boundary_error.has_value());
  set_data_files(page, model);
  page.set("inputs", input_rows(model));
}

// The papers' headline: #V, #H, min and mean scaled Jacobian, #inverted,
// overlaps, Hausdorff distance (% of the reference's bbox diagonal).
void set_headline(data& page, const ReportModel& model) {
  const MeshSummary& m = model.analysis.mesh_summary;
  const QualitySummary& q = model.analysis.quality;
  data headline{data::type::list};
  const CellComposition& c = model.analysis.composition;
  // A hybrid mesh names its cells by kind and counts over all of them.
  const bool hybrid = c.num_cells > c.count[0];
  headline.push_back(card("vertices", show_count(m.num_vertices)));
  if (m.is_surface) {
    // A surface mesh: its faces by kind, its plane, its cells' numbers.
    headline.push_back(card("cells", show_count(c.num_cells)));
    if (c.num_quads > 0) headline.push_back(card("quads", show_count(c.num_quads)));
    if (c.num_triangles > 0) headline.push_back(card("triangles", show_count(c.num_triangles)));
    const bool planar = !is_curved_surface(m);
    headline.push_back(card("surface", planar ? "planar" : "not planar"));
    if (planar) {
      headline.push_back(card("min scaled Jacobian (per cell, signed against the plane's normal)",
                              show(q.scaled_jacobian.min), q.scaled_jacobian.min <= 0));
      headline.push_back(card("mean scaled Jacobian (per cell)", show(q.scaled_jacobian.mean)));
      headline.push_back(card("inverted cells (folded or reversed against the plane)", show_count(q.num_inverted),
                              q.num_inverted > 0));
    } else {
      // A curved surface has no "inside": its inverted cells are its
      // reversed faces (orientation flipped against their neighbours), whose
      // corners are measured against the orientation the neighbours agree
      // on, so they are negative: the min scaled Jacobian card agrees with
      // the count of reversed faces, as the histograms, charts and views do.
      headline.push_back(card("min scaled Jacobian (per cell, signed against the neighbours' orientation)",
                              show(q.scaled_jacobian.min), q.scaled_jacobian.min <= 0));
      headline.push_back(card("mean scaled Jacobian (per cell)", show(q.scaled_jacobian.mean)));
      headline.push_back(card("reversed faces (orientation flipped against their neighbours: their corners negative)",
                              show_count(q.num_inverted), q.num_inverted > 0));
    }
  } else if (hybrid) {
    headline.push_back(card("cells", show_count(c.num_cells)));
    // One card per kind present, then the two hex fractions.
    static constexpr const char* kKindLabels[kNumVolumeKinds] = {"hexahedra", "tetrahedra", "wedges", "pyramids"};
    for (std::size_t k = 0; k < kNumVolumeKinds; ++k)
      if (c.count[k] > 0) headline.push_back(card(kKindLabels[k], show_count(c.count[k])));
    headline.push_back(card("hex fraction (by count)", c.hex_fraction ? show(*c.hex_fraction) : std::string("–")));
    headline.push_back(
        card("hex fraction (by volume)", c.hex_volume_fraction ? show(*c.hex_volume_fraction) : std::string("–")));
    headline.push_back(card("min scaled Jacobian (per cell, all kinds)", show(q.scaled_jacobian.min), q.scaled_jacobian.min <= 0));
    headline.push_back(card("mean scaled Jacobian (per cell, all kinds)", show(q.scaled_jacobian.mean)));
    headline.push_back(card("inverted cells", show_count(q.num_inverted), q.num_inverted > 0));
  } else {
    headline.push_back(card("hexahedra", show_count(m.num_hexes)));
    headline.push_back(card("min scaled Jacobian (per hex)", show(q.scaled_jacobian.min), q.scaled_jacobian.min <= 0));
    headline.push_back(card("mean scaled Jacobian (per hex)", show(q.scaled_jacobian.mean)));
    headline.push_back(
        card("inverted hexes", show_count(q.scaled_jacobian.num_inverted), q.scaled_jacobian.num_inverted > 0));
  }
  // One word for one count (issue 47 part F, issue 45): "intersecting
  // hexes" (cells; a surface mesh's "intersecting faces"), as the overlap
  // table and the overview's and view A's legends say; the overlap
  // module's other finding, vertices at one place, is "coincident vertices".
  const char* overlap_label = m.is_surface ? "intersecting faces" : hybrid ? "intersecting cells" : "intersecting hexes";
  if (model.analysis.overlap)
    headline.push_back(card(overlap_label, show_count(model.analysis.overlap->num_intersecting_cells),
                            model.analysis.overlap->num_intersecting_cells > 0));
  else
    headline.push_back(card(overlap_label, "not checked"));
  if (model.analysis.boundary_error) {
    const BoundaryError& e = *model.analysis.boundary_error;
    data hausdorff = card("Hausdorff distance (sampled, symmetric), % of bbox diagonal",
                          show(sampled_relative(e, e.sampled_symmetric)) + " %");
    hausdorff.set("href", "boundary.html");
    headline.push_back(hausdorff);
  }
  // A surface's faces have no axis (the 47d review's minor: hex wording).
  headline.push_back(card(m.is_surface ? "degenerate faces (a zero-length edge)"
                          : hybrid     ? "degenerate cells (a zero-length edge or axis)"
                                       : "degenerate hexes (a zero-length edge or axis)",
                          show_count(q.scaled_jacobian.num_degenerate), q.scaled_jacobian.num_degenerate > 0));
  headline.push_back(card("min vertex quality", show(q.vertex_quality.min), q.vertex_quality.min <= 0));
  if (model.analysis.fem_elements) {
    // The count (a Gauss-point det J <= 0: not a valid Q1 element,
    // nothing is solved) beside the stricter one (a corner det J <= 0: the
    // trilinear map folds over; still solved when the Gauss points are positive).
    const FemElementField& f = *model.analysis.fem_elements;
    headline.push_back(card("invalid Q1 elements (a Gauss-point det J \u2264 0: not solved)",
                            show_count(f.num_invalid), f.num_invalid > 0));
    headline.push_back(card("non-invertible trilinear maps (a corner det J \u2264 0; solved if Gauss points > 0)",
                            show_count(f.num_not_invertible), f.num_not_invertible > 0));
  }
  if (model.analysis.overlap && model.analysis.overlap->num_coincident_vertices > 0)
    headline.push_back(card("coincident vertices", show_count(model.analysis.overlap->num_coincident_vertices), true));
  page.set("headline", headline);

  // Input warnings in red; what HQView does not do yet on this mesh
  // (analysis/limitations.h) apart, neutral, as the batch page calls them
  // (the 47d review's M3).
  data warnings{data::type::list}, limitations{data::type::list};
  for (const std::string& w : model.analysis.warnings) (is_limitation_warning(w) ? limitations : warnings).push_back(w);
  page.set("warnings", warnings);
  page.set("has_warnings", !warnings.is_empty_list());
  page.set("limitations", limitations);
  page.set("has_limitations", !limitations.is_empty_list());
  // Notes (information: not in the warning colour).
  data notes{data::type::list};
  for (const std::string& n : model.analysis.notes) notes.push_back(n);
  page.set("notes", notes);
  page.set("has_notes", !model.analysis.notes.empty());
}

bool has_view(const ReportModel& model, std::string_view id) {
  return std::any_of(model.views.begin(), model.views.end(),
                     [&](const ViewEntry& v) { return v.id == id && !v.files.empty(); });
}

// The short names of index.html's panels with a figure ("A main", "S
// structure", ...), in page order; F (the compare view) left out.
std::vector<std::string> drawn_panels_but_f(const ReportModel& model) {
  std::vector<std::string> names;
  for (const PanelSpec& spec : index_panels()) {
    if (spec.letter == 'F') continue;
    const std::vector<std::string_view> ids = panel_view_ids(spec.letter);
    if (std::any_of(ids.begin(), ids.end(), [&](std::string_view id) { return has_view(model, id); }))
      names.emplace_back(spec.nav);
  }
  return names;
}

// What of each mesh a compare page shows (46r review M2: a reader took the
// missing panels of the compared mesh, or of a run with fewer --views, for
// a regression): the panels drawn are the first mesh's; the compared one
// is in the compare view and this table, its own panels in its own report.
std::string compare_scope(const ReportModel& model, const CompareTable& t) {
  const std::vector<std::string> panels = drawn_panels_but_f(model);
  std::string list;
  for (std::size_t i = 0; i < panels.size(); ++i)
    list += (i == 0 ? "" : i + 1 == panels.size() ? " and " : ", ") + panels[i];
  std::string text = panels.empty()        ? "No panel of either mesh was drawn in this run (--views)."
                     : panels.size() == 1 ? "Panel " + list + " shows " + t.mine_name + " only."
                                          : "Panels " + list + " show " + t.mine_name + " only.";
  text += " " + t.theirs_name + " is shown " +
          (has_view(model, "compare") ? std::string("by its ") + (is_surface_mesh(model.analysis.mesh) ? "faces" : "boundary") +
                                              " beside it in the compare view (panel F) and "
                                        : std::string()) +
          "by this table: a comparison draws one mesh's views, not both; its own panels are in its own report (hqview "
          "analyze " + t.theirs_name + " with the same --views).";
  return text;
}

// --compare: both meshes' numbers side by side and their differences.
void set_comparison(data& page, const ReportModel& model) {
  page.set("has_compare", model.analysis.compare.has_value());
  if (!model.analysis.compare) return;
  const CompareTable t = compare_table(model.analysis);
  page.set("compare_mine", t.mine_name);
  page.set("compare_theirs", t.theirs_name);
  page.set("compare_alignment", t.alignment.empty() ? std::string("as read (same frame)") : t.alignment);
  page.set("compare_scope", compare_scope(model, t));
  data rows{data::type::list};
  for (const CompareTableRow& r : t.rows) {
    data d;
    d.set("label", r.label);
    d.set("mine", r.mine);
    d.set("theirs", r.theirs);
    d.set("difference", r.difference);
    d.set("is_worse", r.is_worse);
    rows.push_back(d);
  }
  page.set("compare_rows", rows);
}

bool has_non_hex(const ReportModel& model) {
  const Mesh& mesh = model.analysis.mesh;
  return !mesh.tets.empty() || !mesh.wedges.empty() || !mesh.pyramids.empty();
}

// A panel's text on a mesh with tets, wedges or pyramids: what it says of
// hexes said of the cells of every kind (46q review Q-M9).
std::string hybrid_wording(std::string text) {
  static const std::pair<const char*, const char*> kWords[] = {
      {"The hex boundary", "The boundary (every cell kind)"},
      {"the inverted hexes", "the inverted cells"},
      {"clusters and intersecting hexes", "clusters and intersecting cells"},
      {"one-ring hexes of a vertex", "one-ring cells of a vertex"},
      {"The hexes around a chosen vertex", "The cells of every kind around a chosen vertex"},
      {"one bar per incident hex", "one bar per corner of an incident cell"},
      {"and the hexes around them", "and the cells around them"},
      // Each boundary face takes its own kind's corners (the overview's legend).
      {"Overview: vertex quality on the boundary", "Overview: corner quality on the boundary"},
      {"the boundary coloured by vertex quality", "the boundary coloured by corner quality (each face: its own cell kind's corners)"},
  };
  for (const auto& [from, to] : kWords)
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + std::strlen(to)))
      text.replace(at, std::strlen(from), to);
  return text;
}

// The intro of panels A and S from the views drawn, so that the text never
// promises a picture the page lacks (46r review M2: "Then sphere glyphs
// sit on bad vertices" over a panel A of the overview alone); the other
// panels' from their spec.
std::string panel_intro(const PanelSpec& spec, const ReportModel& model) {
  std::string text;
  const auto add = [&text](const std::string& sentence) { text += (text.empty() ? "" : " ") + sentence; };
  if (spec.letter == 'A') {
    const bool overview = has_view(model, "overview"), main = has_view(model, "main");
    if (overview)
      add("First the overview: the boundary coloured by vertex quality, a ring around the inverted hexes (dashed when "
          "they are inside the volume or on the far side, and then also drawn cut out in a corner inset).");
    if (main)
      add(std::string(overview ? "Then sphere" : "Sphere") +
          " glyphs sit on bad vertices (the lower the quality, the larger), merged where they overlap; the worst "
          "clusters each have a colour, all others are grey; arrows point at overlapping elements.");
    return text;
  }
  if (spec.letter == 'S') {
    if (has_view(model, "structure"))
      add("The singular edges (an interior edge without 4 hexes, a boundary edge without 2) coloured by valence, "
          "inside the translucent boundary; dark spheres are the nodes where singular curves meet or end.");
    if (has_view(model, "size_gradation"))
      add("The size gradation image colours the boundary by each cell's largest ratio of equivalent edge lengths "
          "(the cube root of its volume; of several kinds: the regular cell of its kind with that volume) to a face "
          "neighbour's; a smooth grading stays pale by design, as the ratio is between neighbours.");
    add("Counts: report.json structure; every singular, irregular or non-manifold edge: data/edges.csv.");
    return text;
  }
  if (spec.letter == 'F') {
    const std::vector<std::string_view> ids = panel_view_ids('F');
    if (std::any_of(ids.begin(), ids.end(), [&](std::string_view id) { return id != "compare" && has_view(model, id); }))
      add(model.analysis.mesh_summary.is_surface ? "The surface mesh against the reference surface (--reference)."
                                                 : "The hex boundary against the reference surface (--reference).");
    if (has_view(model, "compare"))
      add("The compared mesh (--compare) beside this one: one camera, one colour map; the Comparison section below "
          "says what of each mesh the page shows.");
    return text;
  }
  return spec.intro;
}

// Panel A's and S's titles name what they show when only one of their two
// kinds of picture was drawn; the others keep their spec's.
std::string panel_title(const PanelSpec& spec, const ReportModel& model) {
  if (spec.letter == 'A' && !has_view(model, "main")) return "A · Overview: vertex quality on the boundary";
  if (spec.letter == 'A' && !has_view(model, "overview")) return "A · Main view: glyphs, clusters and intersecting hexes";
  if (spec.letter == 'S' && !has_view(model, "size_gradation")) return "S · Structure: singularity graph";
  if (spec.letter == 'S' && !has_view(model, "structure")) return "S · Structure: size gradation";
  return spec.title;
}

// Panel A's and S's title and text on a surface mesh (no hexes, nothing
// inside; the structure is irregular vertices and separatrices): nullptr
// for the other panels, which keep theirs (47c review item 8).
const char* surface_panel_title(char letter) {
  if (letter == 'A') return "A · Overview and main view: vertex quality, faces by scaled Jacobian, glyphs and clusters";
  if (letter == 'S') return "S · Structure: irregular vertices, separatrices and patches";
  if (letter == 'B') return "B · Sorted vertex quality";
  if (letter == 'C') return "C · The faces of the worst clusters";
  if (letter == 'D') return "D · Local views: the faces of a vertex";
  if (letter == 'E') return "E · Corner charts";
  return nullptr;
}
const char* surface_panel_intro(char letter) {
  if (letter == 'A')
    return "First the overview: the faces coloured by vertex quality (the lowest corner scaled Jacobian at each "
           "vertex), each inverted face outlined whole in dark blue-violet. Then the main view: each face filled "
           "by its own scaled Jacobian (its lowest corner; signed against the plane's normal on a planar mesh, so a "
           "folded quad is negative) in five bins, every bin counted in the legend; sphere glyphs sit on bad "
           "vertices (the lower the quality, the larger), merged where they overlap; the worst clusters each have a "
           "colour, all others are grey. A planar mesh is seen along its normal, orthographic; a curved one from "
           "the three-quarter view. Arrows point at coincident vertices and at faces that intersect the surface "
           "elsewhere.";
  if (letter == 'S')
    return "Each irregular vertex (valence = the number of incident quads; interior not 4, boundary not its ideal "
           "valence from its corner angles) as a sphere coloured by its class; the separatrices traced from them "
           "along edge lines, straight on through regular vertices, as dark lines; the mesh boundary in blue-grey; "
           "the patches (quads joined across untraced edges) tinted. The layout is traced as is, not simplified "
           "(no collapse of nearby singularity pairs, no motorcycle graph): on an unstructured mesh nearly every "
           "edge lies on a separatrix and a patch holds a quad or two, which the legend's counts say. Counts: "
           "report.json structure.";
  if (letter == 'B')
    return "Each bar of the sorted chart is one of the worst vertices (its lowest corner scaled Jacobian over its "
           "faces), worst on the left. Click a bar to go to its cluster's faces (C), or to its local view (D) when "
           "its cluster has no view C.";
  if (letter == 'C')
    return "One view per top cluster (the table's bold rows): the faces at its vertices, each filled by its scaled "
           "Jacobian (its lowest corner) on the quality colour bar, inverted ones in dark blue-violet; its glyphs "
           "(size is severity as in view A, all scaled by one factor: the largest at most 0.35 of the shortest edge, at "
           "least 0.08 of the mean edge; the worst vertex's glyph ringed yellow and black), the cluster's edges drawn "
           "over the glyphs, and the neighbouring faces pale. A planar mesh is "
           "seen along its normal, orthographic, a fold's inverted faces over the others; a curved one upright, "
           "its faces in depth. Each links to the local "
           "view (D) and corner chart (E) of the cluster's worst vertex, and back to its table row.";
  if (letter == 'D')
    return "The faces around a chosen vertex (the worst of each top cluster, then any --focus-vertex), each "
           "corner at the vertex a disc inside its face next to the vertex, coloured and labelled with its signed "
           "scaled Jacobian (inverted: dark blue-violet), with the value's three decimals as in C's title and chart E. "
           "A planar mesh is seen along its normal.";
  if (letter == 'E')
    return "The corner scaled Jacobians at each chosen vertex, one bar per incident face, in the quality bar's colour "
           "of its value (inverted: dark blue-violet; the key under the axis).";
  return nullptr;
}

// Panels A–F with the links between them (every view of kViews has a
// panel here or on boundary.html).
void set_panels(data& page, const ReportModel& model, const PanelIndex& index) {
  data panels{data::type::list};
  for (const PanelSpec& spec : index_panels()) {
    data figures = figures_of(model, panel_view_ids(spec.letter), index);
    if (figures.is_empty_list()) continue;
    data panel;
    panel.set("anchor", spec.anchor);
    panel.set("nav", spec.nav);
    panel.set("title", panel_title(spec, model));
    const std::string intro = panel_intro(spec, model);
    panel.set("intro", has_non_hex(model) ? hybrid_wording(intro) : intro);
    if (has_non_hex(model)) panel.set("title", hybrid_wording(panel_title(spec, model)));
    if (model.analysis.mesh_summary.is_surface && surface_panel_intro(spec.letter)) {
      panel.set("intro", std::string(surface_panel_intro(spec.letter)));
      panel.set("title", std::string(surface_panel_title(spec.letter)));
    }
    // Panel A's intro under its figures, so that the overview starts right
    // under the heading and fits the first screen (issue 45e).
    panel.set("intro_after", spec.letter == 'A');
    panel.set("figures", figures);
    panel.set("has_viewer", spec.letter == 'A' && model.has_viewer);
    panels.push_back(panel);
  }
  page.set("panels", panels);
  page.set("has_views", !model.views.empty());
}

// The structure table: counts of report.json `structure`, one row each.
void set_structure(data& page, const HexStructure& s) {
  data rows{data::type::list};
  auto row = [&rows](const std::string& name, const std::string& value, const std::string& key) {
    data d;
    d.set("name", name);
    d.set("value", value);
    d.set("key", key);
    rows.push_back(d);
  };
  auto by_valence = [](const std::map<Index, Index>& counts) {
    std::string text;
    for (const auto& [valence, count] : counts)
      text += (text.empty() ? "" : ", ") + std::string("valence ") + std::to_string(valence) + ": " + display_count(count);
    return text.empty() ? std::string("none") : text;
  };
  row("edges", display_count(s.num_edges), "num_edges");
  row("singular interior edges (valence ≠ 4)", display_count(s.num_singular_edges_interior) + " — " +
      by_valence(s.interior_by_valence), "num_singular_edges_interior");
  row("singular boundary edges (valence ≠ 2)", display_count(s.num_singular_edges_boundary) + " — " +
      by_valence(s.boundary_by_valence), "num_singular_edges_boundary");
  row("irregular boundary edges (valence ≠ round(angle / 90°))", display_count(s.num_irregular_edges_boundary),
      "num_irregular_edges_boundary");
  row("non-manifold edges", display_count(s.num_nonmanifold_edges), "num_nonmanifold_edges");
  row("singular vertices", display_count(s.num_singular_vertices), "num_singular_vertices");
  row("singularity nodes", display_count(static_cast<long long>(s.nodes.size())), "num_singularity_nodes");
  std::string curves = display_count(s.num_curves);
  if (!s.curve_lengths.empty()) {
    const auto [lo, hi] = std::minmax_element(s.curve_lengths.begin(), s.curve_lengths.end());
    curves += " — " + std::to_string(*lo) + " to " + std::to_string(*hi) + " edges long";
  }
  row("singular curves", curves, "num_singular_curves");
  row("size gradation (volume ratio to a face neighbour)",
      s.gradation.count == 0 ? std::string("undefined")
                             : "median " + display_number(s.gradation.p50, 3) + ", p95 " +
                                   display_number(s.gradation.p95, 3) + ", max " + display_number(s.gradation.max, 3) +
                                   "; above 2: " + display_count(s.num_gradation_above_2) +
                                   ", above 4: " + display_count(s.num_gradation_above_4),
      "size_gradation");
  page.set("structure_rows", rows);
}

// The statistics of the Jacobian fields and of every Verdict metric.
void set_statistics(data& page, const QualitySummary& q, bool is_surface, bool is_hybrid) {
  data stats{data::type::list};
  // A surface mesh's cells: signed corners (docs/analysis.md, "Surface meshes").
  // A hybrid mesh's: each kind's Verdict scaled Jacobian and corners (46q review Q-M9).
  stats.push_back(stats_row("cell scaled Jacobian",
                            is_surface  ? "lowest signed corner (against the plane of a planar mesh)"
                            : is_hybrid ? "Verdict's, of each cell's kind (a hex: min over centre and 8 corner frames)"
                                        : "Verdict: min over centre and 8 corner frames",
                            q.scaled_jacobian));
  stats.push_back(stats_row("corner scaled Jacobian",
                            is_surface  ? "4 corners of every quad, 3 of every triangle"
                            : is_hybrid ? "every cell's corners: 8 per hex, 4 per tet, 6 per wedge, a pyramid's 4 base corners"
                                        : "all 8 corners of every hex",
                            q.corner_scaled_jacobian));
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
  // A surface mesh has no hexes: its quad and triangle metrics are in
  // report.json quality.by_kind (no table here yet).
  page.set("has_metrics", !q.metrics.empty() && !is_surface);
}

void set_gates(data& page, const GateSummary& gate_summary) {
  data gates{data::type::list};
  for (const GateResult& g : gate_summary.results) {
    data d;
    d.set("rule", g.rule);
    d.set("value", show(g.value));
    d.set("passed", g.passed);
    gates.push_back(d);
  }
  page.set("gates", gates);
  page.set("has_gates", !gate_summary.results.empty());
  page.set("gates_passed", gate_summary.passed);
}

// The worst vertices (linked to their cluster's views) and cells.
void set_worst(data& page, const QualitySummary& q, const PanelIndex& index) {
  data worst_vertices{data::type::list};
  for (const WorstVertex& w : q.worst_vertices) {
    data d;
    d.set("vertex", std::to_string(w.vertex));
    const std::string target = index.target_of_vertex(w.vertex);
    // A link only to another panel or table (not to the row itself).
    const bool has_target = !target.empty() && !target.starts_with("#worst-vertex-");
    d.set("target", target);
    d.set("has_target", has_target);
    d.set("quality", show(w.quality));
    d.set("position", show_vec(w.position));
    worst_vertices.push_back(d);
  }
  page.set("worst_vertices", worst_vertices);
  data worst_cells{data::type::list};
  for (const WorstCell& w : q.worst_cells) {
    data d;
    d.set("cell", std::to_string(w.cell));
    d.set("kind", std::string(cell_kind_name(w.kind)));
    d.set("source_index", std::to_string(w.source_index));  // its number in the file (mesh.h)
    d.set("scaled_jacobian", w.scaled_jacobian >= 1e30 ? "degenerate" : show(w.scaled_jacobian));
    worst_cells.push_back(d);
  }
  page.set("worst_cells", worst_cells);
  // The kind column on a mesh with other kinds than hexahedra.
  page.set("worst_cells_hybrid", std::any_of(q.worst_cells.begin(), q.worst_cells.end(),
                                             [](const WorstCell& w) { return w.kind != CellKind::hex; }) ||
                                     q.scaled_jacobian.count > static_cast<std::int64_t>(q.by_kind.empty() ? 0 : q.by_kind[0].count));
}

void set_mesh_rows(data& page, const MeshSummary& m) {
  data mesh_rows{data::type::list};
  // A surface mesh counts its edges, not hex faces (47c review item 8).
  if (m.is_surface) {
    mesh_rows.push_back(kv("boundary edges (on one face)", show_count(m.num_boundary_edges)));
    mesh_rows.push_back(kv("boundary vertices", show_count(m.num_boundary_vertices)));
    mesh_rows.push_back(kv("unreferenced vertices", show_count(m.num_unreferenced_vertices)));
    mesh_rows.push_back(kv("non-manifold edges (on > 2 faces)", show_count(m.num_non_manifold_edges)));
    mesh_rows.push_back(kv("reversed faces (against their neighbours)", show_count(m.num_reversed_faces)));
  } else {
    mesh_rows.push_back(kv("boundary faces", show_count(m.num_boundary_faces)));
    mesh_rows.push_back(kv("boundary vertices", show_count(m.num_boundary_vertices)));
    mesh_rows.push_back(kv("unreferenced vertices", show_count(m.num_unreferenced_vertices)));
    mesh_rows.push_back(kv("faces shared by > 2 hexes", show_count(m.num_non_manifold_faces)));
  }
  if (m.num_non_conforming_faces > 0)  // hybrid meshes only: pure-hex pages keep their bytes
    mesh_rows.push_back(kv("non-conforming faces (a quad against two triangles)", show_count(m.num_non_conforming_faces)));
  mesh_rows.push_back(kv("bounding box min", show_vec(m.bbox_min)));
  mesh_rows.push_back(kv("bounding box max", show_vec(m.bbox_max)));
  mesh_rows.push_back(kv("bounding box diagonal", show(m.bbox_diagonal)));
  mesh_rows.push_back(kv("edge length min / mean / max",
                         show(m.edge_length_min) + " / " + show(m.edge_length_mean) + " / " + show(m.edge_length_max)));
  page.set("mesh_rows", mesh_rows);
}

// Glyph clusters: the worst cluster_rows, with their palette colour; the
// first top_clusters are the ones later views show in detail.
void set_glyphs(data& page, const ReportModel& model, const PanelIndex& index, std::size_t cluster_rows) {
  page.set("has_glyphs", model.analysis.glyphs.has_value());
  if (model.analysis.glyphs) {
    const GlyphResult& g = *model.analysis.glyphs;
    const bool is_relative = g.options.rmax_unit == RmaxUnit::kMeanEdgeLength;
    page.set("glyph_summary",
             show_count(g.num_glyphs) + " vertices with quality below " + show(1.0 - g.options.threshold) +
                 " have a glyph, in " + show_count(static_cast<long long>(g.clusters.size())) +
                 " clusters of overlapping glyphs; rmax " + show(g.rmax) +
                 (is_relative ? " (" + show(g.options.rmax) + " × mean edge length)." : " (model units).") +
                 (g.options.size_rule == GlyphSizeRule::kPaper
                      ? " A cluster's glyph radius is (1 − min quality + 0.1 per 10 members, at most + 1) · rmax "
                        "(--glyph-size paper, HQViewer's rule)."
                      : " A cluster's glyph radius is (1 − min quality) · rmax, its size the member count."));
    data clusters{data::type::list};
    const std::size_t rows = cluster_rows;
    const std::vector<Index> slots =
        glyph_colour_slots(g.clusters, static_cast<Index>(labelled_cluster_count(g.options.top_clusters)));
    for (std::size_t i = 0; i < rows; ++i) {
      const AggregatedGlyph& c = g.clusters[i];
      data d;
      d.set("id", std::to_string(c.id));
      d.set("color", cluster_color_hex(slots[i], g.options.top_clusters));
      d.set("size", show_count(c.size));
      d.set("min_quality", show(c.min_quality));
      d.set("vertex", std::to_string(c.representative_vertex));
      d.set("position", show_vec(c.position));
      d.set("radius", show(c.radius));
      d.set("is_top", static_cast<int>(i) < g.options.top_clusters);
      d.set("has_view", index.cluster_views.count(c.id) > 0);
      d.set("has_viewer", model.has_viewer && i < 1000);
      data links{data::type::list};
      index.push_detail_links(c.id, links, true);
      d.set("links", links);
      clusters.push_back(d);
    }
    page.set("clusters", clusters);
    page.set("has_clusters", rows > 0);
    page.set("has_more_clusters", g.clusters.size() > rows);
    page.set("more_clusters", show_count(static_cast<long long>(g.clusters.size() - rows)));
  }
}

constexpr std::size_t kHtmlOverlapRows = 20;

// The first kHtmlOverlapRows intersecting pairs.
void set_overlap_pairs(data& page, const OverlapReport& o) {
  data pairs{data::type::list};
  const std::size_t shown = std::min(o.intersecting_pairs.size(), kHtmlOverlapRows);
  for (std::size_t i = 0; i < shown; ++i) {
    const IntersectingPair& p = o.intersecting_pairs[i];
    data d;
    d.set("a", std::to_string(p.cells[0]));
    d.set("b", std::to_string(p.cells[1]));
    d.set("vertex", o.is_surface ? std::string(cell_kind_name(p.kinds[0])) + " / " + std::string(cell_kind_name(p.kinds[1]))
                   : p.inside_vertex == kNoIndex ? "– (duplicates)" : std::to_string(p.inside_vertex));
    d.set("position", show_vec(p.position));
    pairs.push_back(d);
  }
  page.set("overlap_pairs", pairs);
  page.set("overlap_of_faces", o.is_surface);
  page.set("has_overlap_pairs", shown > 0);
  page.set("has_more_overlap_pairs", o.intersecting_pairs.size() > shown);
  page.set("more_overlap_pairs", show_count(static_cast<long long>(o.intersecting_pairs.size() - shown)));
}

data count_row(const std::string& key, std::size_t value) {
  data d = kv(key, show_count(static_cast<long long>(value)));
  d.set("alert", value > 0);
  return d;
}

// A surface mesh's findings (check_surface_overlap): faces, not hexes.
void set_surface_overlap(data& page, const OverlapReport& o) {
  page.set("overlap_summary",
           std::string(o.certified_clean ? "Clean: no two faces meet other than in the vertices and edges they share"
                                         : "Faces whose triangles meet other than in the vertices and edges they share") +
               " (" + show_count(o.num_candidate_pairs) +
               " triangle pairs tested exactly; a quad is split along the diagonal that does not fold it, else the "
               "shorter; coincident vertices count as one).");
  data rows{data::type::list};
  rows.push_back(count_row("intersecting faces", static_cast<std::size_t>(o.num_intersecting_cells)));
  rows.push_back(count_row("intersecting face pairs", o.intersecting_pairs.size()));
  rows.push_back(count_row("faces folded onto themselves", o.self_intersecting_faces.size()));
  rows.push_back(count_row("coincident vertices", static_cast<std::size_t>(o.num_coincident_vertices)));
  rows.push_back(count_row("zero-length edges", o.zero_length_edges.size()));
  rows.push_back(count_row("duplicate faces", o.duplicate_cells.size()));
  page.set("overlap_rows", rows);
  set_overlap_pairs(page, o);
}

// Overlap findings: the counts, then the first kHtmlOverlapRows pairs.
void set_overlap(data& page, const ReportModel& model) {
  page.set("has_overlap", model.analysis.overlap.has_value());
  if (model.analysis.overlap) {
    const OverlapReport& o = *model.analysis.overlap;
    const std::string mode(overlap_mode_name(o.mode));
    if (o.is_surface) {
      set_surface_overlap(page, o);
      return;
    }
    page.set("overlap_summary",
             o.certified_clean
                 ? "Certified: every hex is positively oriented (24 exact tets each) and the boundary is embedded and "
                   "unnested, so no two hexes overlap (Lipman's theorem)" +
                       std::string(o.mode == OverlapMode::exhaustive ? "; the exhaustive pair tests agree."
                                                                     : "; no pair tests were needed.")
                 : "Not certified: " + show_count(o.num_flagged_cells) +
                       " hexes were tested against every hex near them (" + show_count(o.num_candidate_pairs) +
                       " pairs, " + mode + " mode). A pair intersects when a vertex of one lies inside the other.");
    data rows{data::type::list};
    auto row = [&](const std::string& key, std::size_t value) { rows.push_back(count_row(key, value)); };
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
    set_overlap_pairs(page, o);
  }
}

}  // namespace

std::string_view report_stylesheet() { return report_template("style.css"); }

std::string index_html(const ReportModel& model) {
  constexpr std::size_t kHtmlClusterRows = 20;
  const std::size_t cluster_rows =
      model.analysis.glyphs ? std::min(model.analysis.glyphs->clusters.size(), kHtmlClusterRows) : 0;
  const PanelIndex index = index_panels_of(model, cluster_rows);
  data page;
  set_header(page, model);
  set_headline(page, model);
  set_panels(page, model, index);
  set_comparison(page, model);
  set_statistics(page, model.analysis.quality, model.analysis.mesh_summary.is_surface, has_non_hex(model));
  page.set("is_surface", model.analysis.mesh_summary.is_surface);
  set_structure(page, model.analysis.structure);
  set_gates(page, model.gates);
  set_worst(page, model.analysis.quality, index);
  set_mesh_rows(page, model.analysis.mesh_summary);
  set_glyphs(page, model, index, cluster_rows);
  set_overlap(page, model);
  page.set("lightbox", std::string(report_template("lightbox.html")));
  mustache tmpl{std::string(report_template("index.html.mustache"))};
  if (!tmpl.is_valid()) throw Error("internal: index.html template: " + tmpl.error_message());
  tmpl.set_custom_escape([](const std::string& s) { return html_escape(s); });
  return tmpl.render(page);
}

std::string boundary_html(const ReportModel& model) {
  if (!model.analysis.boundary_error) throw Error("internal: boundary.html without a boundary error");
  const BoundaryError& e = *model.analysis.boundary_error;
  data page;
  page.set("mesh_name", std::filesystem::path(model.analysis.mesh_input.path).filename().string());
  page.set("reference_name", model.analysis.reference_input
                                 ? std::filesystem::path(model.analysis.reference_input->path).filename().string()
                                 : "");
  page.set("version", model.tool_version);
  set_data_files(page, model);
  // --reference-align: what was done to the reference, said on the page.
  const CompareAlignment& moved = model.analysis.reference_alignment;
  page.set("has_reference_alignment", moved.requested != CompareAlign::none);
  page.set("reference_align_mode", compare_align_name(moved.requested));
  page.set("reference_alignment",
           alignment_description(moved).empty() ? std::string("left as read (already in place)") : alignment_description(moved));

  data headline{data::type::list};
  // The sampled figures (over the surfaces, certified); the vertex figures below.
  headline.push_back(card("Hausdorff distance (sampled, symmetric), % of bbox diagonal",
                          show(sampled_relative(e, e.sampled_symmetric)) + " %"));
  headline.push_back(card("Hausdorff distance (sampled, symmetric), model units", show(e.sampled_symmetric)));
  headline.push_back(card("sampled mesh → reference, % of diagonal",
                          show(sampled_relative(e, e.sampled_mesh_to_reference.max)) + " %"));
  headline.push_back(card("sampled reference → mesh, % of diagonal",
                          show(sampled_relative(e, e.sampled_reference_to_mesh.max)) + " %"));
  // A surface mesh's vertices are all on its "boundary" here; a planar
  // mesh's boundary polylines are measured against the reference's outline.
  const std::string vertices = e.planar ? "the mesh's boundary vertices"
                               : model.analysis.mesh_summary.is_surface ? "the mesh's vertices"
                                                                        : "hex boundary vertices";
  const std::string measure = e.planar ? "length" : "area", over = e.planar ? "along the polylines" : "over the surfaces";
  headline.push_back(card("mesh → reference at " + vertices + " (the papers' figure), % of diagonal",
                          show(100.0 * e.relative_mesh_to_reference) + " %"));
  const std::string floor = show(sampled_relative(e, e.on_surface_tolerance));
  headline.push_back(card("boundary " + measure + " outside / on / inside the reference (on: |error| ≤ " + floor +
                              " % of the diagonal)",
                          // No spaces around the slashes: the card's value does not wrap (a phone's 375 px).
                          one_decimal(100.0 * e.fraction_outside) + "/" + one_decimal(100.0 * e.fraction_on_surface) +
                              "/" + one_decimal(100.0 * e.fraction_inside) + " %"));
  page.set("headline", headline);

  // No links between these views: an empty panel index.
  PanelIndex no_links;
  no_links.model = &model;
  data figures = figures_of(model, panel_view_ids(0), no_links);
  page.set("has_figures", !figures.is_empty_list());
  page.set("is_surface", model.analysis.mesh_summary.is_surface);
  page.set("is_planar", e.planar);
  page.set("reference_diagonal", show(e.reference_bbox_diagonal));
  page.set("figures", figures);

  const Statistics& s = e.signed_stats;
  data stats{data::type::list};
  auto stat = [&](const std::string& key, const std::string& value) { stats.push_back(kv(key, value)); };
  stat("boundary vertices", show_count(s.count));
  stat("min (most inside)", show(s.min));
  stat("p01 / p05", show(s.p01) + " / " + show(s.p05));
  stat("median", show(s.p50));
  stat("mean / std", show(s.mean) + " / " + show(s.std));
  stat("p95 / p99", show(s.p95) + " / " + show(s.p99));
  stat("max (most outside)", show(s.max));
  page.set("signed_rows", stats);

  data rows{data::type::list};
  rows.push_back(kv("Hausdorff sampled " + over + ", mesh → reference: max sampled (certified upper bound)",
                    show(e.sampled_mesh_to_reference.max) + " (" + show(e.sampled_mesh_to_reference.upper_bound) + ")"));
  rows.push_back(kv("Hausdorff sampled " + over + ", reference → mesh: max sampled (certified upper bound)",
                    show(e.sampled_reference_to_mesh.max) + " (" + show(e.sampled_reference_to_mesh.upper_bound) + ")"));
  rows.push_back(kv("sampling tolerance / samples",
                    show(e.sampling_tolerance) + " / " +
                        show_count(e.sampled_mesh_to_reference.num_samples + e.sampled_reference_to_mesh.num_samples)));
  rows.push_back(kv("sampled " + measure + "-weighted mean / mean |error| / rms, mesh → reference",
                    show(e.sampled_mesh_to_reference.mean) + " / " + show(e.sampled_mesh_to_reference.mean_abs) + " / " +
                        show(e.sampled_mesh_to_reference.rms)));
  rows.push_back(kv("sampled " + measure + "-weighted mean / mean |error| / rms, reference → mesh",
                    show(e.sampled_reference_to_mesh.mean) + " / " + show(e.sampled_reference_to_mesh.mean_abs) +
                        " / " + show(e.sampled_reference_to_mesh.rms)));
  rows.push_back(kv("Hausdorff at " + vertices + ", mesh → reference", show(e.hausdorff_mesh_to_reference)));
  rows.push_back(kv(e.planar ? std::string("Hausdorff at the reference outline's vertices, reference → mesh")
                             : std::string("Hausdorff at reference vertices and face centres, reference → mesh"),
                    show(e.hausdorff_reference_to_mesh)));
  rows.push_back(kv("Hausdorff (vertex figures), symmetric", show(e.hausdorff_symmetric)));
  rows.push_back(kv("reference bbox diagonal", show(e.reference_bbox_diagonal)));
  rows.push_back(
      kv(measure + "-weighted mean / mean |error| / rms (" + vertices + ")",
         show(e.area_weighted_mean) + " / " + show(e.area_weighted_mean_abs) + " / " + show(e.area_weighted_rms)));
  rows.push_back(kv("sign method", sign_method_name(e.sign_method)));
  rows.push_back(kv("uncertain signs", show_count(e.num_uncertain_signs)));
  rows.push_back(kv("reference triangles read / repaired / zero area",
                    show_count(e.num_reference_triangles) + " / " + show_count(e.num_repaired_triangles) + " / " +
                        show_count(e.num_zero_area_triangles)));
  if (model.analysis.uv_atlas) {
    const UvAtlas& a = *model.analysis.uv_atlas;
    rows.push_back(kv("UV atlas charts (splits / laid out by LSCM or ARAP)", show_count(a.num_charts) + " (" + show_count(a.num_splits) +
                                                            " / " + show_count(a.num_lscm_charts) + ")"));
    rows.push_back(
        kv("UV flipped triangles / overlapping pairs", show_count(a.num_flipped) + " / " + show_count(a.num_overlaps)));
    rows.push_back(kv("UV packing efficiency", show(100.0 * a.packing_efficiency) + " %"));
  }
  page.set("detail_rows", rows);

  data warnings{data::type::list};
  for (const std::string& w : e.warnings) warnings.push_back(w);
  page.set("warnings", warnings);
  page.set("has_warnings", !e.warnings.empty());
  page.set("inputs", input_rows(model));

  page.set("lightbox", std::string(report_template("lightbox.html")));
  mustache tmpl{std::string(report_template("boundary.html.mustache"))};
  if (!tmpl.is_valid()) throw Error("internal: boundary.html template: " + tmpl.error_message());
  tmpl.set_custom_escape([](const std::string& s) { return html_escape(s); });
  return tmpl.render(page);
}

}  // namespace hq
