// The builders of kViews (one per view, in table order) and the render loop
// that runs them.
#include "hqview/views/views.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>

#include "hqview/analysis/resting_up.h"
#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/core/quality_text.h"
#include "hqview/core/progress.h"
#include "hqview/core/stop.h"
#include "hqview/core/text.h"
#include "hqview/image/png.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/quality/cell_corner_jacobian.h"
#include "hqview/quality/hex_metrics.h"
#include "hqview/render/upright.h"
#include "hqview/views/boundary_views.h"
#include "hqview/views/detail_views.h"
#include "hqview/views/error_density_views.h"
#include "hqview/views/inverted_callout.h"
#include "hqview/views/main_views.h"
#include "hqview/views/overview_viewpoint.h"
#include "hqview/views/overview_views.h"
#include "hqview/views/structure_views.h"
#include "hqview/views/surface_views.h"
#include "hqview/views/uv_key_view.h"

namespace hq {

// The camera and size of a rendered frame (report.json views[].cameras).
struct FrameRecord {
  std::optional<Camera> camera;  // none before the first frame
  double aspect = 1.0;           // width / height
  int width = 0, height = 0;     // pixels
};

// What the builders share: the analysis, the options, the renderer, and what
// several views derive from the analysis (glyphs, the top clusters, the
// vertices with a local view).
struct ViewContext {
  const Analysis& a;
  const ViewOptions& options;
  Renderer& renderer;
  std::string name;  // the mesh's file name, for titles
  GlyphResult no_glyphs;
  const GlyphResult* glyphs = nullptr;
  std::size_t num_top = 0;            // clusters with a C view
  std::vector<Index> local_vertices;  // views D and E
  const FrameRecord* last_frame = nullptr;  // the frame rendered last
  OverviewViewpoint overview_viewpoint{};   // the overview's and thumbnail's eye (overview_viewpoint.h)
  std::vector<Index> inverted_cells;        // ringed on the overview and thumbnail (inverted_callout.h)

  Index cluster_of(Index v) const { return glyphs->vertex_cluster[static_cast<std::size_t>(v)]; }
  const std::vector<double>& quality() const { return a.field.vertex_quality; }
};

namespace {

// The wrapped renderer, keeping the camera of the last frame (report.json
// views[].cameras).
class RecordingRenderer final : public Renderer {
 public:
  explicit RecordingRenderer(Renderer& inner) : inner_(inner) {}
  Image render(const Scene& scene, const Camera& camera, int width, int height) override {
    last_frame = {camera, static_cast<double>(width) / static_cast<double>(std::max(height, 1)), width, height};
    return inner_.render(scene, camera, width, height);
  }
  IdImage render_ids(const Scene& scene, const Camera& camera, int width, int height) override {
    return inner_.render_ids(scene, camera, width, height);
  }
  FrameRecord last_frame;

 private:
  Renderer& inner_;
};

// Waits for a task group's tasks, also when leaving by an exception (the
// tasks write into the views being returned).
struct WaitOnExit {
  tbb::task_group& group;
  ~WaitOnExit() {
    try {
      group.wait();
    } catch (...) {  // the exception already on its way wins
    }
  }
};

template <class Options>
Options sized(const ViewContext& c) {
  Options o;
  o.width = c.options.width;
  o.height = c.options.height;
  o.up = c.options.up;
  return o;
}

// The inverted cells as the headline counts them (quality_summary.cpp):
// hexes of scaled Jacobian <= 0 (not Verdict's sentinel), other kinds by
// their own rule.
std::vector<Index> inverted_cell_ids(const QualityField& field) {
  std::vector<Index> cells;
  for (std::size_t h = 0; h < field.num_hexes && h < field.cell_scaled_jacobian.size(); ++h) {
    const double v = field.cell_scaled_jacobian[h];
    if (v <= 0.0 && !is_verdict_sentinel(v)) cells.push_back(static_cast<Index>(h));
  }
  for (std::size_t i = 0; i < field.non_hex_validity.size(); ++i)
    if (is_inverted(field.non_hex_validity[i])) cells.push_back(static_cast<Index>(field.num_hexes + i));
  return cells;
}

// Whether a volume mesh has tets, wedges or pyramids.
static bool has_non_hex(const HexMesh& m) { return !m.tets.empty() || !m.wedges.empty() || !m.pyramids.empty(); }

// The one noun for the mesh's cells in titles and legends (plural: core/
// text.h): a surface mesh's "quad", "triangle" or "face" (both kinds);
// "hex", or "cell" on a volume mesh with other kinds (the per-cell fields
// cover every kind).
static std::string cell_noun(const Analysis& a) {
  if (is_surface_mesh(a.mesh)) return a.mesh.triangles.empty() ? "quad" : a.mesh.quads.empty() ? "triangle" : "face";
  return has_non_hex(a.mesh) ? "cell" : "hex";
}

// A 3D view's file: its image and the camera that drew it.
ViewFile framed(std::string relative_path, Image image, const ViewContext& c) {
  ViewFile file{std::move(relative_path), std::move(image), {}};
  if (c.last_frame) {
    file.camera = c.last_frame->camera;
    file.camera_aspect = c.last_frame->aspect;
    file.frame_width = c.last_frame->width;
    file.frame_height = c.last_frame->height;
  }
  return file;
}

// Charts: SVG for the HTML page and a PNG twin, from one Chart each.
std::vector<ViewFile> chart_files(const std::string& name, const Chart& chart) {
  std::vector<ViewFile> files{{"views/" + name + ".svg", {}, chart_svg(chart)},
                              {"views/" + name + ".png", chart_image(chart), {}}};
  // Hotspots in fractions of the image: they follow the image when scaled.
  const double sx = 1.0 / chart.width, sy = 1.0 / chart.height;
  for (ChartHotspot h : chart.hotspots) {
    h.rect = {h.rect.x * sx, h.rect.y * sy, h.rect.width * sx, h.rect.height * sy, {}};
    for (ViewFile& f : files) f.hotspots.push_back(h);
  }
  return files;
}

// D and E: the worst vertex of each top cluster, then the focus vertices;
// vertices no cell uses are left out.
std::vector<Index> choose_local_vertices(const ViewContext& c) {
  const GlyphResult& glyphs = *c.glyphs;
  const std::vector<double>& quality = c.quality();
  std::vector<Index> vertices;
  for (std::size_t k = 0; k < c.num_top; ++k) {
    Index worst = kNoIndex;
    for (Index i = glyphs.cluster_offsets[k]; i < glyphs.cluster_offsets[k + 1]; ++i) {
      const Index v = glyphs.cluster_vertices[static_cast<std::size_t>(i)];
      if (worst == kNoIndex || quality[static_cast<std::size_t>(v)] < quality[static_cast<std::size_t>(worst)])
        worst = v;
    }
    if (worst != kNoIndex) vertices.push_back(worst);
  }
  for (Index v : c.options.focus_vertices) {
    if (v < 0 || v >= c.a.mesh.num_vertices())
      throw ValueError("--focus-vertex: vertex " + std::to_string(v) + " does not exist (the mesh has " +
                       std::to_string(c.a.mesh.num_vertices()) + " vertices, ids from 0)");
    if (std::find(vertices.begin(), vertices.end(), v) == vertices.end()) vertices.push_back(v);
  }
  const Topology& topology = c.a.topology;
  std::erase_if(vertices, [&](Index v) {
    return topology.vertex_hex_offsets[static_cast<std::size_t>(v)] ==
               topology.vertex_hex_offsets[static_cast<std::size_t>(v) + 1] &&
           non_hex_cells_of(c.a.mesh, v).empty();
  });
  return vertices;
}

bool has_inputs(const Analysis& a, ViewNeeds needs) {
  switch (needs) {
    case ViewNeeds::mesh:
      return true;
    case ViewNeeds::reference:
      return a.boundary_error && a.reference_surface;
    case ViewNeeds::uv_atlas:
      return a.boundary_error && a.reference_surface && a.uv_atlas;
    case ViewNeeds::compare:
      return a.compare.has_value();
    case ViewNeeds::simulation:
      return a.poisson && a.poisson->skipped.empty() && !a.poisson->cell_error_density.empty();
  }
  return false;
}

}  // namespace

// ---- the builders, in kViews order -------------------------------------------

std::vector<ViewFile> build_overview(ViewContext& c) {
  auto overview = sized<OverviewOptions>(c);
  overview.title = c.name + (is_surface_mesh(c.a.mesh) ? ": vertex quality on the surface"
                             : !has_non_hex(c.a.mesh) ? ": vertex quality on the boundary"
                                 : ": corner quality on the boundary (each face: its cell kind's corners)");
  const OverviewViewpoint& eye = c.overview_viewpoint;
  overview.view_direction = eye.direction;
  if (!is_surface_mesh(c.a.mesh)) overview.up = eye.up;
  overview.inverted_cells = c.inverted_cells;
  overview.cell_noun = cell_noun(c.a);
  if (is_surface_mesh(c.a.mesh)) {
    overview.outline_inverted_faces = true;
    overview.outline_on_top = planar_view_direction(c.a).has_value();
    overview.inverted_are_reversed = !planar_view_direction(c.a).has_value();
  }
  if (c.a.overlap) {
    overview.intersecting_cells = c.a.overlap->num_intersecting_cells;
    // Drawn on a volume mesh (mostly inside); a surface mesh's are its own
    // faces, outlined when inverted: not overdrawn (legend text only).
    if (!is_surface_mesh(c.a.mesh))
      for (std::size_t cell = 0; cell < c.a.overlap->cell_intersecting.size(); ++cell)
        if (c.a.overlap->cell_intersecting[cell]) overview.intersecting_cell_ids.push_back(static_cast<Index>(cell));
  }
  const KindVertexQuality kinds = kind_vertex_quality(c.a.mesh, c.a.field);
  overview.kind_quality = &kinds;
  // Where the eye is, in words and degrees from the model's front (issue
  // 45f round 2: every overview says it, so titles of copies compare).
  // A shape without a front of its own (a ball): its front is the worst
  // region's side (overview_viewpoint.h, issue 45g).
  overview.title += overview_eye_words(eye, overview.up, overview.cell_noun);
  Image image = render_quality_overview(c.a.mesh, c.a.topology, c.quality(), overview, c.renderer);
  return {framed("views/overview.png", std::move(image), c)};
}

std::vector<ViewFile> build_main(ViewContext& c) {
  auto main = sized<MainViewOptions>(c);
  main.cell_kinds = mesh_kinds_text(c.a.mesh);
  main.cell_noun = cell_noun(c.a);
  main.orientation_note = mostly_inverted_note(c.a.field);
  std::vector<std::uint8_t> inverted_cells(c.a.field.cell_scaled_jacobian.size(), 0);
  for (std::size_t cell = 0; cell < inverted_cells.size(); ++cell)
    inverted_cells[cell] = cell_is_inverted(c.a.field, cell) ? 1 : 0;
  main.inverted_cells = &inverted_cells;
  const std::vector<Vec3> points = main_view_points(c.a.mesh, c.a.topology, *c.glyphs);
  main.title = "-";  // the layout of a titled figure
  const double aspect = main_view_aspect(main);
  // A surface mesh: its faces filled by quality; a planar one seen once,
  // along its normal (surface_views.h).
  const std::optional<Vec3> planar = planar_view_direction(c.a);
  if (is_surface_mesh(c.a.mesh)) {
    main.surface_cell_quality = &c.a.field.cell_scaled_jacobian;
    main.surface_inverted_cells = c.inverted_cells;
    main.surface_fill_lit = !planar;
    main.surface_inverted_are_reversed = !planar;
  }
  // A curved surface mesh: the eyes aim at the worst clusters' faces.
  const std::vector<Vec3> directions =
      planar                       ? std::vector<Vec3>{*planar}
      : is_surface_mesh(c.a.mesh) ? choose_surface_main_viewpoints(c.a.mesh, c.a.topology, *c.glyphs,
                                                                   c.a.field.cell_scaled_jacobian, points, aspect, 2,
                                                                   main.up, main.fov_y_degrees)
                                  : choose_main_viewpoints(points, *c.glyphs, aspect, 2, main.up, main.fov_y_degrees);
  const OverlapReport* overlap = c.a.overlap ? &*c.a.overlap : nullptr;
  // Once for the mesh (issue 44 part V): the tie classes, and one glyph
  // scale for both views (a cluster the same size in each).
  const std::vector<Index> ties = glyph_tie_classes(c.glyphs->clusters);
  main.glyph_ties = ties;
  main.glyph_scale = mesh_glyph_scale(c.a.mesh, c.a.topology, *c.glyphs, directions, main);
  std::vector<ViewFile> files;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    main.title =
        c.name +
        (main.surface_cell_quality ? ": faces by scaled Jacobian and glyph clusters, view "
                                   : ": glyph clusters and intersecting " + plural(cell_noun(c.a)) + ", view ") +
        std::to_string(i + 1) +
        (planar ? std::string(" (along the plane's normal)")  // metric: squares stay squares
                : " (from " + viewpoint_name(directions[i], main.up) + ")");
    Image image = render_main_view(c.a.mesh, c.a.topology, *c.glyphs, overlap, directions[i], main, c.renderer);
    files.push_back(framed("views/main_" + std::to_string(i + 1) + ".png", std::move(image), c));
  }
  return files;
}

// C and D: a surface mesh's faces filled by their scaled Jacobian (C), a
// planar one seen flat along its normal (surface_views.h).
DetailViewOptions detail_options(const ViewContext& c) {
  auto detail = sized<DetailViewOptions>(c);
  if (!is_surface_mesh(c.a.mesh)) return detail;
  detail.view_direction = planar_view_direction(c.a);
  detail.cell_quality = c.a.field.cell_scaled_jacobian;
  return detail;
}

std::vector<ViewFile> build_clusters(ViewContext& c) {
  // The scenes and cameras of all the top clusters at once (the camera
  // search is the costly part), then drawn one by one, in order.
  std::vector<DetailViewOptions> detail(c.num_top, detail_options(c));
  for (std::size_t k = 0; k < c.num_top; ++k) {
    const AggregatedGlyph& g = c.glyphs->clusters[k];
    detail[k].title = c.name + ": cluster #" + std::to_string(k) + " (" + std::to_string(g.size) +
                      " glyphs, min quality (lowest corner) " + quality_text(g.min_quality) +
                      ") and its neighbours";
  }
  std::vector<ClusterShot> shots(c.num_top);
  tbb::parallel_for(std::size_t{0}, c.num_top, [&](std::size_t k) {
    shots[k] = cluster_shot(c.a.mesh, c.a.topology, c.quality(), *c.glyphs, static_cast<Index>(k), detail[k]);
  });
  std::vector<ViewFile> files;
  for (std::size_t k = 0; k < c.num_top; ++k) {
    Image image = render_cluster_shot(shots[k], detail[k], c.renderer);
    shots[k] = ClusterShot{};  // freed once drawn
    files.push_back(framed("views/cluster_" + std::to_string(k) + ".png", std::move(image), c));
    files.back().cluster = static_cast<Index>(k);
  }
  return files;
}

std::vector<ViewFile> build_local(ViewContext& c) {
  auto detail = detail_options(c);
  const bool hybrid = !c.a.mesh.tets.empty() || !c.a.mesh.wedges.empty() || !c.a.mesh.pyramids.empty();
  std::vector<ViewFile> files;
  for (Index v : c.local_vertices) {
    // Named by its cluster: the local vertex of a lower-ranked cluster is
    // not read as cluster #0's worst.
    const Index cluster = c.cluster_of(v);
    detail.title = c.name + ": " + (cluster == kNoIndex ? std::string() : "cluster #" + std::to_string(cluster) + ", ") +
                   "vertex " + std::to_string(v) +
                   (is_surface_mesh(c.a.mesh) ? ", its faces" : hybrid ? ", its cells" : ", its hexes") +
                   " and their corner scaled Jacobians";
    Image image = render_local_view(c.a.mesh, c.a.topology, c.a.field.corner_scaled_jacobian, v, detail, c.renderer);
    files.push_back(framed("views/local_v" + std::to_string(v) + ".png", std::move(image), c));
    files.back().cluster = c.cluster_of(v);
    files.back().vertex = v;
  }
  return files;
}

std::vector<ViewFile> build_corners(ViewContext& c) {
  std::vector<ViewFile> files;
  for (Index v : c.local_vertices) {
    std::vector<double> values;
    std::vector<std::string> labels;
    for (const VertexCorner& corner : vertex_corners(c.a.mesh, c.a.topology, c.a.field.corner_scaled_jacobian, v)) {
      values.push_back(corner.value);
      labels.push_back(std::string(cell_kind_name(corner.kind)) + " " + std::to_string(corner.hex));
    }
    const Chart chart = corner_chart(values, labels,
                                     {std::max(480, 90 * static_cast<int>(values.size()) + 120), 420,
                                      c.name + ": corners at vertex " + std::to_string(v)});
    for (ViewFile& file : chart_files("corners_v" + std::to_string(v), chart)) {
      file.cluster = c.cluster_of(v);
      file.vertex = v;
      files.push_back(std::move(file));
    }
  }
  return files;
}

// What the boundary views call MESH's side of the comparison with the
// reference: a volume mesh's boundary, or a surface mesh itself.
const char* mesh_side(const Analysis& a) { return is_surface_mesh(a.mesh) ? "surface mesh" : "hex boundary"; }

BoundaryViewOptions boundary_options(ViewContext& c) {
  auto b = sized<BoundaryViewOptions>(c);
  if (is_surface_mesh(c.a.mesh)) b.mesh_word = "mesh";
  return b;
}

std::vector<ViewFile> build_boundary_error(ViewContext& c) {
  auto b = boundary_options(c);
  std::vector<ViewFile> files;
  if (c.a.boundary_error->planar) {  // one flat figure of both polylines (the plane is its own UV map)
    b.title = c.name + ": boundary and reference outline by signed error, seen along the plane's normal";
    Image flat = render_planar_boundary_error_view(c.a.mesh, c.a.topology, *c.a.reference_surface,
                                                   *c.a.boundary_error, b, c.renderer);
    files.push_back(framed("views/boundary_error_plane.png", std::move(flat), c));
    return files;
  }
  b.title = c.name + ": signed boundary error, front";
  Image front = render_boundary_error_view(c.a.mesh, c.a.topology, *c.a.boundary_error, three_quarter_view(b.up), b,
                                           c.renderer);
  files.push_back(framed("views/boundary_error_front.png", std::move(front), c));
  b.title = c.name + ": signed boundary error, back";
  Image back = render_boundary_error_view(c.a.mesh, c.a.topology, *c.a.boundary_error, three_quarter_back_view(b.up),
                                          b, c.renderer);
  files.push_back(framed("views/boundary_error_back.png", std::move(back), c));
  return files;
}

std::vector<ViewFile> build_reference_error(ViewContext& c) {
  auto b = boundary_options(c);
  std::vector<ViewFile> files;
  const BoundaryError& e = *c.a.boundary_error;
  if (e.planar) return files;  // the outline is in boundary_error's flat figure
  b.title = c.name + ": reference coloured by signed distance to the " + mesh_side(c.a) + ", front";
  files.push_back(framed("views/reference_error_front.png",
                         render_reference_error_view(*c.a.reference_surface, e, three_quarter_view(b.up), b, c.renderer), c));
  b.title = c.name + ": reference coloured by signed distance to the " + mesh_side(c.a) + ", back";
  files.push_back(framed("views/reference_error_back.png",
                         render_reference_error_view(*c.a.reference_surface, e, three_quarter_back_view(b.up), b, c.renderer), c));
  return files;
}

std::vector<ViewFile> build_uv_error(ViewContext& c) {
  auto b = boundary_options(c);
  b.title = c.name + ": reference UV atlas, reference to " + mesh_side(c.a) + " error";
  return {{"views/uv_error.png",
           render_uv_error_map(*c.a.reference_surface, *c.a.uv_atlas, *c.a.boundary_error, b, c.renderer),
           {}}};
}

std::vector<ViewFile> build_uv_key(ViewContext& c) {
  auto b = boundary_options(c);
  b.title = c.name + ": UV key, the reference's " + std::to_string(c.a.uv_atlas->num_charts) +
            " charts numbered (two opposite sides; the atlas as the UV error map lays it out)";
  return {{"views/uv_key.png", render_uv_key(*c.a.reference_surface, *c.a.uv_atlas, b, c.renderer), {}}};
}

std::vector<ViewFile> build_reference_overlay(ViewContext& c) {
  if (c.a.boundary_error->planar) return {};  // coplanar surfaces: boundary_error's flat figure draws both
  auto b = boundary_options(c);
  b.title = c.name + ": " + mesh_side(c.a) + " (grey) and reference (orange, translucent)";
  Image image =
      render_reference_overlay(c.a.mesh, c.a.topology, *c.a.reference_surface, three_quarter_view(b.up), b, c.renderer);
  return {framed("views/reference_overlay.png", std::move(image), c)};
}

std::vector<ViewFile> build_compare(ViewContext& c) {
  const Analysis::Compared& other = *c.a.compare;
  auto overview = sized<OverviewOptions>(c);
  const CompareAlignment& align = other.alignment;
  // Each side's min in the title, so the picture says which is worse (46r
  // review); "corner quality" when either mesh has non-hex cells (each face
  // takes its own kind's corners).
  const bool hybrid = has_non_hex(c.a.mesh) || has_non_hex(other.mesh);
  overview.title = c.name + " (left, min " + display_number(c.a.quality.vertex_quality.min, 3) + ") vs " +
                   std::filesystem::path(other.input.path).filename().string() + " (right, min " +
                   display_number(other.quality.vertex_quality.min, 3) + "): " +
                   (hybrid ? "corner quality" : "vertex quality") + ", one camera" +
                   (alignment_description(align).empty() ? std::string() : ", right " + alignment_description(align));
  // Two surface meshes (analyze refuses a surface against a volume): a
  // planar pair seen along MESH's normal, like its overview.
  if (const std::optional<Vec3> planar = planar_view_direction(c.a)) overview.view_direction = *planar;
  const HexMesh placed = aligned_copy(other.mesh, align);
  const KindVertexQuality kinds = kind_vertex_quality(c.a.mesh, c.a.field), other_kinds = kind_vertex_quality(other.mesh, other.field);
  overview.kind_quality = &kinds;
  overview.other_kind_quality = &other_kinds;
  Image image = render_compare_overview(c.a.mesh, c.a.topology, c.quality(), placed, other.topology,
                                        other.field.vertex_quality, overview, c.renderer);
  return {framed("views/compare.png", std::move(image), c)};
}

// The sampled hex boundary errors (% of the reference's diagonal) and their areas.
struct PercentErrors {
  std::vector<double> error, area;
  double per_unit = 1.0;  // % of the diagonal per model unit
};
PercentErrors percent_errors(const BoundaryError& e) {
  PercentErrors out;
  out.per_unit = e.reference_bbox_diagonal > 0.0 ? 100.0 / e.reference_bbox_diagonal : 1.0;
  for (const auto& p : e.mesh_patches) {
    out.error.push_back(out.per_unit * p.error);
    out.area.push_back(p.area);
  }
  return out;
}

// The boundary error charts' words: a planar mesh's boundary pieces,
// weighted by length, against the reference's outline.
ErrorChartLabels error_chart_labels(const Analysis& a, const PercentErrors& v) {
  const BoundaryError& e = *a.boundary_error;
  if (e.planar)
    return {.items = "mesh boundary pieces",
            .unit = "% of diagonal",
            .on_band = v.per_unit * e.on_surface_tolerance,
            .measure = "length",
            .on_word = "on the reference outline"};
  return {.items = std::string(mesh_side(a)) + " samples",
          .unit = "% of diagonal",
          .on_band = v.per_unit * e.on_surface_tolerance};
}

std::vector<ViewFile> build_boundary_error_sorted(ViewContext& c) {
  const PercentErrors v = percent_errors(*c.a.boundary_error);
  const bool planar = c.a.boundary_error->planar;
  return chart_files(
      "boundary_error_sorted",
      sorted_boundary_error_chart(
          v.error,
          {900, 460,
           c.name + (planar ? ": sorted signed boundary error, mesh \u2192 reference (+ outside the reference)"
                            : ": sorted signed boundary error (+ outside the reference)")},
          error_chart_labels(c.a, v), planar ? std::span<const double>(v.area) : std::span<const double>()));
}

std::vector<ViewFile> build_boundary_area(ViewContext& c) {
  const BoundaryError& e = *c.a.boundary_error;
  const PercentErrors v = percent_errors(e);
  return chart_files("boundary_area",
                     boundary_area_chart(v.error, v.area, v.per_unit * e.on_surface_tolerance,
                                         {900, 500, c.name + (e.planar ? ": boundary length outside / inside the reference, mesh \u2192 reference"
                                                                        : ": boundary area outside / inside the reference")},
                                         error_chart_labels(c.a, v)));
}

// The histograms' axes: what is counted, and on a surface mesh what its
// sign is measured against (a curved surface's values below 0: its
// reversed faces, every corner negated, and concave faces' reflex corners).
HistogramAxes histogram_axes(const Analysis& a) {
  if (is_surface_mesh(a.mesh))
    return {planar_view_direction(a) ? "scaled Jacobian (per face, signed against the plane)"
                                     : "scaled Jacobian (per face; < 0: reversed faces, concave corners)",
            "faces"};
  if (cell_noun(a) == "cell") return {"scaled Jacobian (per cell)", "cells"};
  return {};
}

std::vector<ViewFile> build_histogram(ViewContext& c) {
  return chart_files("histogram",
                     quality_histogram_chart(c.a.field.cell_scaled_jacobian, false,
                                             {800, 460, c.name + ": scaled Jacobian per " + cell_noun(c.a)}, 0.05,
                                             histogram_axes(c.a)));
}

std::vector<ViewFile> build_histogram_log(ViewContext& c) {
  return chart_files(
      "histogram_log",
      quality_histogram_chart(c.a.field.cell_scaled_jacobian, true,
                              {800, 460, c.name + ": scaled Jacobian per " + cell_noun(c.a) + " (log scale)"}, 0.05,
                              histogram_axes(c.a)));
}

std::vector<ViewFile> build_sorted_quality(ViewContext& c) {
  return chart_files("sorted_quality",
                     sorted_quality_chart(c.quality(), c.options.worst_vertices,
                                          {900, 460, c.name + ": sorted vertex quality (min corner scaled Jacobian)"}));
}

// A surface mesh's structure view: one figure, along a planar mesh's
// normal, else from the three-quarter view (surface_views.h).
std::vector<ViewFile> build_quad_structure(ViewContext& c) {
  if (!c.a.quad_structure) return {};
  const QuadStructure& s = *c.a.quad_structure;
  QuadStructureViewOptions options;
  options.width = c.options.width;
  options.height = c.options.height;
  options.up = c.options.up;
  const std::optional<Vec3> planar = planar_view_direction(c.a);
  options.is_lit = !planar;
  const Vec3 direction = planar ? *planar : three_quarter_view(options.up);
  options.title = c.name + ": quad structure, " + std::to_string(s.num_irregular) + " irregular vertices, " +
                  std::to_string(s.num_separatrices) + " separatrices, " + std::to_string(s.num_patches) +
                  (s.num_patches == 1 ? " patch" : " patches") +
                  (planar ? std::string(" (along the plane's normal)") : " (from " + viewpoint_name(direction, options.up) + ")");
  Image image = render_quad_structure_view(c.a.mesh, c.a.topology, s, c.a.mesh_summary.edge_length_mean, direction,
                                           options, c.renderer);
  return {framed("views/structure_1.png", std::move(image), c)};
}

std::vector<ViewFile> build_structure(ViewContext& c) {
  if (is_surface_mesh(c.a.mesh)) return build_quad_structure(c);
  auto options = sized<StructureViewOptions>(c);
  options.title = "-";  // the layout of a titled figure
  const HexStructure& s = c.a.structure;
  const std::vector<Vec3> directions = choose_singularity_viewpoints(c.a.mesh, c.a.topology, s, 2, options);
  std::vector<ViewFile> files;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    options.title = c.name + ": singularity graph, view " + std::to_string(i + 1) + " (from " +
                    viewpoint_name(directions[i], options.up) + ")";
    Image image = render_singularity_view(c.a.mesh, c.a.topology, s, directions[i], options, c.renderer);
    files.push_back(framed("views/structure_" + std::to_string(i + 1) + ".png", std::move(image), c));
  }
  return files;
}

std::vector<ViewFile> build_size_gradation(ViewContext& c) {
  auto options = sized<StructureViewOptions>(c);
  const HexStructure& s = c.a.structure;
  // Every kind has a gradation; a pure-hex mesh's title keeps its words.
  const std::string cells = plural(cell_noun(c.a));
  // The numbers are over all cells (46w review M5: "of the boundary cells"
  // read as their scope, beside an `(inside)` max cell).
  options.title = c.name + ": size gradation, boundary " + cells + " shown (all " + cells + ": p95 " +
                  display_number(s.gradation.p95, 3) + ", max " + display_number(s.gradation.max, 3) + ", " +
                  std::to_string(s.num_gradation_above_2) + " above 2)";
  const Vec3 direction = choose_gradation_viewpoint(c.a.mesh, c.a.topology, s, options);
  Image image = render_gradation_view(c.a.mesh, c.a.topology, s, direction, options, c.renderer);
  return {framed("views/size_gradation.png", std::move(image), c)};
}

// 320 x 240, no title, legend or edges: the boundary coloured by vertex quality
// from the overview's eye (the three-quarter view of --up unless the worst
// region is out of its sight: overview_viewpoint.h), the camera fitted to the boundary's
// vertices (was: to their bounding box's corners, which drew a part like
// rockarm at a third of the frame; issue 45f). With inverted cells: each group
// ringed as on the overview (solid in sight, dashed not; no labels, which
// the batch index's 128 x 96 would shrink to 7 px) and a band on top
// (kThumbnailBadgeBand) saying "N inverted" at kThumbnailBadgeText pixels,
// 11 px on the batch index (issue 45f, the 45e review's M7); the model is
// fitted below it.
std::vector<ViewFile> build_thumbnail(ViewContext& c) {
  OverviewOptions options;
  options.up = is_surface_mesh(c.a.mesh) ? c.options.up : c.overview_viewpoint.up;
  const int width = 320, height = 240;
  const int band = c.inverted_cells.empty() ? 0 : kThumbnailBadgeBand;
  const Camera camera = fit_camera_to_points(boundary_points(c.a.mesh, c.a.topology), c.overview_viewpoint.direction,
                                             static_cast<double>(width) / (height - band), {.up = options.up});
  const KindVertexQuality kinds = kind_vertex_quality(c.a.mesh, c.a.field);
  options.kind_quality = &kinds;
  Scene scene = build_quality_overview_scene(c.a.mesh, c.a.topology, c.quality(), options);
  scene.lines.clear();  // at 320 pixels the edges of a real mesh are a grey smear
  Image image = make_image(width, height, scene.background);
  paste(image, c.renderer.render(scene, camera, width, height - band), 0, band);
  if (band > 0) {
    // Rings sized for the batch index, which shows the thumbnail at 0.4 of its size.
    const PixelRect view{0, band, width, height - band};
    const std::vector<InvertedCallout> callouts =
        inverted_callouts(c.a.mesh, c.a.topology, c.inverted_cells, c.quality(), camera, view, 16.0, c.renderer);
    draw_inverted_callouts(image, view, callouts, "", 3.0, 0, annotation_style_for(height));
    // A curved surface's inverted cells are its reversed faces.
    const bool reversed = is_surface_mesh(c.a.mesh) && !planar_view_direction(c.a).has_value();
    const std::string badge = std::to_string(c.inverted_cells.size()) + (reversed ? " reversed" : " inverted");
    draw_text(image, 6, band - 9, badge, kThumbnailBadgeText, annotation_style_for(height));
  }
  return {framed("views/thumbnail.png", std::move(image), c)};
}

// ---- the table's readers -----------------------------------------------------

const ViewSpec* find_view(std::string_view id) {
  for (const ViewSpec& spec : kViews)
    if (spec.id == id) return &spec;
  return nullptr;
}

std::vector<const ViewSpec*> views_of_panel(char panel) {
  std::vector<const ViewSpec*> views;
  for (const ViewSpec& spec : kViews)
    if (spec.panel == panel) views.push_back(&spec);
  std::stable_sort(views.begin(), views.end(),
                   [](const ViewSpec* x, const ViewSpec* y) { return x->panel_order < y->panel_order; });
  return views;
}

// A view's title; "per hex" reads "per cell" on a mesh with other volume
// cells (the per-cell fields cover every kind).
static std::string view_title(std::string_view title, const Analysis& a) {
  std::string t(title);
  if (const auto at = t.find("per hex"); at != std::string::npos && cell_noun(a) != "hex") t.replace(at, 7, "per cell");
  constexpr std::string_view kIntersectingHexes = "intersecting hexes";
  if (const auto at = t.find(kIntersectingHexes); at != std::string::npos && cell_noun(a) != "hex")
    t.replace(at, kIntersectingHexes.size(), "intersecting cells");
  // A mesh with tets, wedges or pyramids colours each boundary face by its
  // own kind's corners: not the vertex quality (the min over every cell;
  // 46r review), as the overview's legend says.
  constexpr std::string_view kVertexQuality = "coloured by vertex quality";
  if (const auto at = t.find(kVertexQuality);
      at != std::string::npos && has_non_hex(a.mesh))
    t.replace(at, kVertexQuality.size(), "coloured by corner quality (each face: its own cell kind's corners)");
  // A surface mesh's views speak of its faces and quad structure (47c
  // review item 8).
  if (is_surface_mesh(a.mesh)) {
    static const std::pair<std::string_view, std::string_view> kSurfaceTitles[] = {
        {"Structure: the singularity graph by valence", "Structure: irregular vertices, separatrices and patches"},
        {"Boundary coloured by vertex quality", "Faces coloured by vertex quality"},
        {"A: glyphs, clusters and intersecting hexes", "A: faces by scaled Jacobian, glyphs and clusters"},
        {"C: sub-region of each top cluster", "C: each top cluster's faces by scaled Jacobian"},
        {"D: one-ring hexes around chosen vertices, corner scaled Jacobians",
         "D: the faces around chosen vertices, corner scaled Jacobians"},
        {"Thumbnail: the boundary by vertex quality, bounding-box frame",
         "Thumbnail: the faces by vertex quality, bounding-box frame"},
        {"Compare: both boundaries coloured by vertex quality, one camera",
         "Compare: both surfaces coloured by vertex quality, one camera"},
        {"Boundary error: hex boundary coloured by signed distance to the reference",
         "Boundary error: the surface mesh coloured by signed distance to the reference"},
        {"Reference error: the reference coloured by signed distance to the hex boundary",
         "Reference error: the reference coloured by signed distance to the surface mesh"},
        {"F: hex boundary over the translucent reference surface", "F: the surface mesh over the translucent reference"},
        {"Sorted boundary error (signed, hex boundary samples, % of diagonal)",
         "Sorted boundary error (signed, surface mesh samples, % of diagonal)"}};
    for (const auto& [from, to] : kSurfaceTitles)
      if (t == from) t = to;
    if (a.boundary_error && a.boundary_error->planar && t.starts_with("Boundary error:"))
      t = "Boundary error: the boundary polylines and the reference outline by signed error, seen along the plane's normal";
    if (a.boundary_error && a.boundary_error->planar && t.starts_with("Boundary area"))
      t.replace(0, 13, "Boundary length");
  }
  return t;
}

std::vector<RenderedView> render_views(const Analysis& analysis, const ViewOptions& options, Renderer& base_renderer,
                                       StageClock* clock, const std::function<void(ViewNeeds)>& before_view) {
  // The views that are wanted, with what each is selected by (a view that is
  // not selectable is drawn with the selectable one before it).
  std::vector<std::size_t> wanted;
  {
    std::string_view selected_by;
    for (std::size_t i = 0; i < std::size(kViews); ++i) {
      if (kViews[i].is_selectable) selected_by = kViews[i].id;
      if (options.views.empty() || std::find(options.views.begin(), options.views.end(), selected_by) != options.views.end())
        wanted.push_back(i);
    }
  }
  // Drawn in kViews order, except that the views that need the UV atlas
  // come last: the atlas is built on its own thread while the others draw.
  std::stable_partition(wanted.begin(), wanted.end(),
                        [](std::size_t i) { return kViews[i].needs != ViewNeeds::uv_atlas; });

  // Two threads draw the views when the renderer has a sibling: one view's
  // scenes, cameras and figures are made on the CPU while the other's
  // frames rasterise, so both cores stay busy. Each thread takes the next
  // view; the files land in the view's own slot, so the result is the same
  // in kViews order for any thread count. PNG encoding overlaps the drawing:
  // a finished view's images go to TBB tasks at once (ViewFile::png). A
  // slot's files never move, so the tasks may hold references to them.
  std::vector<std::vector<ViewFile>> slots(std::size(kViews));  // each view's files
  tbb::task_group encoding;
  const WaitOnExit wait_for_encoding{encoding};

  ViewContext shared{analysis, options, base_renderer, analysis.mesh_name(), {}, nullptr, 0, {}, nullptr, {}, {}};
  if (!analysis.glyphs) shared.no_glyphs.vertex_cluster.assign(analysis.mesh.points.size(), kNoIndex);
  shared.glyphs = analysis.glyphs ? &*analysis.glyphs : &shared.no_glyphs;
  // The top clusters (C views; their worst vertices get D and E): as the glyph stage was asked.
  shared.num_top = std::min<std::size_t>(static_cast<std::size_t>(std::max(0, shared.glyphs->options.top_clusters)),
                                         shared.glyphs->clusters.size());
  // A surface mesh draws its own views only (surface_views.h).
  const bool is_surface = is_surface_mesh(analysis.mesh);
  if (is_surface) std::erase_if(wanted, [](std::size_t i) { return !is_surface_mesh_view(kViews[i].id); });
  shared.local_vertices = choose_local_vertices(shared);
  // The overview's and thumbnail's eye, once for both.
  shared.overview_viewpoint.direction = three_quarter_view(options.up);
  if (is_surface) {
    // A planar surface mesh along its normal; a curved one from the
    // three-quarter view of --up.
    if (const std::optional<Vec3> planar = planar_view_direction(analysis)) shared.overview_viewpoint.direction = *planar;
    shared.inverted_cells = inverted_cell_ids(analysis.field);
  } else if (std::any_of(wanted.begin(), wanted.end(),
                  [](std::size_t i) { return kViews[i].id == "overview" || kViews[i].id == "thumbnail"; })) {
    const GlyphResult& g = *shared.glyphs;
    std::span<const Index> worst_cluster;
    if (!g.clusters.empty() && g.cluster_offsets.size() > 1)
      worst_cluster = std::span<const Index>(g.cluster_vertices).subspan(
          static_cast<std::size_t>(g.cluster_offsets[0]),
          static_cast<std::size_t>(g.cluster_offsets[1] - g.cluster_offsets[0]));
    // The data could not tell up (a ball): the eye may take its up from
    // the worst region too (overview_viewpoint.h, issue 45g).
    const std::vector<Vec3> free_up = analysis.resting_up && resting_up_undecided(*analysis.resting_up)
                                          ? resting_up_candidates() : std::vector<Vec3>{};
    shared.inverted_cells = inverted_cell_ids(analysis.field);
    // The inverted cells' corners' mean: a ball's target when its worst
    // region is inside (no boundary face flagged).
    std::optional<Vec3> inside_target;
    if (!shared.inverted_cells.empty()) {
      Vec3 sum;
      std::size_t n = 0;
      for (Index cell : shared.inverted_cells) {
        const CellRef ref = volume_cell(analysis.mesh, cell);
        for (int k = 0; k < ref.num_corners; ++k, ++n)
          sum = sum + analysis.mesh.points[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])];
      }
      if (n > 0) inside_target = (1.0 / static_cast<double>(n)) * sum;
    }
    shared.overview_viewpoint = choose_overview_viewpoint(
        analysis.mesh, analysis.topology, worst_boundary_faces(analysis.topology, shared.quality(), worst_cluster),
        options.up, free_up, inside_target);
  }

  // Taking the next view, before_view, the clock and the encoding tasks'
  // submission happen under this lock.
  std::mutex lock;
  std::size_t next = 0;
  bool failed = false;
  auto work = [&](Renderer& inner, bool is_second) {
    RecordingRenderer renderer(inner);
    ViewContext context{analysis, options, renderer, shared.name, {}, shared.glyphs, shared.num_top,
                        shared.local_vertices, &renderer.last_frame, shared.overview_viewpoint,
                        shared.inverted_cells};
    for (;;) {
      std::size_t i = 0;
      {
        const std::lock_guard<std::mutex> guard(lock);
        if (failed || next == wanted.size()) return;
        // The views that need the atlas (last) are the first thread's, so
        // that its wait for the atlas is a stage of this thread's.
        if (is_second && kViews[wanted[next]].needs == ViewNeeds::uv_atlas) return;
        i = wanted[next++];
        if (before_view) before_view(kViews[i].needs);
        if (!has_inputs(analysis, kViews[i].needs)) continue;
        progress::stage_started("view " + std::string(kViews[i].id));
      }
      const auto begin = std::chrono::steady_clock::now();
      std::vector<ViewFile> files = kViews[i].build(context);
      const std::lock_guard<std::mutex> guard(lock);
      // Up to the lock: a wait for it is this thread's time too.
      const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - begin;
      slots[i] = std::move(files);
      for (ViewFile& file : slots[i])
        if (file.text.empty() && !file.image.rgba.empty()) encoding.run([&file] { file.png = encode_png(file.image); });
      if (clock) clock->record("view " + std::string(kViews[i].id), seconds.count(), is_second);
    }
  };

  std::chrono::steady_clock::time_point last_view_end;  // when this thread's last view was done
  // One thread when TBB may use one (-j1): the run then uses one core.
  const bool two_threads = options.render_threads > 1 && wanted.size() > 1 &&
                           tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
  if (two_threads) {
    // The second thread makes its renderer (a sibling of the caller's; none:
    // the caller draws every view) while the first view draws, keeps this
    // thread's deadline, and stops at its next check when this one fails.
    std::atomic<bool> cancel{false};
    std::exception_ptr second_error;
    std::thread thread([&, deadline = stop::current_deadline()] {
      const stop::ScopedDeadline same(deadline);
      const stop::ScopedCancel abandoned(cancel);
      try {
        const std::unique_ptr<Renderer> second = base_renderer.sibling();
        // Its TBB waits run only its own tasks (as the caller's do in a
        // batch, whose meshes each check their own deadline).
        if (second) tbb::this_task_arena::isolate([&] { work(*second, true); });
      } catch (...) {
        second_error = std::current_exception();
        const std::lock_guard<std::mutex> guard(lock);
        failed = true;
      }
    });
    try {
      work(base_renderer, false);
      last_view_end = std::chrono::steady_clock::now();
    } catch (...) {
      {
        const std::lock_guard<std::mutex> guard(lock);
        failed = true;
      }
      cancel = true;
      thread.join();
      throw;
    }
    thread.join();
    if (second_error) std::rethrow_exception(second_error);
  } else {
    work(base_renderer, false);
    last_view_end = std::chrono::steady_clock::now();
  }
  progress::stage_started("");
  encoding.wait();
  // This thread's wait, after its last view, for the second thread and the
  // PNG encoding: timed as a stage of its own, so that the stages this
  // thread timed add up to the wall time (the second thread's are flagged
  // concurrent).
  if (clock)
    clock->record("views wait", std::chrono::duration<double>(std::chrono::steady_clock::now() - last_view_end).count(),
                  false);

  std::vector<RenderedView> views;
  for (std::size_t i = 0; i < std::size(kViews); ++i)
    if (!slots[i].empty())
      views.push_back({std::string(kViews[i].id), view_title(kViews[i].title, analysis), std::move(slots[i])});
  return views;
}

// ---- --simulate: the finite-element check's charts (panel P) ----


std::vector<ViewFile> build_fem_correlation(ViewContext& c) {
  std::vector<CorrelationBar> bars;
  for (const MetricCorrelation& m : c.a.fem_correlations)
    bars.push_back({m.metric, m.correlation.rho, m.adjusted_interval.lo, m.adjusted_interval.hi, m.rho_given_size,
                    metric_agreement(metric_direction(m.metric), m.correlation.rho), metric_is_size(m.metric)});
  if (bars.empty()) return {};
  // The verdicts rest on the intervals simultaneous over the directed metrics.
  return chart_files("fem_correlation",
                     metric_correlation_chart(bars, {900, 300, c.name + ": which metrics rank the hexes by FEM error"},
                                              c.a.poisson->error_density_stats.count,
                                              verdict_family_size(c.a.fem_correlations)));
}

std::vector<ViewFile> build_fem_error_scatter(ViewContext& c) {
  return chart_files("fem_error_scatter",
                     error_density_scatter_chart(c.a.field.cell_scaled_jacobian, c.a.poisson->cell_error_density,
                                                 {900, 560, c.name + ": FEM error density against scaled Jacobian"}));
}

// Two figures from one viewpoint facing the densest hexes: the boundary, and
// the cells under the quality threshold (1 - the glyph threshold, as the
// viewer's low cells) with the densest 1% inside the translucent boundary.
std::vector<ViewFile> build_fem_error_density(ViewContext& c) {
  const PoissonCheck& p = *c.a.poisson;
  if (p.cell_error_density.size() != c.a.mesh.hexes.size()) return {};
  auto options = sized<ErrorDensityViewOptions>(c);
  options.quality_threshold = 1.0 - (c.a.glyphs ? c.a.glyphs->options.threshold : 0.5);
  options.reference = c.options.error_density_reference;
  const Vec3 direction = choose_error_density_viewpoint(c.a.mesh, c.a.topology, p.cell_error_density, options, &c.renderer);
  const ErrorDensityWorst worst = error_density_worst(c.a.topology, p.cell_error_density);
  // The median the colour bar's "(median)" tick is (over the positive
  // densities, as the log scale takes them), not report.json's p50 over
  // every finite value: the two differ when some densities are 0.
  const double median = error_density_scale(p.cell_error_density).median;
  // Where the max is (the ring says it too), then the boundary's own max.
  const std::string max_text =
      worst.hex == kNoIndex ? std::string("no density")
                            : "mesh max " + display_number(worst.density, 3) + " at hex " + std::to_string(worst.hex) +
                                  (worst.on_boundary ? " (on the boundary)" : " (interior, ringed)");
  options.title = c.name + ": FEM error density, boundary faces; " + max_text +
                  (worst.on_boundary || !std::isfinite(worst.boundary_max)
                       ? std::string()
                       : ", boundary max " + display_number(worst.boundary_max, 3)) +
                  (std::isfinite(median) ? ", median " + display_number(median, 3) : std::string()) +
                  (worst.hex != kNoIndex && median > 0 ? ", max/median " + display_number(worst.density / median, 2)
                                                       : std::string());
  std::vector<ViewFile> files;
  files.push_back(framed("views/fem_error_density.png",
                         render_error_density_boundary(c.a.mesh, c.a.topology, p.cell_error_density, direction,
                                                       options, c.renderer),
                         c));
  const std::vector<Index> cells = error_density_cells(p.cell_error_density, options);
  std::size_t low = 0;
  for (Index h : cells) low += c.a.field.cell_scaled_jacobian[static_cast<std::size_t>(h)] < options.quality_threshold;
  // Issue 48d: "0 with scaled Jacobian < 0.5" read as "no bad hexes" on a
  // mesh with hexes at SJ -0.13 the density does not rank among its
  // densest (docs/analysis.md): the count is of these cells, and the
  // mesh's own min SJ and its hexes at SJ <= 0 follow.
  double min_sj = std::numeric_limits<double>::infinity();
  std::size_t not_positive = 0;
  for (double sj : c.a.field.cell_scaled_jacobian)
    if (std::isfinite(sj)) {
      min_sj = std::min(min_sj, sj);
      not_positive += sj <= 0;
    }
  options.title = c.name + ": the " + std::to_string(cells.size()) + " densest hexes (top 1%" +
                  (cells.size() >= options.max_cells ? ", at most " + std::to_string(options.max_cells) : "") +
                  "), " + std::to_string(low) + " of them with scaled Jacobian < " +
                  display_number(options.quality_threshold, 3) +
                  (std::isfinite(min_sj) ? " (mesh: min SJ " + display_number(min_sj, 2) + ", " +
                                               std::to_string(not_positive) + " with SJ \u2264 0)"
                                         : std::string()) +
                  ";\n" + max_text;  // two lines (issue 48e: on one it shrank below the legend's text)
  files.push_back(framed("views/fem_error_density_cells.png",
                         render_error_density_cells(c.a.mesh, c.a.topology, p.cell_error_density,
                                                    c.a.field.cell_scaled_jacobian, direction, options, c.renderer),
                         c));
  return files;
}

}  // namespace hq
