#include "hqview/pipeline/analyze.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numeric>

#include <tbb/parallel_invoke.h>

#include "hqview/core/error.h"
#include "hqview/core/sha256.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/pipeline/metric_summary.h"
#include "hqview/quality/corner_jacobian.h"
#include "hqview/report/report_json.h"
#include "hqview/render/osmesa_renderer.h"
#include "hqview/render/views.h"

namespace hq {
namespace fs = std::filesystem;
namespace {

StatisticsOptions jacobian_histogram() {
  StatisticsOptions o;
  o.histogram_min = -1.0;
  o.histogram_max = 1.0;
  o.histogram_bins = 20;
  return o;
}

// The path as the user gave it, or only its file name when absolute, so
// report.json holds no machine-specific path.
std::string reported_path(const fs::path& p) { return p.is_absolute() ? p.filename().string() : p.lexically_normal().string(); }

// Boundary error and UV atlas against the reference surface (ALGORITHMS.md §5).
void analyze_reference(const fs::path& path, const ReadLimits& limits, ReportModel& model) {
  const TriSurface reference = read_surface(path, limits);  // checks the file before it is read whole
  const std::string bytes = read_file_bytes(path);
  std::string format = path.extension().string();
  std::transform(format.begin(), format.end(), format.begin(), [](unsigned char c) { return std::tolower(c); });
  format = format == ".mesh" ? "medit" : format.substr(std::min<std::size_t>(1, format.size()));
  model.reference_input = InputFile{reported_path(path), format, sha256_hex(bytes)};
  try {
    model.boundary_error = compute_boundary_error(model.mesh, model.topology, reference);
  } catch (const InputError& e) {
    throw InputError(path.string() + ": " + e.what());
  }
  model.warnings.insert(model.warnings.end(), model.boundary_error->warnings.begin(), model.boundary_error->warnings.end());
  model.uv_atlas = build_uv_atlas(reference, UvOptions{.improve_with_lscm = true});
  model.reference_surface = reference;
}

}  // namespace

MeshSummary summarize_mesh(const HexMesh& mesh, const Topology& topo) {
  MeshSummary s;
  s.num_vertices = mesh.num_vertices();
  s.num_hexes = mesh.num_hexes();
  s.num_unreferenced_vertices = static_cast<Index>(topo.unreferenced_vertices.size());
  s.num_boundary_faces = static_cast<Index>(topo.boundary_faces.size());
  s.num_boundary_vertices = static_cast<Index>(topo.boundary_vertices.size());
  s.num_non_manifold_faces = static_cast<Index>(topo.non_manifold_faces.size());
  // Bounding box of the vertices hexes use (stray points do not frame views).
  bool first = true;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (topo.vertex_hex_offsets[v] == topo.vertex_hex_offsets[v + 1]) continue;
    const Vec3& p = mesh.points[v];
    if (first) {
      s.bbox_min = s.bbox_max = p;
      first = false;
    }
    s.bbox_min = {std::min(s.bbox_min.x, p.x), std::min(s.bbox_min.y, p.y), std::min(s.bbox_min.z, p.z)};
    s.bbox_max = {std::max(s.bbox_max.x, p.x), std::max(s.bbox_max.y, p.y), std::max(s.bbox_max.z, p.z)};
  }
  s.bbox_diagonal = norm(s.bbox_max - s.bbox_min);
  if (!topo.edges.empty()) {
    double sum = 0.0;
    s.edge_length_min = INFINITY;
    for (const Edge& e : topo.edges) {
      const double l = norm(mesh.points[e[1]] - mesh.points[e[0]]);
      s.edge_length_min = std::min(s.edge_length_min, l);
      s.edge_length_max = std::max(s.edge_length_max, l);
      sum += l;
    }
    s.edge_length_mean = sum / static_cast<double>(topo.edges.size());
  }
  return s;
}

QualitySummary summarize_quality(const HexMesh& mesh, const QualityField& field, int worst_count) {
  QualitySummary q;
  const auto options = jacobian_histogram();
  // A corner with a zero-length edge is degenerate: counted, kept out of the
  // distribution (its value 0 still reaches vertex quality).
  std::vector<std::uint8_t> corner_flags(field.corner_scaled_jacobian.size());
  for (std::size_t h = 0; h < field.corner_degenerate_mask.size(); ++h)
    for (int i = 0; i < 8; ++i) corner_flags[8 * h + static_cast<std::size_t>(i)] = (field.corner_degenerate_mask[h] >> i) & 1u;
  // Three independent sorts (the corners': 8 values per hex) run at once.
  tbb::parallel_invoke([&] { q.scaled_jacobian = compute_statistics(field.cell_scaled_jacobian, options); },
                       [&] {
                         q.corner_scaled_jacobian =
                             compute_statistics(field.corner_scaled_jacobian, options, corner_flags);
                       },
                       [&] { q.vertex_quality = compute_statistics(field.vertex_quality, options); });

  // The headline's cell counts (Verdict metrics: summarize_hex_metrics).
  q.num_inverted = q.scaled_jacobian.num_inverted;
  q.num_degenerate = q.scaled_jacobian.num_degenerate;

  // Worst vertices: lowest quality first, ties by id; unreferenced ones skipped.
  std::vector<Index> vertices;
  for (std::size_t v = 0; v < field.vertex_quality.size(); ++v)
    if (!std::isnan(field.vertex_quality[v])) vertices.push_back(static_cast<Index>(v));
  const std::size_t nv = std::min<std::size_t>(static_cast<std::size_t>(worst_count), vertices.size());
  std::partial_sort(vertices.begin(), vertices.begin() + static_cast<std::ptrdiff_t>(nv), vertices.end(), [&](Index a, Index b) {
    const double qa = field.vertex_quality[a], qb = field.vertex_quality[b];
    return qa != qb ? qa < qb : a < b;
  });
  for (std::size_t i = 0; i < nv; ++i)
    q.worst_vertices.push_back({vertices[i], field.vertex_quality[vertices[i]], mesh.points[vertices[i]]});

  // Worst cells: degenerate (1e30) cells first, they are the worst of all,
  // then ascending scaled Jacobian, ties by id.
  std::vector<Index> cells(field.cell_scaled_jacobian.size());
  std::iota(cells.begin(), cells.end(), 0);
  auto rank = [&](Index c) {
    const double v = field.cell_scaled_jacobian[c];
    return v >= kVerdictDegenerate ? -INFINITY : v;
  };
  const std::size_t nc = std::min<std::size_t>(static_cast<std::size_t>(worst_count), cells.size());
  std::partial_sort(cells.begin(), cells.begin() + static_cast<std::ptrdiff_t>(nc), cells.end(), [&](Index a, Index b) {
    const double ra = rank(a), rb = rank(b);
    return ra != rb ? ra < rb : a < b;
  });
  for (std::size_t i = 0; i < nc; ++i) q.worst_cells.push_back({cells[i], field.cell_scaled_jacobian[cells[i]]});
  return q;
}

Analysis analyze(const AnalyzeOptions& options) {
  Analysis result;
  ReportModel& model = result.model;
  model.tool_version = options.tool_version;
  model.has_annotated_vtu = true;  // every analyze bundle has data/annotated.vtu

  const std::string bytes = read_hex_mesh_bytes(options.mesh_path, options.mesh_format, options.read_limits);
  LoadedMesh loaded = read_hex_mesh_as(options.mesh_path, bytes, options.mesh_format, options.read_limits);
  model.mesh_input = {reported_path(options.mesh_path), loaded.format, sha256_hex(bytes)};
  model.warnings = std::move(loaded.warnings);
  model.mesh = std::move(loaded.mesh);

  model.topology = build_topology(model.mesh);
  model.field = compute_quality(model.mesh, model.topology);
  model.mesh_summary = summarize_mesh(model.mesh, model.topology);
  model.metrics = compute_hex_metrics(model.mesh, options.metrics);
  model.quality = summarize_quality(model.mesh, model.field, options.worst_count);
  model.quality.metrics = summarize_hex_metrics(model.metrics);
  model.glyphs = compute_glyphs(model.mesh.points, model.field.vertex_quality, model.mesh_summary.edge_length_mean,
                                options.glyphs);
  if (options.overlap) model.overlap = check_overlap(model.mesh, model.topology, *options.overlap);
  if (!model.topology.unreferenced_vertices.empty())
    model.warnings.push_back(std::to_string(model.topology.unreferenced_vertices.size()) +
                             " vertices are used by no hexahedron (ignored by the analysis)");
  if (!options.reference_path.empty()) analyze_reference(options.reference_path, options.read_limits, model);
  if (!options.compare_path.empty()) {
    const std::string other_bytes = read_hex_mesh_bytes(options.compare_path, options.mesh_format, options.read_limits);
    LoadedMesh other = read_hex_mesh_as(options.compare_path, other_bytes, options.mesh_format, options.read_limits);
    ReportModel::Compared& c = model.compare.emplace();
    c.input = {reported_path(options.compare_path), other.format, sha256_hex(other_bytes)};
    c.mesh = std::move(other.mesh);
    c.topology = build_topology(c.mesh);
    c.field = compute_quality(c.mesh, c.topology);
    c.mesh_summary = summarize_mesh(c.mesh, c.topology);
    c.quality = summarize_quality(c.mesh, c.field, options.worst_count);
    c.quality.metrics = summarize_hex_metrics(compute_hex_metrics(c.mesh, options.metrics));
  }

  if (options.render) {
    const auto renderer = make_osmesa_renderer();
    ViewInputs inputs{&model.mesh, &model.topology, &model.field.vertex_quality, &model.field.cell_scaled_jacobian,
                      model.glyphs ? &*model.glyphs : nullptr,
                      model.overlap ? &*model.overlap : nullptr,
                      fs::path(model.mesh_input.path).filename().string(),
                      model.boundary_error ? &*model.boundary_error : nullptr,
                      model.reference_surface ? &*model.reference_surface : nullptr,
                      model.uv_atlas ? &*model.uv_atlas : nullptr};
    if (model.compare) {
      inputs.compare_mesh = &model.compare->mesh;
      inputs.compare_topology = &model.compare->topology;
      inputs.compare_vertex_quality = &model.compare->field.vertex_quality;
      inputs.compare_name = fs::path(model.compare->input.path).filename().string();
    }
    for (RenderedView& view : render_views(inputs, {options.image_width, options.image_height, 40, options.glyphs.top_clusters, options.focus_vertices, options.views}, *renderer)) {
      ViewEntry& entry = model.views.emplace_back();
      entry.id = view.id;
      entry.title = view.title;
      for (ViewFile& file : view.files) {
        entry.files.push_back(file.relative_path);
        entry.links.push_back({file.cluster, file.vertex, std::move(file.hotspots)});
        // A PNG already encoded by render_views is written as its bytes.
        const bool encoded = !file.png.empty();
        result.images.push_back({file.relative_path, encoded ? Image{} : std::move(file.image),
                                 encoded ? std::move(file.png) : std::move(file.text)});
      }
    }
  }
  // Gates read the finished report, so any numeric key can be gated on.
  model.gates = evaluate_gates(options.gates, report_json(model));
  return result;
}

}  // namespace hq
