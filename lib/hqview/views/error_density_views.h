#pragma once
// The finite-element error density in 3D (index.html panel P, --simulate):
// the per-hex normalised H1 error density of the Poisson check
// (poisson_check.h; dimensionless) on a log colour map, high = the quality
// map's red end (sample_quality_map(1 - t): the few hexes where the mesh
// simulates worst are the conspicuous ones), with its legend.
//   - Boundary figure: every boundary face coloured by its hex's density,
//     faint boundary edges.
//   - Cells figure: the densest 1% of the hexes (at most 300), opaque,
//     coloured by density, black edges where the cell scaled Jacobian is
//     below the quality threshold (grey otherwise), inside the boundary
//     drawn as a translucent blue-green veil (off the map, its own legend
//     swatch) drawn first, the cells and their edges over it (the overlay
//     layer, Scene), so no veil is blended over a cell: every cell shows its
//     legend colour (each face at most 15 % darker by its angle to the
//     camera, so the faces of a cluster differ); where the worst cells are,
//     also inside. Depth: a cell the boundary hides (seen through the veil,
//     error_density_cells_behind_boundary) gets dashed edges; the max hex's
//     own edges are drawn black on a white halo.
// Boundary faces unlit (the legend's colours exactly; edges give the depth). In both,
// the densest hex is ringed (its projected extent plus a few pixels, at
// least kMinRingRadius) and labelled with its value and whether it is on
// the boundary (the ring dashed when it is inside, or on the boundary but
// hidden from the viewpoint: then "(on the boundary, hidden: seen
// through)", and in the cells figure its front edges dashed too), the label
// in the free margin beside the model with a leader line to the ring. In
// the boundary figure its 12 edges are outlined in kMaxHexEdgeColor on a
// white halo (issue 48f: not when it is seen but so small in the figure
// that the outline would cover most of it: then only the ring, and the
// label gives its pixels; the ring is centred on its pixels in sight): solid and depth-tested when it is seen, dashed and drawn
// through the surface when hidden, never filled over the faces in front of
// it (issue 48; in the cells figure it is one of the cells, all drawn over
// the veil). Every mark has its own legend entry. Both from one upright,
// orthographic viewpoint: the one that shows the most of the densest 1% of
// the hexes (choose_viewpoints), so the worst region faces the camera. The
// colour is the density relative to the mesh's median (error_density_scale;
// the legend says so).

#include <array>
#include <span>
#include <string>
#include <vector>

#include "hqview/image/color.h"
#include "hqview/image/image.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"

namespace hq {

// The edges of the max hex (both figures): magenta, a colour no other mark
// of the figures uses (not on the density map, the veil, the black SJ edges or
// the grey cell edges), so the max is found by its edge colour alone.
inline constexpr Rgba8 kMaxHexEdgeColor{204, 0, 204, 255};

// A view direction (eye to target) for the error-density figures:
// direction, or, when it is within 15 degrees of edge-on to the thinnest
// axis n of points (their covariance's), the direction 30 degrees from
// edge-on with the same azimuth about n, the eye on focus's side of n
// (issue 48r: an extruded plate was seen edge-on, as a rectangle).
Vec3 away_from_edge_on(const Vec3& direction, std::span<const Vec3> points, const Vec3& focus);

// The colour scale (issue 48c): log10 of the density relative to a
// reference, by default the mesh's median: lo = the reference (values at or
// below it the map's pale end), hi = kErrorDensitySpan times it, or the
// mesh's max when that is higher (so the max is the map's red end and a mesh
// whose max is twice its median shows no red); with a reference given
// (ErrorDensityViewOptions::reference, --error-density-reference), hi is
// always kErrorDensitySpan times it: one scale for every mesh, values above
// clamped. max: the mesh's largest density, median its median of the positive
// densities (NaN for none). No positive density and no reference: 0.01 to 10.
inline constexpr double kErrorDensityLo = 1e-2, kErrorDensityHi = 10.0, kErrorDensitySpan = 10.0;
struct ErrorDensityScale {
  double lo = kErrorDensityLo, hi = kErrorDensityHi;
  double max = 0, median = 0;
  bool given = false;  // lo is a given reference, not the median
};
ErrorDensityScale error_density_scale(std::span<const double> density, double reference = 0);
// sample_quality_map(1 - t), t = (log10 d - log10 lo) / (log10 hi - log10 lo)
// clamped to [0, 1]; kUndefinedColor for NaN or d <= 0.
Color error_density_color(double density, const ErrorDensityScale& scale);
// Its legend: the map over log10 [lo, hi], ticks "<= 0.0428 (median)" at the
// bottom, the multiples 2x, 5x, 10x, 20x ... of lo between, each with its
// value (whole decades only over more than two), and "mesh max 0.0857 = 2.0x"
// at the max (at the top with an arrow when above a given scale); values
// crowding an end's or the max's label dropped; an "undefined" swatch (the
// boundary figure drops it when every face it draws has a density).
ColorBar error_density_color_bar(const ErrorDensityScale& scale);

// The hex of largest density (the first on ties; kNoIndex when none has a
// positive density), whether it has a boundary face, and the largest density
// of a hex with a boundary face (NaN when none).
struct ErrorDensityWorst {
  Index hex = kNoIndex;
  double density = 0;
  bool on_boundary = false;
  double boundary_max = 0;
};
ErrorDensityWorst error_density_worst(const Topology& topology, std::span<const double> density);

struct ErrorDensityViewOptions {
  int width = 1600;  // figure size in pixels, legend and title included
  int height = 1200;
  std::string title;  // empty: no title band
  Vec3 up{0.0, 0.0, 1.0};  // the model axis drawn upwards (--up)
  double quality_threshold = 0.5;  // cells figure: drawn cells with scaled Jacobian below it get black edges
  double densest_fraction = 0.01;  // cells figure: this fraction of the densest hexes (at least 1) ...
  std::size_t max_cells = 300;     // ... and at most this many
  Rgba8 background{255, 255, 255, 255};
  double reference = 0;  // > 0: the colour scale's reference (error_density_scale); else the mesh's median
};

// The hexes of the cells figure, ascending: the densest densest_fraction
// (at least 1, at most max_cells; ties by id). Selected by the density
// alone, so the figure does not assume which metric predicts it.
std::vector<Index> error_density_cells(std::span<const double> density, const ErrorDensityViewOptions& options);

// The upright direction that shows the most of the densest hexes, turned
// away from edge-on to the model (away_from_edge_on, the max hex the focus);
// with a renderer, of the 3 best such directions the first from which a
// boundary max hex is seen (error_density_cells_behind_boundary), the first
// when it is seen from none.
Vec3 choose_error_density_viewpoint(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                    const ErrorDensityViewOptions& options, Renderer* renderer = nullptr);

// The ring about the max is at least this many pixels (times the style's
// scale) in radius, at most kMaxRingFraction of the view's smaller side,
// and inside the view (moved in from its edges when the max is at one).
inline constexpr double kMinRingRadius = 18.0;
inline constexpr double kMaxRingFraction = 0.15;

// What a figure drew, for tests: the 3D scene, the legend's swatches, the
// ring's centre and radius in pixels (radius 0: no max), whether the max
// was called hidden and the seen hex named beside it (kNoIndex: none).
struct ErrorDensityFigureParts {
  Scene scene;
  std::vector<ColorBarSwatch> swatches;
  double ring_x = 0, ring_y = 0, ring_radius = 0;
  bool max_hidden = false;
  Index nearest_seen = kNoIndex;
  std::size_t max_pixels = 0;  // a seen max's pixels in the view (0: hidden)
  bool max_outlined = true;    // false: seen but too small for its outline (only the ring)
};

// The two figures; `camera` (may be null) receives the 3D camera and
// `view` (may be null) the pixel rectangle it drew into (for tests that
// project cells), `parts` (may be null) the scene and legend. Throws Error
// when a field has the wrong size, RenderError from the renderer.
Image render_error_density_boundary(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                    const Vec3& view_direction, const ErrorDensityViewOptions& options,
                                    Renderer& renderer, Camera* camera = nullptr, PixelRect* view = nullptr,
                                    ErrorDensityFigureParts* parts = nullptr);
Image render_error_density_cells(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                 std::span<const double> cell_scaled_jacobian, const Vec3& view_direction,
                                 const ErrorDensityViewOptions& options, Renderer& renderer, Camera* camera = nullptr,
                                 PixelRect* view = nullptr, ErrorDensityFigureParts* parts = nullptr);

// The legends' entries for the marks each figure draws (every mark one
// entry, no two entries alike; issue 48). Boundary figure: the ring and
// the max's outline (solid, or dashed when max_hidden). Cells figure: the
// ring, the max's front edges (thick; dashed when hidden) and back edges
// (thin dashed), the veil, the cells' edges, and when drawn the low-SJ
// edges and the dashed edges of hidden cells.
// A hidden max drawn solid (max_undashed: every edge shorter than a dash)
// says so.
std::vector<ColorBarSwatch> error_density_boundary_swatches(const ErrorDensityWorst& worst, bool max_hidden,
                                                            bool max_undashed = false, bool max_outlined = true);
struct ErrorDensityCellsMarks {
  bool any_low = false;     // a drawn cell with scaled Jacobian below the threshold
  bool max_low = false;     // ... the max among them (its halo black)
  bool any_hidden = false;  // a drawn cell the boundary hides (dashed edges)
  bool max_outlined = true;  // false: a seen max too small for its magenta edges (only the ring)
};
std::vector<ColorBarSwatch> error_density_cells_swatches(const ErrorDensityWorst& worst, bool max_hidden,
                                                         const ErrorDensityCellsMarks& marks, double quality_threshold);

// Per edge of a hex (kHexEdges order): whether one of its two faces turns to
// the camera (its normal, oriented away from the hex's centre, points to the
// eye; for an orthographic camera the eye's direction): the hex's own front
// edges, drawn solid for the cells figure's max; the others lie behind its
// faces (thin, dashed).
std::array<bool, 12> hex_edges_facing(const HexMesh& mesh, const Hex& hex, const Camera& camera);

// Which of `cells` the boundary hides from the direction of `camera`: a
// cell none of whose boundary faces, drawn opaque with the whole boundary,
// shows at least half of the pixels it covers drawn alone, face by face (id
// images, Renderer::render_ids, of 1200 x 1200 px along the camera's
// direction framing the cells' boundary faces, so the verdict depends on
// neither the figure's size and legend nor the face's size; issue 48e),
// a face drawn alone covering under 0.15 of its area (seen edge-on) or 16
// px not counted: an interior cell, one behind a fold or on the far side,
// or one seen only edge-on. Face by face (issue 48c): one face seen at a
// grazing angle makes a cell seen, however large its faces turned away.
// All false when the renderer draws no id images.
std::vector<bool> error_density_cells_behind_boundary(const HexMesh& mesh, const Topology& topology,
                                                      std::span<const Index> cells, const Camera& camera,
                                                      Renderer& renderer);

}  // namespace hq
