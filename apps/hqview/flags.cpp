#include "flags.h"

#include <charconv>
#include <cmath>
#include <exception>

#include "hqview/core/error.h"
#include "hqview/core/error_kind.h"
#include "hqview/core/stop.h"
#include "hqview/core/text.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/render/upright.h"
#include "hqview/views/views.h"

namespace hqcli {

int exit_code_of_current_exception() {
  try {
    throw;
  } catch (const UsageError&) {
    return kUsage;
  } catch (const hq::Interrupted& e) {
    return 128 + e.signal();
  } catch (...) {
    switch (hq::kind_of_current_exception()) {
      case hq::ErrorKind::usage: return kUsage;
      case hq::ErrorKind::input: return kInput;
      case hq::ErrorKind::environment: return kEnvironment;
      case hq::ErrorKind::interrupted:  // caught above
      case hq::ErrorKind::internal: break;
    }
    return kInternal;
  }
}

ExitCode batch_exit_code(const std::vector<hq::BatchEntry>& entries) {
  bool any_gate = false, any_failed = false, any_environment = false;
  for (const hq::BatchEntry& e : entries) {
    any_failed = any_failed || e.status == hq::BatchStatus::failed;
    any_environment = any_environment || (e.status == hq::BatchStatus::failed && e.environment_failure);
    any_gate = any_gate || e.status == hq::BatchStatus::gate_failed;
  }
  if (any_environment) return kEnvironment;
  if (any_failed) return kInput;
  return any_gate ? kGateFailed : kOk;
}

std::optional<double> parse_finite(std::string_view text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

void parse_size(const std::string& size, int& width, int& height) {
  const auto x = size.find('x');
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    std::size_t used = 0;
    width = std::stoi(size.substr(0, x), &used);
    if (used != x) throw std::invalid_argument("width");
    height = std::stoi(size.substr(x + 1), &used);
    if (used != size.size() - x - 1) throw std::invalid_argument("height");
  } catch (const std::exception&) {
    throw UsageError("--size: expected WIDTHxHEIGHT, e.g. 1600x1200, got '" + size + "'");
  }
  if (width < 64 || height < 64 || width > 8192 || height > 8192)
    throw UsageError("--size: width and height must be between 64 and 8192, got '" + size + "'");
}

hq::Vec3 parse_up(const std::string& text) {
  if (const std::optional<hq::Vec3> up = hq::parse_up_axis(text)) return *up;
  throw UsageError("--up: expected one of +x -x +y -y +z -z, got '" + text + "'");
}

void parse_rmax(const std::string& text, hq::GlyphOptions& glyphs) {
  std::string_view number = text;
  const bool is_relative = !number.empty() && number.back() == 'x';
  if (is_relative) number.remove_suffix(1);
  const auto value = parse_finite(number);
  if (!value || !(*value > 0))
    throw UsageError(
        "--rmax: expected a positive number in model units (e.g. 0.05) or a multiple of the mean "
        "edge length (e.g. 1.5x), got '" +
        text + "'");
  glyphs.rmax = *value;
  glyphs.rmax_unit = is_relative ? hq::RmaxUnit::kMeanEdgeLength : hq::RmaxUnit::kModel;
}

double parse_glyph_threshold(const std::string& text) {
  const auto value = parse_finite(text);
  if (!value || *value < 0 || *value > 2)
    throw UsageError("--glyph-threshold: expected a number from 0 to 2 (glyphs where 1 - quality is above it), got '" +
                     text + "'");
  return *value;
}

double parse_error_density_reference(const std::string& text) {
  if (text.empty()) return 0;  // not given: the mesh's median
  const auto value = parse_finite(text);
  if (!value || !(*value > 0))
    throw UsageError("--error-density-reference: expected a positive number (an error density), got '" + text + "'");
  return *value;
}

std::optional<hq::OverlapOptions> parse_overlap(const std::string& mode, const std::string& coincident_eps,
                                                bool no_overlap) {
  if (no_overlap) return std::nullopt;
  hq::OverlapOptions overlap;
  if (mode == "certificate")
    overlap.mode = hq::OverlapMode::certificate;
  else if (mode == "exhaustive")
    overlap.mode = hq::OverlapMode::exhaustive;
  else
    throw UsageError("--overlap: expected certificate or exhaustive, got '" + mode + "'");
  const auto eps = parse_finite(coincident_eps);
  if (!eps || *eps < 0 || *eps > 1)
    throw UsageError(
        "--coincident-eps: expected a number from 0 (exact equality) to 1, a fraction of the bounding-box "
        "diagonal, got '" +
        coincident_eps + "'");
  overlap.coincident_eps = *eps;
  return overlap;
}

std::string parse_mesh_format(const std::string& format) {
  if (format.empty()) return format;
  const std::string names = hq::mesh_format_names();
  const std::string padded = ", " + names + ",";
  if (padded.find(", " + format + ",") == std::string::npos)
    throw UsageError("--format: unknown format '" + format + "' (expected one of: " + names + ")");
  return format;
}

hq::HexMetricSet parse_metric_list(std::string_view list) {
  hq::HexMetricSet set;
  for (const std::string_view entry : hq::split(list, ',')) {
    const std::string_view item = hq::trim(entry, " ");
    if (item == "all") {
      set.set();
    } else if (item == kFemElementMetric) {
      // The Q1 element conditioning (lists_fem_element); no Verdict metric.
    } else if (const auto m = hq::hex_metric_from_name(item)) {
      hq::insert(set, *m);
    } else {
      std::string names;
      for (int i = 0; i < hq::kNumHexMetrics; ++i)
        names += (names.empty() ? "" : ", ") + std::string(hq::hex_metric_name(static_cast<hq::HexMetric>(i)));
      throw UsageError(
          "--metrics: " + (item.empty() ? std::string("empty entry") : "unknown metric '" + std::string(item) + "'") +
          " in '" + std::string(list) + "'; choose from: all, " + names);
    }
  }
  return set;
}

bool lists_fem_element(std::string_view list) {
  for (const std::string_view entry : hq::split(list, ','))
    if (hq::trim(entry, " ") == kFemElementMetric) return true;
  return false;
}

std::vector<std::string> parse_view_list(const std::string& list) {
  std::vector<std::string_view> asked;
  for (const std::string_view id : hq::split(list, ','))
    if (!id.empty()) asked.push_back(id);
  auto is_selectable = [](std::string_view id) {
    const hq::ViewSpec* spec = hq::find_view(id);
    return spec != nullptr && spec->is_selectable;
  };
  std::vector<std::string> ids;
  for (const std::string_view id : asked) {
    if (id == "all") {
      for (const hq::ViewSpec& spec : hq::kViews)
        if (spec.is_selectable) ids.emplace_back(spec.id);
      return ids;
    }
    if (!is_selectable(id)) {
      std::string known;
      for (const hq::ViewSpec& spec : hq::kViews)
        if (spec.is_selectable) known += std::string(known.empty() ? "" : ", ") + std::string(spec.id);
      throw UsageError("--views: unknown view '" + std::string(id) + "' (known: all, " + known + ")");
    }
  }
  for (const hq::ViewSpec& spec : hq::kViews)
    if (spec.is_selectable && std::find(asked.begin(), asked.end(), spec.id) != asked.end()) ids.emplace_back(spec.id);
  return ids;
}

std::uint64_t parse_memory_size(std::string_view text, std::string_view flag) {
  std::string_view number = text;
  if (!number.empty() && (number.back() == 'B' || number.back() == 'b')) number.remove_suffix(1);
  double unit = 1;
  if (!number.empty()) {
    switch (number.back()) {
      case 'K':
      case 'k':
        unit = 0x1p10;
        break;
      case 'M':
      case 'm':
        unit = 0x1p20;
        break;
      case 'G':
      case 'g':
        unit = 0x1p30;
        break;
      case 'T':
      case 't':
        unit = 0x1p40;
        break;
      default:
        break;
    }
  }
  if (unit != 1) number.remove_suffix(1);
  double value = 0;
  const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), value);
  const double bytes = value * unit;
  if (number.empty() || error != std::errc() || end != number.data() + number.size() || !std::isfinite(bytes) ||
      !(bytes == 0 || bytes >= 1) || bytes >= 0x1p64)
    throw UsageError(std::string(flag) +
                     ": expected a size such as 512M, 4G or 0.5T (K, M, G, T: powers of 1024; 0: no limit), got '" +
                     std::string(text) + "'");
  return static_cast<std::uint64_t>(bytes);
}

hq::Shard parse_shard(std::string_view text) {
  const auto slash = text.find('/');
  hq::Shard shard;
  auto parse_int = [](std::string_view s, int& value) {
    const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
    return error == std::errc() && end == s.data() + s.size();
  };
  if (slash == std::string_view::npos || !parse_int(text.substr(0, slash), shard.index) ||
      !parse_int(text.substr(slash + 1), shard.count) || shard.count < 1 || shard.index < 1 ||
      shard.index > shard.count)
    throw UsageError("--shard: expected I/N with 1 <= I <= N, e.g. 2/8, got '" + std::string(text) + "'");
  return shard;
}

}  // namespace hqcli
