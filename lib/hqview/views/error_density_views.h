#pragma once
// The finite-element error density in 3D (index.html panel P, --simulate):
// the per-hex normalised H1 error density of the Poisson check
// (poisson_check.h; dimensionless) on a log colour map, high = the quality
// map's red end (sample_quality_map(1 - t): the few hexes where the mesh
// simulates worst are the conspicuous ones), with its legend.
//   - Boundary figure: every boundary face coloured by its hex's density,
//     faint boundary edges.
//   - Cells figure: the cells under the quality threshold (cell scaled
//     Jacobian below it) and the densest 1% of the hexes, opaque, coloured
//     by density with dark edges, inside the boundary drawn as a translucent
//     grey veil: where the bad cells are and how much error they carry,
//     also when they are inside.
// Both from one upright, orthographic viewpoint: the one that shows the most
// of the densest 1% of the hexes (choose_viewpoints), so the worst region
// faces the camera.

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

namespace hq {

// The colour scale: log10 of the density from lo to hi (both > 0).
struct ErrorDensityScale {
  double lo = 1e-3, hi = 1.0;
};
// lo: the 1st percentile of the positive finite densities (at least hi /
// 1e4), hi: their max (a decade above lo when all are equal); the default
// for none.
ErrorDensityScale error_density_scale(std::span<const double> density);
// sample_quality_map(1 - t), t = (log10 d - log10 lo) / (log10 hi - log10 lo)
// clamped to [0, 1]; kUndefinedColor for NaN or d <= 0.
Color error_density_color(double density, const ErrorDensityScale& scale);
// Its legend: the map over log10 [lo, hi], ticks at the ends and the whole
// decades between, an "undefined" swatch.
ColorBar error_density_color_bar(const ErrorDensityScale& scale);

struct ErrorDensityViewOptions {
  int width = 1600;  // figure size in pixels, legend and title included
  int height = 1200;
  std::string title;  // empty: no title band
  Vec3 up{0.0, 0.0, 1.0};  // the model axis drawn upwards (--up)
  double quality_threshold = 0.5;  // cells figure: cells with scaled Jacobian below it
  double densest_fraction = 0.01;  // and this fraction of the densest hexes (at least 1)
  Rgba8 background{255, 255, 255, 255};
};

// The hexes of the cells figure, ascending: scaled Jacobian below the
// threshold (or a Verdict sentinel), or among the densest (ties by id).
std::vector<Index> error_density_cells(std::span<const double> cell_scaled_jacobian, std::span<const double> density,
                                       const ErrorDensityViewOptions& options);

// The upright direction that shows the most of the densest hexes.
Vec3 choose_error_density_viewpoint(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                    const ErrorDensityViewOptions& options);

// The two figures; `camera` (may be null) receives the 3D camera and
// `view` (may be null) the pixel rectangle it drew into (for tests that
// project cells). Throws Error when a field has the wrong size, RenderError
// from the renderer.
Image render_error_density_boundary(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                    const Vec3& view_direction, const ErrorDensityViewOptions& options,
                                    Renderer& renderer, Camera* camera = nullptr, PixelRect* view = nullptr);
Image render_error_density_cells(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                 std::span<const double> cell_scaled_jacobian, const Vec3& view_direction,
                                 const ErrorDensityViewOptions& options, Renderer& renderer, Camera* camera = nullptr,
                                 PixelRect* view = nullptr);

}  // namespace hq
