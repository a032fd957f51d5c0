// hqview: command-line entry point. Parses the command line (CLI11), calls the
// pipeline, writes the bundle, maps exceptions to the exit codes of
// CONTRACT.md. Nothing else happens here.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <OpenMesh/Core/System/config.h>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string_view>
#include <iostream>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/version.h>

#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/pipeline/analyze.h"
#include "hqview/report/bundle_writer.h"
#include "hqview/report/report_json.h"

namespace {

namespace fs = std::filesystem;

enum ExitCode { kOk = 0, kGateFailed = 1, kUsage = 2, kInput = 3, kInternal = 4 };

struct AnalyzeArgs {
  std::string mesh;
  std::string reference;
  std::string output;
  std::string json;
  std::string size = "1600x1200";
  int threads = 0;
  bool quiet = false;
  bool no_render = false;
  bool force = false;
  std::vector<std::string> gates;
  std::string metrics = "all";
  std::string rmax = "1x";
  std::string glyph_threshold = "0.5";
  int top_clusters = 8;
  std::string overlap = "certificate";
  std::string coincident_eps = "0";
  bool no_overlap = false;
};

std::string version_text() {
  std::string text = std::string("hqview ") + HQVIEW_VERSION + "\n";
  text += "  formats: .mesh (MEDIT ASCII), .vtk (legacy, ASCII and BINARY, up to 5.1)\n";
  text += "  surfaces: .obj .off .stl .ply (OpenMesh " + std::to_string(OM_GET_VER) + "." + std::to_string(OM_GET_MAJ) + "), .mesh Triangles\n";
  text += "  threads: TBB " + std::string(TBB_VERSION_STRING) + "; rendering: OSMesa (offscreen OpenGL 4.5 core)\n";
  return text;
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
    throw hq::UsageError("--size: expected WIDTHxHEIGHT, e.g. 1600x1200, got '" + size + "'");
  }
  if (width < 64 || height < 64 || width > 8192 || height > 8192)
    throw hq::UsageError("--size: width and height must be between 64 and 8192, got '" + size + "'");
}

// The whole of `text` as a finite number, or nullopt.
std::optional<double> parse_finite(std::string_view text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

// --rmax R (model units) or Rx (R times the mean edge length), R > 0.
void parse_rmax(const std::string& text, hq::GlyphOptions& glyphs) {
  std::string_view number = text;
  const bool is_relative = !number.empty() && number.back() == 'x';
  if (is_relative) number.remove_suffix(1);
  const auto value = parse_finite(number);
  if (!value || !(*value > 0))
    throw hq::UsageError("--rmax: expected a positive number in model units (e.g. 0.05) or a multiple of the mean "
                         "edge length (e.g. 1.5x), got '" + text + "'");
  glyphs.rmax = *value;
  glyphs.rmax_unit = is_relative ? hq::RmaxUnit::kMeanEdgeLength : hq::RmaxUnit::kModel;
}

// --glyph-threshold T: a ratio 1 - Jm, in [0, 2].
double parse_glyph_threshold(const std::string& text) {
  const auto value = parse_finite(text);
  if (!value || *value < 0 || *value > 2)
    throw hq::UsageError("--glyph-threshold: expected a number from 0 to 2 (glyphs where 1 - quality is above it), got '" +
                         text + "'");
  return *value;
}

// --overlap certificate|exhaustive and --coincident-eps E (a fraction of the
// bounding-box diagonal, 0 = exact equality); nullopt with --no-overlap.
std::optional<hq::OverlapOptions> parse_overlap(const AnalyzeArgs& args) {
  if (args.no_overlap) return std::nullopt;
  hq::OverlapOptions overlap;
  if (args.overlap == "certificate")
    overlap.mode = hq::OverlapMode::certificate;
  else if (args.overlap == "exhaustive")
    overlap.mode = hq::OverlapMode::exhaustive;
  else
    throw hq::UsageError("--overlap: expected certificate or exhaustive, got '" + args.overlap + "'");
  const auto eps = parse_finite(args.coincident_eps);
  if (!eps || *eps < 0 || *eps > 1)
    throw hq::UsageError("--coincident-eps: expected a number from 0 (exact equality) to 1, a fraction of the bounding-box "
                         "diagonal, got '" + args.coincident_eps + "'");
  overlap.coincident_eps = *eps;
  return overlap;
}

int run_analyze(const AnalyzeArgs& args) {
  const fs::path mesh_path = args.mesh;
  const fs::path output =
      args.output.empty() ? fs::path("hqview-report") / mesh_path.stem() : fs::path(args.output);
  if (!args.json.empty() && args.json != "-") throw hq::UsageError("--json: only '-' (standard output) is supported");

  hq::AnalyzeOptions options;
  options.mesh_path = mesh_path;
  options.reference_path = args.reference;
  options.tool_version = HQVIEW_VERSION;
  options.render = !args.no_render;
  options.metrics = hq::parse_hex_metric_list(args.metrics);
  // Rules are checked for syntax before the work; whether their key exists is
  // known once the report is (analyze throws UsageError then, no bundle).
  for (const std::string& rule : args.gates) options.gates.push_back(hq::parse_gate_rule(rule));
  parse_size(args.size, options.image_width, options.image_height);
  parse_rmax(args.rmax, options.glyphs);
  options.glyphs.threshold = parse_glyph_threshold(args.glyph_threshold);
  options.glyphs.top_clusters = args.top_clusters;
  options.overlap = parse_overlap(args);
  const hq::BundleOptions bundle{.force = args.force};
  hq::check_output_dir(output, bundle);  // fail before the work, not after

  const hq::Analysis analysis = hq::analyze(options);
  if (!args.quiet)
    for (const std::string& w : analysis.model.warnings) std::cerr << "hqview: warning: " << w << "\n";
  hq::write_bundle(analysis.model, analysis.images, output, bundle);
  if (args.json == "-") std::cout << hq::report_json(analysis.model) << std::flush;
  if (!args.quiet) std::cerr << "hqview: report written to " << (output / "index.html").string() << "\n";
  // Failing gates are printed even with --quiet: they explain exit code 1.
  for (const hq::GateResult& g : analysis.model.gates.results)
    if (!g.passed) std::cerr << "hqview: gate failed: " << g.rule << " (value " << hq::format_double(g.value) << ")\n";
  return analysis.model.gates.passed ? kOk : kGateFailed;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"HQView: hexahedral mesh quality analysis and report bundles"};
  app.require_subcommand(0, 1);
  bool show_version = false;
  app.add_flag("--version", show_version, "Print the version and build features, then exit");

  AnalyzeArgs args;
  CLI::App* analyze = app.add_subcommand("analyze", "Analyse one hex mesh and write a report bundle");
  analyze->add_option("MESH", args.mesh, "Hex mesh: .mesh (MEDIT) or .vtk (legacy VTK)")->required();
  analyze->add_option("--reference", args.reference,
                      "Reference surface (.obj .off .stl .ply, .mesh Triangles): boundary error and UV atlas");
  analyze->add_option("-o,--output", args.output, "Bundle directory (default: ./hqview-report/<mesh stem>)");
  analyze->add_option("-j,--threads", args.threads, "Worker threads (default: all cores); results are identical for any N")
      ->check(CLI::Range(1, 1024));
  analyze->add_option("--json", args.json, "Also print report.json to standard output ('-')");
  analyze->add_option("--size", args.size, "Image size WIDTHxHEIGHT")->capture_default_str();
  analyze->add_flag("--no-render", args.no_render, "Skip the rendered views");
  analyze->add_flag("--force", args.force, "Replace an output directory that is not an HQView bundle");
  analyze->add_option("--gate", args.gates,
                      "Pass/fail rule on a report.json number, e.g. quality.scaled_jacobian.min>=0.2 (repeatable); "
                      "exit code 1 when one fails")
      ->allow_extra_args(false)
      ->take_all();
  analyze->add_option("--metrics", args.metrics, "Verdict metrics to compute: comma-separated names, or all")
      ->capture_default_str();
  analyze->add_option("--rmax", args.rmax,
                      "Glyph radius at quality 0: R in model units, or Rx for R times the mean edge length")
      ->capture_default_str();
  analyze->add_option("--glyph-threshold", args.glyph_threshold,
                      "No glyph where 1 - vertex quality is at or below T (0 to 2)")
      ->capture_default_str();
  analyze->add_option("--top-clusters", args.top_clusters, "Glyph clusters that get detail views (the worst K)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  CLI::Option* overlap_mode =
      analyze->add_option("--overlap", args.overlap,
                          "Intersecting cells: certificate (pair tests only where the certificate fails) or exhaustive "
                          "(pair tests on every pair of cells whose boxes overlap)")
          ->capture_default_str();
  CLI::Option* coincident_eps =
      analyze->add_option("--coincident-eps", args.coincident_eps,
                          "Vertices closer than E times the bounding-box diagonal coincide (0: exact equality)")
          ->capture_default_str();
  analyze->add_flag("--no-overlap", args.no_overlap, "Skip the overlap stages (report.json overlap is null)")
      ->excludes(overlap_mode)
      ->excludes(coincident_eps);
  analyze->add_flag("-q,--quiet", args.quiet, "Print nothing on standard error but errors");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kUsage;
  }
  if (show_version) {
    std::cout << version_text();
    return kOk;
  }
  if (!*analyze) {
    std::cerr << app.help();
    return kUsage;
  }

  try {
    const int threads = args.threads > 0 ? args.threads : tbb::info::default_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    return run_analyze(args);
  } catch (const hq::UsageError& e) {
    std::cerr << "hqview: " << e.what() << "\n";
    return kUsage;
  } catch (const hq::InputError& e) {
    std::cerr << "hqview: " << e.what() << "\n";
    return kInput;
  } catch (const std::exception& e) {
    std::cerr << "hqview: internal error: " << e.what() << " (please report this)\n";
    return kInternal;
  }
}
