#include "hqview/report/batch_index.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <kainjow/mustache.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "hqview/analysis/limitations.h"
#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/core/fault_point.h"
#include "hqview/report/atomic_file.h"
#include "hqview/report/junit.h"
#include "hqview/report/link_base.h"
#include "hqview/report/collection_correlation.h"
#include "hqview/report/comparison.h"
#include "hqview/report/escape.h"
#include "hqview/report/json_path.h"
#include "hqview/report/report_templates.h"
#include "hqview/report/single_file.h"

namespace hq {
namespace fs = std::filesystem;
using nlohmann::json;

std::size_t headline_slot(std::string_view key) {
  for (std::size_t k = 0; k < kNumHeadlineKeys; ++k)
    if (key == kHeadlineKeys[k]) return k;
  throw Error("internal: no headline key " + std::string(key));
}

namespace {

constexpr int kIndexSchemaVersion = 1;

// "1 file", "5 files".
std::string count_files(std::size_t n) { return std::to_string(n) + (n == 1 ? " file" : " files"); }

// Column titles of the headline keys (kHeadlineKeys order).
constexpr const char* kHeadlineTitles[] = {"#V",        "#H",        "min SJ",           "mean SJ",
                                           "p05 SJ",    "#inverted", "#intersecting",    "Hausdorff (rel.)",
                                           "#singular interior edges", "#singular boundary edges",
                                           "#invalid Q1 elements (Gauss det J \u2264 0)",
                                           "#non-invertible maps (corner det J \u2264 0)", "FEM L2 error (rel.)",
                                           "FEM H1 error (rel., semi-norm)",
                                           "FEM cond. (Jacobi)", "#cells", "#tet", "#wedge", "#pyramid",
                                           "hex fraction", "hex fraction (volume)"};
static_assert(std::size(kHeadlineTitles) == kNumHeadlineKeys);

std::string show(std::optional<double> v) { return v ? display_number(*v) : "–"; }


// The thumbnail's URL from the batch index.
std::string row_thumbnail(const BatchEntry& e) {
  return !e.bundle.empty() && !e.thumbnail.empty() ? url_path(e.bundle) + "/" + url_path(e.thumbnail) : "";
}

// What the lightbox opens: the overview (1600 x 1200, with its legend),
// else the thumbnail.
std::string lightbox_url(const BatchEntry& e) {
  return !e.bundle.empty() && !e.overview.empty() ? url_path(e.bundle) + "/" + url_path(e.overview) : row_thumbnail(e);
}

// A warning as the batch index shows it: the mesh's path as the batch
// names it (relative to the batch input) in place of the absolute path the
// reader wrote ("/work/data/meshes/a.vtk: 68 cells ..." -> "meshes/a.vtk: 68 cells ...").
std::string relative_warning(const std::string& warning, const std::string& path) {
  const std::string key = "/" + path + ":";
  const std::size_t at = warning.find(key);
  if (path.empty() || at == std::string::npos || warning.find(':') < at) return warning;
  return warning.substr(at + 1);
}


// Text for a table cell that may break only after '_', '/', '.', '-' or a
// space (issue 45, the 45t review: overflow-wrap anywhere broke "rockar|m",
// "padde|d" and "mi|n>=0.2"): html_escape'd, with <wbr> after each of
// those, so a long name wraps where its words meet.
std::string html_with_breaks(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    std::size_t j = text.find_first_of("_/.-", i);
    j = j == std::string_view::npos ? text.size() : j + 1;
    out += html_escape(text.substr(i, j - i));
    if (j < text.size()) out += "<wbr>";
    i = j;
  }
  return out;
}

json number_or_null(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  // Counts stay integers in the JSON.
  if (*v == std::floor(*v) && std::abs(*v) < 9e15) return static_cast<long long>(*v);
  return *v;
}

BatchStatus status_from(const std::string& s, const std::string& name) {
  if (s == "ok") return BatchStatus::ok;
  if (s == "gate_failed") return BatchStatus::gate_failed;
  if (s == "failed") return BatchStatus::failed;
  if (s == "skipped") return BatchStatus::skipped;
  throw InputError(name + ": unknown mesh status '" + s + "'");
}

constexpr double kNaNValue = std::numeric_limits<double>::quiet_NaN();

double number_or_nan(const json& v) { return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN(); }

bool has_fem_metrics(const std::vector<BatchEntry>& entries) {
  return std::any_of(entries.begin(), entries.end(), [](const BatchEntry& e) { return !e.metrics.empty(); });
}

// index.json `fem_correlation` (collection_correlation.h).
json correlation_json(const CollectionCorrelation& c) {
  json rows = json::array();
  for (const CollectionCorrelationRow& r : c.rows)
    rows.push_back({{"metric", r.metric},
                    {"stat", r.stat},
                    {"direction", r.direction > 0 ? "higher is better" : r.direction < 0 ? "lower is better" : "none"},
                    {"rho_l2_error", number_or_null(r.rho_l2)},
                    {"p_l2_error", number_or_null(r.p_l2)},
                    {"rho_h1_error", number_or_null(r.rho_h1)},
                    {"p_h1_error", number_or_null(r.p_h1)},
                    {"q_l2_error", number_or_null(r.q_l2)},
                    {"q_h1_error", number_or_null(r.q_h1)},
                    {"num_meshes", r.num_meshes},
                    {"length_power", r.length_power},
                    {"restates", r.restates.empty() ? json(nullptr) : json(r.restates)},
                    {"rho_l2_error_given_h_over_l", number_or_null(r.rho_l2_given_h)},
                    {"rho_h1_error_given_h_over_l", number_or_null(r.rho_h1_given_h)}});
  json duplicates = json::array();
  for (const CollectionDuplicate& d : c.duplicates)
    duplicates.push_back({{"path", d.path},
                          {"same_as", d.same_as},
                          {"l2_error_difference", number_or_null(d.l2_difference)},
                          {"h1_error_difference", number_or_null(d.h1_difference)}});
  return {{"num_meshes", c.num_meshes},   {"min_meshes", c.min_meshes},
          {"metrics", std::move(rows)},   {"duplicates", std::move(duplicates)},
          {"min_p", number_or_null(c.min_p)}, {"critical_rho", number_or_null(c.critical_rho)},
          {"num_hypotheses_l2_error", c.num_hypotheses_l2}, {"num_hypotheses_h1_error", c.num_hypotheses_h1},
          {"inverted_left_out", c.inverted}};
}

bool has_labels(const std::vector<BatchEntry>& entries) {
  return std::any_of(entries.begin(), entries.end(), [](const BatchEntry& e) { return !e.label.empty(); });
}

}  // namespace

std::string_view to_string(BatchStatus status) {
  switch (status) {
    case BatchStatus::ok:
      return "ok";
    case BatchStatus::gate_failed:
      return "gate_failed";
    case BatchStatus::failed:
      return "failed";
    case BatchStatus::skipped:
      return "skipped";
  }
  return "failed";
}

void fill_entry_from_report(BatchEntry& entry, const ReportDocument& report) {
  entry.sha256 = report.at("input").at("mesh").at("sha256").get<std::string>();
  for (std::size_t k = 0; k < kNumHeadlineKeys; ++k) entry.headline[k] = json_number_at(report, kHeadlineKeys[k]);
  entry.metrics = metric_summaries_from_report(report);
  entry.failed_gates.clear();
  bool passed = true;
  if (report.contains("gates") && report["gates"].is_object()) {
    passed = report["gates"].value("passed", true);
    for (const ReportDocument& g : report["gates"].value("results", ReportDocument::array()))
      if (!g.value("passed", true)) entry.failed_gates.push_back(g.value("rule", ""));
  }
  entry.status = passed ? BatchStatus::ok : BatchStatus::gate_failed;
  entry.error.clear();
  entry.thumbnail.clear();
  entry.overview.clear();
  if (report.contains("views") && report["views"].is_array())
    for (const ReportDocument& v : report["views"]) {
      if (!v.contains("files") || !v["files"].is_array() || v["files"].empty() || !v["files"][0].is_string()) continue;
      if (v.value("id", "") == "thumbnail") entry.thumbnail = v["files"][0].get<std::string>();
      if (v.value("id", "") == "overview") entry.overview = v["files"][0].get<std::string>();
    }
  entry.warnings.clear();
  if (report.contains("warnings") && report["warnings"].is_array())
    for (const ReportDocument& w : report["warnings"])
      if (w.is_string()) entry.warnings.push_back(w.get<std::string>());
  entry.surface.reset();
  if (report.contains("mesh") && report["mesh"].is_object() && report["mesh"].value("dimension", "") == "surface") {
    SurfaceCounts counts;
    counts.quads = json_number_at(report, "headline.num_cells_by_kind.quad").value_or(0.0);
    counts.triangles = json_number_at(report, "headline.num_cells_by_kind.triangle").value_or(0.0);
    counts.irregular_interior = json_number_at(report, "structure.num_irregular_vertices_interior");
    counts.irregular_boundary = json_number_at(report, "structure.num_irregular_vertices_boundary");
    counts.planar = report["mesh"].value("planar", true);
    entry.surface = counts;
  }
}

std::vector<MethodSummary> summarize_methods(const std::vector<BatchEntry>& entries) {
  if (!has_labels(entries)) return {};
  std::map<std::string, MethodSummary> by_label;
  std::map<std::string, int> analysed;
  const std::size_t k_min = headline_slot("quality.scaled_jacobian.min");
  const std::size_t k_mean = headline_slot("quality.scaled_jacobian.mean");
  const std::size_t k_inv = headline_slot("quality.num_inverted");
  for (const BatchEntry& e : entries) {  // entries are sorted: fixed-order sums
    if (e.status == BatchStatus::skipped) continue;
    MethodSummary& m = by_label[e.label];
    m.label = e.label;
    ++m.num_meshes;
    if (e.status == BatchStatus::failed) {
      ++m.num_failed;
      continue;
    }
    if (e.status == BatchStatus::gate_failed) ++m.num_gate_failed;
    const double min_sj = e.headline[k_min].value_or(std::numeric_limits<double>::quiet_NaN());
    const double mean_sj = e.headline[k_mean].value_or(std::numeric_limits<double>::quiet_NaN());
    if (e.headline[k_inv].value_or(0) > 0) ++m.num_with_inverted;
    int& n = analysed[e.label];
    m.worst_min_scaled_jacobian = n == 0 ? min_sj : std::min(m.worst_min_scaled_jacobian, min_sj);
    m.mean_min_scaled_jacobian += min_sj;
    m.mean_mean_scaled_jacobian += mean_sj;
    ++n;
  }
  std::vector<MethodSummary> methods;
  for (auto& [label, m] : by_label) {
    const int n = analysed[label];
    if (n > 0) {
      m.mean_min_scaled_jacobian /= n;
      m.mean_mean_scaled_jacobian /= n;
    } else {
      m.mean_min_scaled_jacobian = m.mean_mean_scaled_jacobian = m.worst_min_scaled_jacobian =
          std::numeric_limits<double>::quiet_NaN();
    }
    methods.push_back(m);
  }
  return methods;
}

std::string batch_index_json(const std::vector<BatchEntry>& entries, const std::string& tool_version) {
  json j = json::object();
  j["schema_version"] = kIndexSchemaVersion;
  j["tool"] = {{"name", "hqview"}, {"version", tool_version}};
  int ok = 0, gate_failed = 0, failed = 0, skipped = 0;
  for (const BatchEntry& e : entries) {
    ok += e.status == BatchStatus::ok;
    gate_failed += e.status == BatchStatus::gate_failed;
    failed += e.status == BatchStatus::failed;
    skipped += e.status == BatchStatus::skipped;
  }
  j["counts"] = {{"meshes", entries.size() - static_cast<std::size_t>(skipped)},
                 {"ok", ok},
                 {"gate_failed", gate_failed},
                 {"failed", failed},
                 {"skipped", skipped}};
  json meshes = json::array();
  for (const BatchEntry& e : entries) {
    json m = json::object();
    m["path"] = e.path;
    m["label"] = e.label;
    m["model"] = e.model;
    m["variant"] = e.variant;
    m["paper"] = e.paper.empty() ? json(nullptr)
                                 : json{{"title", e.paper.title}, {"year", e.paper.year}, {"doi", e.paper.doi}};
    m["status"] = std::string(to_string(e.status));
    m["error"] = e.error.empty() ? json(nullptr) : json(e.error);
    m["bundle"] = e.bundle.empty() ? json(nullptr) : json(e.bundle);
    m["sha256"] = e.sha256;
    json headline = json::object();
    for (std::size_t k = 0; k < kNumHeadlineKeys; ++k) headline[kHeadlineKeys[k]] = number_or_null(e.headline[k]);
    m["headline"] = std::move(headline);
    if (e.surface)  // a surface mesh only: volume rows keep their bytes
      m["surface"] = {{"num_quads", number_or_null(e.surface->quads)},
                      {"num_triangles", number_or_null(e.surface->triangles)},
                      {"num_irregular_vertices_interior", number_or_null(e.surface->irregular_interior)},
                      {"num_irregular_vertices_boundary", number_or_null(e.surface->irregular_boundary)},
                      {"planar", e.surface->planar}};
    if (!e.metrics.empty()) {  // a solved finite-element check only: other rows keep their bytes
      json metrics = json::object();
      for (const MeshMetricRange& s : e.metrics)
        metrics[s.metric] = {
            {"min", number_or_null(s.min)}, {"mean", number_or_null(s.mean)}, {"max", number_or_null(s.max)}};
      m["metrics"] = std::move(metrics);
    }
    m["failed_gates"] = e.failed_gates;
    m["thumbnail"] = e.thumbnail.empty() ? json(nullptr) : json(e.thumbnail);
    m["overview"] = e.overview.empty() ? json(nullptr) : json(e.overview);
    // As the page shows them: the mesh's path relative to the batch input,
    // so that index.json does not depend on where the batch ran (a merge of
    // shards equals the unsharded batch).
    json warnings = json::array();
    for (const std::string& w : e.warnings) warnings.push_back(relative_warning(w, e.path));
    m["warnings"] = std::move(warnings);
    meshes.push_back(std::move(m));
  }
  j["meshes"] = std::move(meshes);
  json methods = json::array();
  // Per method and headline key, what merges exactly across shards: count,
  // sum, sum of squares, min and max over the analysed meshes' values.
  auto key_aggregates = [&](const std::string& label) {
    json keys = json::object();
    for (std::size_t k = 0; k < kNumHeadlineKeys; ++k) {
      long long count = 0;
      double sum = 0, sum_squares = 0, lo = 0, hi = 0;
      for (const BatchEntry& e : entries) {
        if (e.label != label || (e.status != BatchStatus::ok && e.status != BatchStatus::gate_failed)) continue;
        if (!e.headline[k] || !std::isfinite(*e.headline[k])) continue;
        const double v = *e.headline[k];
        lo = count == 0 ? v : std::min(lo, v);
        hi = count == 0 ? v : std::max(hi, v);
        sum += v;
        sum_squares += v * v;
        ++count;
      }
      keys[kHeadlineKeys[k]] = {{"count", count},
                                {"sum", number_or_null(sum)},
                                {"sum_squares", number_or_null(sum_squares)},
                                {"min", count ? number_or_null(lo) : json(nullptr)},
                                {"max", count ? number_or_null(hi) : json(nullptr)}};
    }
    return keys;
  };
  const bool any_fem = has_fem_metrics(entries);
  for (const MethodSummary& m : summarize_methods(entries)) {
    methods.push_back({{"label", m.label},
                       {"num_meshes", m.num_meshes},
                       {"num_failed", m.num_failed},
                       {"num_gate_failed", m.num_gate_failed},
                       {"num_with_inverted", m.num_with_inverted},
                       {"mean_min_scaled_jacobian", number_or_null(m.mean_min_scaled_jacobian)},
                       {"mean_mean_scaled_jacobian", number_or_null(m.mean_mean_scaled_jacobian)},
                       {"worst_min_scaled_jacobian", number_or_null(m.worst_min_scaled_jacobian)},
                       {"keys", key_aggregates(m.label)}});
    if (any_fem) methods.back()["fem_correlation"] = correlation_json(correlate_collection(entries, m.label));
  }
  j["methods"] = std::move(methods);
  if (any_fem) j["fem_correlation"] = correlation_json(correlate_collection(entries));
  return json_message_text(j).dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

std::vector<BatchEntry> parse_batch_index_json(std::string_view text, const std::string& name) {
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("meshes") || !j["meshes"].is_array())
    throw InputError(name + ": not an HQView batch index.json (no 'meshes' array)");
  std::vector<BatchEntry> entries;
  try {
    for (const json& m : j["meshes"]) {
      BatchEntry e;
      e.path = m.at("path").get<std::string>();
      e.label = m.value("label", "");
      e.model = m.value("model", "");
      e.variant = m.value("variant", "");
      if (m.contains("paper") && m["paper"].is_object())
        e.paper = {m["paper"].value("title", ""), m["paper"].value("year", ""), m["paper"].value("doi", "")};
      e.status = status_from(m.at("status").get<std::string>(), name);
      if (m.contains("error") && m["error"].is_string()) e.error = m["error"].get<std::string>();
      if (m.contains("bundle") && m["bundle"].is_string()) e.bundle = m["bundle"].get<std::string>();
      e.sha256 = m.value("sha256", "");
      const json& headline = m.at("headline");
      for (std::size_t k = 0; k < kNumHeadlineKeys; ++k)
        if (headline.contains(kHeadlineKeys[k]) && headline[kHeadlineKeys[k]].is_number())
          e.headline[k] = headline[kHeadlineKeys[k]].get<double>();
      if (m.contains("surface") && m["surface"].is_object()) {
        const json& f = m["surface"];
        const auto number = [&](const char* key) -> std::optional<double> {
          if (f.contains(key) && f[key].is_number()) return f[key].get<double>();
          return std::nullopt;
        };
        e.surface = SurfaceCounts{number("num_quads").value_or(0.0), number("num_triangles").value_or(0.0),
                                  number("num_irregular_vertices_interior"),
                                  number("num_irregular_vertices_boundary"),
                                  !f.contains("planar") || !f["planar"].is_boolean() || f["planar"].get<bool>()};
      }
      if (m.contains("failed_gates")) e.failed_gates = m["failed_gates"].get<std::vector<std::string>>();
      if (m.contains("thumbnail") && m["thumbnail"].is_string()) e.thumbnail = m["thumbnail"].get<std::string>();
      if (m.contains("overview") && m["overview"].is_string()) e.overview = m["overview"].get<std::string>();
      if (m.contains("warnings") && m["warnings"].is_array())
        for (const json& w : m["warnings"])
          if (w.is_string()) e.warnings.push_back(w.get<std::string>());
      if (m.contains("metrics") && m["metrics"].is_object())
        for (const auto& [metric, stats] : m["metrics"].items())
          e.metrics.push_back({metric, number_or_nan(stats.at("min")), number_or_nan(stats.at("mean")),
                               stats.contains("max") ? number_or_nan(stats["max"]) : kNaNValue});
      entries.push_back(std::move(e));
    }
  } catch (const json::exception& e) {
    throw InputError(name + ": malformed index.json: " + e.what());
  }
  return entries;
}

namespace {

// One group of the Comparison section (comparison.h): its tables, one per
// key, its thumbnails and its methods.
kainjow::mustache::data comparison_data(const Comparison& c) {
  using kainjow::mustache::data;
  data methods = data::type::list;
  for (const MethodColumn& m : c.methods) {
    data d;
    d.set("label_html", html_with_breaks(m.label));
    d.set("year", m.paper.year);
    d.set("title", m.paper.title);
    d.set("doi", m.paper.doi);
    // Empty strings are true in mustache sections: flags, so that a method
    // without a paper shows "–", not " () · doi:".
    d.set("has_year", !m.paper.year.empty());
    d.set("has_doi", !m.paper.doi.empty());
    d.set("has_paper", !m.paper.empty());
    d.set("num_meshes", std::to_string(m.num_meshes));
    d.set("num_models", std::to_string(m.num_models));
    d.set("num_valid", std::to_string(m.num_valid));
    d.set("num_failed", std::to_string(m.num_failed));
    data stats = data::type::list;
    for (std::size_t k = 0; k < c.keys.size(); ++k) {
      data x;
      x.set("mean", show(m.mean[k]));
      x.set("median", show(m.median[k]));
      x.set("sort", m.mean[k] ? format_double(*m.mean[k]) : "");
      stats.push_back(x);
    }
    d.set("stats", stats);
    methods.push_back(d);
  }
  data tables = data::type::list;
  for (std::size_t k = 0; k < c.keys.size(); ++k) {
    data table;
    table.set("title", std::string(c.keys[k].title));
    table.set("key", std::string(c.keys[k].key));
    table.set("direction", c.keys[k].direction > 0   ? "higher is better"
                           : c.keys[k].direction < 0 ? "lower is better"
                                                     : "no better direction");
    data columns = data::type::list;
    for (const ComparisonColumn& column : c.columns) columns.push_back(data("heading", column_heading(column)));
    table.set("columns", columns);
    data rows = data::type::list;
    for (const ComparisonRow& row : c.rows) {
      data r;
      r.set("model_html", html_with_breaks(row.model));
      data cells = data::type::list;
      for (const ComparisonCell& cell : comparison_cells(c, row, k)) {
        data x;
        x.set("text", cell.text);
        x.set("best", cell.is_best);
        x.set("sort", cell.value ? format_double(*cell.value) : "");
        x.set("has_link", cell.entry && !cell.entry->bundle.empty());
        x.set("link", cell.entry ? url_path(cell.entry->bundle) + "/index.html" : "");
        x.set("path", cell.entry ? cell.entry->path : "");
        cells.push_back(x);
      }
      r.set("cells", cells);
      rows.push_back(r);
    }
    table.set("rows", rows);
    tables.push_back(table);
  }
  // Thumbnails: one row per model, one cell per method and variant.
  bool any_thumbnail = false;
  data thumb_rows = data::type::list;
  for (const ComparisonRow& row : c.rows) {
    data r;
    r.set("model_html", html_with_breaks(row.model));
    data cells = data::type::list;
    for (const ComparisonColumn& column : c.columns) {
      data x;
      const auto it = row.cells.find({column.label, column.variant});
      const BatchEntry* e = it == row.cells.end() ? nullptr : it->second;
      const bool has = e && !e->bundle.empty() && !e->thumbnail.empty();
      any_thumbnail = any_thumbnail || has;
      x.set("has_image", has);
      x.set("image", has ? row_thumbnail(*e) : "");
      x.set("lightbox", has ? lightbox_url(*e) : "");
      x.set("link", has ? url_path(e->bundle) + "/index.html" : "");
      x.set("alt", e ? e->path : "");
      x.set("text", e ? (e->status == BatchStatus::failed ? "failed" : "not rendered") : "–");
      cells.push_back(x);
    }
    r.set("cells", cells);
    thumb_rows.push_back(r);
  }
  data columns = data::type::list;
  for (const ComparisonColumn& column : c.columns) columns.push_back(data("heading", column_heading(column)));
  data keys_data = data::type::list;
  for (const ComparisonKey& key : c.keys) keys_data.push_back(data("title", std::string(key.title)));
  data d;
  d.set("tables", tables);
  d.set("methods", methods);
  d.set("keys", keys_data);
  d.set("chart", c.chart_file);
  d.set("has_group", !c.group.empty());  // an empty string would open a mustache section
  d.set("group", group_heading(c));
  d.set("group_id", c.group.substr(0, c.group.find(' ')));  // "volume", "surface"
  d.set("chart_alt", "Min scaled Jacobian of every mesh" + (c.group.empty() ? std::string() : " (" + c.group + ")") +
                         ", one column per method");
  d.set("has_thumbnails", any_thumbnail);
  d.set("thumbnail_rows", thumb_rows);
  d.set("columns", columns);
  return d;
}

bool is_baseline_row(const CollectionCorrelationRow& r) { return r.metric == "num_hexes" || r.metric == "h_over_l"; }

// Of the counted meshes (solved, not a duplicate), the pairs whose errors
// (headline slot) differ by less than `noise` relative: ties within the
// placement effect.
std::size_t pairs_within(const std::vector<BatchEntry>& entries, const CollectionCorrelation& c, std::size_t slot,
                         double noise) {
  // Over the counted meshes only (not the duplicates, not the meshes left
  // out for inverted hexes: issue 48h round 2).
  std::vector<double> errors;
  for (const BatchEntry& e : entries) {
    if (e.metrics.empty() || !e.headline[slot]) continue;
    if (std::find(c.counted.begin(), c.counted.end(), e.path) == c.counted.end()) continue;
    errors.push_back(*e.headline[slot]);
  }
  std::size_t n = 0;
  for (std::size_t i = 0; i < errors.size(); ++i)
    for (std::size_t j = i + 1; j < errors.size(); ++j) {
      const double m = std::max(std::abs(errors[i]), std::abs(errors[j]));
      n += m > 0 && std::abs(errors[i] - errors[j]) < noise * m;
    }
  return n;
}

// index.html's "Which metrics rank these meshes by their simulation error" table: the two
// baselines first, then the rows by |rho| with the H1 error, largest first (nulls last, then metric order).
kainjow::mustache::data fem_correlation_data(const CollectionCorrelation& c, const std::vector<BatchEntry>& entries) {
  using kainjow::mustache::data;
  std::vector<std::size_t> order(c.rows.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto strength = [&](std::size_t i) { return std::isfinite(c.rows[i].rho_h1) ? std::abs(c.rows[i].rho_h1) : -1.0; };
  // Groups: the baselines, the metrics with a better direction, the sizes (in units of L).
  const auto group = [&](std::size_t i) { return is_baseline_row(c.rows[i]) ? 0 : c.rows[i].direction != 0 ? 1 : 2; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return group(a) != group(b) ? group(a) < group(b) : strength(a) > strength(b);
  });
  const auto rho = [](double v) {
    if (!std::isfinite(v)) return std::string("–");
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", v);  // as the per-mesh chart
    return std::string(text);
  };
  // p (and q) to 3 significant digits.
  const auto p_text = [](double p) {
    if (!std::isfinite(p)) return std::string("–");
    char text[48];
    std::snprintf(text, sizeof text, p < 1e-3 ? "%.1e" : "%.3g", p);
    return std::string(text);
  };
  // The sign a metric's worst should have if it said "worse mesh, higher
  // error": a higher-is-better metric's min falls as the error rises (rho <
  // 0), a lower-is-better one's max rises (rho > 0). " ✗" where rho has the
  // other sign.
  // Only where the sign is supported: |rho| at least the critical value (p <= 0.05 before correction).
  const auto wrong_way = [&](const CollectionCorrelationRow& r, double rho_value) {
    if (r.direction == 0 || !std::isfinite(rho_value) || rho_value == 0) return false;
    if (!(std::abs(rho_value) >= c.critical_rho - 1e-12)) return false;
    return (rho_value < 0) != (r.direction > 0);
  };
  data rows = data::type::list;
  for (const std::size_t i : order) {
    const CollectionCorrelationRow& r = c.rows[i];
    data row;
    row.set("metric", r.metric + (r.length_power == 1   ? " / L"
                                  : r.length_power == 2 ? " / L\u00b2"
                                  : r.length_power == 3 ? " / L\u00b3"
                                                        : ""));
    row.set("stat", r.restates.empty() ? r.stat : r.stat + " (restates " + r.restates + ")");
    row.set("direction", r.direction > 0 ? "higher is better" : r.direction < 0 ? "lower is better" : "–");
    row.set("rho_l2", rho(r.rho_l2) + (wrong_way(r, r.rho_l2) ? " \u2717" : ""));
    row.set("rho_h1", rho(r.rho_h1) + (wrong_way(r, r.rho_h1) ? " \u2717" : ""));
    row.set("p_l2", p_text(r.p_l2));
    row.set("p_h1", p_text(r.p_h1));
    row.set("q_l2", p_text(r.q_l2));
    row.set("q_h1", p_text(r.q_h1));
    row.set("sort_q_l2", std::isfinite(r.q_l2) ? format_double(r.q_l2) : "");
    row.set("sort_q_h1", std::isfinite(r.q_h1) ? format_double(r.q_h1) : "");
    // Greyed: neither error's q reaches 0.05 (no discovery at a 5 % false discovery rate).
    row.set("not_significant", !(r.q_l2 <= 0.05) && !(r.q_h1 <= 0.05));
    row.set("rho_l2_given_h", rho(r.rho_l2_given_h));
    row.set("rho_h1_given_h", rho(r.rho_h1_given_h));
    row.set("sort_l2_given_h", std::isfinite(r.rho_l2_given_h) ? format_double(r.rho_l2_given_h) : "");
    row.set("sort_h1_given_h", std::isfinite(r.rho_h1_given_h) ? format_double(r.rho_h1_given_h) : "");
    row.set("sort_l2", std::isfinite(r.rho_l2) ? format_double(r.rho_l2) : "");
    row.set("sort_h1", std::isfinite(r.rho_h1) ? format_double(r.rho_h1) : "");
    row.set("sort_p_l2", std::isfinite(r.p_l2) ? format_double(r.p_l2) : "");
    row.set("sort_p_h1", std::isfinite(r.p_h1) ? format_double(r.p_h1) : "");
    row.set("baseline", is_baseline_row(r));
    row.set("num_meshes", std::to_string(r.num_meshes));
    rows.push_back(row);
  }
  data d;
  d.set("rows", rows);
  // How far significance is out of reach, in plain words.
  std::string power;
  if (std::isfinite(c.min_p)) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "With %d distinct meshes the smallest p any \u03c1 can have is 2/%d! = %s; without correction "
                  "|\u03c1| \u2265 %.3f is needed for p \u2264 0.05.",
                  c.num_meshes, c.num_meshes, p_text(c.min_p).c_str(), c.critical_rho);
    power = text;
    // Benjamini-Hochberg over the family (the rows that are their own
    // hypothesis): the k rows with the smallest p get q = p m / k at best, so
    // q < 0.05 needs at least `needed` rows at the smallest p. Then what the
    // table's rows reach: the q printed here is the q of those rows.
    const std::size_t m = static_cast<std::size_t>(c.num_hypotheses_h1);
    const double spread = static_cast<double>(m) * c.min_p;
    std::string restated;
    for (const CollectionCorrelationRow& r : c.rows)
      if (!r.restates.empty()) restated += (restated.empty() ? "" : ", ") + r.stat + " " + r.metric + " (restates " + r.restates + ")";
    power += " The Benjamini\u2013Hochberg family: the " + std::to_string(m) +
             " rows that are their own hypothesis (the two baselines included" +
             (restated.empty() ? std::string() : "; " + restated + " is not counted again: the same ranks") + ").";
    if (spread > 0.05) {
      const auto needed = static_cast<std::size_t>(std::floor(spread / 0.05)) + 1;
      power += " A row reaches q < 0.05 only when at least " + std::to_string(needed) + " rows reach p = " +
               p_text(c.min_p) + " together; a row alone there gets q = " + p_text(std::min(1.0, spread)) + ".";
    }
    for (const bool h1 : {true, false}) {
      double best = kNaNValue;
      for (const CollectionCorrelationRow& r : c.rows) {
        const double p = h1 ? r.p_h1 : r.p_l2;
        if (r.restates.empty() && std::isfinite(p) && !(p >= best)) best = p;
      }
      if (!std::isfinite(best)) continue;
      std::string names;
      std::size_t k = 0;
      double q = kNaNValue;
      for (const CollectionCorrelationRow& r : c.rows)
        if (r.restates.empty() && (h1 ? r.p_h1 : r.p_l2) == best) {
          names += (k++ ? ", " : "") + r.metric + (r.stat == "value" || r.stat == "count" ? "" : " (" + r.stat + ")");
          q = h1 ? r.q_h1 : r.q_l2;
        }
      power += std::string(h1 ? " Here, H1: " : " L2: ") + std::to_string(k) + (k == 1 ? " row" : " rows") +
               " at the smallest p, " + p_text(best) + " (" + names + "): q = " + p_text(q) + (h1 ? ";" : ".");
    }
    power += " Too few meshes for significance: a greyed row means \u201ccould not detect\u201d, not \u201cno effect\u201d.";
    // Resolution alone: when h/L ranks the errors as well as the critical rho.
    const auto hl = std::find_if(c.rows.begin(), c.rows.end(),
                                 [](const CollectionCorrelationRow& r) { return r.metric == "h_over_l"; });
    if (hl != c.rows.end() && (std::abs(hl->rho_h1) >= c.critical_rho - 1e-12 || std::abs(hl->rho_l2) >= c.critical_rho - 1e-12)) {
      char text[600];
      const double n = c.num_meshes;
      std::snprintf(text, sizeof text,
                    " h/L alone ranks these meshes\u2019 errors (\u03c1 = %.3f with L2, %.3f with H1): a metric\u2019s "
                    "\u03c1 here may only restate their resolution; the \u201cgiven h/L\u201d columns keep what it "
                    "adds (\u2013 where h/L leaves nothing to explain). Over %d meshes one swap of neighbouring "
                    "ranks moves \u03c1 by 12/(n(n\u00b2\u22121)) = %.2g.",
                    hl->rho_l2, hl->rho_h1, c.num_meshes, 12.0 / (n * (n * n - 1.0)));
      power += text;
    }
  }
  // The placement effect (a duplicate's errors) as the noise of the error columns.
  if (!c.duplicates.empty()) {
    double l2_noise = 0, h1_noise = 0;
    for (const CollectionDuplicate& dup : c.duplicates) {
      l2_noise = std::max(l2_noise, dup.l2_difference);
      h1_noise = std::max(h1_noise, dup.h1_difference);
    }
    const std::size_t l2_ties = pairs_within(entries, c, headline_slot("fem.poisson.mean.l2_error"), l2_noise),
                      h1_ties = pairs_within(entries, c, headline_slot("fem.poisson.mean.h1_error"), h1_noise);
    char text[600];
    std::snprintf(text, sizeof text,
                  " Placing the same mesh differently (the duplicate below) moved the L2 error by %.2g %% and the H1 "
                  "error by %.2g %%: meshes whose errors differ by less are ties. Here %zu pair%s of counted meshes "
                  "%s within that in L2 and %zu in H1, so the L2 (H1) column's \u03c1 is uncertain by at least as "
                  "many swaps.",
                  100.0 * l2_noise, 100.0 * h1_noise, l2_ties, l2_ties == 1 ? "" : "s", l2_ties == 1 ? "is" : "are",
                  h1_ties);
    power += text;
  }
  d.set("power", power);
  d.set("has_power", !power.empty());
  // The meshes the table is computed from, and the duplicates left out.
  data meshes = data::type::list;
  static const std::size_t l2_slot = headline_slot("fem.poisson.mean.l2_error"),
                           h1_slot = headline_slot("fem.poisson.mean.h1_error"),
                           hexes_slot = headline_slot("mesh.num_hexes"),
                           sj_slot = headline_slot("quality.scaled_jacobian.min"),
                           inverted_slot = headline_slot("quality.num_inverted");
  const auto cell = [&](const std::optional<double>& v, int digits) {
    return v ? display_number(*v, digits) : std::string("–");
  };
  for (const BatchEntry& e : entries) {
    if (e.metrics.empty() || !e.headline[l2_slot]) continue;
    data row;
    row.set("path", e.path);
    row.set("num_hexes", cell(e.headline[hexes_slot], 12));
    std::optional<double> h_over_l;
    for (const MeshMetricRange& m : e.metrics)
      if (m.metric == "h_over_l") h_over_l = m.mean;
    row.set("h_over_l", cell(h_over_l, 3));
    row.set("l2", cell(e.headline[l2_slot], 3));
    row.set("h1", cell(e.headline[h1_slot], 3));
    row.set("min_sj", cell(e.headline[sj_slot], 3));
    row.set("inverted", cell(e.headline[inverted_slot], 12));
    std::string counted = "counted";
    if (std::find(c.inverted.begin(), c.inverted.end(), e.path) != c.inverted.end())
      counted = "left out: " + cell(e.headline[inverted_slot], 12) +
                " inverted hexes (a corner Jacobian \u2264 0): the check\u2019s map folds there, so its error is no "
                "finite-element error of this mesh";
    for (const CollectionDuplicate& dup : c.duplicates)
      if (dup.path == e.path) {
        char text[96];
        std::snprintf(text, sizeof text, "errors differ by %.2g %% L2, %.2g %% H1", 100.0 * dup.l2_difference,
                      100.0 * dup.h1_difference);
        counted = "left out: same counts and scale-invariant quality summaries as " + dup.same_as +
                  ", so treated as the same mesh (the first by path is kept; " + text + ")";
      }
    row.set("counted", counted);
    meshes.push_back(row);
  }
  d.set("meshes", meshes);
  d.set("has_duplicates", !c.duplicates.empty());
  d.set("num_duplicates", std::to_string(c.duplicates.size()));
  d.set("num_meshes", std::to_string(c.num_meshes));
  d.set("min_meshes", std::to_string(c.min_meshes));
  d.set("too_few", c.num_meshes < c.min_meshes);
  return d;
}

// The inputs not analysed (status skipped: reference surfaces beside the
// meshes), grouped by reason in first-seen order, paths in entry order:
// index.html and summary.md list them apart from the mesh table, one line
// per reason, not as rows of dashes.
struct SkippedFiles {
  std::string reason;
  std::vector<std::string> paths;
};
std::vector<SkippedFiles> skipped_files(const std::vector<BatchEntry>& entries) {
  std::vector<SkippedFiles> groups;
  for (const BatchEntry& e : entries) {
    if (e.status != BatchStatus::skipped) continue;
    auto it = std::find_if(groups.begin(), groups.end(), [&](const SkippedFiles& g) { return g.reason == e.error; });
    if (it == groups.end()) it = groups.insert(groups.end(), {e.error, {}});
    it->paths.push_back(e.path);
  }
  return groups;
}

// The order of index.html's mesh table: worst first (batch_index.h).
int status_rank(BatchStatus s) {
  switch (s) {
    case BatchStatus::failed:
      return 0;
    case BatchStatus::gate_failed:
      return 1;
    case BatchStatus::ok:
      return 2;
    case BatchStatus::skipped:
      return 3;
  }
  return 3;
}

}  // namespace

std::vector<std::size_t> worst_first_order(const std::vector<BatchEntry>& entries) {
  static const std::size_t inverted = headline_slot("quality.num_inverted");
  static const std::size_t min_sj = headline_slot("quality.scaled_jacobian.min");
  // A missing value sorts as the best (after every known one).
  const auto value = [](const BatchEntry& e, std::size_t k, double missing) {
    return e.headline[k] && std::isfinite(*e.headline[k]) ? *e.headline[k] : missing;
  };
  std::vector<std::size_t> order(entries.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    const BatchEntry &a = entries[i], &b = entries[j];
    if (status_rank(a.status) != status_rank(b.status)) return status_rank(a.status) < status_rank(b.status);
    if (a.failed_gates.size() != b.failed_gates.size()) return a.failed_gates.size() > b.failed_gates.size();
    const double ia = value(a, inverted, -1), ib = value(b, inverted, -1);
    if (ia != ib) return ia > ib;
    const double sa = value(a, min_sj, INFINITY), sb = value(b, min_sj, INFINITY);
    if (sa != sb) return sa < sb;
    return a.path < b.path;
  });
  return order;
}

std::string batch_index_html(const std::vector<BatchEntry>& entries, const std::string& tool_version,
                             const std::vector<ComparisonKey>* keys) {
  using kainjow::mustache::data;
  using kainjow::mustache::mustache;
  data page;
  page.set("version", tool_version);
  // Columns no row has a value in are left out (a batch without references
  // has no Hausdorff distance; a directory has no labels).
  std::vector<bool> shown(kNumHeadlineKeys, false);
  bool any_label = false, any_model = false, any_variant = false, any_detail = false, any_thumbnail = false;
  // The composition columns only when some mesh is not pure-hex.
  static const std::size_t hex_fraction_key = headline_slot("headline.hex_fraction");
  static const std::size_t first_composition_key = headline_slot("headline.num_cells");
  const bool any_hybrid = std::any_of(entries.begin(), entries.end(), [](const BatchEntry& e) {
    return e.headline[hex_fraction_key].has_value() && *e.headline[hex_fraction_key] != 1.0;
  });
  // Surface meshes (issue 47): the hex column counts their cells by kind,
  // the singular-edge columns their irregular vertices.
  static const std::size_t hexes_key = headline_slot("mesh.num_hexes");
  static const std::size_t singular_keys[2] = {headline_slot("structure.num_singular_edges_interior"),
                                               headline_slot("structure.num_singular_edges_boundary")};
  const bool any_surface = std::any_of(entries.begin(), entries.end(), [](const BatchEntry& e) { return e.surface.has_value(); });
  for (const BatchEntry& e : entries) {
    if (e.status == BatchStatus::skipped) continue;  // listed apart, above the table
    for (std::size_t k = 0; k < kNumHeadlineKeys; ++k)
      shown[k] = shown[k] || (e.headline[k].has_value() && (k < first_composition_key || any_hybrid));
    if (e.surface) {
      shown[hexes_key] = true;
      shown[singular_keys[0]] = shown[singular_keys[0]] || e.surface->irregular_interior.has_value();
      shown[singular_keys[1]] = shown[singular_keys[1]] || e.surface->irregular_boundary.has_value();
    }
    any_label = any_label || !e.label.empty();
    any_model = any_model || !e.model.empty();
    any_variant = any_variant || !e.variant.empty();
    any_detail = any_detail || !e.error.empty() || !e.failed_gates.empty();
    any_thumbnail = any_thumbnail || (!e.bundle.empty() && !e.thumbnail.empty());
  }
  page.set("has_label", any_label);
  page.set("has_model", any_model);
  page.set("has_variant", any_variant);
  page.set("has_detail", any_detail);
  page.set("has_thumbnail", any_thumbnail);
  static const std::size_t inverted_key = headline_slot("quality.num_inverted");
  static const std::size_t min_sj_key = headline_slot("quality.scaled_jacobian.min");
  static const std::size_t invalid_key = headline_slot("fem.element.num_invalid");
  static const std::size_t not_invertible_key = headline_slot("fem.element.num_not_invertible");
  static const std::size_t intersecting_key = headline_slot("overlap.num_intersecting_cells");
  data headers = data::type::list;
  for (std::size_t k = 0; k < kNumHeadlineKeys; ++k) {
    if (!shown[k]) continue;
    std::string title = kHeadlineTitles[k];
    if (any_surface && k == hexes_key) title = "#cells (hex / quad / tri)";
    if (any_surface && k == singular_keys[0]) title = "#singular edges / irregular vertices, interior";
    if (any_surface && k == singular_keys[1]) title = "#singular edges / irregular vertices, boundary";
    // The one long word may break (a soft hyphen): the table fits 1400 px.
    if (k == intersecting_key) title = "#inter\u00ADsecting";
    headers.push_back(data("title", title));
  }
  page.set("headline_columns", headers);
  page.set("has_surface", any_surface);
  int failed = 0, gate_failed = 0, with_findings = 0, with_warnings = 0, limited = 0;
  std::size_t skipped = 0;
  std::vector<std::string> limitations;  // distinct, in first-seen order (rows worst first)
  data rows = data::type::list;
  for (const std::size_t i : worst_first_order(entries)) {
    const BatchEntry& e = entries[i];
    // Inputs not analysed (reference surfaces beside the meshes) are no
    // rows of dashes: they are listed apart, above the table.
    if (e.status == BatchStatus::skipped) {
      ++skipped;
      continue;
    }
    failed += e.status == BatchStatus::failed;
    gate_failed += e.status == BatchStatus::gate_failed;
    data row;
    row.set("path", e.path);
    row.set("path_html", html_with_breaks(e.path));
    row.set("label", e.label);
    row.set("label_html", html_with_breaks(e.label));
    row.set("model", e.model);
    row.set("model_html", html_with_breaks(e.model));
    row.set("variant", e.variant);
    row.set("variant_html", html_with_breaks(e.variant));
    const std::string findings = batch_findings(e);
    with_findings += !findings.empty() && e.status != BatchStatus::failed && e.status != BatchStatus::skipped;
    const bool is_limited = (e.status == BatchStatus::ok || e.status == BatchStatus::gate_failed) && has_limited_analysis(e);
    with_warnings += findings.find("input warning") != std::string::npos;
    limited += is_limited;
    row.set("status", std::string(to_string(e.status)) + (findings.empty() ? "" : " finding") +
                          (is_limited && findings.empty() ? " limited" : ""));
    row.set("status_text", batch_status_text(e));
    row.set("has_bundle", !e.bundle.empty());
    row.set("link", url_path(e.bundle) + "/index.html");
    const bool has_thumbnail = !e.bundle.empty() && !e.thumbnail.empty();
    row.set("has_thumbnail_image", has_thumbnail);
    row.set("thumbnail_src", row_thumbnail(e));
    row.set("lightbox_src", lightbox_url(e));
    std::string detail = e.error;
    for (const std::string& g : e.failed_gates) detail += (detail.empty() ? "" : "; ") + g;
    // Input warnings under the mesh's path (the details column is for errors and gates).
    std::string warning;
    // Tool limitations once under the table, not per row.
    for (const std::string& w : e.warnings) {
      if (is_limitation_warning(w)) {
        if (std::find(limitations.begin(), limitations.end(), w) == limitations.end()) limitations.push_back(w);
        continue;
      }
      warning += (warning.empty() ? "warning: " : "; warning: ") + relative_warning(w, e.path);
    }
    row.set("warning", warning);
    row.set("has_warning", !warning.empty());
    row.set("detail", html_with_breaks(detail));
    data cells = data::type::list;
    for (std::size_t k = 0; k < kNumHeadlineKeys; ++k) {
      if (!shown[k]) continue;
      data cell;
      std::optional<double> value = e.headline[k];
      std::string text = show(value);
      if (any_surface && k == hexes_key) {
        // "216 quad", "200 quad + 16 tri", "1000 hex" (+ " + 12 other" on a hybrid mesh).
        const auto count = [](double v) { return display_number(v); };
        if (e.surface) {
          value = e.surface->quads + e.surface->triangles;
          text = e.surface->triangles == 0 ? count(e.surface->quads) + " quad"
                 : e.surface->quads == 0   ? count(e.surface->triangles) + " tri"
                                           : count(e.surface->quads) + " quad + " + count(e.surface->triangles) + " tri";
        } else if (value) {
          static const std::size_t cells_key = headline_slot("headline.num_cells");
          const double others = e.headline[cells_key] ? *e.headline[cells_key] - *value : 0.0;
          text = count(*value) + " hex" + (others > 0 ? " + " + count(others) + " other" : "");
          if (others > 0) value = *value + others;
        }
      } else if (e.surface && !e.surface->planar && k == inverted_key && value && *value > 0) {
        text += " reversed";  // a curved surface's flipped faces, not a bad shape
      } else if (e.surface && (k == singular_keys[0] || k == singular_keys[1])) {
        value = k == singular_keys[0] ? e.surface->irregular_interior : e.surface->irregular_boundary;
        text = value ? show(value) + " vertices" : "–";
      }
      cell.set("text", text);
      // The sort key: the exact number, or empty (sorted last).
      cell.set("sort", value && std::isfinite(*value) ? format_double(*value) : "");
      // Inverted hexes, a non-positive min SJ and invalid elements stand out.
      const bool alert = e.headline[k] && (((k == inverted_key || k == invalid_key || k == not_invertible_key) && *e.headline[k] > 0) ||
                                           (k == min_sj_key && *e.headline[k] <= 0));
      cell.set("alert", alert);
      cells.push_back(cell);
    }
    row.set("cells", cells);
    rows.push_back(row);
  }
  page.set("rows", rows);
  page.set("num_meshes", std::to_string(entries.size() - skipped));
  page.set("num_failed", std::to_string(failed));
  page.set("num_gate_failed", std::to_string(gate_failed));
  page.set("num_with_findings", std::to_string(with_findings));
  if (with_warnings > 0) page.set("num_with_warnings", std::to_string(with_warnings));
  if (skipped > 0) page.set("num_skipped", count_files(skipped));
  // The inputs not analysed, one line per reason (skipped_files): "Skipped:
  // 5 files, not analysed (a surface file beside volume meshes, ...): a.off, ...".
  data skipped_rows = data::type::list;
  for (const auto& [reason, paths] : skipped_files(entries)) {
    data d;
    d.set("count", count_files(paths.size()));
    d.set("reason", reason);
    data names = data::type::list;
    for (std::size_t k = 0; k < paths.size(); ++k) {
      data n("path", paths[k]);
      n.set("last", k + 1 == paths.size());
      names.push_back(n);
    }
    d.set("paths", names);
    skipped_rows.push_back(d);
  }
  page.set("skipped", skipped_rows);
  if (limited > 0) page.set("num_limited", std::to_string(limited));
  data limitation_rows = data::type::list;
  for (const std::string& w : limitations) limitation_rows.push_back(data("text", w));
  page.set("limitations", limitation_rows);
  const std::vector<MethodSummary> methods = summarize_methods(entries);
  page.set("has_methods", !methods.empty());
  data method_rows = data::type::list;
  for (const MethodSummary& m : methods) {
    data row;
    row.set("label_html", html_with_breaks(m.label));
    row.set("num_meshes", std::to_string(m.num_meshes));
    row.set("num_failed", std::to_string(m.num_failed));
    row.set("num_gate_failed", std::to_string(m.num_gate_failed));
    row.set("num_with_inverted", std::to_string(m.num_with_inverted));
    row.set("mean_min", show(m.mean_min_scaled_jacobian));
    row.set("mean_mean", show(m.mean_mean_scaled_jacobian));
    row.set("worst_min", show(m.worst_min_scaled_jacobian));
    method_rows.push_back(row);
  }
  page.set("methods", method_rows);
  page.set("has_fem_correlation", has_fem_metrics(entries));
  if (has_fem_metrics(entries)) page.set("fem_correlation", fem_correlation_data(correlate_collection(entries), entries));
  page.set("has_comparison", has_comparison(entries));
  if (has_comparison(entries)) {
    // Volume and surface meshes apart (issue 47): one group each.
    data groups = data::type::list;
    const std::vector<Comparison> comparisons = comparison_groups(entries, keys);
    for (const Comparison& c : comparisons) groups.push_back(comparison_data(c));
    page.set("comparison", groups);
    page.set("comparison_grouped", comparisons.size() > 1);
  }
  page.set("lightbox", std::string(report_template("lightbox.html")));
  mustache tmpl{std::string(report_template("batch_index.html.mustache"))};
  if (!tmpl.is_valid()) throw Error("batch index template: " + tmpl.error_message());
  tmpl.set_custom_escape([](const std::string& s) { return html_escape(s); });
  return tmpl.render(page);
}

// What a row's quality.num_inverted counts: "reversed faces" on a curved
// surface (orientation flipped against their neighbours), else "inverted".
static const char* inverted_word(const BatchEntry& e) { return e.surface && !e.surface->planar ? "reversed faces" : "inverted"; }

std::string batch_findings(const BatchEntry& e) {
  static const std::size_t inverted_key = headline_slot("quality.num_inverted");
  static const std::size_t intersecting_key = headline_slot("overlap.num_intersecting_cells");
  std::string findings;
  auto find = [&](bool found, const char* what) {
    if (found) findings += (findings.empty() ? "" : ", ") + std::string(what);
  };
  find(e.headline[inverted_key] && *e.headline[inverted_key] > 0, inverted_word(e));
  find(e.headline[intersecting_key] && *e.headline[intersecting_key] > 0, "intersecting");
  find(std::any_of(e.warnings.begin(), e.warnings.end(), [](const std::string& w) { return !is_limitation_warning(w); }),
       "input warning");
  return findings;
}

bool has_limited_analysis(const BatchEntry& e) {
  return std::any_of(e.warnings.begin(), e.warnings.end(), [](const std::string& w) { return is_limitation_warning(w); });
}

std::string batch_status_text(const BatchEntry& e) {
  const std::string findings = batch_findings(e);
  const std::string status = e.status == BatchStatus::failed        ? "✗ failed"
         : e.status == BatchStatus::gate_failed ? "✗ gate failed"
         : e.status == BatchStatus::skipped     ? "skipped"
         : findings.empty()                     ? "ok"
                                                : "⚠ " + findings;
  // A skipped or failed mesh has no analysis to call limited.
  const bool analysed = e.status == BatchStatus::ok || e.status == BatchStatus::gate_failed;
  return analysed && has_limited_analysis(e) ? status + " · limited analysis" : status;
}

std::string batch_summary_markdown(const std::vector<BatchEntry>& entries) {
  // The counts of index.html's subtitle (issue 45f: the header read as an
  // all-clear above meshes with inverted hexes).
  int failed = 0, gate_failed = 0, with_findings = 0, with_warnings = 0;
  std::size_t skipped = 0;  // meshes as index.json counts.meshes: skipped inputs left out
  for (const BatchEntry& e : entries) {
    skipped += e.status == BatchStatus::skipped;
    failed += e.status == BatchStatus::failed;
    gate_failed += e.status == BatchStatus::gate_failed;
    with_findings += !batch_findings(e).empty() && e.status != BatchStatus::failed && e.status != BatchStatus::skipped;
    with_warnings += std::any_of(e.warnings.begin(), e.warnings.end(),
                                 [](const std::string& w) { return !is_limitation_warning(w); });
  }
  std::string md = "## HQView batch: " + std::to_string(entries.size() - skipped) + " meshes, " + std::to_string(failed) +
                   " failed, " + std::to_string(gate_failed) + " with failed gates, " + std::to_string(with_findings) +
                   " with inverted or intersecting cells or input warnings";
  if (with_warnings > 0) md += " (" + std::to_string(with_warnings) + " with input warnings)";
  if (skipped > 0) md += ", " + count_files(skipped) + " skipped (listed under the table)";
  md += "\n\n";
  // The table in parts that a terminal and GitHub show whole (issue 45, the
  // 45t review: 24 columns): the quality numbers beside each mesh's status,
  // then the other headline numbers in tables of their own, each with the
  // columns some row has a value in (as index.html), none without any.
  const std::vector<std::size_t> order = worst_first_order(entries);
  const bool any_label = std::any_of(entries.begin(), entries.end(), [](const BatchEntry& e) { return !e.label.empty(); });
  struct Part {
    const char* heading;  // empty: the first table
    std::size_t first, end;  // headline keys [first, end)
  };
  static const std::size_t structure_key = headline_slot("boundary_error.hausdorff.relative");
  static const std::size_t fem_key = headline_slot("fem.element.num_invalid");
  static const std::size_t cells_key = headline_slot("headline.num_cells");
  const Part parts[] = {{"", 0, structure_key},
                        {"Reference and structure", structure_key, fem_key},
                        {"Finite elements", fem_key, cells_key},
                        {"Cell kinds", cells_key, kNumHeadlineKeys}};
  // The cell kinds only when some mesh is not pure-hex (as index.html).
  static const std::size_t hex_fraction_key = headline_slot("headline.hex_fraction");
  const bool any_hybrid = std::any_of(entries.begin(), entries.end(), [](const BatchEntry& e) {
    return e.headline[hex_fraction_key].has_value() && *e.headline[hex_fraction_key] != 1.0;
  });
  for (const Part& part : parts) {
    const bool first = part.first == 0;
    if (part.first == cells_key && !any_hybrid) continue;
    std::vector<std::size_t> keys;
    for (std::size_t k = part.first; k < part.end; ++k)
      if (first || std::any_of(entries.begin(), entries.end(), [&](const BatchEntry& e) {
            return e.status != BatchStatus::skipped && e.headline[k].has_value();
          }))
        keys.push_back(k);
    if (keys.empty()) continue;
    if (!first) md += std::string("\n### ") + part.heading + "\n\n";
    md += std::string("| mesh |") + (first && any_label ? " label |" : "") + (first ? " status |" : "");
    for (const std::size_t k : keys) md += std::string(" ") + kHeadlineTitles[k] + " |";
    md += std::string("\n|---|") + (first && any_label ? "---|" : "") + (first ? "---|" : "");
    for (std::size_t k = 0; k < keys.size(); ++k) md += "--:|";
    md += "\n";
    // Worst first, as index.html (worst_first_order).
    for (const std::size_t i : order) {
      const BatchEntry& e = entries[i];
      if (e.status == BatchStatus::skipped) continue;  // listed under the table
      md += "| " + (e.bundle.empty() ? markdown_escape(e.path)
                                     : "[" + markdown_escape(e.path) + "](" + url_path(e.bundle) + "/index.html)") + " |";
      if (first && any_label) md += " " + markdown_escape(e.label) + " |";
      if (first) md += " " + batch_status_text(e) + " |";  // fixed words, no input
      for (const std::size_t k : keys) md += " " + show(e.headline[k]) + " |";
      md += "\n";
    }
  }
  for (const SkippedFiles& group : skipped_files(entries)) {
    md += "\nSkipped: " + count_files(group.paths.size()) + ", not analysed (" + markdown_escape(group.reason) + "):";
    for (std::size_t k = 0; k < group.paths.size(); ++k) md += (k == 0 ? " " : ", ") + markdown_escape(group.paths[k]);
    md += ".\n";
  }
  // Every mesh that is not plainly ok, worst first, with why: its error,
  // failed gates, inverted and intersecting cell counts, input warnings
  // (each without the mesh's path, which the line starts with).
  static const std::size_t inverted_key = headline_slot("quality.num_inverted");
  static const std::size_t intersecting_key = headline_slot("overlap.num_intersecting_cells");
  bool any_problem = false;
  for (const std::size_t i : order) {
    const BatchEntry& e = entries[i];
    const bool finding = !batch_findings(e).empty();
    if (e.status == BatchStatus::ok && !finding) continue;
    if (e.status == BatchStatus::skipped) continue;
    if (!any_problem) md += "\n### Problems\n\n";
    any_problem = true;
    // Fixed words and numbers as they are; input text (errors, gates,
    // warnings) escaped; a limitation of HQView is "limited", not a warning.
    std::string what = markdown_escape(e.error);
    for (const std::string& g : e.failed_gates) what += (what.empty() ? "gate failed: " : "; ") + markdown_escape(g);
    auto count = [&](std::size_t key, const char* word) {
      if (e.headline[key] && *e.headline[key] > 0)
        what += (what.empty() ? "" : "; ") + show(e.headline[key]) + " " + word;
    };
    count(inverted_key, inverted_word(e));
    count(intersecting_key, "intersecting");
    for (const std::string& w : e.warnings) {
      std::string text = relative_warning(w, e.path);
      if (text.starts_with(e.path + ": ")) text.erase(0, e.path.size() + 2);
      what += std::string(what.empty() ? "" : "; ") + (is_limitation_warning(w) ? "limited: " : "warning: ") +
              markdown_escape(text);
    }
    md += "- " + markdown_escape(e.path) + ": " + what + "\n";
  }
  const std::vector<MethodSummary> methods = summarize_methods(entries);
  if (!methods.empty()) {
    md +=
        "\n### Methods\n\n| method | meshes | failed | gate failed | with inverted | mean min SJ | mean mean SJ | "
        "worst min SJ |\n|---|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const MethodSummary& m : methods)
      md += "| " + markdown_escape(m.label) + " | " + std::to_string(m.num_meshes) + " | " + std::to_string(m.num_failed) +
            " | " + std::to_string(m.num_gate_failed) + " | " + std::to_string(m.num_with_inverted) + " | " +
            show(m.mean_min_scaled_jacobian) + " | " + show(m.mean_mean_scaled_jacobian) + " | " +
            show(m.worst_min_scaled_jacobian) + " |\n";
  }
  return md;
}

void write_batch_index(const std::vector<BatchEntry>& entries, const std::string& tool_version, const fs::path& dir,
                       const std::vector<ComparisonKey>* keys, const std::string& link_base) {
  fs::create_directories(dir);
  fault_point("batch-before-index");
  write_file_atomically(dir / "index.json", batch_index_json(entries, tool_version));
  fault_point("batch-index-write");
  write_file_atomically(dir / "index.html", absolute_links_html(batch_index_html(entries, tool_version, keys), link_base));
  write_file_atomically(dir / "summary.md", absolute_links_markdown(batch_summary_markdown(entries), link_base));
  write_file_atomically(dir / "junit.xml", junit_xml("hqview batch", batch_junit_cases(entries)));
  if (has_comparison(entries)) {
    const std::vector<Comparison> groups = comparison_groups(entries, keys);
    write_file_atomically(dir / "comparison.csv", comparison_csv(entries));
    write_file_atomically(dir / "comparison.md", absolute_links_markdown(comparison_markdown(groups), link_base));
    write_file_atomically(dir / "comparison.tex", comparison_latex(groups));
    for (const Comparison& c : groups) write_file_atomically(dir / c.chart_file, comparison_chart_svg(c));
  }
}

void write_batch_single_file(const fs::path& dir, const std::string& link_base) {
  auto read = [&dir](const std::string& relative) -> std::optional<std::string> {
    const fs::path p = fs::path(relative).lexically_normal();
    if (p.is_absolute() || p.empty() || *p.begin() == "..") return std::nullopt;
    std::ifstream in(dir / p, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return std::move(text).str();
  };
  const std::string index = read("index.html").value_or("");
  SingleFileSources sources;
  sources.index_html = index;
  sources.read_file = read;
  sources.link_base = link_base;
  sources.page_link = [&dir](const std::string& relative) -> std::optional<std::string> {
    constexpr std::string_view kIndex = "/index.html";
    if (relative.size() <= kIndex.size() || relative.compare(relative.size() - kIndex.size(), kIndex.size(), kIndex) != 0)
      return std::nullopt;
    const std::string bundle = relative.substr(0, relative.size() - kIndex.size());
    if (!fs::is_regular_file(dir / bundle / "report.html")) return std::nullopt;
    return url_path(bundle + "/report.html");
  };
  write_file_atomically(dir / "report.html", single_file_html(sources));
}

void check_batch_output_dir(const fs::path& dir, bool force) {
  std::error_code ec;
  const auto status = fs::symlink_status(dir, ec);
  if (ec || !fs::exists(status)) return;
  if (!fs::is_directory(status)) throw ValueError(dir.string() + ": exists and is not a directory; choose another -o");
  if (!force && !fs::is_empty(dir) && !fs::is_regular_file(dir / "index.json") &&
      !fs::is_regular_file(dir / kBatchMarkerFile))
    throw ValueError(dir.string() +
                     ": is a non-empty directory that is not an HQView batch output (no index.json); "
                     "use --force to write into it");
}

void mark_batch_output_dir(const fs::path& dir) {
  fs::create_directories(dir);
  if (!fs::is_regular_file(dir / kBatchMarkerFile))
    write_file_atomically(dir / kBatchMarkerFile, "an HQView batch output (hqview batch / merge)\n");
}

}  // namespace hq
