// hqview: command-line entry point. Parses the command line (CLI11), calls the
// pipeline, writes the bundle, maps exceptions to the exit codes of
// CONTRACT.md. Nothing else happens here.

#include <sys/stat.h>
#include <unistd.h>

#include <csignal>

#include <OpenMesh/Core/System/config.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/version.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <charconv>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string_view>
#include <thread>

#include "flags.h"
#include "hqview/core/error.h"
#include "hqview/core/message_text.h"
#include "hqview/core/number_format.h"
#include "hqview/core/progress.h"
#include "hqview/core/stop.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/io/read_limits.h"
#include "hqview/pipeline/analyze.h"
#include "hqview/pipeline/batch.h"
#include "hqview/pipeline/diff.h"
#include "hqview/render/osmesa_renderer.h"
#include "hqview/render/upright.h"
#include "hqview/report/atomic_file.h"
#include "hqview/report/batch_index.h"
#include "hqview/report/bundle_writer.h"
#include "hqview/report/comparison.h"
#include "hqview/report/escape.h"
#include "hqview/report/junit.h"
#include "hqview/report/link_base.h"
#include "hqview/report/report_json.h"
#include "hqview/views/views.h"

namespace {

namespace fs = std::filesystem;

// Large arrays on transparent huge pages: glibc's malloc asks for them
// (madvise) only when told so at startup by GLIBC_TUNABLES
// glibc.malloc.hugetlb=1, so hqview sets it and executes itself again, once.
// Page faults dominated the large runs (on a virtual machine each one is a
// trip to the hypervisor): 2.9M hexes 34 s -> 19 s, 363k 4.1 s -> 2.7 s,
// peak memory unchanged (docs/performance.md). HQVIEW_NO_HUGEPAGES=1, or a
// GLIBC_TUNABLES already naming hugetlb, leaves the process as it is; so does
// an exec that fails. Only where it pays for the second start (0.1 s):
// `batch`, and `analyze` given a file of 8 MiB or more.
bool worth_huge_pages(int argc, char** argv) {
  if (argc < 2) return false;
  const std::string_view command = argv[1];
  if (command == "batch") return true;
  if (command != "analyze") return false;
  for (int i = 2; i < argc; ++i) {
    struct stat st {};
    if (::stat(argv[i], &st) == 0 && S_ISREG(st.st_mode) && st.st_size >= (8 << 20)) return true;
  }
  return false;
}

void use_huge_pages(int argc, char** argv) {
  if (std::getenv("HQVIEW_NO_HUGEPAGES") != nullptr || !worth_huge_pages(argc, argv)) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::string value = tunables != nullptr ? tunables : "";
  if (value.find("glibc.malloc.hugetlb") != std::string::npos) return;
  // With it, memory freed is kept for the next array instead of returned
  // and faulted in again: no array below 32 MiB gets pages of its own
  // (mmap) and no heap shrinks by less than 2 GiB, and the heap grows 64 MiB
  // at a time. Each page the kernel hands out is zeroed first, the largest
  // single cost of the 363k-hex run in a profile (12-16 % of its CPU): this
  // takes 5 % off its CPU time, peak memory +2 % (docs/performance.md).
  // A setting the user gave is kept.
  for (const char* tunable : {"glibc.malloc.hugetlb=1", "glibc.malloc.mmap_threshold=33554432",
                              "glibc.malloc.trim_threshold=2147483648", "glibc.malloc.top_pad=67108864"}) {
    const std::string_view name = std::string_view(tunable).substr(0, std::string_view(tunable).find('='));
    if (value.find(name) != std::string::npos) continue;
    value += value.empty() ? tunable : ":" + std::string(tunable);
  }
  if (::setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  ::execv("/proc/self/exe", argv);
  // Not executed again: go on as we are, without the variable.
  if (tunables != nullptr)
    ::setenv("GLIBC_TUNABLES", tunables, 1);
  else
    ::unsetenv("GLIBC_TUNABLES");
}

// SIGINT, SIGTERM, SIGHUP: recorded, and honoured by the stages at their next
// poll (hq::stop): the bundle being written is dropped with its temporary
// directory and hqview exits 128 + the signal. A second signal while the
// first is being honoured ends the process at once (the next run removes
// what it left). SIGXFSZ (a file size limit, `ulimit -f`) and SIGPIPE are
// ignored: the write fails with "File too large" / "Broken pipe" instead,
// and the error names the file.
extern "C" void on_stop_signal(int signal) {
  if (hq::stop::requested() != 0) ::_exit(128 + signal);
  hq::stop::request(signal);
}

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(s, &action, nullptr);
  std::signal(SIGXFSZ, SIG_IGN);
  std::signal(SIGPIPE, SIG_IGN);
}

// The process's start (first use at the top of main): timings.json's wall time.
std::chrono::steady_clock::time_point process_start() {
  static const auto start = std::chrono::steady_clock::now();
  return start;
}

using namespace hqcli;

struct AnalyzeArgs {
  std::string mesh;
  std::string format;
  std::string dimension = "auto";  // --dimension: auto, volume, surface
  std::string reference;
  std::string compare;
  std::string compare_align = "auto";
  std::string reference_align = "none";
  double boundary_tolerance = 1e-4;  // --boundary-tolerance
  std::string up = "auto";  // --up: per mesh by default (docs/analysis.md "Up axis: auto")
  bool no_viewer = false;
  std::string link_base;  // --link-base URL; empty: relative links
  std::string single_file;  // --single-file[=viewer]: "pages" or "viewer"; empty: no report.html
  double viewer_max_mb = 25;
  std::string data{hq::kDefaultDataList};  // --data
  std::string output;
  std::string json;
  std::string size = "1600x1200";
  std::string views = "all";
  std::vector<long long> focus_vertices;
  int threads = 0;
  bool quiet = false;
  bool verbose = false;  // each stage's wall time on standard error (analyze)
  bool no_render = false;
  bool force = false;
  std::vector<std::string> gates;
  std::string metrics = "all";
  std::string rmax = "1x";
  std::string glyph_threshold = "0.5";
  std::string glyph_size = "severity";
  int top_clusters = 8;
  std::string overlap = "certificate";
  std::string coincident_eps = "0";
  bool no_overlap = false;
  bool simulate = false;   // --simulate: the finite-element (Poisson) check
  std::string error_density_reference;  // --error-density-reference; empty: the mesh's median
  std::string max_memory;  // --max-memory; empty: hq::default_max_memory()
};

std::string version_text() {
  std::string text = std::string("hqview ") + HQVIEW_VERSION + "\n";
  text += "  formats: .mesh (MEDIT ASCII), .vtk (legacy, ASCII and BINARY, up to 5.1),\n";
  text += std::string("           .vtu (VTK XML: ascii, binary, appended; zlib ") +
          (hq::has_zlib_support() ? "on" : "off: built without zlib") +
          "), .msh (Gmsh 2.2 and 4.1, ASCII and binary),\n";
  text += std::string("           .ovm (OpenVolumeMesh ASCII), .inp (Abaqus), .e .exo (Exodus II: ") +
          (hq::has_exodus_support() ? "on, netCDF" : "off: built without netCDF") + ")\n";
  text += "  surfaces: .obj .off .stl .ply (OpenMesh " + std::to_string(OM_GET_VER) + "." + std::to_string(OM_GET_MAJ) +
          "), .mesh Triangles\n";
  text += "  threads: TBB " + std::string(TBB_VERSION_STRING) + "; rendering: OSMesa (offscreen OpenGL 4.5 core)\n";
  return text;
}

// The analysis options shared by `analyze` and `batch` (everything but the
// input files). Throws UsageError for a bad value.
hq::AnalyzeOptions make_analyze_options(const AnalyzeArgs& args) {
  hq::AnalyzeOptions options;
  options.tool_version = HQVIEW_VERSION;
  options.mesh_format = parse_mesh_format(args.format);
  options.metrics = parse_metric_list(args.metrics);
  options.fem_elements = lists_fem_element(args.metrics) || args.simulate;
  options.simulate = args.simulate;
  options.views.error_density_reference = parse_error_density_reference(args.error_density_reference);
  if (!args.error_density_reference.empty() && !args.simulate)
    throw UsageError("--error-density-reference: needs --simulate (the error density comes from its Poisson check)");
  // Rules are checked for syntax before the work; whether their key exists is
  // known once the report is (analyze throws hq::ValueError then, no bundle).
  for (const std::string& rule : args.gates) options.gates.push_back(hq::parse_gate_rule(rule));
  parse_size(args.size, options.views.width, options.views.height);
  options.up_auto = args.up == "auto";
  if (!options.up_auto) options.views.up = parse_up(args.up);
  options.viewer = !args.no_viewer;
  options.data = hq::parse_data_formats(args.data);
  options.viewer_max_mb = args.viewer_max_mb;
  options.reference_align = args.reference_align == "bbox"   ? hq::CompareAlign::bbox
                            : args.reference_align == "auto" ? hq::CompareAlign::auto_
                                                             : hq::CompareAlign::none;
  options.boundary.sampling_tolerance = args.boundary_tolerance;
  options.views.views = parse_view_list(args.views);
  for (long long v : args.focus_vertices) {
    if (v > 2147483647LL) throw UsageError("--focus-vertex: vertex " + std::to_string(v) + " does not exist");
    options.views.focus_vertices.push_back(static_cast<hq::Index>(v));
  }
  parse_rmax(args.rmax, options.glyphs);
  options.glyphs.threshold = parse_glyph_threshold(args.glyph_threshold);
  options.glyphs.top_clusters = args.top_clusters;
  options.glyphs.size_rule = args.glyph_size == "paper" ? hq::GlyphSizeRule::kPaper : hq::GlyphSizeRule::kSeverity;
  options.overlap = parse_overlap(args.overlap, args.coincident_eps, args.no_overlap);
  options.read_limits.max_memory =
      args.max_memory.empty() ? hq::default_max_memory() : parse_memory_size(args.max_memory, "--max-memory");
  options.read_limits.dimension = args.dimension == "volume"    ? hq::MeshDimension::volume
                                  : args.dimension == "surface" ? hq::MeshDimension::surface
                                                                : hq::MeshDimension::automatic;
  return options;
}

// Text from input (paths, error messages that quote a file, rules given on
// the command line) as it is shown on standard error and output: bytes that
// are not UTF-8 and control characters as \xhh (docs/contract.md,
// "Messages are text").
std::string shown(std::string_view text) { return hq::message_text(text); }

// `hqview: STAGE: SECONDS s`, with the peak memory under --verbose.
std::string stage_line(const hq::StageTime& t, bool with_memory) {
  std::string line = "hqview: " + t.name + ": " + hq::display_number(t.seconds, 3) + " s";
  if (with_memory)
    line += " (peak memory " + hq::display_number(static_cast<double>(t.peak_rss_bytes) / 1e6, 4) + " MB)";
  return line;
}

// analyze's progress on a terminal: one line per finished stage and, below
// it, the running stage redrawn every 0.1 s once it has run 0.2 s: a bar
// when the stage reports its work (reading, metrics, overlap, writing),
// else its elapsed time. Only on a terminal (stderr a TTY), never with
// --quiet: piped output stays the plain lines of --verbose, or nothing.
class TerminalProgress {
 public:
  explicit TerminalProgress(bool with_memory) : with_memory_(with_memory), thread_([this] { run(); }) {}
  TerminalProgress(const TerminalProgress&) = delete;
  TerminalProgress& operator=(const TerminalProgress&) = delete;
  ~TerminalProgress() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
    std::cerr << "\r\033[K" << std::flush;
  }

  void stage_finished(const hq::StageTime& t) {
    const std::lock_guard lock(mutex_);
    std::cerr << "\r\033[K" << stage_line(t, with_memory_) << "\n" << std::flush;
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    std::string stage;
    auto since = std::chrono::steady_clock::now();
    while (!wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stop_; })) {
      const hq::progress::Snapshot s = hq::progress::snapshot();
      const auto now = std::chrono::steady_clock::now();
      if (s.stage != stage) {
        stage = s.stage;
        since = now;
      }
      const double elapsed = std::chrono::duration<double>(now - since).count();
      if (stage.empty() || elapsed < 0.2) continue;
      std::string line = "hqview: " + stage + " ";
      if (s.total > 0) {
        constexpr int kWidth = 30;
        const double f = std::min(1.0, static_cast<double>(s.done) / static_cast<double>(s.total));
        const int filled = static_cast<int>(f * kWidth);
        line += "[" + std::string(static_cast<std::size_t>(filled), '#') +
                std::string(static_cast<std::size_t>(kWidth - filled), ' ') + "] " +
                std::to_string(static_cast<int>(100 * f)) + "% ";
      }
      line += hq::display_number(elapsed, 2) + " s";
      std::cerr << "\r\033[K" << line << std::flush;
    }
  }

  bool with_memory_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;  // last: started once the members above exist
};

int run_analyze(const AnalyzeArgs& args) {
  const fs::path mesh_path = args.mesh;
  const fs::path output = args.output.empty() ? fs::path("hqview-report") / mesh_path.stem() : fs::path(args.output);
  if (!args.json.empty() && args.json != "-") throw UsageError("--json: only '-' (standard output) is supported");

  hq::AnalyzeOptions options = make_analyze_options(args);
  options.mesh_path = mesh_path;
  options.reference_path = args.reference;
  options.compare_path = args.compare;
  options.compare_align = args.compare_align == "none"   ? hq::CompareAlign::none
                          : args.compare_align == "bbox" ? hq::CompareAlign::bbox
                                                         : hq::CompareAlign::auto_;
  hq::BundleOptions bundle;
  bundle.force = args.force;
  if (!args.link_base.empty()) bundle.link_base = hq::normalize_link_base(args.link_base);
  if (!args.single_file.empty()) bundle.single_file = hq::parse_single_file(args.single_file);
  std::optional<TerminalProgress> terminal;
  if (!args.quiet && ::isatty(2) != 0) {
    terminal.emplace(args.verbose);
    options.on_stage = bundle.on_stage = [&terminal](const hq::StageTime& t) { terminal->stage_finished(t); };
  } else if (args.verbose && !args.quiet) {
    options.on_stage = bundle.on_stage = [](const hq::StageTime& t) { std::cerr << stage_line(t, true) << "\n"; };
  }
  hq::check_output_dir(output, bundle);  // fail before the work, not after
  bundle.started = process_start();

  std::vector<hq::StageTime> setup;
  std::unique_ptr<hq::Renderer> renderer;
  if (!args.no_render) {
    hq::StageClock clock(setup, options.on_stage);
    clock.start("renderer");
    renderer = hq::make_osmesa_renderer();
  }
  hq::AnalyzeResult result = hq::analyze(options, renderer.get());
  result.model.analysis.timings.insert(result.model.analysis.timings.begin(), setup.begin(), setup.end());
  if (!args.quiet) {
    for (const std::string& n : result.model.analysis.notes) std::cerr << "hqview: note: " << shown(n) << "\n";
    for (const std::string& w : result.model.analysis.warnings) std::cerr << "hqview: warning: " << shown(w) << "\n";
  }
  hq::write_bundle(result.model, result.document, result.images, output, bundle);
  terminal.reset();  // the last stage line stays; the running line is cleared
  if (args.json == "-") std::cout << hq::report_json_text(result.document) << std::flush;
  if (!args.quiet) std::cerr << "hqview: report written to " << shown((output / "index.html").string()) << "\n";
  // Failing gates are printed even with --quiet: they explain exit code 1.
  for (const hq::GateResult& g : result.model.gates.results)
    if (!g.passed)
      std::cerr << "hqview: gate failed: " << shown(g.rule) << " (value " << hq::format_double(g.value) << ")\n";
  return result.model.gates.passed ? kOk : kGateFailed;
}

// ---- batch, merge, diff (issue 9) -------------------------------------------

struct BatchArgs {
  AnalyzeArgs analysis;  // the analysis options (mesh, reference, output, json unused)
  std::string input;     // DIR or MANIFEST
  std::string output;
  int jobs = 0;  // 0: all cores
  std::string shard;
  std::string memory_budget;  // e.g. 8G; default: half the physical memory
  bool resume = false;
  std::string compare_keys;  // --compare-keys; empty: the default keys
  double mesh_timeout = 0;   // --mesh-timeout SECONDS; 0: none
  bool list = false;         // --list: print the collection as JSON and stop
};

struct MergeArgs {
  std::vector<std::string> shards;
  std::string output;
  bool force = false;
  std::string compare_keys;
  std::string link_base;
};

constexpr const char* kCompareKeysHelp =
    "Keys of the method comparison tables (comparison.md/.tex, index.html), comma-separated report.json paths, e.g. "
    "quality.scaled_jacobian.min,quality.num_inverted (default: #V, #H, min and mean SJ, #inverted, Hausdorff, "
    "singular interior edges)";

// The comparison keys of --compare-keys (nullopt: the default keys).
std::optional<std::vector<hq::ComparisonKey>> comparison_keys_of(const std::string& list) {
  if (list.empty()) return std::nullopt;
  return hq::parse_comparison_keys(list);
}

struct DiffArgs {
  std::string baseline;
  std::string current;
  std::vector<std::string> gates;
  std::string markdown;
  std::size_t markdown_max_chars = hq::kDiffMarkdownMaxChars;
  std::string junit;
  bool quiet = false;
};

// A progress bar on a terminal, one line per mesh otherwise (CI logs).
class StderrProgress : public hq::BatchProgress {
 public:
  explicit StderrProgress(bool quiet) : quiet_(quiet), is_terminal_(::isatty(2) != 0) {}
  void mesh_finished(const hq::BatchEntry& entry, bool is_resumed, double seconds, int done, int total) override {
    std::string what = is_resumed ? "kept" : std::string(hq::to_string(entry.status));
    if (is_terminal_) {
      constexpr int kWidth = 30;
      const int filled = total > 0 ? done * kWidth / total : kWidth;
      std::cerr << "\r\033[K[" << std::string(static_cast<std::size_t>(filled), '#')
                << std::string(static_cast<std::size_t>(kWidth - filled), ' ') << "] " << done << "/" << total << " "
                << shown(entry.path) << std::flush;
      if (entry.status == hq::BatchStatus::failed)
        std::cerr << "\r\033[Khqview: failed: " << shown(entry.error) << "\n";
      if (done == total) std::cerr << "\r\033[K";
    } else if (!quiet_ || entry.status == hq::BatchStatus::failed) {
      char time[32];
      std::snprintf(time, sizeof time, "%.2f s", seconds);
      std::cerr << "hqview: [" << done << "/" << total << "] " << what << " " << shown(entry.path) << " (" << time
                << ")" << (entry.error.empty() ? "" : ": " + shown(entry.error)) << "\n";
    }
  }

 private:
  bool quiet_;
  bool is_terminal_;
};

// --memory-budget: "" -> half the physical memory.
std::uint64_t parse_memory_budget(const std::string& text) {
  if (!text.empty()) return parse_memory_size(text, "--memory-budget");
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 2 : 0;
}

// The analysis options `analyze` and `batch` share, registered once.
void add_analysis_options(CLI::App* cmd, AnalyzeArgs& args) {
  cmd->add_option("--up", args.up,
                  "The model axis drawn upwards in the 3D views and the UV map: +x -x +y -y +z -z, or auto (per "
                  "mesh, the axis it would rest on a table with; docs/analysis.md); views look from 15-35 degrees "
                  "above the horizon (given twice, the last wins; in batch, a manifest's up column wins)")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)
      ->capture_default_str();
  cmd->add_option("--data", args.data,
                  "Per-cell and per-vertex data files, comma-separated: vtu.zlib (data/annotated.vtu, compressed), "
                  "vtu (uncompressed), csv (data/cells.csv, data/vertices.csv), csv.gz (gzip'ed), or none; "
                  "data/edges.csv is always written")
      ->capture_default_str();
  cmd->add_flag("--no-viewer", args.no_viewer, "Leave the interactive 3D viewer (viewer.html) out of the bundle");
  cmd->add_option("--link-base", args.link_base,
                  "Absolute links under URL in index.html, boundary.html and summary.md (and the batch pages), for "
                  "bundles published at URL (e.g. GitHub Pages); summary.md then shows the key view inline");
  cmd->add_flag("--single-file{pages}", args.single_file,
                "Also write report.html: the index page with its stylesheet, images and the boundary page in one "
                "file (links to the data files stay); --single-file=viewer also embeds the 3D viewer and its data")
      ->check(CLI::IsMember({"pages", "viewer"}));
  cmd->add_option("--viewer-max-mb", args.viewer_max_mb,
                  "Size budget of the viewer's data in MB: over it, what is drawn is reduced (never the glyphs, "
                  "the cells under the threshold or any number); the page says what was reduced")
      ->check(CLI::Range(0.001, 100000.0))
      ->capture_default_str();
  cmd->add_option("--reference-align", args.reference_align,
                  "Move the reference into the mesh's frame before the boundary error: bbox (onto the mesh "
                  "boundary's bounding box: uniform scale and translation; errors in the mesh's units), auto (as "
                  "--compare-align auto: the 24 axis rotations, ICP) or none (the default: a misplacement is "
                  "shown, not hidden)")
      ->check(CLI::IsMember({"none", "bbox", "auto"}))
      ->capture_default_str();
  cmd->add_option("--boundary-tolerance", args.boundary_tolerance,
                  "Sampled boundary error: each certified upper bound within this fraction of the reference's "
                  "bounding-box diagonal of the maximum found (smaller: more samples)")
      ->check(CLI::Range(1e-7, 1e-1))
      ->capture_default_str();
  cmd->add_option("--compare-align", args.compare_align,
                  "Place MESH2 in the compare view: auto (align by bounding box when the diagonals differ by "
                  "more than 2x or the boxes do not overlap, then the one of the 24 axis rotations that brings the "
                  "boundaries closest if it halves the distance, refined by ICP; a mirror image is reported), bbox "
                  "(always, no rotation), none; numbers stay in each mesh's units")
      ->check(CLI::IsMember({"auto", "bbox", "none"}));
  cmd->add_option("--format", args.format,
                  "Read meshes as this format whatever their extension: " + hq::mesh_format_names());
  cmd->add_option("--dimension", args.dimension,
                  "Which cells to analyse: auto (a file with volume cells is a volume mesh, its quadrilaterals and "
                  "triangles boundary faces; a file with only quadrilaterals and triangles is a surface mesh), "
                  "volume, surface")
      ->check(CLI::IsMember({"auto", "volume", "surface"}))
      ->capture_default_str();
  cmd->add_option("--size", args.size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_flag("--no-render", args.no_render, "Skip the rendered views");
  std::string view_ids;  // from the table of views, so the help never goes stale
  for (const hq::ViewSpec& spec : hq::kViews)
    if (spec.is_selectable) view_ids += (view_ids.empty() ? "" : ", ") + std::string(spec.id);
  cmd->add_option("--views", args.views, "Views to render: comma-separated ids (" + view_ids + "), or all")
      ->capture_default_str();
  cmd->add_flag("--force", args.force, "Replace an output directory that is not an HQView output");
  cmd->add_option("--gate", args.gates,
                  "Pass/fail rule on a report.json number, e.g. quality.scaled_jacobian.min>=0.2 (repeatable); "
                  "exit code 1 when one fails")
      ->allow_extra_args(false)
      ->take_all();
  cmd->add_option("--metrics", args.metrics,
                  "Verdict metrics to compute: comma-separated names, or all; fem_element adds the Q1 element "
                  "conditioning (report.json fem.element)")
      ->capture_default_str();
  cmd->add_flag("--simulate", args.simulate,
                "Run the finite-element check: element conditioning and a Poisson solve with three manufactured "
                "solutions (report.json fem)");
  cmd->add_option("--error-density-reference", args.error_density_reference,
                  "With --simulate: colour the error-density view relative to this density instead of the mesh's "
                  "median (pale at or below it, red at 10 times it), one scale for every mesh");
  cmd->add_option("--rmax", args.rmax,
                  "Glyph radius at quality 0: R in model units, or Rx for R times the mean edge length")
      ->capture_default_str();
  cmd->add_option("--glyph-threshold", args.glyph_threshold,
                  "No glyph where 1 - vertex quality is at or below T (0 to 2)")
      ->capture_default_str();
  cmd->add_option("--glyph-size", args.glyph_size,
                  "Aggregated glyphs: severity (clusters within 2 radii of their worst vertex, the glyph there, "
                  "radius (1 - min quality) * rmax; the member count is in the labels) or paper (HQViewer's clusters "
                  "and radius: + 0.1 * rmax per 10 members, up to + rmax)")
      ->check(CLI::IsMember({"severity", "paper"}))
      ->capture_default_str();
  cmd->add_option("--top-clusters", args.top_clusters, "Glyph clusters that get detail views (the worst K)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  CLI::Option* overlap_mode =
      cmd->add_option("--overlap", args.overlap,
                      "Intersecting cells: certificate (pair tests only where the certificate fails) or exhaustive "
                      "(pair tests on every pair of cells whose boxes overlap)")
          ->capture_default_str();
  CLI::Option* coincident_eps =
      cmd->add_option("--coincident-eps", args.coincident_eps,
                      "Vertices closer than E times the bounding-box diagonal coincide (0: exact equality)")
          ->capture_default_str();
  cmd->add_flag("--no-overlap", args.no_overlap, "Skip the overlap stages (report.json overlap is null)")
      ->excludes(overlap_mode)
      ->excludes(coincident_eps);
  cmd->add_option("--max-memory", args.max_memory,
                  "Refuse (exit 3) a mesh whose size or declared counts need more memory than SIZE, e.g. 512M, 4G, "
                  "0.5T; 0: no limit (default: 75% of the physical or cgroup memory, " +
                      hq::format_memory_size(hq::default_max_memory()) + " here)");
  cmd->add_flag("-q,--quiet", args.quiet, "Print nothing on standard error but failures and errors");
  cmd->add_flag(
      "-v,--verbose", args.verbose,
      "analyze: print each stage's wall time on standard error as it ends (every bundle has them in timings.json)");
}

CLI::App* add_batch_command(CLI::App& app, BatchArgs& args) {
  CLI::App* cmd =
      app.add_subcommand("batch", "Analyse every mesh of a directory or manifest; one bundle each plus an index");
  AnalyzeArgs& a = args.analysis;
  cmd->add_option(
         "INPUT", args.input,
         "Directory (every .mesh/.vtk below it) or manifest (.csv/.json: mesh, reference, compare, label, model)")
      ->required();
  cmd->add_option("-o,--output", args.output, "Output directory: one bundle per mesh, index.html/json, summary.md")
      ->required();
  cmd->add_option("-j,--jobs", args.jobs,
                  "Meshes analysed at once, within the memory budget, and threads in all (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--shard", args.shard,
                  "Only shard I of N (1-based, stable by path); join shards with `hqview merge`");
  cmd->add_flag("--resume", args.resume, "Keep a bundle whose mesh hash and HQView version are unchanged");
  cmd->add_option("--compare-keys", args.compare_keys, kCompareKeysHelp);
  cmd->add_option("--memory-budget", args.memory_budget,
                  "Estimated memory of the meshes in flight, e.g. 8G (default: half the physical memory; 0: no limit)");
  cmd->add_flag("--list", args.list,
                "Print the collection (after --shard) as JSON, one object per mesh {path, mesh, reference, compare, "
                "up, skipped}, and stop: what a workflow engine schedules (workflow/Snakefile)");
  cmd->add_option("--mesh-timeout", args.mesh_timeout,
                  "Stop a mesh's analysis after SECONDS: it is recorded failed with the reason and the batch goes on "
                  "(default: no limit)")
      ->check(CLI::PositiveNumber);
  add_analysis_options(cmd, a);
  return cmd;
}

CLI::App* add_merge_command(CLI::App& app, MergeArgs& args) {
  CLI::App* cmd = app.add_subcommand("merge", "Join the outputs of `batch --shard` runs into one index");
  cmd->add_option("SHARD_DIR", args.shards, "Output directories of the shards")->required();
  cmd->add_option("-o,--output", args.output, "Merged output directory")->required();
  cmd->add_flag("--force", args.force, "Write into a directory that is not an HQView output");
  cmd->add_option("--compare-keys", args.compare_keys, kCompareKeysHelp);
  cmd->add_option("--link-base", args.link_base,
                  "Absolute links under URL in the merged index.html, summary.md and comparison.md (give the shards "
                  "the same --link-base)");
  return cmd;
}

CLI::App* add_diff_command(CLI::App& app, DiffArgs& args) {
  CLI::App* cmd =
      app.add_subcommand("diff", "Compare two report.json or two index.json; gates relative to the baseline");
  cmd->add_option("BASELINE", args.baseline, "report.json or index.json (or a bundle / batch directory)")->required();
  cmd->add_option("CURRENT", args.current, "report.json or index.json (or a bundle / batch directory)")->required();
  cmd->add_option("--gate", args.gates,
                  "Rule, e.g. quality.scaled_jacobian.min>=baseline-0.01 (repeatable); exit code 1 when one fails")
      ->allow_extra_args(false)
      ->take_all();
  cmd->add_option("--markdown", args.markdown, "Also write the comparison as Markdown (a pull-request comment)");
  cmd->add_option("--markdown-max-chars", args.markdown_max_chars,
                  "Size cap of --markdown's file (default 60000; GitHub allows 65536): the worst changes are kept")
      ->check(CLI::Range(hq::kDiffMarkdownMinChars, std::size_t{100000000}));
  cmd->add_option("--junit", args.junit, "Also write the gates as JUnit XML (one test case per gate and mesh)");
  cmd->add_flag("-q,--quiet", args.quiet, "Print only failed gates");
  return cmd;
}

int run_batch_command(const BatchArgs& args, int jobs) {
  hq::BatchOptions options;
  options.analyze = make_analyze_options(args.analysis);
  options.output = args.output;
  options.jobs = jobs;
  options.resume = args.resume;
  options.force = args.analysis.force;
  options.memory_budget = parse_memory_budget(args.memory_budget);
  options.mesh_timeout = args.mesh_timeout;
  if (!args.analysis.link_base.empty()) options.link_base = hq::normalize_link_base(args.analysis.link_base);
  if (!args.analysis.single_file.empty()) options.single_file = hq::parse_single_file(args.analysis.single_file);
  if (!args.analysis.no_render) options.make_renderer = [] { return hq::make_osmesa_renderer(); };
  const auto keys = comparison_keys_of(args.compare_keys);  // a usage error before any mesh is read
  std::vector<hq::BatchInput> inputs = hq::collect_batch_inputs(args.input);
  if (!args.shard.empty()) inputs = hq::select_shard(inputs, parse_shard(args.shard));
  if (args.list) {
    nlohmann::json rows = nlohmann::json::array();
    for (const hq::BatchInput& in : inputs)
      rows.push_back({{"path", in.path},
                      {"mesh", in.mesh_file.string()},
                      {"reference", in.reference_file.string()},
                      {"compare", in.compare_file.string()},
                      {"up", in.up},
                      {"skipped", in.skip_reason}});
    std::cout << hq::json_message_text(rows).dump(1) << "\n";
    return kOk;
  }
  hq::check_batch_output_dir(options.output, options.force);
  hq::mark_batch_output_dir(options.output);
  // What a killed run left: its temporary bundles go, a bundle it had moved
  // aside comes back.
  hq::remove_stale_temporaries(options.output, true);

  StderrProgress progress(args.analysis.quiet);
  const std::vector<hq::BatchEntry> entries = hq::run_batch(inputs, options, &progress);
  hq::write_batch_index(entries, HQVIEW_VERSION, options.output, keys ? &*keys : nullptr, options.link_base);
  if (options.single_file != hq::SingleFile::none) hq::write_batch_single_file(options.output, options.link_base);
  if (!args.analysis.quiet)
    std::cerr << "hqview: " << entries.size() << " meshes; index written to "
              << shown((options.output / "index.html").string()) << "\n";
  for (const hq::BatchEntry& e : entries)
    for (const std::string& rule : e.failed_gates)
      std::cerr << "hqview: gate failed: " << shown(e.path) << ": " << shown(rule) << "\n";
  return batch_exit_code(entries);
}

int run_merge_command(const MergeArgs& args) {
  std::vector<fs::path> shards(args.shards.begin(), args.shards.end());
  const auto keys = comparison_keys_of(args.compare_keys);
  hq::check_batch_output_dir(args.output, args.force);
  hq::mark_batch_output_dir(args.output);
  const std::vector<hq::BatchEntry> entries = hq::merge_shards(shards, args.output);
  hq::write_batch_index(entries, HQVIEW_VERSION, args.output, keys ? &*keys : nullptr,
                        args.link_base.empty() ? "" : hq::normalize_link_base(args.link_base));
  std::cerr << "hqview: merged " << entries.size() << " meshes from " << shards.size() << " shards into "
            << shown((fs::path(args.output) / "index.html").string()) << "\n";
  return batch_exit_code(entries);
}

// A report.json/index.json, or the directory holding one (index.json first).
fs::path diff_input_file(const std::string& arg) {
  const fs::path path = arg;
  if (!fs::is_directory(path)) return path;
  if (fs::is_regular_file(path / "index.json")) return path / "index.json";
  return path / "report.json";
}

std::string read_input_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw hq::InputError(path.string() + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return std::move(text).str();
}

int run_diff_command(const DiffArgs& args) {
  std::vector<hq::DiffGate> gates;
  for (const std::string& rule : args.gates) gates.push_back(hq::parse_diff_gate(rule));
  const fs::path baseline = diff_input_file(args.baseline), current = diff_input_file(args.current);
  const hq::DiffResult diff = hq::diff_reports(read_input_text(baseline), read_input_text(current), gates,
                                               baseline.parent_path(), current.parent_path());
  if (!args.markdown.empty()) {
    hq::write_file_atomically(args.markdown, hq::diff_markdown(diff, args.markdown_max_chars));
  }
  if (!args.junit.empty()) hq::write_file_atomically(args.junit, hq::junit_xml("hqview diff", hq::diff_junit_cases(diff)));
  if (!args.quiet) std::cout << hq::message_text(hq::diff_text(diff), hq::LineBreaks::kept) << std::flush;
  for (const hq::DiffGateResult& g : diff.gates)
    if (!g.passed)
      std::cerr << "hqview: gate failed: " << shown(g.rule) << (g.mesh.empty() ? "" : " [" + shown(g.mesh) + "]")
                << " (value " << (g.value ? hq::format_double(*g.value) : std::string("none: the mesh failed"))
                << ")\n";
  return diff.passed ? kOk : kGateFailed;
}

}  // namespace

int main(int argc, char** argv) {
  use_huge_pages(argc, argv);
  process_start();
  install_signal_handlers();
  CLI::App app{"HQView: hexahedral mesh quality analysis and report bundles"};
  app.require_subcommand(0, 1);
  bool show_version = false;
  app.add_flag("--version", show_version, "Print the version and build features, then exit");

  AnalyzeArgs args;
  CLI::App* analyze = app.add_subcommand("analyze", "Analyse one hex mesh and write a report bundle");
  analyze->add_option("MESH", args.mesh, "Hex mesh: .mesh .vtk .vtu .msh .ovm .inp .e .exo")->required();
  analyze->add_option("--reference", args.reference,
                      "Reference surface (.obj .off .stl .ply, .mesh Triangles): boundary error and UV atlas");
  analyze->add_option("--compare", args.compare,
                      "Second hex mesh (e.g. before/after optimisation): its quality summary and differences in "
                      "report.json compare, both boundaries side by side (view compare)");
  analyze->add_option("-o,--output", args.output, "Bundle directory (default: ./hqview-report/<mesh stem>)");
  analyze
      ->add_option("-j,--threads", args.threads, "Worker threads (default: all cores); results are identical for any N")
      ->check(CLI::Range(1, 1024));
  analyze->add_option("--json", args.json, "Also print report.json to standard output ('-')");
  analyze
      ->add_option("--focus-vertex", args.focus_vertices,
                   "Also draw the local view D and chart E of vertex V (repeatable)")
      ->check(CLI::NonNegativeNumber)
      ->allow_extra_args(false);
  add_analysis_options(analyze, args);

  BatchArgs batch_args;
  CLI::App* batch = add_batch_command(app, batch_args);
  MergeArgs merge_args;
  CLI::App* merge = add_merge_command(app, merge_args);
  DiffArgs diff_args;
  CLI::App* diff = add_diff_command(app, diff_args);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11's message quotes the arguments: shown as text.
    std::ostringstream out, err;
    app.exit(e, out, err);
    std::cout << hq::message_text(out.str(), hq::LineBreaks::kept);
    std::cerr << hq::message_text(err.str(), hq::LineBreaks::kept);
    return kUsage;
  }
  if (show_version) {
    std::cout << version_text();
    return kOk;
  }
  if (!*analyze && !*batch && !*merge && !*diff) {
    std::cerr << app.help();
    return kUsage;
  }

  try {
    if (*merge) return run_merge_command(merge_args);
    if (*diff) return run_diff_command(diff_args);
    const int requested = *batch ? batch_args.jobs : args.threads;
    const int threads = requested > 0 ? requested : tbb::info::default_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    const int code = *batch ? run_batch_command(batch_args, threads) : run_analyze(args);
    // A signal that arrived after the last poll point (the bundles already
    // swapped in) is not ignored silently: the run says that it finished.
    if (const int s = hq::stop::requested(); s != 0)
      std::cerr << "hqview: " << hq::stop::signal_name(s) << " arrived after the work was complete; the output is kept\n";
    return code;
  } catch (const std::bad_alloc&) {
    std::cerr << "hqview: out of memory (see --max-memory, --memory-budget)\n";
    return kEnvironment;
  } catch (const std::exception& e) {
    const int code = exit_code_of_current_exception();
    if (code == kInternal)
      std::cerr << "hqview: internal error: " << shown(e.what()) << " (please report this)\n";
    else
      std::cerr << "hqview: " << shown(e.what()) << "\n";
    return code;
  }
}
