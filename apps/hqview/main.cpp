// hqview: command-line entry point. Parses the command line (CLI11), calls the
// pipeline, writes the bundle, maps exceptions to the exit codes of
// CONTRACT.md. Nothing else happens here.

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <OpenMesh/Core/System/config.h>
#include <filesystem>
#include <iostream>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/version.h>

#include "hqview/core/error.h"
#include "hqview/pipeline/analyze.h"
#include "hqview/report/bundle_writer.h"
#include "hqview/report/report_json.h"

namespace {

namespace fs = std::filesystem;

enum ExitCode { kOk = 0, kGateFailed = 1, kUsage = 2, kInput = 3, kInternal = 4 };

struct AnalyzeArgs {
  std::string mesh;
  std::string output;
  std::string json;
  std::string size = "1600x1200";
  int threads = 0;
  bool quiet = false;
  bool no_render = false;
  bool force = false;
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

int run_analyze(const AnalyzeArgs& args) {
  const fs::path mesh_path = args.mesh;
  const fs::path output =
      args.output.empty() ? fs::path("hqview-report") / mesh_path.stem() : fs::path(args.output);
  if (!args.json.empty() && args.json != "-") throw hq::UsageError("--json: only '-' (standard output) is supported");

  hq::AnalyzeOptions options;
  options.mesh_path = mesh_path;
  options.tool_version = HQVIEW_VERSION;
  options.render = !args.no_render;
  parse_size(args.size, options.image_width, options.image_height);
  const hq::BundleOptions bundle{.force = args.force};
  hq::check_output_dir(output, bundle);  // fail before the work, not after

  const hq::Analysis analysis = hq::analyze(options);
  if (!args.quiet)
    for (const std::string& w : analysis.model.warnings) std::cerr << "hqview: warning: " << w << "\n";
  hq::write_bundle(analysis.model, analysis.images, output, bundle);
  if (args.json == "-") std::cout << hq::report_json(analysis.model) << std::flush;
  if (!args.quiet) std::cerr << "hqview: report written to " << (output / "index.html").string() << "\n";
  return kOk;
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
  analyze->add_option("-o,--output", args.output, "Bundle directory (default: ./hqview-report/<mesh stem>)");
  analyze->add_option("-j,--threads", args.threads, "Worker threads (default: all cores); results are identical for any N")
      ->check(CLI::Range(1, 1024));
  analyze->add_option("--json", args.json, "Also print report.json to standard output ('-')");
  analyze->add_option("--size", args.size, "Image size WIDTHxHEIGHT")->capture_default_str();
  analyze->add_flag("--no-render", args.no_render, "Skip the rendered views");
  analyze->add_flag("--force", args.force, "Replace an output directory that is not an HQView bundle");
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
