// The collection `batch` reads: a directory tree, a CSV or JSON manifest,
// or HexaLab's published datasets/index.json; and the model and variant a
// mesh path stands for (batch.h declares them all).
#include <algorithm>
#include <map>
#include <set>
#include <nlohmann/json.hpp>
#include <sstream>

#include "hqview/core/error.h"
#include "hqview/core/text.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/pipeline/batch.h"
#include "hqview/render/upright.h"

namespace hq {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Splits one CSV line; fields may be double-quoted ("" is a quote).
std::vector<std::string> split_csv(std::string_view line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  for (std::string& f : fields) f = std::string(trim(f, " \t\r"));
  return fields;
}

fs::path resolve(const fs::path& base_dir, const std::string& name) {
  if (name.empty()) return {};
  const fs::path p(name);
  return p.is_absolute() ? p : base_dir / p;
}

// The index key of a manifest row: the mesh as written, normalised, without
// leading "../" or root (it names the bundle directory under OUT).
std::string manifest_key(const std::string& mesh) {
  fs::path p = fs::path(mesh).lexically_normal();
  fs::path key;
  for (const fs::path& part : p.relative_path())
    if (part != ".." && part != ".") key /= part;
  return key.generic_string();
}

}  // namespace

bool is_hex_mesh_extension(const fs::path& path) { return has_hex_mesh_extension(path); }

namespace {

bool is_separator(char c) { return c == '_' || c == '-' || c == '.'; }

bool is_variant_suffix(std::string_view word) {
  static constexpr std::string_view kWords[] = {"in", "out", "padded", "opt", "graded", "coarse", "fine", "final"};
  if (std::find(std::begin(kWords), std::end(kWords), word) != std::end(kWords)) return true;
  return !word.empty() && std::all_of(word.begin(), word.end(), [](char c) { return c >= '0' && c <= '9'; });
}

bool is_generic_stem(std::string_view stem) {
  static constexpr std::string_view kWords[] = {"hex",    "mesh",   "model",  "polycube",
                                                "volume", "output", "result", "input"};
  return stem.empty() || std::find(std::begin(kWords), std::end(kWords), stem) != std::end(kWords);
}

}  // namespace

ModelAndVariant model_of_path(const fs::path& mesh) {
  const std::string stem = lower(mesh.stem().string());
  ModelAndVariant mv{stem, ""};
  // A hex marker: "<model>_hex" or "<model>_hex<sep><variant>".
  for (std::size_t at = stem.find("hex"); at != std::string::npos; at = stem.find("hex", at + 1)) {
    const std::size_t end = at + 3;
    if (at == 0 || !is_separator(stem[at - 1]) || (end < stem.size() && !is_separator(stem[end]))) continue;
    mv.model = stem.substr(0, at - 1);
    mv.variant = end < stem.size() ? stem.substr(end + 1) : "";
    break;
  }
  if (mv.variant.empty() && mv.model == stem) {
    // Trailing variant suffixes, last first.
    while (true) {
      const std::size_t cut = mv.model.find_last_of("_-");
      if (cut == std::string::npos || cut == 0 || !is_variant_suffix(std::string_view(mv.model).substr(cut + 1))) break;
      mv.variant = mv.model.substr(cut + 1) + (mv.variant.empty() ? "" : "_" + mv.variant);
      mv.model.resize(cut);
    }
  }
  if (is_generic_stem(mv.model)) {
    const std::string parent = lower(mesh.parent_path().filename().string());
    mv.model = parent.empty() ? stem : parent;
    mv.variant = stem == "hex" || stem == "mesh" || parent.empty() ? "" : stem;
  }
  return mv;
}

std::string strip_trailing_commas(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) out += text[++i];
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    if (c == ',') {
      std::size_t j = i + 1;
      while (j < text.size() && (text[j] == ' ' || text[j] == '\t' || text[j] == '\r' || text[j] == '\n')) ++j;
      if (j < text.size() && (text[j] == '}' || text[j] == ']')) continue;  // a trailing comma: dropped
    }
    out += c;
  }
  return out;
}

std::vector<BatchInput> parse_hexalab_index(const json& index, const std::string& name, const fs::path& base_dir) {
  std::vector<BatchInput> inputs;
  const json& sources = index.at("sources");
  if (!sources.is_array()) throw ParseError(name, 0, "'sources' must be an array");
  int number = 0;
  for (const json& source : sources) {
    ++number;
    const std::string where = "source " + std::to_string(number) + ": ";
    if (!source.is_object()) throw ParseError(name, 0, where + "expected an object");
    auto text = [&](const json& object, const char* key) {
      if (!object.contains(key) || object[key].is_null()) return std::string();
      if (object[key].is_string()) return object[key].get<std::string>();
      if (object[key].is_number_integer()) return std::to_string(object[key].get<long long>());  // a year as a number
      throw ParseError(name, 0, where + "'" + key + "' must be a string");
    };
    const std::string folder = text(source, "path");
    std::string label = text(source, "label");
    if (label.empty()) label = folder;
    PaperInfo paper;
    if (source.contains("paper") && source["paper"].is_object()) {
      const json& p = source["paper"];
      paper.title = text(p, "title");
      paper.year = text(p, "year");
      paper.doi = text(p, "DOI").empty() ? text(p, "doi") : text(p, "DOI");
    }
    if (!source.contains("data") || !source["data"].is_array())
      throw ParseError(name, 0, where + "no 'data' array of mesh paths");
    for (const json& item : source["data"]) {
      if (!item.is_string()) throw ParseError(name, 0, where + "every 'data' entry must be a path string");
      const std::string relative = (fs::path(folder) / item.get<std::string>()).generic_string();
      BatchInput input;
      input.path = manifest_key(relative);
      input.mesh_file = resolve(base_dir, relative);
      input.label = label;
      const ModelAndVariant mv = model_of_path(input.mesh_file);
      input.model = mv.model;
      input.variant = mv.variant;
      input.paper = paper;
      if (!is_hex_mesh_extension(input.mesh_file))
        input.skip_reason = "not a hex mesh file (extension '" + input.mesh_file.extension().string() + "')";
      inputs.push_back(std::move(input));
    }
  }
  return inputs;
}

std::vector<BatchInput> collect_directory(const fs::path& dir) {
  std::vector<BatchInput> inputs;
  std::error_code ec;
  fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
  if (ec) throw InputError(dir.string() + ": cannot list the directory: " + ec.message());
  for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) throw InputError(dir.string() + ": cannot list the directory: " + ec.message());
    const fs::path& file = it->path();
    if (file.filename().string().starts_with(".")) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;  // hidden files and HQView's temporary siblings
    }
    if (it->is_directory() && (fs::exists(file / "report.json") || fs::exists(file / "index.json") ||
                                 fs::exists(file / kBatchMarkerFile))) {
      // HQView's own outputs (a bundle holds data/annotated.vtu): an output
      // directory inside the collection is not analysed on the next run.
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file() || !(is_hex_mesh_extension(file) || has_polygon_mesh_extension(file))) continue;
    BatchInput input;
    input.path = file.lexically_relative(dir).generic_string();
    input.mesh_file = file;
    const ModelAndVariant mv = model_of_path(input.path);
    input.model = mv.model;
    input.variant = mv.variant;
    inputs.push_back(std::move(input));
  }
  // Polygon files (.obj .off .ply) are surface meshes, but in a folder that
  // also holds volume-format files they are taken for those meshes'
  // reference surfaces (HexaLab's layout: bunny.off beside bunny_in.mesh):
  // listed, not analysed (skipped rows, so the index names them).
  std::set<fs::path> volume_folders;
  for (const BatchInput& input : inputs)
    if (is_hex_mesh_extension(input.mesh_file)) volume_folders.insert(input.mesh_file.parent_path());
  for (BatchInput& input : inputs)
    if (has_polygon_mesh_extension(input.mesh_file) && volume_folders.count(input.mesh_file.parent_path()) != 0)
      input.skip_reason =
          "a surface file beside volume meshes, taken for their reference surface; a manifest can analyse it";
  std::sort(inputs.begin(), inputs.end(), [](const BatchInput& a, const BatchInput& b) { return a.path < b.path; });
  return inputs;
}

std::vector<BatchInput> parse_manifest(std::string_view text, const std::string& name, const fs::path& base_dir,
                                       bool is_json) {
  std::vector<BatchInput> inputs;
  std::vector<int> lines;
  auto where = [&](int line) { return is_json ? "row " + std::to_string(line) + ": " : std::string(); };
  auto add = [&](int line, const std::string& mesh, const std::string& reference, const std::string& compare,
                 const std::string& label, const std::string& model, const std::string& variant,
                 const std::string& up) {
    // JSON rows have no line numbers: messages name the row instead.
    if (mesh.empty()) throw ParseError(name, is_json ? 0 : line, where(line) + "no mesh in this row");
    const bool up_auto = lower(up) == "auto";
    const std::optional<Vec3> axis = parse_up_axis(lower(up));
    if (!up.empty() && !axis && !up_auto)
      throw ParseError(name, is_json ? 0 : line,
                       where(line) + "up: expected one of +x -x +y -y +z -z auto (or empty), got '" + up + "'");
    BatchInput input;
    input.path = manifest_key(mesh);
    input.mesh_file = resolve(base_dir, mesh);
    input.reference_file = resolve(base_dir, reference);
    input.compare_file = resolve(base_dir, compare);
    input.label = label;
    // The manifest's model and variant win; a model without a variant names
    // one mesh of it, so the variant is derived only with the model.
    const ModelAndVariant mv = model_of_path(mesh);
    input.model = model.empty() ? mv.model : model;
    input.variant = !variant.empty() || !model.empty() ? variant : mv.variant;
    input.up = up.empty() ? std::string() : up_auto ? std::string("auto") : up_axis_name(*axis);
    inputs.push_back(std::move(input));
    lines.push_back(line);
  };
  if (is_json) {
    json rows = json::parse(text, nullptr, false);
    if (rows.is_discarded()) {
      // HexaLab's published index has a trailing comma: accepted for a
      // {"sources": ...} document only.
      const json relaxed = json::parse(strip_trailing_commas(text), nullptr, false);
      if (!relaxed.is_discarded() && relaxed.is_object() && relaxed.contains("sources")) {
        rows = relaxed;
      } else {
        try {
          rows = json::parse(text);  // throws: the strict parser's message
        } catch (const json::parse_error& e) {
          throw ParseError(name, 0, std::string("not valid JSON: ") + e.what());
        }
      }
    }
    if (rows.is_object() && rows.contains("sources")) {
      std::vector<BatchInput> hexalab = parse_hexalab_index(rows, name, base_dir);
      for (BatchInput& input : hexalab) {
        inputs.push_back(std::move(input));
        lines.push_back(static_cast<int>(lines.size()) + 1);
      }
      rows = json::array();
    }
    if (rows.is_object() && rows.contains("meshes")) rows = rows["meshes"];
    if (!rows.is_array()) throw ParseError(name, 0, "expected an array of rows (or {\"meshes\": [...]})");
    int row_number = 0;
    for (const json& row : rows) {
      ++row_number;
      auto field = [&](const char* key) {
        if (!row.contains(key) || row[key].is_null()) return std::string();
        if (!row[key].is_string()) throw ParseError(name, 0, where(row_number) + "'" + key + "' must be a string");
        return row[key].get<std::string>();
      };
      if (row.is_string()) {
        add(row_number, row.get<std::string>(), "", "", "", "", "", "");
      } else if (row.is_object()) {
        std::string label = field("label");
        if (label.empty()) label = field("method");
        add(row_number, field("mesh"), field("reference"), field("compare"), label, field("model"), field("variant"),
            field("up"));
      } else {
        throw ParseError(name, 0, where(row_number) + "expected an object or a string");
      }
    }
  } else {
    std::istringstream in{std::string(text)};
    std::string line;
    int line_number = 0;
    std::map<std::string, std::size_t> columns;
    while (std::getline(in, line)) {
      ++line_number;
      if (trim(line, " \t\r").empty() || trim(line, " \t\r").starts_with("#")) continue;
      std::vector<std::string> fields = split_csv(line);
      if (columns.empty()) {
        for (std::size_t i = 0; i < fields.size(); ++i) {
          std::string key = lower(fields[i]);
          if (key == "method") key = "label";
          if (key != "mesh" && key != "reference" && key != "compare" && key != "label" && key != "model" &&
              key != "variant" && key != "up")
            throw ParseError(name, line_number,
                             "unknown column '" + fields[i] +
                                 "' (expected mesh, reference, compare, label/method, model, variant, up)");
          if (columns.count(key)) throw ParseError(name, line_number, "column '" + key + "' appears twice");
          columns[key] = i;
        }
        if (!columns.count("mesh")) throw ParseError(name, line_number, "the header has no 'mesh' column");
        continue;
      }
      if (fields.size() > columns.size())
        throw ParseError(
            name, line_number,
            "expected at most " + std::to_string(columns.size()) + " fields, got " + std::to_string(fields.size()));
      auto field = [&](const char* key) {
        const auto it = columns.find(key);
        return it != columns.end() && it->second < fields.size() ? fields[it->second] : std::string();
      };
      add(line_number, field("mesh"), field("reference"), field("compare"), field("label"), field("model"),
          field("variant"), field("up"));
    }
  }
  std::map<std::string, int> seen;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const auto [it, is_new] = seen.emplace(inputs[i].path, lines[i]);
    if (!is_new)
      throw ParseError(name, is_json ? 0 : lines[i],
                       where(lines[i]) + "mesh '" + inputs[i].path + "' already listed (" +
                           (is_json ? "row " : "line ") + std::to_string(it->second) + ")");
  }
  return inputs;
}

std::vector<BatchInput> read_manifest(const fs::path& file) {
  const std::string ext = lower(file.extension().string());
  if (ext != ".csv" && ext != ".json")
    throw ValueError(file.string() + ": a batch input is a directory or a manifest (.csv or .json)");
  return parse_manifest(read_file_bytes(file), file.string(), file.parent_path(), ext == ".json");
}

std::vector<BatchInput> collect_batch_inputs(const fs::path& dir_or_manifest) {
  std::error_code ec;
  if (fs::is_directory(dir_or_manifest, ec)) return collect_directory(dir_or_manifest);
  if (!fs::exists(dir_or_manifest, ec)) throw InputError(dir_or_manifest.string() + ": no such file or directory");
  return read_manifest(dir_or_manifest);
}

}  // namespace hq
