#pragma once
// View A, the quality overview: the mesh boundary coloured by vertex quality,
// boundary edges on top, a colour bar and a title. The first image of the
// report.

#include <algorithm>
#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "hqview/core/box3.h"
#include "hqview/image/image.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/kind_vertex_quality.h"
#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"
#include "hqview/views/inverted_inset.h"

namespace hq {

// The outline of an inverted surface face (OverviewOptions): a darker
// blue-violet than kInvertedColor, apart from its fill and from the map.
inline constexpr Rgba8 kInvertedOutlineColor{70, 20, 170, 255};
// The intersecting cells' edges: the main view's intersection colour
// (main_views.h kIntersectionArrowColor, lilac), so one colour names them
// in both figures.
inline constexpr Rgba8 kIntersectingEdgeColor{204, 136, 255, 255};
// Beside inverted cells (OverviewOptions::intersecting_cell_ids): the same
// lilac at 45 % opacity, thinner, without the white halo, so that the
// inverted hexes' blue stays what the eye finds first; the legend's swatch
// is that lilac as it looks on the white legend.
inline constexpr Rgba8 kFadedIntersectingEdgeColor{204, 136, 255, 115};
inline constexpr Rgba8 kFadedIntersectingSwatchColor{232, 201, 255, 255};

struct OverviewOptions {
  int width = 1600;  // figure size in pixels, legend and title included
  int height = 1200;
  Vec3 up{0.0, 0.0, 1.0};       // the model axis drawn upwards (--up)
  Vec3 view_direction{0, 0, 0};  // from the eye towards the mesh; zero: the three-quarter view of up (upright.h)
  std::string title = "Vertex quality";   // empty: no title band
  Rgba8 background{255, 255, 255, 255};
  Rgba8 edge_color{40, 40, 46, 255};  // boundary edges
  float edge_width = 1.0f;            // in output pixels
  // The inverted cells (ids over all volume cells): ringed where they are
  // (inverted_callout.h), with a legend entry; none: no rings.
  std::vector<Index> inverted_cells;
  std::string cell_noun = "hex";  // "hex" or "cell": the rings' labels and legend entry
  // A surface mesh: each inverted cell's face (a quad or triangle of
  // inverted_cells) is outlined whole, 4 px at 1200 px of height on a 7 px
  // white halo, in kInvertedOutlineColor over everything else (the per-pixel vertex
  // quality shows only its inverted corners in blue), with a legend entry
  // "outlined: N inverted <noun>s".
  bool outline_inverted_faces = false;
  // A curved surface: its inverted cells are its reversed faces
  // (orientation flipped against their neighbours): the outline's entry
  // reads "outlined: N reversed <noun>s" and a second line "(orientation
  // flipped)"; the colour bar's swatch below 0 reads kCurvedBelowZeroLabel
  // over kCurvedBelowZeroNote (not "inverted (< 0)").
  bool inverted_are_reversed = false;
  // With it: the outlines drawn over everything (a planar mesh seen along
  // its normal: nothing lies behind), else depth-tested (a curved surface:
  // a face on the far side stays hidden). Also the planar mesh's top sits
  // under the title (quality_overview_frame), not centred in the view.
  bool outline_on_top = false;
  // overlap.num_intersecting_cells and the cells (ids over all volume
  // cells, or a surface mesh's face ids): their edges are drawn over
  // everything (seen through the surface: most are inside) in
  // kIntersectingEdgeColor on a white halo, with the legend entry
  // "intersecting hexes: N (edges, seen through)" (issue 45g: the legend
  // named them and nothing showed them). Ids out of range are skipped.
  long long intersecting_cells = 0;
  std::vector<Index> intersecting_cell_ids;
  // On a mesh of several kinds: each boundary face's corners take the
  // vertex quality of its own cell's kind (kind_vertex_quality.h), so a hex
  // face beside tets shows the hexes' corners (46q review Q-M2); null or
  // empty: vertex_quality everywhere. Not owned.
  const KindVertexQuality* kind_quality = nullptr;
  const KindVertexQuality* other_kind_quality = nullptr;  // the compared mesh's (render_compare_overview)
};

// The overview's 3D content: every boundary face over all kinds
// (boundary_polygons: hex quads, non-hex quads, triangles); a quad as 4
// triangles around its centre, a triangle as itself, so that the quality of the 4 corners
// blends without a diagonal artefact, flat-shaded with the quad's normal,
// with scalars = vertex quality (the centre: the mean of its corners') and the
// quality map (quality_map_samples, kInvertedColor below 0, kUndefinedColor
// for NaN) applied per fragment after interpolation, so that every pixel of a
// face is a colour of the legend and an inverted vertex keeps the inverted
// colour in the part of its faces nearest to it (colors: quality_color per
// vertex, the same values; a caller that recolours the faces must clear
// scalars, which win over colors); then the unique boundary edges as lines
// in options.edge_color (boundary_edges_all_kinds); the non-conforming faces'
// outlines in scene.overlay (none on a pure-hex mesh). The scene's origin is
// the centre of the boundary's bounding box.
//   vertex_quality: mesh.num_vertices() values (min corner scaled Jacobian,
//                   NaN for vertices no hex uses); a face's corners take
//                   options.kind_quality's values of its cell's kind instead
//                   when that is given and not empty.
// Throws Error when vertex_quality has the wrong size.
Scene build_quality_overview_scene(const HexMesh& mesh, const Topology& topology,
                                   const std::vector<double>& vertex_quality, const OverviewOptions& options);

// Non-conforming faces (Topology::non_conforming_faces: a quad against two
// triangles, inside the mesh) are drawn in this colour as an outline frame
// (kNonConformingFrame of the way from each corner to the face's centre),
// over everything else (Scene::overlay), so that an interface inside the
// model shows where it is; they are never part of the boundary.
inline constexpr Rgba8 kNonConformingColor{125, 70, 20, 255};  // dark brown: in no palette of the overview or structure views
// The colour bar's title on a mesh with tets, wedges or pyramids, whose
// boundary faces take their own kind's corners (kind_vertex_quality): not
// "vertex quality", the min over every cell (46r review).
inline constexpr const char* kKindCornerQualityLabel =
    "corner quality (min scaled\nJacobian at the vertex over\nthe face's cell kind's corners)";
// A curved surface's swatch below 0 (OverviewOptions::inverted_are_reversed)
// and the line under it; the viewer's legend says the same.
inline constexpr const char* kCurvedBelowZeroLabel = "< 0: corner of a reversed face";
inline constexpr const char* kCurvedBelowZeroNote = "or reflex corner of a concave one";
inline constexpr double kNonConformingFrame = 0.15;
inline constexpr int kNonConformingDashes = 5;
// The frame, and inside it the diagonal the two triangles split the quad
// along, dashed (what makes the face non-conforming).
TriangleSet non_conforming_outlines(const HexMesh& mesh, const Topology& topology, const Vec3& origin);
// Appends the dashed diagonal of one non-conforming face (kNonConformingDashes
// dashes, unlit, as wide as half the frame's depth) to `set`; end_margin:
// the fraction of the diagonal left out at each end (view S: its rings at
// the corners stay uncovered).
void add_non_conforming_diagonal(const HexMesh& mesh, const NonConformingFace& nc, const Vec3& origin,
                                 const Rgba8& color, TriangleSet& set, double end_margin = 0.0);

// The overview's legend: quality_color_bar(), its "inverted (< 0)" swatch
// only when a boundary vertex is below 0 (a legend names only what is
// drawn), plus on a hybrid mesh a "no value" swatch when a boundary vertex
// has no quality (NaN) and a "non-conforming (N, inside)" swatch when the
// mesh has such faces.
ColorBar overview_color_bar(const Topology& topology, const std::vector<double>& vertex_quality);

// The positions of the boundary faces' vertices, each once, in vertex id
// order (all points when there is no boundary face).
std::vector<Vec3> boundary_points(const HexMesh& mesh, const Topology& topology);

// Bounding box of the boundary faces' vertices (all points when there is no
// boundary face); lo = hi = (0, 0, 0) for an empty mesh.
Box3 boundary_bounding_box(const HexMesh& mesh, const Topology& topology);

// A 3D figure's frame: the annotation style for its height (on
// `background`), its layout (make_layout of that style) and the orthographic
// camera fitted to `points` from view_direction, upright along `up`, for the
// layout's view. Throws RenderError "<what> size must be positive" for a
// width or height <= 0.
struct FigureFrame3d {
  AnnotationStyle style;
  FigureLayout layout;
  Camera camera;
};
FigureFrame3d figure_frame_3d(const std::string& what, int width, int height, Rgba8 background,
                              const std::function<FigureLayout(const AnnotationStyle&)>& make_layout,
                              std::span<const Vec3> points, const Vec3& view_direction, const Vec3& up,
                              double fov_y_degrees);

// A figure of width x height in style.background: the scene rendered into
// layout.view, the title in layout.title (the legend is the caller's).
Image render_figure(Renderer& renderer, const Scene& scene, const Camera& camera, int width, int height,
                    const FigureLayout& layout, const std::string& title, const AnnotationStyle& style);

// The overview's frame (render_quality_overview's): its annotation style,
// legend (overview_color_bar, and with inverted cells a "solid ring" and a
// "dashed ring" entry: the figure keeps those it draws), layout and camera.
// The overview's text (title, legend, ring labels, inset captions) is drawn
// this much larger than annotation_style_for's: the page fits the overview
// on the first screen, at about half its size (style.css figure.overview),
// and its legend must stay at least 11 px there (issue 45e).
inline constexpr double kOverviewTextScale = 1.3;
// The rings' core thickness on the overview (pixels; their labels'
// leaders and the placement's discs use it too).
inline double overview_ring_thickness(const AnnotationStyle& style) { return std::max(2.0, 4.0 * style.scale); }
struct OverviewFrame {
  AnnotationStyle style;
  ColorBar bar;
  FigureLayout layout;
  Camera camera;
  int label_size = 0;  // the rings' labels and the insets' captions (pixels)
  // With outline_on_top, the outlined cells under an overlapping face
  // (cells_under_other_faces), ascending: outlined dashed and thinner,
  // with a legend line of their own.
  std::vector<Index> hidden_cells;
  // With outline_on_top and no inverted cell: the vertex of least quality
  // (lowest index on ties; kNoIndex when none is finite), ringed and
  // labelled "min <value>", with a legend line (the 47j review: on a plate
  // whose values all lay in the bar's pale part the worst could not be found).
  Index worst_vertex = kNoIndex;
};
// The vertex of cells (quads, triangles) of least finite quality, lowest
// index on ties; kNoIndex when none.
Index least_quality_vertex(const HexMesh& mesh, const std::vector<double>& vertex_quality);
OverviewFrame quality_overview_frame(const HexMesh& mesh, const Topology& topology,
                                    const std::vector<double>& vertex_quality, const OverviewOptions& options);

// The outlines of options.inverted_cells (outline_inverted_faces) as the
// overview draws them over its frame f: the cells of f.hidden_cells dashed
// (pieces of about 10 px with 7 px gaps at 1200 px of height, each edge
// whole periods), the others solid, both a 4 px line on a 7 px white halo;
// in order halo, line, hidden halo, hidden line (the dashes drawn over the
// solid lines), positions relative to origin.
std::array<LineSet, 4> inverted_face_outlines(const HexMesh& mesh, const OverviewOptions& options, const OverviewFrame& f,
                                              const Vec3& origin);

// The overview's plan (render_quality_overview's): its frame, whose
// layout.view is where the model is drawn (the whole view, less the insets'
// strip when there are insets: inset_strip), and camera fitted to it; the
// view before the strip (full_view: where the rings' labels may go); the
// rings (inverted_callouts, with the minimum radius of the overview) and
// the insets, placed in the strip. Renders id images only.
struct OverviewPlan {
  OverviewFrame frame;
  PixelRect full_view;
  std::vector<InvertedCallout> callouts;
  std::vector<InvertedInset> insets;
};
OverviewPlan plan_quality_overview(const HexMesh& mesh, const Topology& topology,
                                   const std::vector<double>& vertex_quality, const OverviewOptions& options,
                                   Renderer& renderer);

// Whether a ring of `callouts` (callout_discs: the ring's outer edge,
// its dashed ring of hidden groups too) reaches into an inset's rectangle.
// plan_quality_overview places the model, of its arrangements, the largest
// where none does (issue 45: an inset covered part of a ring).
bool rings_under_insets(std::span<const InvertedCallout> callouts, std::span<const InvertedInset> insets, double thickness);

// The overview figure: options.width x options.height, the 3D view on the
// left framing the boundary vertices tightly (fit_camera_to_points), the quality colour bar on the
// right, the title on top; each group of options.inverted_cells ringed and
// labelled (inverted_callout.h), those out of sight also drawn in a
// cut-away inset (inverted_inset.h) beside the model, never over it, the legend saying so. Boundary edges fade (down to 30% opacity) when
// the median edge is shorter than 8 pixels on screen. Throws RenderError
// from the renderer or when the font is missing, Error when vertex_quality
// has the wrong size.
Image render_quality_overview(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                              const OverviewOptions& options, Renderer& renderer);

// --compare: two meshes' boundaries coloured by vertex quality side by side
// (first on the left), one camera (fitted to both boundaries, so the same
// model region is at the same place in each half), one colour bar, the title.
Image render_compare_overview(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                              const HexMesh& other, const Topology& other_topology,
                              const std::vector<double>& other_vertex_quality, const OverviewOptions& options,
                              Renderer& renderer);

}  // namespace hq
