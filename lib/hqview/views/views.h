#pragma once
// The views of a report: one table (kViews) that says which views exist,
// which paper panel and page show them, what each needs, and which builder
// draws it. The --views list, the render loop, report.json, index.html and
// boundary.html all read this table.

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/analysis/analysis.h"
#include "hqview/chart/chart.h"
#include "hqview/image/image.h"
#include "hqview/render/renderer.h"

namespace hq {

struct ViewFile {
  std::string relative_path;  // "views/<name>.png" or "views/<name>.svg"
  Image image;                // for .png
  std::string text;           // for .svg
  // What the file shows, for the links between panels (index.html).
  Index cluster = kNoIndex;  // C: its cluster; D, E: the cluster of its vertex (kNoIndex: none)
  Index vertex = kNoIndex;   // D, E: its vertex
  // Chart B: one clickable region per bar, as fractions of the image's width
  // and height (x, y from the top left), key = the bar's vertex id.
  std::vector<ChartHotspot> hotspots{};
  std::string png{};  // for .png: image encoded (encode_png), the bytes to write
  std::optional<Camera> camera{};  // a 3D view's camera (report.json views[].cameras)
  double camera_aspect = 1.0;      // its frame's width / height
  int frame_width = 0, frame_height = 0;  // its frame's size, pixels
};

struct RenderedView {
  std::string id, title;
  std::vector<ViewFile> files;
};

struct ViewOptions {
  int width = 1600, height = 1200;
  int worst_vertices = 40;            // bars in chart B
  std::vector<Index> focus_vertices;  // more D and E views (--focus-vertex)
  std::vector<std::string> views;     // ids of kViews to draw (selectable ones); empty: all
  Vec3 up{0.0, 0.0, 1.0};             // the model axis drawn upwards in every 3D view (--up)
  int render_threads = 2;             // threads drawing views, each with its own renderer (Renderer::sibling)
  double error_density_reference = 0;  // --error-density-reference: view fem_error_density's scale (0: the mesh's median)
};

struct ViewContext;  // what the builders share (views.cpp)
using ViewBuilder = std::vector<ViewFile> (*)(ViewContext&);

// Where a view is shown: index.html's panels A-F and S, or boundary.html.
enum class ViewPage { index, boundary };

// What a view needs beyond the mesh.
// simulation: a solved finite-element check (--simulate).
enum class ViewNeeds { mesh, reference, uv_atlas, compare, simulation };  // uv_atlas: the reference and its atlas

struct ViewSpec {
  std::string_view id;     // report.json views[].id
  std::string_view title;  // report.json views[].title
  char panel;              // index.html panel 'A'..'F' (paper's letters), 'S' structure, 'P' simulation; 0 on boundary.html;
                           // 'T' the thumbnail (on the batch index only)
  int panel_order;         // position inside its panel or page
  ViewNeeds needs;
  bool is_selectable;  // a --views id of its own; else drawn with the view before it
  int summary_order;   // position among summary.md's links (its first PNG); -1: not linked
  ViewBuilder build;   // no files: the view is left out (nothing to show)
};

// The builders (views.cpp).
std::vector<ViewFile> build_overview(ViewContext&);
std::vector<ViewFile> build_main(ViewContext&);
std::vector<ViewFile> build_clusters(ViewContext&);
std::vector<ViewFile> build_local(ViewContext&);
std::vector<ViewFile> build_corners(ViewContext&);
std::vector<ViewFile> build_boundary_error(ViewContext&);
std::vector<ViewFile> build_reference_error(ViewContext&);
std::vector<ViewFile> build_uv_error(ViewContext&);
std::vector<ViewFile> build_uv_key(ViewContext&);
std::vector<ViewFile> build_reference_overlay(ViewContext&);
std::vector<ViewFile> build_compare(ViewContext&);
std::vector<ViewFile> build_boundary_error_sorted(ViewContext&);
std::vector<ViewFile> build_boundary_area(ViewContext&);
std::vector<ViewFile> build_histogram(ViewContext&);
std::vector<ViewFile> build_histogram_log(ViewContext&);
std::vector<ViewFile> build_sorted_quality(ViewContext&);
std::vector<ViewFile> build_structure(ViewContext&);
std::vector<ViewFile> build_size_gradation(ViewContext&);
std::vector<ViewFile> build_thumbnail(ViewContext&);
std::vector<ViewFile> build_fem_correlation(ViewContext&);
std::vector<ViewFile> build_fem_error_scatter(ViewContext&);
std::vector<ViewFile> build_fem_error_density(ViewContext&);

// Every view, in report order (the order they are drawn and listed).
inline constexpr ViewSpec kViews[] = {
    {"overview", "Boundary coloured by vertex quality", 'A', 0, ViewNeeds::mesh, true, -1, build_overview},
    {"main", "A: glyphs, clusters and intersecting hexes", 'A', 1, ViewNeeds::mesh, true, 0, build_main},
    {"clusters", "C: sub-region of each top cluster", 'C', 0, ViewNeeds::mesh, true, 2, build_clusters},
    {"local", "D: one-ring hexes around chosen vertices, corner scaled Jacobians", 'D', 0, ViewNeeds::mesh, true, 3,
     build_local},
    {"corners", "E: corner scaled Jacobians at each chosen vertex", 'E', 0, ViewNeeds::mesh, true, 4, build_corners},
    {"boundary_error", "Boundary error: hex boundary coloured by signed distance to the reference", 0, 0,
     ViewNeeds::reference, true, 8, build_boundary_error},
    {"reference_error", "Reference error: the reference coloured by signed distance to the hex boundary", 0, 1,
     ViewNeeds::reference, true, -1, build_reference_error},
    {"uv_error", "UV error map of the reference", 0, 2, ViewNeeds::uv_atlas, true, 11, build_uv_error},
    {"uv_key", "UV key: the reference's charts numbered, in 3D and in the atlas", 0, 2, ViewNeeds::uv_atlas, true, -1,
     build_uv_key},
    {"reference_overlay", "F: hex boundary over the translucent reference surface", 'F', 0, ViewNeeds::reference, true,
     6, build_reference_overlay},
    {"compare", "Compare: both boundaries coloured by vertex quality, one camera", 'F', 1, ViewNeeds::compare, true, 7,
     build_compare},
    {"boundary_error_sorted", "Sorted boundary error (signed, hex boundary samples, % of diagonal)", 0, 3, ViewNeeds::reference,
     true, 9, build_boundary_error_sorted},
    {"boundary_area", "Boundary area outside / inside the reference", 0, 4, ViewNeeds::reference, true, 10,
     build_boundary_area},
    {"histogram", "Quality histogram (per hex scaled Jacobian)", 'B', 1, ViewNeeds::mesh, true, 5, build_histogram},
    {"histogram_log", "Quality histogram, log scale", 'B', 2, ViewNeeds::mesh, false, -1, build_histogram_log},
    {"sorted_quality", "B: sorted vertex quality", 'B', 0, ViewNeeds::mesh, true, 1, build_sorted_quality},
    {"structure", "Structure: the singularity graph by valence", 'S', 0, ViewNeeds::mesh, true, 12, build_structure},
    {"size_gradation", "Structure: size gradation on the boundary", 'S', 1, ViewNeeds::mesh, true, -1,
     build_size_gradation},
    {"fem_correlation", "P: which metrics say where the simulation error is (Spearman \u03c1 per hex)", 'P', 0,
     ViewNeeds::simulation, true, -1, build_fem_correlation},
    {"fem_error_scatter", "P: error density against scaled Jacobian per hex (log-log)", 'P', 1,
     ViewNeeds::simulation, true, -1, build_fem_error_scatter},
    {"fem_error_density", "P: the boundary and the low-quality cells coloured by FEM error density", 'P', 2,
     ViewNeeds::simulation, true, -1, build_fem_error_density},
    // On no page of its own: the batch comparison's strip of thumbnails.
    {"thumbnail", "Thumbnail: the boundary by vertex quality, bounding-box frame", 'T', 0, ViewNeeds::mesh, true, -1,
     build_thumbnail},
};

// The view of an id, or nullptr.
const ViewSpec* find_view(std::string_view id);

// The views a page shows in its order: panel (0: boundary.html) or 'A'..'F'.
std::vector<const ViewSpec*> views_of_panel(char panel);

// Draws the selected views and returns them in kViews order. They are
// drawn in that order but for those that need the UV atlas, which come
// last; on two or more TBB threads (and options.render_threads > 1) by two
// threads, the second with renderer.sibling(). The PNG images of finished
// views are encoded (ViewFile::png) by TBB tasks while later views render.
// Throws RenderError (from either thread); ValueError for a focus vertex
// that does not exist. clock (may be null) times each view as "view <id>"
// (the second thread's flagged concurrent) and the wait after the last as
// "views wait". before_view (may be empty) is called once per view before
// it is drawn, under a lock, with what the view needs: the pipeline
// completes `analysis` there (the UV atlas, built on its own thread while
// the first views are drawn; the views that need it are the first thread's).
std::vector<RenderedView> render_views(const Analysis& analysis, const ViewOptions& options, Renderer& renderer,
                                       StageClock* clock = nullptr,
                                       const std::function<void(ViewNeeds)>& before_view = {});

}  // namespace hq
