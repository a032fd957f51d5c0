#include "hqview/pipeline/diff.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/core/text.h"
#include "hqview/report/batch_index.h"
#include "hqview/report/comparison.h"
#include "hqview/report/escape.h"
#include "hqview/report/json_path.h"
#include "hqview/report/key_quantity.h"

namespace hq {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A gate's value: a number, or a boolean as 1 / 0.
std::optional<double> lookup(const json& j, const std::vector<std::string>& path) {
  const json* node = find_json_path(j, std::span<const std::string>(path));
  if (node == nullptr) return std::nullopt;
  if (node->is_boolean()) return node->get<bool>() ? 1.0 : 0.0;
  if (!node->is_number()) return std::nullopt;
  return node->get<double>();
}

std::string join(const std::vector<std::string>& path) {
  std::string s;
  for (const std::string& k : path) s += (s.empty() ? "" : ".") + k;
  return s;
}

// Numeric leaves of a report, by dotted path; arrays (histograms, lists of
// clusters, worst cells) are left out: their entries have no stable identity.
// `present`: every leaf path, whatever its value (null, a string, an array),
// to tell a key that is null from a key that is absent.
void flatten(const json& j, const std::string& prefix, std::map<std::string, double>& out,
             std::set<std::string>& present) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (key == "schema_version") continue;
    if (it->is_object()) {
      flatten(*it, key, out, present);
      continue;
    }
    present.insert(key);
    if (it->is_number()) out[key] = it->get<double>();
  }
}

// Whether a report has `key`: the key itself, or one of its dotted
// prefixes as a leaf (`compare: null` holds `compare.mesh.num_vertices` as
// null: a changed value when the other side has a number there, not a key
// added by another HQView version).
bool has_path(const std::set<std::string>& present, const std::string& key) {
  for (std::size_t dot = key.find('.'); dot != std::string::npos; dot = key.find('.', dot + 1))
    if (present.count(key.substr(0, dot))) return true;
  return present.count(key) > 0;
}

// Files `key`'s two values: a key on one side only is added or removed, a
// value that differs (a number against null too) changed.
void file_difference(DiffResult& result, const std::string& mesh, const std::string& key,
                     std::optional<double> baseline, std::optional<double> current, bool is_in_baseline,
                     bool is_in_current) {
  if (baseline == current) return;
  if (!is_in_baseline) result.added.push_back({mesh, key, baseline, current});
  else if (!is_in_current) result.removed.push_back({mesh, key, baseline, current});
  else result.changed.push_back({mesh, key, baseline, current});
}

json parse_or_throw(std::string_view text, const std::string& what) {
  json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw InputError(what + ": not a JSON object (expected report.json or index.json)");
  return j;
}

std::string string_or_empty(const json& object, const char* key) {
  return object.contains(key) && object[key].is_string() ? object[key].get<std::string>() : std::string();
}

bool is_index(const json& j) { return j.contains("meshes") && j["meshes"].is_array(); }

std::string show(std::optional<double> v) {
  if (!v) return "–";
  return format_double(*v, "–");
}

std::string show_delta(const DiffValue& d) {
  if (!d.baseline || !d.current) return d.baseline ? "vanished" : "new";
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%+.6g", *d.current - *d.baseline);
  return buffer;
}

// A JSON member, or an empty object.
const json& member(const json& j, const char* key) {
  static const json kEmpty = json::object();
  return j.is_object() && j.contains(key) && j[key].is_object() ? j[key] : kEmpty;
}

std::string file_name_at(const json& input) {
  const json& path = input.is_object() && input.contains("path") ? input["path"] : json();
  return path.is_string() ? fs::path(path.get<std::string>()).filename().string() : std::string("?");
}

// The side-by-side tables of two report.json (DiffResult::side_by_side).
std::vector<DiffSideBySide> side_by_side_tables(const json& base, const json& cur) {
  std::vector<DiffSideBySide> tables;
  // Only reports with their summaries (not a hand-cut excerpt).
  for (const json* j : {&base, &cur})
    if (member(*j, "mesh").empty() || member(*j, "quality").empty()) return tables;
  const json &bi = member(base, "input"), &ci = member(cur, "input");
  const auto table = [](std::string what, std::string baseline_name, std::string current_name, const json& b,
                        const json& c) {
    const CompareNumbers bn = compare_numbers(member(b, "headline"), member(b, "mesh"), member(b, "quality"));
    const CompareNumbers cn = compare_numbers(member(c, "headline"), member(c, "mesh"), member(c, "quality"));
    return DiffSideBySide{std::move(what), std::move(baseline_name), std::move(current_name), compare_rows(bn, cn),
                          mesh_cells(bn, cn)};
  };
  tables.push_back(table("mesh", file_name_at(member(bi, "mesh")), file_name_at(member(ci, "mesh")), base, cur));
  const json &bc = member(base, "compare"), &cc = member(cur, "compare");
  if (!bc.empty() && !cc.empty())
    tables.push_back(table("compared mesh (--compare)", file_name_at(member(bi, "compare")),
                           file_name_at(member(ci, "compare")), bc, cc));
  return tables;
}

// A mesh of an index: its entry and, on demand, its bundle's report.json.
struct IndexedMesh {
  const json* entry = nullptr;
  fs::path report_path;
  std::optional<json> report;
};

std::optional<double> mesh_value(IndexedMesh& m, const std::vector<std::string>& path) {
  const std::string key = join(path);
  const json& headline = (*m.entry)["headline"];
  if (headline.is_object() && headline.contains(key)) return lookup(headline, {key});
  if (!m.report) {
    std::ifstream in(m.report_path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    m.report = json::parse(text.str(), nullptr, false);
  }
  return lookup(*m.report, path);
}

bool is_method_gate(const DiffGate& g) { return !g.rule.path.empty() && g.rule.path[0] == "method"; }

// A method's numbers by gate path ("method.num_valid", "method.mean.KEY").
std::map<std::string, std::map<std::string, double>> method_values(const Comparison& c) {
  std::map<std::string, std::map<std::string, double>> out;
  for (const MethodColumn& m : c.methods) {
    auto& v = out[m.label];
    v["method.num_meshes"] = m.num_meshes;
    v["method.num_models"] = m.num_models;
    v["method.num_valid"] = m.num_valid;
    v["method.num_failed"] = m.num_failed;
    for (std::size_t k = 0; k < c.keys.size(); ++k) {
      if (m.mean[k]) v["method.mean." + std::string(c.keys[k].key)] = *m.mean[k];
      if (m.median[k]) v["method.median." + std::string(c.keys[k].key)] = *m.median[k];
    }
  }
  return out;
}

// The cells of the comparison whose value moved, by the key's direction.
void diff_comparison_cells(const Comparison& b, const Comparison& c, std::vector<DiffCellChange>& out) {
  std::map<std::string, const ComparisonRow*> rows;
  for (const ComparisonRow& row : b.rows) rows[row.model] = &row;
  for (const ComparisonRow& row : c.rows) {
    const auto base = rows.find(row.model);
    if (base == rows.end()) continue;
    for (const auto& [column, entry] : row.cells) {
      const auto other = base->second->cells.find(column);
      if (other == base->second->cells.end()) continue;
      for (const ComparisonKey& key : c.keys) {
        if (key.direction == 0) continue;
        // A headline key or a surface count (issue 47): comparison_value.
        const std::optional<double> bv = comparison_value(*other->second, key.key),
                                    cv = comparison_value(*entry, key.key);
        if (!bv || !cv || *bv == *cv || !std::isfinite(*bv) || !std::isfinite(*cv)) continue;
        out.push_back({row.model, column.first, column.second, std::string(key.key), *bv, *cv,
                       key.direction > 0 ? *cv > *bv : *cv < *bv});
      }
    }
  }
}

}  // namespace

DiffGate parse_diff_gate(std::string_view text) {
  DiffGate gate;
  const auto at = text.find("baseline");
  if (at == std::string_view::npos) {
    gate.rule = parse_gate_rule(text);
    return gate;
  }
  // PATH OP baseline[+-NUMBER]: parse "PATH OP 0" for the path and operator.
  gate.rule = parse_gate_rule(std::string(text.substr(0, at)) + "0");
  gate.rule.text = std::string(trim(text, " \t"));
  gate.is_relative = true;
  const std::string_view offset = trim(text.substr(at + 8), " \t");
  gate.rule.threshold = 0;
  if (!offset.empty()) {
    std::string_view number = offset;
    const bool is_negative = number.front() == '-';
    if (number.front() != '-' && number.front() != '+')
      throw ValueError("--gate '" + std::string(text) + "': expected baseline, baseline+NUMBER or baseline-NUMBER");
    number = trim(number.substr(1), " \t");
    double value = 0;
    const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), value);
    if (error != std::errc() || end != number.data() + number.size() || !std::isfinite(value))
      throw ValueError("--gate '" + std::string(text) + "': '" + std::string(number) + "' is not a number");
    gate.rule.threshold = is_negative ? -value : value;
  }
  return gate;
}

DiffResult diff_reports(std::string_view baseline_text, std::string_view current_text,
                        const std::vector<DiffGate>& gates, const fs::path& baseline_dir, const fs::path& current_dir) {
  const json base = parse_or_throw(baseline_text, "BASELINE");
  const json cur = parse_or_throw(current_text, "CURRENT");
  DiffResult result;
  result.is_index = is_index(base);
  if (result.is_index != is_index(cur))
    throw InputError("BASELINE and CURRENT must both be report.json or both be index.json");
  std::vector<int> evaluated(gates.size(), 0);

  auto evaluate = [&](const std::string& mesh, std::size_t g, std::optional<double> b, std::optional<double> c,
                      bool current_failed) {
    const DiffGate& gate = gates[g];
    DiffGateResult r;
    r.mesh = mesh;
    r.rule = gate.rule.text;
    if (current_failed) {
      r.passed = false;  // a mesh that analysed in the baseline and fails now is a regression
      ++evaluated[g];
      result.gates.push_back(r);
      return;
    }
    if (!c || (gate.is_relative && !b)) return;  // the key is null here (e.g. no reference)
    ++evaluated[g];
    r.value = c;
    r.baseline = b;
    r.threshold = gate.is_relative ? *b + gate.rule.threshold : gate.rule.threshold;
    r.passed = gate_holds(*c, gate.rule.op, r.threshold);
    result.gates.push_back(r);
  };

  if (!result.is_index) {
    result.side_by_side = side_by_side_tables(base, cur);
    std::map<std::string, double> b, c;
    std::set<std::string> in_base, in_cur;
    flatten(base, "", b, in_base);
    flatten(cur, "", c, in_cur);
    std::set<std::string> keys;
    for (const auto& [k, v] : b) keys.insert(k);
    for (const auto& [k, v] : c) keys.insert(k);
    for (const std::string& k : keys) {
      const auto bi = b.find(k);
      const auto ci = c.find(k);
      const std::optional<double> bv = bi == b.end() ? std::nullopt : std::optional<double>(bi->second);
      const std::optional<double> cv = ci == c.end() ? std::nullopt : std::optional<double>(ci->second);
      file_difference(result, "", k, bv, cv, has_path(in_base, k), has_path(in_cur, k));
    }
    for (std::size_t g = 0; g < gates.size(); ++g)
      evaluate("", g, lookup(base, gates[g].rule.path), lookup(cur, gates[g].rule.path), false);
  } else {
    std::map<std::string, IndexedMesh> b, c;
    for (const json& m : base["meshes"])
      b[string_or_empty(m, "path")] = {&m, baseline_dir / string_or_empty(m, "bundle") / "report.json", std::nullopt};
    for (const json& m : cur["meshes"])
      c[string_or_empty(m, "path")] = {&m, current_dir / string_or_empty(m, "bundle") / "report.json", std::nullopt};
    for (auto& [path, m] : b)
      if (!c.count(path)) result.vanished_meshes.push_back(path);
    for (auto& [path, cm] : c) {
      const auto bi = b.find(path);
      const bool current_failed = string_or_empty(*cm.entry, "status") == "failed";
      if (bi == b.end()) {
        result.new_meshes.push_back(path);
        for (std::size_t g = 0; g < gates.size(); ++g)
          if (!gates[g].is_relative && !is_method_gate(gates[g]))
            evaluate(path, g, std::nullopt, current_failed ? std::nullopt : mesh_value(cm, gates[g].rule.path), false);
        continue;
      }
      IndexedMesh& bm = bi->second;
      const std::string bs = string_or_empty(*bm.entry, "status"), cs = string_or_empty(*cm.entry, "status");
      if (bs != cs) result.status_changes.push_back({path, bs, cs});
      const json& bh = (*bm.entry)["headline"];
      const json& ch = (*cm.entry)["headline"];
      if (bh.is_object() && ch.is_object()) {
        std::set<std::string> keys;
        for (auto it = bh.begin(); it != bh.end(); ++it) keys.insert(it.key());
        for (auto it = ch.begin(); it != ch.end(); ++it) keys.insert(it.key());
        for (const std::string& k : keys) {
          file_difference(result, path, k, lookup(bh, {k}), lookup(ch, {k}), bh.contains(k), ch.contains(k));
        }
      }
      const bool baseline_failed = bs == "failed";
      for (std::size_t g = 0; g < gates.size(); ++g) {
        if (is_method_gate(gates[g])) continue;
        if (current_failed) {
          if (!baseline_failed) evaluate(path, g, std::nullopt, std::nullopt, true);
          continue;
        }
        evaluate(path, g, baseline_failed ? std::nullopt : mesh_value(bm, gates[g].rule.path),
                 mesh_value(cm, gates[g].rule.path), false);
      }
    }
  }
  if (result.is_index) {
    // The methods compared: cells that moved, and the per-method gates.
    const std::vector<BatchEntry> be = parse_batch_index_json(baseline_text, "BASELINE");
    const std::vector<BatchEntry> ce = parse_batch_index_json(current_text, "CURRENT");
    if (has_comparison(be) && has_comparison(ce)) {
      const Comparison bc = build_comparison(be, comparison_keys()), cc = build_comparison(ce, comparison_keys());
      diff_comparison_cells(bc, cc, result.cells);
      const auto bm = method_values(bc), cm = method_values(cc);
      for (const auto& [label, values] : cm) {
        const auto base = bm.find(label);
        for (std::size_t g = 0; g < gates.size(); ++g) {
          if (!is_method_gate(gates[g])) continue;
          auto value = [&](const std::map<std::string, double>& v) {
            const auto it = v.find(join(gates[g].rule.path));
            return it == v.end() ? std::nullopt : std::optional<double>(it->second);
          };
          evaluate("method " + label, g, base == bm.end() ? std::nullopt : value(base->second), value(values), false);
        }
      }
    }
  }
  for (std::size_t g = 0; g < gates.size(); ++g)
    if (evaluated[g] == 0)
      throw ValueError("--gate '" + gates[g].rule.text + "': '" + join(gates[g].rule.path) +
                       "' is a number in neither report (check the key; relative rules need it in both)");
  for (const DiffGateResult& r : result.gates) result.passed = result.passed && r.passed;
  return result;
}

namespace {

// diff_markdown's parts: fixed text, and rows that may be left out to keep
// under the size cap, each with a rank (lower: kept first) and a severity
// (higher: kept first within a rank).
struct MarkdownRow {
  int section = 0;  // index into the sections below
  int rank = 0;
  double severity = 0;
  std::string text;
};

// kSideBySide + i: the i-th side-by-side table (at most two).
enum MarkdownSection { kGates, kSideBySide, kSideBySide2, kMeshes, kChanged, kCells, kKeys, kNumSections };

// Relative size of a change: |current - baseline| / max(|baseline|, |current|);
// 1 for a value that appeared or vanished.
double relative_change(std::optional<double> baseline, std::optional<double> current) {
  if (!baseline || !current) return 1;
  const double scale = std::max(std::fabs(*baseline), std::fabs(*current));
  if (!(scale > 0) || !std::isfinite(scale)) return 0;
  return std::fabs(*current - *baseline) / scale;
}

// The distinct keys of `values` in key order, each with the number of
// meshes (entries) that have it.
std::map<std::string, std::size_t> keys_with_meshes(const std::vector<DiffValue>& values) {
  std::map<std::string, std::size_t> keys;
  for (const DiffValue& v : values) ++keys[v.key];
  return keys;
}

// +1 when higher is better, -1 lower, 0 unknown (the comparison keys' directions).
int key_direction(std::string_view key) {
  for (const ComparisonKey& k : comparison_keys())
    if (k.key == key) return k.direction;
  return 0;
}

std::vector<MarkdownRow> markdown_rows(const DiffResult& d) {
  std::vector<MarkdownRow> rows;
  for (const DiffGateResult& g : d.gates)
    rows.push_back({kGates, g.passed ? 5 : 0, 0,
                    std::string("| ") + (g.passed ? "✅" : "❌") + " | `" + g.rule + "` |" +
                        (d.is_index ? " " + markdown_escape(g.mesh) + " |" : "") + " " +
                        (g.value ? show(g.value) : "failed") + " | " + show(g.baseline) + " | " +
                        (g.value ? format_double(g.threshold) : "–") + " |\n"});
  // The side-by-side rows are kept before any change row (rank 1).
  for (std::size_t t = 0; t < d.side_by_side.size() && t < 2; ++t)
    for (const CompareTableRow& r : d.side_by_side[t].rows)
      rows.push_back({kSideBySide + static_cast<int>(t), 1, 0,
                      "| " + r.label + " | " + r.mine + " | " + r.theirs + " | " +
                          (r.is_worse ? "**" + r.difference + "**" : r.difference) + " |\n"});
  for (const std::string& m : d.new_meshes) rows.push_back({kMeshes, 3, 0, "- new mesh: " + markdown_escape(m) + "\n"});
  for (const std::string& m : d.vanished_meshes)
    rows.push_back({kMeshes, 1, 0, "- vanished mesh: " + markdown_escape(m) + "\n"});
  for (const DiffStatusChange& s : d.status_changes)
    rows.push_back({kMeshes, 1, s.current == "failed" ? 1.0 : 0.0,
                    "- " + markdown_escape(s.mesh) + ": status " + markdown_escape(s.baseline) + " → " +
                        markdown_escape(s.current) + "\n"});
  for (const DiffValue& v : d.changed) {
    const int direction = key_direction(v.key);
    int rank = 3;
    if (direction != 0 && v.baseline && v.current)
      rank = (direction > 0 ? *v.current < *v.baseline : *v.current > *v.baseline) ? 2 : 4;
    rows.push_back({kChanged, rank, relative_change(v.baseline, v.current),
                    "| " + (d.is_index ? markdown_escape(v.mesh) + " | " : "") + "`" + v.key + "` | " +
                        show(v.baseline) + " | " + show(v.current) + " | " + show_delta(v) + " |\n"});
  }
  // Keys on one side only, once each (over the meshes of two indexes): what
  // an earlier HQView did not write is not a change of value; left out first.
  for (const auto& [what, keys] : {std::pair{"added", &d.added}, std::pair{"removed", &d.removed}})
    for (const auto& [key, meshes] : keys_with_meshes(*keys))
      rows.push_back({kKeys, 6, 0,
                      std::string("- ") + what + ": `" + key + "`" +
                          (d.is_index ? " (" + std::to_string(meshes) + (meshes == 1 ? " mesh)" : " meshes)")
                                      : std::string()) +
                          "\n"});
  for (const DiffCellChange& c : d.cells)
    rows.push_back({kCells, c.is_better ? 4 : 2, relative_change(c.baseline, c.current),
                    std::string("| ") + (c.is_better ? "better" : "**worse**") + " | " + markdown_escape(c.model) +
                        " | " + markdown_escape(c.method + (c.variant.empty() ? "" : " · " + c.variant)) + " | `" +
                        c.key + "` | " + format_double(c.baseline) + " | " + format_double(c.current) + " |\n"});
  return rows;
}

// The text around each section's rows (empty when the section has none kept).
std::string section_head(int section, const DiffResult& d) {
  const bool is_index = d.is_index;
  switch (section) {
    case kSideBySide:
    case kSideBySide2:
    {
      const DiffSideBySide& t = d.side_by_side.at(static_cast<std::size_t>(section - kSideBySide));
      return "\n### " + t.what + ": " + markdown_escape(t.baseline_name) + " → " + markdown_escape(t.current_name) +
             "\n\n| | baseline | current | difference |\n|---|---:|---:|---:|\n";
    }
    case kGates:
      return "| | rule |" + std::string(is_index ? " mesh |" : "") + " value | baseline | threshold |\n|---|---|" +
             (is_index ? "---|" : "") + "--:|--:|--:|\n";
    case kChanged:
      return "\n| " + std::string(is_index ? "mesh | " : "") + "key | baseline | current | change |\n|" +
             (is_index ? "---|" : "") + "---|--:|--:|--:|\n";
    case kCells:
      return "\n### Methods compared: cells that moved\n\n| | model | method | key | baseline | current |\n"
             "|---|---|---|---|--:|--:|\n";
    case kKeys:
      return "\n### Keys on one side only\n\nWritten by a different HQView version (report.json keys in "
             "docs/contract.md, changes in CHANGELOG.md): not changes of value.\n\n";
    default:
      return "";
  }
}

std::string section_tail(int section) {
  if (section == kSideBySide || section == kSideBySide2)
    return "\nDifference = current - baseline (bold: current is worse).\n";
  return section == kGates ? "\n" : "";
}

}  // namespace

std::string diff_markdown(const DiffResult& d, std::size_t max_chars) {
  std::string head = std::string(kDiffMarkdownMarker) + "\n## HQView diff: ";
  head += d.passed ? "gates passed" : "**gates failed**";
  head += ", " + std::to_string(d.changed.size()) + " values changed";
  const std::size_t added = keys_with_meshes(d.added).size(), removed = keys_with_meshes(d.removed).size();
  if (added > 0) head += ", " + std::to_string(added) + (added == 1 ? " key added" : " keys added");
  if (removed > 0) head += ", " + std::to_string(removed) + (removed == 1 ? " key removed" : " keys removed");
  if (d.is_index)
    head += ", " + std::to_string(d.new_meshes.size()) + " new, " + std::to_string(d.vanished_meshes.size()) +
            " vanished meshes";
  head += "\n\n";
  const std::vector<MarkdownRow> rows = markdown_rows(d);
  std::vector<char> keep(rows.size(), 1);
  auto render = [&](std::size_t left_out) {
    std::string md = head;
    for (int s = 0; s < kNumSections; ++s) {
      bool any = false;
      for (std::size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].section != s || !keep[i]) continue;
        if (!any) md += section_head(s, d);
        any = true;
        md += rows[i].text;
      }
      if (any) md += section_tail(s);
    }
    if (left_out > 0)
      md += "\n_" + std::to_string(left_out) + " of " + std::to_string(rows.size()) +
            " rows left out to stay under " + std::to_string(max_chars) +
            " characters (passed gates, improvements and the smallest changes first); `hqview diff` without "
            "`--markdown` prints every one._\n";
    return md;
  };
  std::string full = render(0);
  if (full.size() <= max_chars) return full;

  // Over the cap: the rows by importance, each added while the text (with
  // its section's head and the note saying how many were left out) fits.
  std::vector<std::size_t> order(rows.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (rows[a].rank != rows[b].rank) return rows[a].rank < rows[b].rank;
    return rows[a].severity > rows[b].severity;
  });
  std::fill(keep.begin(), keep.end(), 0);
  const std::size_t note = render(rows.size()).size() - render(0).size() + 2 * 20;  // the note, digits to spare
  std::size_t size = head.size() + note;
  std::vector<char> section_open(kNumSections, 0);
  std::size_t left_out = rows.size();
  for (std::size_t i : order) {
    const int s = rows[i].section;
    const std::size_t extra =
        rows[i].text.size() +
        (section_open[s] ? 0 : section_head(s, d).size() + section_tail(s).size());
    if (size + extra > max_chars) continue;
    size += extra;
    section_open[s] = 1;
    keep[i] = 1;
    --left_out;
  }
  return render(left_out);
}

namespace {

// Characters on a terminal: UTF-8 code points (the tables' text is ASCII,
// "–" and "→").
std::size_t text_width(std::string_view s) {
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

std::string padded(const std::string& s, std::size_t width, bool right) {
  const std::string pad(width > text_width(s) ? width - text_width(s) : 0, ' ');
  return right ? pad + s : s + pad;
}

// A side-by-side table as aligned columns: label, baseline, current,
// difference (current - baseline), "worse" where current is worse.
std::string side_by_side_text(const DiffSideBySide& t) {
  std::size_t w[4] = {0, text_width("baseline"), text_width("current"), text_width("difference")};
  for (const CompareTableRow& r : t.rows) {
    w[0] = std::max(w[0], text_width(r.label));
    w[1] = std::max(w[1], text_width(r.mine));
    w[2] = std::max(w[2], text_width(r.theirs));
    w[3] = std::max(w[3], text_width(r.difference));
  }
  std::string out = t.what + ": " + t.baseline_name + " → " + t.current_name + "\n  " + padded("", w[0], false) + "  " + padded("baseline", w[1], true) + "  " +
                    padded("current", w[2], true) + "  " + padded("difference", w[3], true) + "\n";
  for (const CompareTableRow& r : t.rows) {
    std::string line = "  " + padded(r.label, w[0], false) + "  " + padded(r.mine, w[1], true) + "  " +
                       padded(r.theirs, w[2], true) + "  " + padded(r.difference, w[3], true) +
                       (r.is_worse ? "  worse" : "");
    out += line + "\n";
  }
  // The rows' quantities, where their names are ambiguous (key_quantity.h).
  const std::string plural = cells_plural(t.cells);
  out += "  (scaled Jacobian: " + key_quantity("quality.scaled_jacobian.min", t.cells) + "; degenerate " + plural +
         ": " + key_quantity("quality.num_degenerate", t.cells) + ")\n";
  return out + "\n";
}

}  // namespace

std::string diff_text(const DiffResult& d) {
  std::string out;
  for (const DiffSideBySide& t : d.side_by_side) out += side_by_side_text(t);
  // The changed keys' words follow the first mesh's cells (an index's
  // meshes may differ: they keep the hex words).
  const MeshCells cells = d.side_by_side.empty() ? MeshCells::hex : d.side_by_side.front().cells;
  for (const std::string& m : d.new_meshes) out += "new mesh: " + m + "\n";
  for (const std::string& m : d.vanished_meshes) out += "vanished mesh: " + m + "\n";
  for (const DiffStatusChange& s : d.status_changes)
    out += s.mesh + ": status " + s.baseline + " -> " + s.current + "\n";
  for (const DiffValue& v : d.changed)
    out += (v.mesh.empty() ? "" : v.mesh + ": ") + v.key + ": " + show(v.baseline) + " -> " + show(v.current) + " (" +
           show_delta(v) + ")" + (key_quantity(v.key, cells).empty() ? "" : "  [" + key_quantity(v.key, cells) + "]") +
           "\n";
  // Keys on one side only: once per key over an index's meshes; with the
  // value in two report.json.
  for (const auto& [what, values] : {std::pair{"added key: ", &d.added}, std::pair{"removed key: ", &d.removed}}) {
    if (d.is_index) {
      for (const auto& [key, meshes] : keys_with_meshes(*values))
        out += what + key + " (" + std::to_string(meshes) + (meshes == 1 ? " mesh)" : " meshes)") + "\n";
    } else {
      for (const DiffValue& v : *values) out += what + v.key + " = " + show(v.current ? v.current : v.baseline) + "\n";
    }
  }
  for (const DiffCellChange& c : d.cells)
    out += std::string(c.is_better ? "better: " : "worse: ") + c.model + " · " + c.method +
           (c.variant.empty() ? "" : " · " + c.variant) + ": " + c.key + ": " + format_double(c.baseline) + " -> " +
           format_double(c.current) + "\n";
  for (const DiffGateResult& g : d.gates)
    out += std::string("gate ") + (g.passed ? "passed" : "FAILED") + ": " + g.rule +
           (g.mesh.empty() ? "" : " [" + g.mesh + "]") + " (value " + (g.value ? show(g.value) : "none: mesh failed") +
           (g.value ? ", threshold " + format_double(g.threshold) : "") + ")\n";
  return out;
}

std::vector<JunitCase> diff_junit_cases(const DiffResult& diff) {
  std::vector<JunitCase> cases;
  for (const DiffGateResult& g : diff.gates) {
    JunitCase c{"hqview.diff", g.mesh.empty() ? g.rule : g.mesh + ": " + g.rule, JunitCase::Outcome::passed, "", ""};
    if (!g.passed) {
      c.outcome = JunitCase::Outcome::failed;
      const std::string value = g.value ? format_double(*g.value) : std::string("none: the mesh failed");
      c.message = "gate failed: " + g.rule + " (value " + value + ", threshold " + format_double(g.threshold) + ")";
      c.text = (g.mesh.empty() ? std::string() : "mesh: " + g.mesh + "\n") + "rule: " + g.rule + "\nvalue: " + value +
               "\nthreshold: " + format_double(g.threshold) + "\n" +
               (g.baseline ? "baseline: " + format_double(*g.baseline) + "\n" : std::string());
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace hq
