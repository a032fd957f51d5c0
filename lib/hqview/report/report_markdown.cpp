#include "hqview/report/report_markdown.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace hq {
namespace {

// Display text: 6 significant digits, like the HTML pages.
std::string show(double v) {
  if (!std::isfinite(v)) return "–";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// A bundle path HQView made itself (views/<id>.png): letters, digits and
// _ . / - only, never .. or absolute, so it is safe as a link destination.
bool is_plain_relative_path(const std::string& path) {
  if (path.empty() || path.front() == '/' || path.find("..") != std::string::npos) return false;
  for (char c : path)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '/' || c == '-')) return false;
  return true;
}

// The views summary.md links, one file each (the first PNG), in this order.
constexpr const char* kKeyViews[] = {
    "main",          "sorted_quality",    "clusters", "local",          "corners",
    "histogram",     "reference_overlay", "compare",  "boundary_error", "boundary_error_sorted",
    "boundary_area", "uv_error"};

}  // namespace

std::string markdown_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (u < 0x20 || u == 0x7f)
      out += ' ';
    else if (u < 0x80 && std::ispunct(u)) {
      out += '\\';
      out += c;
    } else {
      out += c;
    }
  }
  return out;
}

std::string summary_markdown(const ReportModel& model) {
  const MeshSummary& m = model.mesh_summary;
  const QualitySummary& q = model.quality;
  const std::string name = std::filesystem::path(model.mesh_input.path).filename().string();
  std::string md;
  md += "## HQView: " + markdown_escape(name) + "\n\n";

  // The papers' headline row.
  std::string header = "| #V | #H | min scaled Jacobian | mean scaled Jacobian | #inverted | overlapping hexes |";
  std::string align = "|---:|---:|---:|---:|---:|---:|";
  std::string row =
      "| " + std::to_string(m.num_vertices) + " | " + std::to_string(m.num_hexes) + " | " +
      show(q.scaled_jacobian.min) + " | " + show(q.scaled_jacobian.mean) + " | " +
      std::to_string(q.scaled_jacobian.num_inverted) + " | " +
      (model.overlap ? std::to_string(model.overlap->num_intersecting_cells) : std::string("not checked")) + " |";
  if (model.boundary_error) {
    header += " Hausdorff (% of bbox diagonal) |";
    align += "---:|";
    row += " " + show(100.0 * model.boundary_error->hausdorff_relative) + " % |";
  }
  md += header + "\n" + align + "\n" + row + "\n\n";
  if (q.scaled_jacobian.num_degenerate > 0)
    md += "Degenerate hexes (Verdict's 1e30): " + std::to_string(q.scaled_jacobian.num_degenerate) + "\n\n";
  if (model.glyphs)
    md += "Glyphs: " + std::to_string(model.glyphs->num_glyphs) + " bad vertices in " +
          std::to_string(model.glyphs->clusters.size()) +
          (model.glyphs->clusters.size() == 1 ? " cluster" : " clusters") + "; min vertex quality " +
          show(q.vertex_quality.min) + ".\n\n";

  if (!model.gates.results.empty()) {
    md += std::string("### Gates: ") + (model.gates.passed ? "passed" : "**failed**") + "\n\n";
    md += "| rule | value | result |\n|---|---:|---|\n";
    for (const GateResult& g : model.gates.results)
      md += "| " + markdown_escape(g.rule) + " | " + show(g.value) + " | " + (g.passed ? "pass" : "**fail**") + " |\n";
    md += "\n";
  }

  if (!model.warnings.empty()) {
    md += "### Warnings\n\n";
    for (const std::string& w : model.warnings) md += "- " + markdown_escape(w) + "\n";
    md += "\n";
  }

  std::string views;
  for (const char* id : kKeyViews)
    for (const ViewEntry& v : model.views) {
      if (v.id != id) continue;
      for (const std::string& f : v.files)
        if (f.ends_with(".png") && is_plain_relative_path(f)) {
          views += "- [" + markdown_escape(v.title) + "](" + f + ")\n";
          break;
        }
    }
  if (!views.empty()) md += "### Views\n\n" + views + "\n";

  md += "Pages: [index.html](index.html)";
  if (model.boundary_error) md += " · [boundary.html](boundary.html)";
  md += " · data: [report.json](report.json) · [cells.csv](data/cells.csv) · [vertices.csv](data/vertices.csv)";
  if (model.has_annotated_vtu) md += " · [annotated.vtu](data/annotated.vtu)";
  md += "\n\n";
  md += "HQView " + markdown_escape(model.tool_version) + " · " + markdown_escape(model.mesh_input.format) +
        " · sha256 " + markdown_escape(model.mesh_input.sha256.substr(0, 12));
  if (model.reference_input)
    md += " · reference " + markdown_escape(std::filesystem::path(model.reference_input->path).filename().string());
  md += "\n";
  return md;
}

}  // namespace hq
