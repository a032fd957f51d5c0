#include "hqview/pipeline/analyze.h"

#include <tbb/parallel_invoke.h>

#include <atomic>
#include <chrono>
#include <future>
#include <limits>
#include <optional>

#include "hqview/core/box3.h"
#include "hqview/core/error.h"
#include "hqview/core/stop.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/io/mesh_source.h"
#include "hqview/mesh/planarity.h"
#include "hqview/mesh/surface_boundary.h"
#include "hqview/quality/quality_summary.h"
#include "hqview/render/upright.h"
#include "hqview/views/surface_views.h"

namespace hq {
namespace fs = std::filesystem;
namespace {

// The matched faces of every cell (Topology::cell_face_offsets/uses) serve
// the overlap and the size gradation only: released once both ran, before
// the metric columns and summaries pile up (2.18 M tets: 52 MiB of the
// run's peak). A later overlap or structure on this topology would match
// the faces itself, to the same table.
void release_cell_faces(Topology& topology) {
  std::vector<Index>().swap(topology.cell_face_offsets);
  std::vector<Index>().swap(topology.cell_face_uses);
}

// The up axis of every view: --up's, or under --up auto the resting one
// (a volume mesh) or a curved surface's axis of revolution
// (surface_view_up).
Vec3 views_up(const Analysis& a, const AnalyzeOptions& options) {
  if (a.resting_up) return a.resting_up->up;
  return options.up_auto ? surface_view_up(a.mesh, a.topology, options.views.up) : options.views.up;
}

// One hex mesh from its file: the source opened once, then read.
LoadedMesh load_mesh(const fs::path& path, const AnalyzeOptions& options, InputFile& input) {
  MeshSource source = open_mesh_source(path, options.mesh_format, options.read_limits);
  LoadedMesh loaded = read_hex_mesh(source, options.read_limits);
  input = input_file(source, loaded);
  return loaded;
}

// Meshes of up to this many volume cells get their metrics and the metrics'
// summaries computed beside the overlap stage, whose box search and sorts
// run largely on one core (363,520 hexes: the whole run 1.42 -> 1.35 s on 2
// cores, medians of 5 interleaved runs). Larger meshes compute them after
// it, so that the overlap scratch (the tetrahedra's points, 24 bytes per
// vertex, face and hex) is freed before the metric arrays (176 bytes per
// hex) exist and the two never add up in the peak memory (2,908,160 hexes:
// 1.77 GB). Counted over every volume cell: 2,181,120 tets (the 363,520
// hexes split 6 each) compute theirs after the overlap stage too.
constexpr std::size_t kMetricsBesideOverlapMaxCells = 1'000'000;
// A surface mesh's faces: its overlap scratch (two triangles, their boxes
// and the pairs of faces whose boxes meet: about 250 bytes a face) and its
// metric columns (8 bytes a face each) are smaller, so its metrics, their
// summaries and its quad structure run beside the self-intersection up to
// this many faces (1,092,416 quads: the run's peak RSS 0.86 GB).
constexpr std::size_t kMetricsBesideSurfaceOverlapMaxFaces = 4'000'000;

// f, timed into `seconds`: for stages that run beside another one.
template <class F>
auto timed(double& seconds, F f) {
  return [&seconds, f] {
    const auto begin = std::chrono::steady_clock::now();
    f();
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  };
}

// Whether a block of another kind keeps a metric's values once summarised:
// those that have a cells.csv column (named as a hex metric).
bool has_cell_column(std::string_view metric) { return hex_metric_from_name(metric).has_value(); }

// A surface mesh's blocks keep their areas too until keep_cell_metric_columns
// (add_surface_warnings reads them for the faces of zero area).
bool has_cell_column_or_area(std::string_view metric) { return has_cell_column(metric) || metric == "area"; }

// A surface mesh's plane and orientation (planarity.h, SurfaceTopology);
// nothing for a volume mesh.
SurfaceOrientation surface_orientation(const HexMesh& mesh, const Topology& topology,
                                       std::optional<Planarity>& planarity) {
  SurfaceOrientation out;
  if (!is_surface_mesh(mesh)) return out;
  const Box3 box = referenced_bounding_box(mesh, topology);
  planarity = measure_planarity(mesh, box.is_empty() ? 0.0 : norm(box.hi - box.lo));
  if (planarity->is_planar)
    out.plane_normal = planarity->normal;
  else
    out.is_reversed = topology.surface.is_reversed;
  return out;
}

// A surface mesh's faces of zero area and non-manifold edges, as warnings.
void add_surface_warnings(Analysis& a) {
  if (!is_surface_mesh(a.mesh)) return;
  const SurfaceTopology& s = a.topology.surface;
  if (s.num_non_manifold_edges > 0)
    a.warnings.push_back(std::to_string(s.num_non_manifold_edges) + " non-manifold edge" +
                         (s.num_non_manifold_edges > 1 ? "s" : "") +
                         " (used by more than two faces): the orientation is not propagated across " +
                         (s.num_non_manifold_edges > 1 ? "them" : "it"));
  std::int64_t zero_area = 0;
  for (const CellBlockMetricField& b : a.cell_metrics)
    if (const std::vector<double>* area = b.of("area"))
      for (double v : *area) zero_area += v == 0.0;
  if (zero_area > 0)
    a.warnings.push_back(std::to_string(zero_area) + " face" + (zero_area > 1 ? "s" : "") +
                         " of zero area (Verdict's area 0)");
}

// Once summarised, a block keeps the values of the metrics that have a
// cells.csv column (those named as a hex metric) and nothing else.
void keep_cell_metric_columns(std::vector<CellBlockMetricField>& blocks) {
  for (CellBlockMetricField& b : blocks) {
    for (std::size_t m = 0; m < b.names.size(); ++m)
      if (!hex_metric_from_name(b.names[m])) std::vector<double>().swap(b.values[m]);
    std::vector<double>().swap(b.corner_scaled_jacobian);
    std::vector<std::uint8_t>().swap(b.corner_degenerate_mask);
  }
}

// The finite-element check: the element conditioning, then with --simulate
// the Poisson check and its correlations with the metrics (after the
// metrics, so that the overlap scratch is gone on large meshes).
void analyze_fem(Analysis& a, const AnalyzeOptions& options, StageClock& clock) {
  if (!options.fem_elements && !options.simulate) return;
  clock.start("fem elements");
  a.fem_elements = compute_fem_elements(a.mesh);
  if (options.simulate) {
    clock.start("fem poisson");
    a.poisson = run_poisson_check(a.mesh, a.topology, *a.fem_elements);
    if (a.poisson->skipped.empty()) {
      clock.start("fem correlations");
      a.fem_correlations = correlate_metrics(a.poisson->cell_error_density, a.metrics, *a.fem_elements,
                                             a.poisson->cell_size);
    }
  }
  clock.stop();
}

// What MESH and MESH2 both get before their metrics: a surface's plane
// and orientation, the quality field, the mesh summary and the cell
// composition.
struct MeshQuality {
  QualityField field;
  MeshSummary summary;
  CellComposition composition;
};

MeshQuality measure_mesh(const HexMesh& mesh, Topology& topology) {
  MeshQuality out;
  std::optional<Planarity> planarity;
  out.field = compute_quality(mesh, topology, surface_orientation(mesh, topology, planarity));
  out.summary = summarize_mesh(mesh, topology);
  out.summary.planarity = planarity;
  // A surface mesh's faces are what the views, the viewer and the compare
  // alignment take as its boundary; after summarize_mesh (the summary's
  // num_boundary_faces stays 0).
  add_surface_faces_as_boundary(mesh, topology);
  out.composition = compute_cell_composition(mesh);
  return out;
}

void analyze_quality(Analysis& a, const AnalyzeOptions& options, StageClock& clock) {
  clock.start("quality");
  const bool is_surface = is_surface_mesh(a.mesh);
  MeshQuality measured = measure_mesh(a.mesh, a.topology);
  a.field = std::move(measured.field);
  a.mesh_summary = std::move(measured.summary);
  a.composition = std::move(measured.composition);
  // Beside the overlap stage: the structure (the singularity graph: one
  // sequential pass over the edges; a surface's quad structure) always, and
  // on meshes up to kMetricsBesideOverlapMaxCells volume cells (surfaces:
  // kMetricsBesideSurfaceOverlapMaxFaces faces) the metrics and their
  // summaries; each is listed as a concurrent stage. Beside it, the metrics do not draw the
  // progress bar (the overlap stage does).
  const bool metrics_beside =
      options.overlap && a.field.cell_scaled_jacobian.size() <=
                             (is_surface ? kMetricsBesideSurfaceOverlapMaxFaces : kMetricsBesideOverlapMaxCells);
  std::vector<MetricSummary> metric_summaries;
  std::vector<SummarizedCellBlock> non_hex_blocks;
  std::vector<KindQualitySummary> by_kind;
  double structure_seconds = 0, metrics_seconds = 0, metric_summaries_seconds = 0;
  // A surface mesh's structure is its quad structure.
  const auto structure = timed(structure_seconds, [&] {
    if (!is_surface) {
      a.structure = compute_structure(a.mesh, a.topology);
    } else {
      // The quad structure (irregular vertices, separatrices, patches);
      // vertices.csv's `singular` marks its irregular vertices.
      QuadStructureOptions quad_options;
      quad_options.hole_edges = a.hole_edges;  // no further cap: each edge is traced at most once (linear)
      a.quad_structure = compute_quad_structure(a.mesh, quad_options);
      a.structure = HexStructure{};
      a.structure.vertex_singular.assign(a.quad_structure->irregular.begin(), a.quad_structure->irregular.end());
      // No size gradation on a surface mesh: one undefined value per cell.
      a.structure.cell_gradation.assign(static_cast<std::size_t>(num_cells(a.mesh)),
                                        std::numeric_limits<double>::quiet_NaN());
    }
  });
  const auto metrics = timed(metrics_seconds, [&] {
    a.metrics = compute_hex_metrics(a.mesh, options.metrics, metrics_beside ? progress::Reporting::silent : progress::Reporting::report);
    // The volume kinds' metrics are summarised as they are computed (one
    // column at a time), keeping only the cells.csv columns.
    non_hex_blocks = summarize_non_hex_blocks(a.mesh, a.field, is_surface ? has_cell_column_or_area : has_cell_column);
  });
  const auto summarize_metrics = timed(metric_summaries_seconds, [&] {
    metric_summaries = summarize_hex_metrics(a.metrics);
    by_kind = summarize_by_kind(a.mesh, a.field, metric_summaries, non_hex_blocks);
    a.cell_metrics.clear();
    for (SummarizedCellBlock& block : non_hex_blocks) a.cell_metrics.push_back(std::move(block.field));
    if (is_surface) add_surface_warnings(a);
    keep_cell_metric_columns(a.cell_metrics);
  });
  const auto concurrent = [&](const char* name, double seconds) {
    a.timings.push_back({name, seconds, peak_rss_bytes(), true});
    if (options.on_stage) options.on_stage(a.timings.back());
  };
  if (options.overlap) {
    // A surface mesh's coincident vertices, zero-length edges and duplicate
    // faces as "overlap", its faces' self-intersection as a stage of its
    // own (the clock is this branch's alone: the others are timed apart).
    clock.start("overlap");
    const auto overlap = [&] {
      a.overlap = is_surface ? check_surface_overlap(a.mesh, a.topology.surface, *a.mesh_summary.planarity,
                                                     *options.overlap, [&] { clock.start("self-intersection"); })
                             : check_overlap(a.mesh, a.topology, *options.overlap);
    };
    if (metrics_beside)
      tbb::parallel_invoke(overlap, structure, [&] {
        metrics();
        summarize_metrics();
      });
    else
      tbb::parallel_invoke(overlap, structure);
    clock.stop();
    release_cell_faces(a.topology);
    concurrent("structure", structure_seconds);
    if (metrics_beside) {
      concurrent("metrics", metrics_seconds);
      concurrent("metric summaries", metric_summaries_seconds);
    }
  }
  if (!metrics_beside) {
    clock.start("metrics");
    metrics();
  }
  clock.start("summaries");
  // A mesh of one kind shares the corner statistics (and a tet mesh the
  // scaled Jacobian's) between by_kind and the whole mesh: the metrics'
  // summaries first, then the quality summary copies them (2,181,120 tets:
  // 8.7 M corner values sorted once, not twice).
  if (!metrics_beside) summarize_metrics();
  a.quality = summarize_quality(a.mesh, a.field, options.worst_count, single_kind_statistics(a.mesh, a.field, by_kind));
  a.quality.metrics = std::move(metric_summaries);
  a.quality.by_kind = std::move(by_kind);
  if (!options.overlap) {
    clock.start("structure");
    structure();
    release_cell_faces(a.topology);
  }
  clock.stop();
  analyze_fem(a, options, clock);
}

// What to try when the reference seems misplaced (unless already tried).
const char* alignment_hint(const AnalyzeOptions& options) {
  return options.reference_align == CompareAlign::none
             ? "; --reference-align bbox moves the reference onto the mesh's bounding box (auto also tries the axis "
               "rotations)"
             : "";
}

// Runs f; an InputError it throws comes back prefixed with the reference's
// path, and with the alignment hint when the boxes do not overlap.
template <class F>
void with_reference_hint(const AnalyzeOptions& options, F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError(options.reference_path.string() + ": " + what +
                     (what.find("do not overlap") != std::string::npos ? alignment_hint(options) : ""));
  }
}

// The reference surface (ALGORITHMS.md §5), read and, with
// --reference-align bbox, moved onto the mesh boundary's bounding box
// (uniform scale and translation); with auto, as --compare-align auto.
TriSurface read_reference(Analysis& a, const AnalyzeOptions& options) {
  SurfaceSource source = open_surface_source(options.reference_path, options.read_limits);
  TriSurface reference = read_surface(source);
  a.reference_input = input_file(source);
  Box3 mesh_box, reference_box;
  for (Index v : measured_vertices(a.mesh, a.topology)) mesh_box.add(a.mesh.points[static_cast<std::size_t>(v)]);
  for (const auto& t : reference.triangles)
    for (Index v : t) reference_box.add(reference.points[static_cast<std::size_t>(v)]);
  a.reference_alignment =
      options.reference_align == CompareAlign::auto_
          ? align_surfaces(boundary_triangles(a.mesh, a.topology), mesh_box, reference, reference_box, CompareAlign::auto_)
          : align_boxes(mesh_box, reference_box, options.reference_align);
  for (Vec3& p : reference.points) p = aligned_point(p, a.reference_alignment);
  // A misplaced reference is refused before its atlas is started.
  with_reference_hint(options, [&] { check_reference_placement(a.mesh, a.topology, reference); });
  return reference;
}

// The UV atlas of the reference on a thread of its own, beside the other
// stages and the first views: it is mostly sequential (the charts' LSCM
// solves) and so are the views, so on two cores it takes the core they
// leave. Its result does not depend on what runs beside it. It works on its
// own copy of the reference; the caller's --mesh-timeout deadline follows it,
// and a stop request stops it at its next check.
struct AtlasJob {
  UvAtlas atlas;
  double seconds = 0;
};
std::future<AtlasJob> start_atlas(TriSurface reference, const Vec3& up, const std::atomic<bool>& cancel) {
  return std::async(std::launch::async,
                    [reference = std::move(reference), up, deadline = stop::current_deadline(), &cancel] {
    const stop::ScopedDeadline same(deadline);
    const stop::ScopedCancel abandoned(cancel);
    const auto begin = std::chrono::steady_clock::now();
    AtlasJob job;
    job.atlas = build_uv_atlas(reference, UvOptions{.up = up, .improve_with_lscm = true});
    job.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    return job;
  });
}

// Boundary error against the reference.
void analyze_boundary_error(Analysis& a, const TriSurface& reference, const AnalyzeOptions& options) {
  with_reference_hint(options, [&] { a.boundary_error = compute_boundary_error(a.mesh, a.topology, reference, options.boundary);
  });
  for (std::string w : a.boundary_error->warnings) {
    if (w.find("same units and placement") != std::string::npos) w += alignment_hint(options);
    a.warnings.push_back(std::move(w));
  }
}

// MESH2 of --compare, read, and refused unless it has MESH's dimension: a
// surface's faces against a volume's boundary would compare different
// cells under one name. Before any of MESH's analysis, so that a refusal
// costs only the reading.
void read_compare(Analysis& a, const AnalyzeOptions& options) {
  Analysis::Compared& c = a.compare.emplace();
  c.mesh = load_mesh(options.compare_path, options, c.input).mesh;
  if (is_surface_mesh(c.mesh) != is_surface_mesh(a.mesh))
    throw InputError(options.compare_path.string() + ": --compare: " +
                     (is_surface_mesh(c.mesh) ? "a surface mesh against a volume mesh"
                                              : "a volume mesh against a surface mesh") +
                     " (compare meshes of one dimension)");
}

// MESH2 of --compare (read_compare), analysed as the mesh is (quality only).
void analyze_compare(Analysis& a, const AnalyzeOptions& options) {
  Analysis::Compared& c = *a.compare;
  c.topology = build_topology(c.mesh);
  MeshQuality measured = measure_mesh(c.mesh, c.topology);
  c.field = std::move(measured.field);
  c.mesh_summary = std::move(measured.summary);
  c.composition = std::move(measured.composition);
  c.quality = summarize_quality(c.mesh, c.field, options.worst_count);
  c.quality.metrics = summarize_hex_metrics(compute_hex_metrics(c.mesh, options.metrics));
  c.alignment = align_compare_mesh(a.mesh, a.topology, c.mesh, c.topology, options.compare_align);
}

std::optional<ViewCameraEntry> camera_entry(const std::optional<Camera>& camera, const ViewFile& file, const Vec3& up) {
  if (!camera) return std::nullopt;
  const Vec3 direction = camera->target - camera->eye;
  return ViewCameraEntry{camera->eye,
                         camera->target,
                         camera->up,
                         view_elevation_degrees(direction, up),
                         view_azimuth_degrees(direction, up),
                         camera->is_perspective,
                         camera->is_perspective ? camera->fov_y_degrees : camera->ortho_height,
                         file.camera_aspect,
                         file.frame_width,
                         file.frame_height};
}

// The rendered views as report entries and bundle files.
void add_views(std::vector<RenderedView> views, const Vec3& up, AnalyzeResult& result) {
  for (RenderedView& view : views) {
    ViewEntry& entry = result.model.views.emplace_back();
    entry.id = view.id;
    entry.title = view.title;
    for (ViewFile& file : view.files) {
      entry.files.push_back(file.relative_path);
      entry.links.push_back({file.cluster, file.vertex, std::move(file.hotspots)});
      entry.cameras.push_back(camera_entry(file.camera, file, up));
      // A PNG already encoded by render_views is written as its bytes.
      const bool encoded = !file.png.empty();
      result.images.push_back({file.relative_path, encoded ? Image{} : std::move(file.image),
                               encoded ? std::move(file.png) : std::move(file.text)});
    }
  }
}

// An analysis whose UV atlas may still be being built (start_atlas). When
// it is left with the atlas unfinished (a stage threw), the atlas is
// cancelled at its next check and waited for (the future's destructor).
struct AnalysisInProgress {
  Analysis analysis;
  std::atomic<bool> cancel_atlas{false};
  std::future<AtlasJob> atlas;

  AnalysisInProgress() = default;
  AnalysisInProgress(const AnalysisInProgress&) = delete;
  AnalysisInProgress& operator=(const AnalysisInProgress&) = delete;
  ~AnalysisInProgress() { cancel_atlas = true; }

  // Waits for the atlas (a stage "uv atlas wait" on `timings`) and files it,
  // with its own time as a concurrent stage "uv atlas". Rethrows what the
  // atlas threw. Does nothing once done or without a reference.
  void finish_atlas(std::vector<StageTime>& timings, const StageSink& sink) {
    if (!atlas.valid()) return;
    AtlasJob job;
    {
      StageClock clock(timings, sink);
      clock.start("uv atlas wait");
      job = atlas.get();
    }
    analysis.uv_atlas = std::move(job.atlas);
    timings.push_back({"uv atlas", job.seconds, peak_rss_bytes(), true});
    if (sink) sink(timings.back());
  }
};

// Every stage but the views, the atlas left running (when there is a reference).
void start_analysis(const AnalyzeOptions& options, AnalysisInProgress& out) {
  Analysis& a = out.analysis;
  StageClock clock(a.timings, options.on_stage);
  clock.start("read");
  LoadedMesh loaded = load_mesh(options.mesh_path, options, a.mesh_input);
  a.warnings = std::move(loaded.warnings);
  a.notes = std::move(loaded.notes);
  a.mesh = std::move(loaded.mesh);
  a.hole_edges = std::move(loaded.hole_edges);
  if (!options.compare_path.empty()) {
    clock.start("read compare mesh");
    read_compare(a, options);
  }
  clock.start("topology");
  a.topology = build_topology(a.mesh);
  const bool is_surface = is_surface_mesh(a.mesh);
  if (options.up_auto && !is_surface) a.resting_up = choose_resting_up(a.mesh, a.topology);
  // The reference as soon as the boundary is known, so that its atlas runs
  // beside everything after.
  if (!options.reference_path.empty()) {
    clock.start("read reference");
    a.reference_surface = read_reference(a, options);
    // A planar mesh's reference is its own UV map (no atlas).
    if (!is_planar_surface(a.mesh, a.topology))
      out.atlas = start_atlas(*a.reference_surface, views_up(a, options), out.cancel_atlas);
  }
  clock.stop();
  analyze_quality(a, options, clock);
  clock.start("glyphs");
  a.glyphs = compute_glyphs(a.mesh.points, a.field.vertex_quality, a.mesh_summary.edge_length_mean, options.glyphs);
  clock.stop();
  if (const std::size_t n = a.topology.unreferenced_vertices.size(); n > 0)
    a.warnings.push_back(std::to_string(n) + " " +
                         (a.topology.across_kinds || is_surface_mesh(a.mesh)
                              ? std::string(n == 1 ? "node is" : "nodes are") +
                                    " no cell's corner (ignored by the analysis and not counted as vertices; a "
                                    "higher-order cell's mid-edge and face nodes are such nodes)"
                              : std::string(n == 1 ? "vertex is" : "vertices are") +
                                    " used by no hexahedron (ignored by the analysis)"));
  if (a.reference_surface) {
    clock.start("boundary error");
    analyze_boundary_error(a, *a.reference_surface, options);
    clock.stop();
  }
  if (!options.compare_path.empty()) {
    clock.start("compare mesh");
    analyze_compare(a, options);
    clock.stop();
  }
}

}  // namespace

Analysis analyze_mesh(const AnalyzeOptions& options) {
  AnalysisInProgress in_progress;
  start_analysis(options, in_progress);
  in_progress.finish_atlas(in_progress.analysis.timings, options.on_stage);
  return std::move(in_progress.analysis);
}

AnalyzeResult analyze(const AnalyzeOptions& options, Renderer* renderer) {
  AnalyzeResult result;
  ReportModel& model = result.model;
  model.tool_version = options.tool_version;
  model.data = options.data;
  AnalysisInProgress in_progress;
  start_analysis(options, in_progress);
  ViewOptions views = options.views;
  views.up = views_up(in_progress.analysis, options);
  if (renderer) {
    // The views that need no atlas are drawn while it is built.
    std::vector<StageTime> view_times;
    {
      StageClock clock(view_times, options.on_stage);
      const auto before_view = [&](ViewNeeds needs) {
        if (needs == ViewNeeds::uv_atlas) in_progress.finish_atlas(view_times, options.on_stage);
      };
      add_views(render_views(in_progress.analysis, views, *renderer, &clock, before_view), views.up, result);
      in_progress.finish_atlas(view_times, options.on_stage);
    }
    in_progress.analysis.timings.insert(in_progress.analysis.timings.end(), view_times.begin(), view_times.end());
  }
  in_progress.finish_atlas(in_progress.analysis.timings, options.on_stage);
  model.analysis = std::move(in_progress.analysis);
  model.data.non_conforming_faces = model.analysis.topology.across_kinds;
  model.has_viewer = renderer && options.viewer;
  model.viewer_max_mb = options.viewer_max_mb;
  model.viewer_up = views.up;
  model.up_auto = options.up_auto;
  model.viewer_error_density_reference = views.error_density_reference;
  // Gates read the finished report, so any numeric key can be gated on.
  {
    StageClock clock(model.analysis.timings, options.on_stage);
    clock.start("report document");
    result.document = report_document(model);
    model.gates = evaluate_gates(options.gates, result.document);
    set_report_gates(result.document, model.gates);
  }
  return result;
}

}  // namespace hq
