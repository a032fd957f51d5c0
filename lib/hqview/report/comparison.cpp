#include "hqview/report/comparison.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <span>

#include "hqview/chart/chart.h"
#include "hqview/core/error.h"
#include "hqview/core/message_text.h"
#include "hqview/core/number_format.h"
#include "hqview/core/text.h"
#include "hqview/report/escape.h"

namespace hq {
namespace {


bool is_analysed(const BatchEntry& e) { return e.status == BatchStatus::ok || e.status == BatchStatus::gate_failed; }

bool needs_reference(std::string_view key) { return key.starts_with("boundary_error."); }

}  // namespace

std::optional<double> comparison_value(const BatchEntry& e, std::string_view key) {
  if (!key.starts_with("surface.")) return e.headline[headline_slot(key)];
  if (!e.surface) return std::nullopt;
  if (key == "surface.num_quads") return e.surface->quads;
  if (key == "surface.num_triangles") return e.surface->triangles;
  if (key == "surface.num_irregular_vertices_interior") return e.surface->irregular_interior;
  if (key == "surface.num_irregular_vertices_boundary") return e.surface->irregular_boundary;
  throw Error("internal: no surface count " + std::string(key));
}

namespace {

std::vector<const BatchEntry*> pointers(const std::vector<BatchEntry>& entries) {
  std::vector<const BatchEntry*> p;
  for (const BatchEntry& e : entries) p.push_back(&e);
  return p;
}

bool is_surface_group(const std::vector<const BatchEntry*>& entries) {
  return std::any_of(entries.begin(), entries.end(), [](const BatchEntry* e) { return e->surface.has_value(); }) &&
         std::none_of(entries.begin(), entries.end(),
                      [](const BatchEntry* e) { return !e->surface && e->status != BatchStatus::failed; });
}

std::vector<ComparisonKey> default_keys(const std::vector<const BatchEntry*>& entries) {
  const auto some_row_has = [&](std::string_view key) {
    return std::any_of(entries.begin(), entries.end(), [&](const BatchEntry* e) {
      const std::optional<double> v = comparison_value(*e, key);
      return v.has_value() && (!key.starts_with("surface.") || *v > 0);
    });
  };
  // In table order; "?": only when some row has it (the singular edges, the
  // finite-element errors, a surface's triangles and irregular vertices).
  static constexpr std::string_view kVolume[] = {"mesh.num_vertices",
                                                  "mesh.num_hexes",
                                                  "quality.scaled_jacobian.min",
                                                  "quality.scaled_jacobian.mean",
                                                  "quality.num_inverted",
                                                  "boundary_error.hausdorff.relative",
                                                  "?structure.num_singular_edges_interior",
                                                  "?fem.poisson.mean.l2_error",
                                                  "?fem.poisson.mean.h1_error"};
  static constexpr std::string_view kSurface[] = {"mesh.num_vertices",
                                                   "surface.num_quads",
                                                   "?surface.num_triangles",
                                                   "quality.scaled_jacobian.min",
                                                   "quality.scaled_jacobian.mean",
                                                   "quality.num_inverted",
                                                   "boundary_error.hausdorff.relative",
                                                   "?surface.num_irregular_vertices_interior"};
  std::vector<ComparisonKey> keys;
  for (std::string_view name : is_surface_group(entries) ? std::span<const std::string_view>(kSurface)
                                                         : std::span<const std::string_view>(kVolume)) {
    const bool optional = name.starts_with('?');
    if (optional) name.remove_prefix(1);
    if (optional && !some_row_has(name)) continue;
    keys.push_back(*std::find_if(comparison_keys().begin(), comparison_keys().end(),
                                 [&](const ComparisonKey& k) { return k.key == name; }));
  }
  return keys;
}

Comparison build(const std::vector<const BatchEntry*>& entries, std::vector<ComparisonKey> keys);

std::optional<double> median_of(std::vector<double> v) {
  if (v.empty()) return std::nullopt;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string csv_field(std::string_view input) {
  const std::string text = message_text(input);  // no line break or raw byte from input (docs/contract.md)
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string method_heading(const MethodColumn& m) { return m.paper.year.empty() ? m.label : m.label + " (" + m.paper.year + ")"; }

std::string show_mean(const std::optional<double>& v) { return v ? display_number(*v) : "–"; }

}  // namespace

std::string column_heading(const ComparisonColumn& c) {
  return (c.year.empty() ? c.label : c.label + " (" + c.year + ")") + (c.variant.empty() ? "" : " · " + c.variant);
}

const std::vector<ComparisonKey>& comparison_keys() {
  static const std::vector<ComparisonKey> keys{
      {"mesh.num_vertices", "#V", 0},
      {"mesh.num_hexes", "#H", 0},
      {"quality.scaled_jacobian.min", "min SJ", +1},
      {"quality.scaled_jacobian.mean", "mean SJ", +1},
      {"quality.scaled_jacobian.p05", "p05 SJ", +1},
      {"quality.num_inverted", "#inverted", -1},
      {"overlap.num_intersecting_cells", "#intersecting", -1},
      {"boundary_error.hausdorff.relative", "Hausdorff (rel.)", -1},
      {"structure.num_singular_edges_interior", "#singular interior edges", -1},
      {"structure.num_singular_edges_boundary", "#singular boundary edges", -1},
      {"fem.element.num_invalid", "#invalid Q1 elements (Gauss det J \u2264 0)", -1},
      {"fem.element.num_not_invertible", "#non-invertible maps (corner det J \u2264 0)", -1},
      {"fem.poisson.mean.l2_error", "FEM L2 error (rel.)", -1},
      {"fem.poisson.mean.h1_error", "FEM H1 error (rel., semi-norm)", -1},
      {"fem.poisson.scaled_matrix.condition", "FEM cond. (Jacobi)", -1},
      {"headline.num_cells", "#cells", 0},
      {"headline.num_cells_by_kind.tet", "#tet", 0},
      {"headline.num_cells_by_kind.wedge", "#wedge", 0},
      {"headline.num_cells_by_kind.pyramid", "#pyramid", 0},
      {"headline.hex_fraction", "hex fraction", +1},
      {"headline.hex_volume_fraction", "hex fraction (volume)", +1},
      // A surface mesh's counts (index.json meshes[].surface; issue 47).
      {"surface.num_quads", "#quads", 0},
      {"surface.num_triangles", "#triangles", 0},
      {"surface.num_irregular_vertices_interior", "#irregular interior vertices", -1},
      {"surface.num_irregular_vertices_boundary", "#irregular boundary vertices", -1},
  };
  return keys;
}

std::vector<ComparisonKey> default_comparison_keys(const std::vector<BatchEntry>& entries) {
  return default_keys(pointers(entries));
}

std::vector<ComparisonKey> parse_comparison_keys(std::string_view list) {
  std::vector<ComparisonKey> keys;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    const std::string_view name = trim(list.substr(start, end - start), " \t");
    start = end + 1;
    if (name.empty()) continue;
    const auto it = std::find_if(comparison_keys().begin(), comparison_keys().end(),
                                 [&](const ComparisonKey& k) { return k.key == name; });
    if (it == comparison_keys().end()) {
      std::string known;
      for (const ComparisonKey& k : comparison_keys()) known += (known.empty() ? "" : ", ") + std::string(k.key);
      throw ValueError("--compare-keys: unknown key '" + std::string(name) + "' (known: " + known + ")");
    }
    keys.push_back(*it);
  }
  if (keys.empty()) throw ValueError("--compare-keys: no key given");
  return keys;
}

bool has_comparison(const std::vector<BatchEntry>& entries) {
  return std::any_of(entries.begin(), entries.end(),
                     [](const BatchEntry& e) { return !e.label.empty() && e.status != BatchStatus::skipped; });
}

namespace {

Comparison build(const std::vector<const BatchEntry*>& entries, std::vector<ComparisonKey> keys) {
  Comparison c;
  c.chart_file = kComparisonChartFile;
  c.entries = entries;
  c.keys = std::move(keys);
  std::map<std::string, MethodColumn> methods;
  std::map<std::string, std::set<std::string>> models_of;
  std::map<std::string, ComparisonRow> rows;
  std::set<std::pair<std::string, std::string>> columns;
  for (const BatchEntry* entry : entries) {  // sorted by path: fixed order
    const BatchEntry& e = *entry;
    if (e.status == BatchStatus::skipped) continue;
    MethodColumn& m = methods[e.label];
    m.label = e.label;
    if (m.paper.empty()) m.paper = e.paper;
    ++m.num_meshes;
    models_of[e.label].insert(e.model);
    if (e.status == BatchStatus::failed) ++m.num_failed;
    if (is_analysed(e) && comparison_value(e, "quality.scaled_jacobian.min").value_or(-1.0) > 0.0) ++m.num_valid;
    ComparisonRow& row = rows[e.model];
    row.model = e.model;
    columns.insert({e.label, e.variant});
    // Two meshes of one model, variant and method (possible only through a
    // manifest): the first by path keeps the cell, the index lists both.
    row.cells.emplace(std::pair{e.label, e.variant}, &e);
  }
  for (auto& [label, m] : methods) {
    m.num_models = static_cast<int>(models_of[label].size());
    for (const ComparisonKey& k : c.keys) {
      std::vector<double> values;
      for (const BatchEntry* e : entries)
        if (e->label == label && is_analysed(*e))
          if (const auto v = comparison_value(*e, k.key); v && std::isfinite(*v)) values.push_back(*v);
      double sum = 0.0;
      for (double v : values) sum += v;
      m.mean.push_back(values.empty() ? std::nullopt : std::optional<double>(sum / static_cast<double>(values.size())));
      m.median.push_back(median_of(values));
    }
    c.methods.push_back(m);
  }
  for (auto& [key, row] : rows) c.rows.push_back(std::move(row));
  for (const auto& [label, variant] : columns) c.columns.push_back({label, variant, methods[label].paper.year});
  return c;
}

}  // namespace

Comparison build_comparison(const std::vector<BatchEntry>& entries, std::vector<ComparisonKey> keys) {
  return build(pointers(entries), std::move(keys));
}

std::vector<Comparison> comparison_groups(const std::vector<BatchEntry>& entries,
                                          const std::vector<ComparisonKey>* keys) {
  std::set<std::string> surface_models;
  for (const BatchEntry& e : entries)
    if (e.surface) surface_models.insert(e.model);
  std::vector<const BatchEntry*> volume, surface;
  for (const BatchEntry& e : entries)
    (e.surface || (e.status == BatchStatus::failed && surface_models.count(e.model)) ? surface : volume).push_back(&e);
  const auto live = [](const std::vector<const BatchEntry*>& group) {
    return std::any_of(group.begin(), group.end(), [](const BatchEntry* e) { return e->status != BatchStatus::skipped; });
  };
  std::vector<Comparison> groups;
  const bool both = live(volume) && live(surface);
  for (const auto* group : {&volume, &surface}) {
    if (!live(*group)) continue;
    Comparison c = build(*group, keys ? *keys : default_keys(*group));
    if (both) {
      c.group = group == &volume ? "volume meshes" : "surface meshes";
      if (group == &surface) c.chart_file = kComparisonSurfaceChartFile;
    }
    groups.push_back(std::move(c));
  }
  return groups;
}

std::vector<ComparisonCell> comparison_cells(const Comparison& c, const ComparisonRow& row, std::size_t k) {
  const ComparisonKey& key = c.keys[k];
  std::vector<ComparisonCell> cells;
  for (const ComparisonColumn& column : c.columns) {
    ComparisonCell cell;
    const auto it = row.cells.find({column.label, column.variant});
    if (it == row.cells.end()) {
      cell.text = "–";
    } else {
      cell.entry = it->second;
      if (cell.entry->status == BatchStatus::failed) {
        cell.text = "failed";
      } else if (const auto v = comparison_value(*cell.entry, key.key); v && std::isfinite(*v)) {
        cell.value = v;
        cell.text = display_number(*v);
      } else {
        cell.text = needs_reference(key.key) ? "no ref." : "n/a";
      }
    }
    cells.push_back(std::move(cell));
  }
  // Bold: the best of two or more values; values that read the same as the
  // best (equal as shown, e.g. a mesh and its scaled copy) are bold too.
  if (key.direction != 0 && std::count_if(cells.begin(), cells.end(), [](const ComparisonCell& x) { return x.value; }) > 1) {
    std::optional<double> best;
    for (const ComparisonCell& x : cells)
      if (x.value && (!best || (key.direction > 0 ? *x.value > *best : *x.value < *best))) best = x.value;
    const std::string shown = display_number(*best);
    for (ComparisonCell& x : cells) x.is_best = x.value && x.text == shown;
  }
  return cells;
}

std::string comparison_csv(const std::vector<BatchEntry>& entries) {
  std::string out = "model,variant,method,mesh,status";
  for (std::size_t k = 0; k < kNumHeadlineKeys; ++k) out += std::string(",") + kHeadlineKeys[k];
  out += '\n';
  for (const BatchEntry& e : entries) {
    if (e.status == BatchStatus::skipped) continue;
    out += csv_field(e.model) + ',' + csv_field(e.variant) + ',' + csv_field(e.label) + ',' + csv_field(e.path) + ',' +
           std::string(to_string(e.status));
    for (std::size_t k = 0; k < kNumHeadlineKeys; ++k) {
      out += ',';
      if (e.headline[k] && std::isfinite(*e.headline[k])) out += format_double(*e.headline[k]);
    }
    out += '\n';
  }
  return out;
}

std::string group_heading(const Comparison& c) {
  std::string s = c.group;
  if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = static_cast<char>(s[0] - 'a' + 'A');
  return s;
}

std::string comparison_chart_svg(const Comparison& c) {
  std::map<std::string, std::vector<double>> by_method;
  for (const BatchEntry* e : c.entries) {
    if (e->status == BatchStatus::skipped || e->label.empty()) continue;
    std::vector<double>& v = by_method[e->label];
    if (const auto x = comparison_value(*e, "quality.scaled_jacobian.min"); x && is_analysed(*e)) v.push_back(*x);
  }
  std::vector<std::string> methods;
  std::vector<std::vector<double>> values;
  for (auto& [label, v] : by_method) {
    methods.push_back(label);
    values.push_back(std::move(v));
  }
  // Wide enough for the title (a group's is longer).
  const int width = std::clamp(160 + 110 * static_cast<int>(methods.size()), c.group.empty() ? 480 : 640, 1600);
  const std::string title = std::string("Min scaled Jacobian per mesh, by method") +
                            (c.group.empty() ? "" : " (" + c.group + ")");
  return chart_svg(method_distribution_chart(methods, values, {width, 420, title}));
}

namespace {

// One group's part of comparison.md; `h` its tables' heading ("##", or
// "###" under a group heading).
std::string group_markdown(const Comparison& c, const std::string& h) {
  std::string md = c.group.empty() ? "" : "\n## " + group_heading(c) + "\n\n";
  md += std::to_string(c.rows.size()) + " models × " + std::to_string(c.methods.size()) + " methods (" +
        std::to_string(c.columns.size()) +
        " columns: one per method and variant). Bold: the best of a row; – no mesh; failed: the mesh failed; no "
        "ref.: analysed without a reference.\n\n![min scaled Jacobian per mesh, by method](" + c.chart_file + ")\n";
  for (std::size_t k = 0; k < c.keys.size(); ++k) {
    md += "\n" + h + " " + std::string(c.keys[k].title) + " (`" + std::string(c.keys[k].key) + "`" +
          (c.keys[k].direction > 0 ? ", higher is better" : c.keys[k].direction < 0 ? ", lower is better" : "") +
          ")\n\n| model |";
    for (const ComparisonColumn& column : c.columns) md += " " + markdown_escape(column_heading(column)) + " |";
    md += "\n|---|";
    for (std::size_t i = 0; i < c.columns.size(); ++i) md += "--:|";
    md += "\n";
    for (const ComparisonRow& row : c.rows) {
      md += "| " + markdown_escape(row.model) + " |";
      for (const ComparisonCell& cell : comparison_cells(c, row, k))
        md += " " + (cell.is_best ? "**" + cell.text + "**" : cell.text) + " |";
      md += "\n";
    }
  }
  md += "\n" + h + " Per method\n\n| method | meshes | models | valid (min SJ > 0) | failed |";
  for (const ComparisonKey& k : c.keys) md += " mean / median " + std::string(k.title) + " |";
  md += "\n|---|--:|--:|--:|--:|";
  for (std::size_t i = 0; i < c.keys.size(); ++i) md += "--:|";
  md += "\n";
  for (const MethodColumn& m : c.methods) {
    md += "| " + markdown_escape(method_heading(m)) + " | " + std::to_string(m.num_meshes) + " | " +
          std::to_string(m.num_models) + " | " + std::to_string(m.num_valid) + " | " + std::to_string(m.num_failed) + " |";
    for (std::size_t k = 0; k < c.keys.size(); ++k) md += " " + show_mean(m.mean[k]) + " / " + show_mean(m.median[k]) + " |";
    md += "\n";
  }
  bool any_paper = false;
  for (const MethodColumn& m : c.methods) {
    if (m.paper.empty()) continue;
    if (!any_paper) md += "\n" + h + " Papers\n\n";
    any_paper = true;
    md += "- " + markdown_escape(m.label) + ": " + markdown_escape(m.paper.title) +
          (m.paper.year.empty() ? "" : " (" + markdown_escape(m.paper.year) + ")") +
          (m.paper.doi.empty() ? "" : ", doi:" + markdown_escape(m.paper.doi)) + "\n";
  }
  return md;
}

}  // namespace

std::string comparison_markdown(const std::vector<Comparison>& groups) {
  std::string md = "# Methods compared\n";
  for (const Comparison& c : groups) md += (c.group.empty() ? "\n" : "") + group_markdown(c, c.group.empty() ? "##" : "###");
  return md;
}

std::string comparison_latex(const std::vector<Comparison>& groups) {
  std::string tex =
      "% HQView: methods compared (one table per key). Needs \\usepackage{booktabs};\n"
      "% UTF-8 input (model and method names are written as they are, TeX specials escaped).\n";
  auto cell_tex = [](const ComparisonCell& cell) {
    if (cell.text == "–") return std::string("--");
    const std::string text = latex_escape(cell.text);
    return cell.is_best ? "\\textbf{" + text + "}" : text;
  };
  for (const Comparison& c : groups) {
    for (std::size_t k = 0; k < c.keys.size(); ++k) {
      tex += "\n\\begin{table}\n\\centering\n\\caption{" +
             (c.group.empty() ? std::string() : latex_escape(group_heading(c)) + ": ") +
             latex_escape(c.keys[k].title) + " (" + latex_escape(c.keys[k].key) +
             (c.keys[k].direction > 0 ? "; higher is better" : c.keys[k].direction < 0 ? "; lower is better" : "") +
             ")}\n\\begin{tabular}{l" + std::string(c.columns.size(), 'r') + "}\n\\toprule\nmodel";
      for (const ComparisonColumn& column : c.columns) tex += " & " + latex_escape(column_heading(column));
      tex += " \\\\\n\\midrule\n";
      for (const ComparisonRow& row : c.rows) {
        tex += latex_escape(row.model);
        for (const ComparisonCell& cell : comparison_cells(c, row, k)) tex += " & " + cell_tex(cell);
        tex += " \\\\\n";
      }
      tex += "\\bottomrule\n\\end{tabular}\n\\end{table}\n";
    }
  }
  return tex;
}

}  // namespace hq
