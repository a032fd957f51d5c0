#include "hqview/render/views.h"

#include <tbb/task_group.h>

#include <algorithm>
#include <functional>

#include "hqview/chart/chart.h"
#include "hqview/core/error.h"
#include "hqview/io/image_file.h"
#include "hqview/render/views_boundary.h"
#include "hqview/render/views_detail.h"
#include "hqview/render/views_main.h"
#include "hqview/render/views_overview.h"

namespace hq {

std::vector<std::string> parse_view_list(const std::string& list) {
  std::vector<std::string> asked;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    std::string id = list.substr(start, end - start);
    if (!id.empty()) asked.push_back(id);
    start = end + 1;
  }
  std::vector<std::string> ids;
  for (const std::string& id : asked) {
    if (id == "all") {
      ids.assign(std::begin(kViewIds), std::end(kViewIds));
      return ids;
    }
    if (std::find(std::begin(kViewIds), std::end(kViewIds), id) == std::end(kViewIds)) {
      std::string known;
      for (const char* k : kViewIds) known += std::string(known.empty() ? "" : ", ") + k;
      throw UsageError("--views: unknown view '" + id + "' (known: all, " + known + ")");
    }
  }
  for (const char* k : kViewIds)
    if (std::find(asked.begin(), asked.end(), k) != asked.end()) ids.push_back(k);
  return ids;
}

namespace {

// Calls before_frame, then the wrapped renderer, for every frame.
class HookedRenderer final : public Renderer {
 public:
  HookedRenderer(Renderer& inner, std::function<void()> before_frame)
      : inner_(inner), before_frame_(std::move(before_frame)) {}
  Image render(const Scene& scene, const Camera& camera, int width, int height) override {
    before_frame_();
    return inner_.render(scene, camera, width, height);
  }

 private:
  Renderer& inner_;
  std::function<void()> before_frame_;
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

}  // namespace

std::vector<RenderedView> render_views(const ViewInputs& in, const ViewOptions& options, Renderer& base_renderer) {
  auto wanted = [&](const char* id) {
    return options.views.empty() || std::find(options.views.begin(), options.views.end(), id) != options.views.end();
  };
  std::vector<RenderedView> views;
  // PNG encoding overlaps rendering: before each frame, the images of the
  // views pushed so far go to TBB tasks that encode them (ViewFile::png);
  // the rest (the charts at the end) before returning. A pushed view's
  // files never move (a vector's elements survive moves of the vector), so
  // the tasks may hold references to them.
  tbb::task_group encoding;
  const WaitOnExit wait_for_encoding{encoding};
  std::size_t num_submitted = 0;
  auto encode_pushed_views = [&] {
    for (; num_submitted < views.size(); ++num_submitted)
      for (ViewFile& file : views[num_submitted].files)
        if (file.text.empty() && !file.image.rgba.empty())
          encoding.run([&file] { file.png = encode_png(file.image); });
  };
  HookedRenderer renderer(base_renderer, encode_pushed_views);
  if (wanted("overview")) {
    OverviewOptions overview;
    overview.width = options.width;
    overview.height = options.height;
    overview.title = in.mesh_name + ": vertex quality on the boundary";
    views.push_back({"overview", "Boundary coloured by vertex quality",
                     {{"views/overview.png",
                       render_quality_overview(*in.mesh, *in.topology, *in.vertex_quality, overview, renderer), {}}}});
  }
  GlyphResult no_glyphs;
  if (!in.glyphs) no_glyphs.vertex_cluster.assign(in.mesh->points.size(), kNoIndex);
  const GlyphResult& glyphs = in.glyphs ? *in.glyphs : no_glyphs;
  if (wanted("main")) {
    MainViewOptions main;
    main.width = options.width;
    main.height = options.height;
    const std::vector<Vec3> points = main_view_points(*in.mesh, *in.topology, glyphs);
    main.title = "-";  // the layout of a titled figure
    const double aspect = main_view_aspect(main);
    const std::vector<Vec3> directions = choose_main_viewpoints(points, glyphs, aspect, 2, main.fov_y_degrees);
    RenderedView view{"main", "A: glyphs, clusters and overlaps", {}};
    for (std::size_t i = 0; i < directions.size(); ++i) {
      main.title = in.mesh_name + ": glyph clusters and overlaps, view " + std::to_string(i + 1) + " (from " +
                   viewpoint_name(directions[i]) + ")";
      view.files.push_back({"views/main_" + std::to_string(i + 1) + ".png",
                            render_main_view(*in.mesh, *in.topology, glyphs, in.overlap, directions[i], main,
                                             renderer),
                            {}});
    }
    views.push_back(std::move(view));
  }
  // Charts: SVG for the HTML page and a PNG twin, from one Chart each.
  auto chart_files = [](const std::string& name, const Chart& chart) {
    std::vector<ViewFile> files{{"views/" + name + ".svg", {}, chart_svg(chart)},
                                {"views/" + name + ".png", chart_image(chart), {}}};
    // Hotspots in fractions of the image: they follow the image when scaled.
    const double sx = 1.0 / chart.width, sy = 1.0 / chart.height;
    for (ChartHotspot h : chart.hotspots) {
      h.rect = {h.rect.x * sx, h.rect.y * sy, h.rect.width * sx, h.rect.height * sy, {}};
      for (ViewFile& f : files) f.hotspots.push_back(h);
    }
    return files;
  };
  auto cluster_of = [&](Index v) { return glyphs.vertex_cluster[static_cast<std::size_t>(v)]; };
  auto add_chart = [&](const char* id, const std::string& title, const std::string& name, const Chart& chart) {
    views.push_back({id, title, chart_files(name, chart)});
  };
  const std::size_t num_top =
      std::min<std::size_t>(static_cast<std::size_t>(std::max(0, options.top_clusters)), glyphs.clusters.size());
  DetailViewOptions detail;
  detail.width = options.width;
  detail.height = options.height;
  if (wanted("clusters") && num_top > 0) {
    RenderedView view{"clusters", "C: sub-region of each top cluster", {}};
    for (std::size_t k = 0; k < num_top; ++k) {
      const AggregatedGlyph& g = glyphs.clusters[k];
      detail.title = in.mesh_name + ": cluster #" + std::to_string(k) + " (" + std::to_string(g.size) +
                     " glyphs, reduced, min quality " + std::to_string(g.min_quality).substr(0, 6) + ") and its neighbours";
      view.files.push_back({"views/cluster_" + std::to_string(k) + ".png",
                            render_cluster_view(*in.mesh, *in.topology, *in.vertex_quality, glyphs,
                                                static_cast<Index>(k), detail, renderer),
                            {},
                            static_cast<Index>(k)});
    }
    views.push_back(std::move(view));
  }
  // D and E: the worst vertex of each top cluster, then the focus vertices.
  std::vector<Index> local_vertices;
  for (std::size_t k = 0; k < num_top; ++k) {
    Index worst = kNoIndex;
    for (Index i = glyphs.cluster_offsets[k]; i < glyphs.cluster_offsets[k + 1]; ++i) {
      const Index v = glyphs.cluster_vertices[static_cast<std::size_t>(i)];
      if (worst == kNoIndex || (*in.vertex_quality)[static_cast<std::size_t>(v)] <
                                   (*in.vertex_quality)[static_cast<std::size_t>(worst)])
        worst = v;
    }
    if (worst != kNoIndex) local_vertices.push_back(worst);
  }
  for (Index v : options.focus_vertices) {
    if (v < 0 || v >= in.mesh->num_vertices())
      throw UsageError("--focus-vertex: vertex " + std::to_string(v) + " does not exist (the mesh has " +
                       std::to_string(in.mesh->num_vertices()) + " vertices, ids from 0)");
    if (std::find(local_vertices.begin(), local_vertices.end(), v) == local_vertices.end()) local_vertices.push_back(v);
  }
  std::erase_if(local_vertices, [&](Index v) {
    return in.topology->vertex_hex_offsets[static_cast<std::size_t>(v)] ==
           in.topology->vertex_hex_offsets[static_cast<std::size_t>(v) + 1];
  });
  if (wanted("local") && !local_vertices.empty()) {
    RenderedView view{"local", "D: one-ring hexes around chosen vertices, corner scaled Jacobians", {}};
    for (Index v : local_vertices) {
      detail.title = in.mesh_name + ": vertex " + std::to_string(v) + ", its hexes and their corner scaled Jacobians";
      view.files.push_back({"views/local_v" + std::to_string(v) + ".png",
                            render_local_view(*in.mesh, *in.topology, v, detail, renderer),
                            {},
                            cluster_of(v),
                            v});
    }
    views.push_back(std::move(view));
  }
  if (wanted("corners") && !local_vertices.empty()) {
    RenderedView view{"corners", "E: corner scaled Jacobians at each chosen vertex", {}};
    for (Index v : local_vertices) {
      std::vector<double> values;
      std::vector<std::string> labels;
      for (const VertexCorner& c : vertex_corners(*in.mesh, *in.topology, v)) {
        values.push_back(c.value);
        labels.push_back("hex " + std::to_string(c.hex));
      }
      const Chart chart = corner_chart(values, labels,
                                       {std::max(480, 90 * static_cast<int>(values.size()) + 120), 420,
                                        in.mesh_name + ": corners at vertex " + std::to_string(v)});
      for (ViewFile& file : chart_files("corners_v" + std::to_string(v), chart)) {
        file.cluster = cluster_of(v);
        file.vertex = v;
        view.files.push_back(std::move(file));
      }
    }
    views.push_back(std::move(view));
  }
  if (in.boundary_error && wanted("boundary_error")) {
    BoundaryViewOptions b;
    b.width = options.width;
    b.height = options.height;
    const Vec3 front = normalized(Vec3{-1.0, -0.8, -0.6});
    RenderedView view{"boundary_error", "Boundary error: hex boundary coloured by signed distance to the reference", {}};
    b.title = in.mesh_name + ": signed boundary error, front";
    view.files.push_back({"views/boundary_error_front.png",
                          render_boundary_error_view(*in.mesh, *in.topology, *in.boundary_error, front, b, renderer), {}});
    b.title = in.mesh_name + ": signed boundary error, back";
    view.files.push_back({"views/boundary_error_back.png",
                          render_boundary_error_view(*in.mesh, *in.topology, *in.boundary_error, -front, b, renderer), {}});
    views.push_back(std::move(view));
  }
  if (in.boundary_error && in.reference && in.uv_atlas && wanted("uv_error")) {
    BoundaryViewOptions b;
    b.width = options.width;
    b.height = options.height;
    b.title = in.mesh_name + ": reference UV atlas, reference to hex boundary error";
    views.push_back({"uv_error", "UV error map of the reference",
                     {{"views/uv_error.png", render_uv_error_map(*in.reference, *in.uv_atlas, *in.boundary_error, b, renderer),
                       {}}}});
  }
  if (in.reference && wanted("reference_overlay")) {
    BoundaryViewOptions b;
    b.width = options.width;
    b.height = options.height;
    b.title = in.mesh_name + ": hex boundary (grey) and reference (orange, translucent)";
    views.push_back({"reference_overlay", "F: hex boundary over the translucent reference surface",
                     {{"views/reference_overlay.png",
                       render_reference_overlay(*in.mesh, *in.topology, *in.reference, normalized(Vec3{-1.0, -0.8, -0.6}), b,
                                                renderer),
                       {}}}});
  }
  if (in.compare_mesh && in.compare_topology && in.compare_vertex_quality && wanted("compare")) {
    OverviewOptions overview;
    overview.width = options.width;
    overview.height = options.height;
    overview.title = in.mesh_name + " (left) vs " + in.compare_name + " (right): vertex quality, one camera";
    views.push_back({"compare", "Compare: both boundaries coloured by vertex quality, one camera",
                     {{"views/compare.png",
                       render_compare_overview(*in.mesh, *in.topology, *in.vertex_quality, *in.compare_mesh,
                                               *in.compare_topology, *in.compare_vertex_quality, overview, renderer),
                       {}}}});
  }
  if (in.boundary_error && wanted("boundary_error_sorted"))
    add_chart("boundary_error_sorted", "Sorted boundary error (signed, every hex boundary vertex)", "boundary_error_sorted",
              sorted_boundary_error_chart(in.boundary_error->vertex_error,
                                          {900, 460, in.mesh_name + ": sorted signed boundary error (+ outside the reference)"}));
  if (in.boundary_error && wanted("boundary_area"))
    add_chart("boundary_area", "Boundary area outside / inside the reference", "boundary_area",
              boundary_area_chart(in.boundary_error->vertex_error, in.boundary_error->vertex_area,
                                  BoundaryOptions{}.on_surface_tolerance * in.boundary_error->reference_bbox_diagonal,
                                  {900, 500, in.mesh_name + ": boundary area outside / inside the reference"}));
  if (wanted("histogram") && in.cell_quality) {
    add_chart("histogram", "Quality histogram (per hex scaled Jacobian)", "histogram",
              quality_histogram_chart(*in.cell_quality, false, {800, 460, in.mesh_name + ": scaled Jacobian per hex"}));
    add_chart("histogram_log", "Quality histogram, log scale", "histogram_log",
              quality_histogram_chart(*in.cell_quality, true,
                                      {800, 460, in.mesh_name + ": scaled Jacobian per hex (log scale)"}));
  }
  if (wanted("sorted_quality"))
    add_chart("sorted_quality", "B: sorted vertex quality", "sorted_quality",
              sorted_quality_chart(*in.vertex_quality, options.worst_vertices,
                                   {900, 460, in.mesh_name + ": sorted vertex quality (min corner scaled Jacobian)"}));
  encode_pushed_views();
  encoding.wait();
  return views;
}

}  // namespace hq
