#pragma once
// All of a report's views: which exist, and rendering the selected ones.
// The pipeline hands the analysis results in; each view comes back as files
// (PNG images, SVG text) with the id and title report.json lists.

#include <optional>
#include <string>
#include <vector>

#include "hqview/boundary/boundary_error.h"
#include "hqview/chart/chart.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/overlap.h"
#include "hqview/render/image.h"
#include "hqview/render/renderer.h"
#include "hqview/uv/uv_atlas.h"

namespace hq {

// View ids, in report order.
inline constexpr const char* kViewIds[] = {"overview", "main", "clusters", "local", "corners", "boundary_error", "uv_error", "reference_overlay", "compare", "boundary_error_sorted", "boundary_area", "histogram", "sorted_quality"};

// Parses a --views list ("all", or ids separated by commas); throws
// UsageError naming the unknown id. The result keeps report order.
std::vector<std::string> parse_view_list(const std::string& list);

struct ViewInputs {
  const HexMesh* mesh = nullptr;
  const Topology* topology = nullptr;
  const std::vector<double>* vertex_quality = nullptr;  // per vertex
  const std::vector<double>* cell_quality = nullptr;    // per hex scaled Jacobian (Verdict); null: no histogram
  const GlyphResult* glyphs = nullptr;     // null: no glyphs
  const OverlapReport* overlap = nullptr;  // null with --no-overlap
  std::string mesh_name;                   // for titles
  // With --reference (all three or none): boundary error views, UV error map.
  const BoundaryError* boundary_error = nullptr;
  const TriSurface* reference = nullptr;
  const UvAtlas* uv_atlas = nullptr;
  // With --compare MESH2: its mesh, topology and vertex quality (all or none).
  const HexMesh* compare_mesh = nullptr;
  const Topology* compare_topology = nullptr;
  const std::vector<double>* compare_vertex_quality = nullptr;
  std::string compare_name;
};

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
};

struct RenderedView {
  std::string id, title;
  std::vector<ViewFile> files;
};

struct ViewOptions {
  int width = 1600, height = 1200;
  int worst_vertices = 40;  // bars in chart B
  int top_clusters = 8;     // clusters with a C view; their worst vertices get D and E
  std::vector<Index> focus_vertices;  // more D and E views (--focus-vertex)
  std::vector<std::string> views;  // ids to render (parse_view_list); empty: all
};

// Renders the selected views in report order. The PNG images of finished
// views are encoded (ViewFile::png) by TBB tasks while later views render.
// Throws RenderError.
std::vector<RenderedView> render_views(const ViewInputs& inputs, const ViewOptions& options, Renderer& renderer);

}  // namespace hq
