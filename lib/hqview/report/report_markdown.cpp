#include "hqview/report/report_markdown.h"

#include "hqview/report/link_base.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "hqview/analysis/limitations.h"
#include "hqview/core/number_format.h"
#include "hqview/report/compare_table.h"
#include "hqview/report/escape.h"
#include "hqview/views/views.h"

namespace hq {
namespace {

// Display text, as on the HTML pages.
std::string show(double v) { return display_number(v); }

// A bundle path HQView made itself (views/<id>.png): letters, digits and
// _ . / - only, never .. or absolute, so it is safe as a link destination.
bool is_plain_relative_path(const std::string& path) {
  if (path.empty() || path.front() == '/' || path.find("..") != std::string::npos) return false;
  for (char c : path)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '/' || c == '-')) return false;
  return true;
}

// The views summary.md links, one file each (the first PNG), in kViews'
// summary order.
std::vector<std::string_view> summary_view_ids() {
  std::vector<const ViewSpec*> specs;
  for (const ViewSpec& spec : kViews)
    if (spec.summary_order >= 0) specs.push_back(&spec);
  std::sort(specs.begin(), specs.end(),
            [](const ViewSpec* a, const ViewSpec* b) { return a->summary_order < b->summary_order; });
  std::vector<std::string_view> ids;
  for (const ViewSpec* spec : specs) ids.push_back(spec->id);
  return ids;
}

}  // namespace

std::string summary_markdown(const ReportModel& model, const std::string& link_base) {
  const MeshSummary& m = model.analysis.mesh_summary;
  const QualitySummary& q = model.analysis.quality;
  const std::string name = std::filesystem::path(model.analysis.mesh_input.path).filename().string();
  std::string md;
  md += "## HQView: " + markdown_escape(name) + "\n\n";

  // The papers' headline row.
  // A surface mesh (quads, triangles) counts its cells.
  const CellComposition& composition = model.analysis.composition;
  // A curved surface's inverted cells are its reversed faces (orientation
  // flipped against their neighbours; their corners signed against the
  // neighbours' orientation); "intersecting faces" as the page and views.
  const bool curved = is_curved_surface(m);
  std::string header = curved ? "| #V | #cells | min scaled Jacobian (per cell, signed against the neighbours) | mean scaled Jacobian (per cell) | "
                                "#reversed faces | intersecting faces |"
                       : m.is_surface ? "| #V | #cells | min scaled Jacobian (per cell) | mean scaled Jacobian (per cell) | "
                                      "#inverted | intersecting faces |"
                                    : "| #V | #H | min scaled Jacobian (per hex) | mean scaled Jacobian (per hex) | "
                                      "#inverted | intersecting hexes |";
  std::string align = "|---:|---:|---:|---:|---:|---:|";
  std::string row = "| " + std::to_string(m.num_vertices) + " | " +
                    std::to_string(m.is_surface ? composition.num_cells : m.num_hexes) + " | " +
                    show(q.scaled_jacobian.min) + " | " + show(q.scaled_jacobian.mean) + " | " +
                    std::to_string(m.is_surface ? q.num_inverted : q.scaled_jacobian.num_inverted) + " | " +
                    (model.analysis.overlap ? std::to_string(model.analysis.overlap->num_intersecting_cells)
                                            : std::string("not checked")) +
                    " |";
  if (model.analysis.boundary_error) {
    // The sampled symmetric Hausdorff (over the surfaces, both ways), named.
    const BoundaryError& e = *model.analysis.boundary_error;
    header += " Hausdorff, sampled symmetric (% of bbox diagonal) |";
    align += "---:|";
    row += " " + show(e.reference_bbox_diagonal > 0 ? 100.0 * e.sampled_symmetric / e.reference_bbox_diagonal : 0.0) +
           " % |";
  }
  md += header + "\n" + align + "\n" + row + "\n\n";
  // A hybrid mesh: its cells by kind, the hex fractions and the inverted
  // cells of every kind (#inverted above counts the scaled Jacobian <= 0).
  if (m.is_surface) {
    md += "Surface mesh: " + std::to_string(composition.num_quads) + " quads, " +
          std::to_string(composition.num_triangles) + " triangles; " +
          (m.planarity && m.planarity->is_planar ? "planar" : "not planar") + " (planarity " +
          show(m.planarity ? m.planarity->planarity : 0.0) + ")" +
          (curved ? std::string("; reversed faces ") + std::to_string(q.num_inverted) +
                        " (orientation flipped against their neighbours: on a curved surface the inverted count; "
                        "their corners, measured against the orientation their neighbours agree on, are negative)"
                  : "; inverted cells " + std::to_string(q.num_inverted)) +
          "; boundary edges " + std::to_string(m.num_boundary_edges) + ", non-manifold edges " +
          std::to_string(m.num_non_manifold_edges) +
          (curved ? std::string() : ", reversed faces " + std::to_string(m.num_reversed_faces)) + "\n\n";
  } else if (const CellComposition& c = composition; c.num_cells > c.count[0]) {
    md += "Cells: " + std::to_string(c.num_cells) + " (hex " + std::to_string(c.count[0]) + ", tet " +
          std::to_string(c.count[1]) + ", wedge " + std::to_string(c.count[2]) + ", pyramid " +
          std::to_string(c.count[3]) + "); hex fraction " + (c.hex_fraction ? show(*c.hex_fraction) : "-") +
          " by count, " + (c.hex_volume_fraction ? show(*c.hex_volume_fraction) : "-") + " by volume; inverted cells " +
          std::to_string(q.num_inverted) + "\n\n";
  }
  if (q.scaled_jacobian.num_degenerate > 0)
    md += "Degenerate hexes (Verdict's 1e30): " + std::to_string(q.scaled_jacobian.num_degenerate) + "\n\n";
  if (model.analysis.glyphs)
    md += "Glyphs: " + std::to_string(model.analysis.glyphs->num_glyphs) + " bad vertices in " +
          std::to_string(model.analysis.glyphs->clusters.size()) +
          (model.analysis.glyphs->clusters.size() == 1 ? " cluster" : " clusters") + "; min vertex quality " +
          show(q.vertex_quality.min) + ".\n\n";

  if (model.analysis.compare) {
    const CompareTable t = compare_table(model.analysis);
    md += "### Compared with " + markdown_escape(t.theirs_name) + "\n\n";
    md += "| | " + markdown_escape(t.mine_name) + " | " + markdown_escape(t.theirs_name) +
          " | difference |\n|---|---:|---:|---:|\n";
    for (const CompareTableRow& r : t.rows)
      md += "| " + r.label + " | " + r.mine + " | " + r.theirs + " | " +
            (r.is_worse ? "**" + r.difference + "**" : r.difference) + " |\n";
    md += "\nDifference = right - left (bold: the right mesh is worse); each mesh in its own units";
    if (!t.alignment.empty()) md += "; the compare view's right mesh: " + markdown_escape(t.alignment);
    md += ".\n\n";
  }

  if (!model.gates.results.empty()) {
    md += std::string("### Gates: ") + (model.gates.passed ? "passed" : "**failed**") + "\n\n";
    md += "| rule | value | result |\n|---|---:|---|\n";
    for (const GateResult& g : model.gates.results)
      md += "| " + markdown_escape(g.rule) + " | " + show(g.value) + " | " + (g.passed ? "pass" : "**fail**") + " |\n";
    md += "\n";
  }

  // Input warnings apart from what HQView does not do yet (limitations.h).
  const auto is_input_warning = [](const std::string& w) { return !is_limitation_warning(w); };
  if (std::any_of(model.analysis.warnings.begin(), model.analysis.warnings.end(), is_input_warning)) {
    md += "### Warnings\n\n";
    for (const std::string& w : model.analysis.warnings)
      if (is_input_warning(w)) md += "- " + markdown_escape(w) + "\n";
    md += "\n";
  }
  if (std::any_of(model.analysis.warnings.begin(), model.analysis.warnings.end(), is_limitation_warning)) {
    md += "### Limitations of this analysis\n\n";
    for (const std::string& w : model.analysis.warnings)
      if (is_limitation_warning(w)) md += "- " + markdown_escape(w) + "\n";
    md += "\n";
  }
  if (!model.analysis.notes.empty()) {
    md += "### Notes\n\n";
    for (const std::string& w : model.analysis.notes) md += "- " + markdown_escape(w) + "\n";
    md += "\n";
  }

  std::string views;
  for (const std::string_view id : summary_view_ids())
    for (const ViewEntry& v : model.views) {
      if (v.id != id) continue;
      for (const std::string& f : v.files)
        if (f.ends_with(".png") && is_plain_relative_path(f)) {
          // Published (--link-base): the key view inline, for a pull-request
          // comment or a CI job summary that shows no files.
          if (views.empty() && !link_base.empty()) views += "![" + markdown_escape(v.title) + "](" + f + ")\n\n";
          views += "- [" + markdown_escape(v.title) + "](" + f + ")\n";
          break;
        }
    }
  if (!views.empty()) md += "### Views\n\n" + views + "\n";

  md += "Pages: [index.html](index.html)";
  if (model.analysis.boundary_error) md += " · [boundary.html](boundary.html)";
  md += " · data: [report.json](report.json)";
  for (const DataFile& f : data_files(model.data)) {
    const std::string name = f.path.substr(f.path.find('/') + 1);
    md += " · [" + name + "](" + f.path + ")";
  }
  md += "\n\n";
  md += "HQView " + markdown_escape(model.tool_version) + " · " + markdown_escape(model.analysis.mesh_input.format) +
        " · sha256 " + markdown_escape(model.analysis.mesh_input.sha256.substr(0, 12));
  if (model.analysis.reference_input)
    md += " · reference " +
          markdown_escape(std::filesystem::path(model.analysis.reference_input->path).filename().string());
  md += "\n";
  return absolute_links_markdown(md, link_base);
}

}  // namespace hq
