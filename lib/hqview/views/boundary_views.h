#pragma once
// Boundary error views (paper §G4): the hex boundary coloured by the signed
// distance to the reference (front and back), and the UV error map of the
// reference (its atlas filled with the interpolated reference -> hex
// boundary error, chart outlines drawn). Symmetric diverging scales.

#include <string>
#include <vector>

#include "hqview/boundary/boundary_error.h"
#include "hqview/image/image.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/render/annotate.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"
#include "hqview/uv/uv_atlas.h"

namespace hq {

struct BoundaryViewOptions {
  int width = 1600, height = 1200;
  std::string title;
  Rgba8 background{255, 255, 255, 255};
  Vec3 up{0.0, 0.0, 1.0};  // the model axis drawn upwards in the 3D views (--up)
};

// The colour scale's half-range (model units): the 98th percentile of |e|
// over the finite values of field, so that a few large errors (a cut-off
// fin) do not wash the rest out; larger errors saturate (the bar's ends read
// "<=" / ">="). 1 when there is no error. The figures never go below 0.01%
// of the diagonal (smaller errors are noise). The 3D views use the hex boundary's
// vertex_error, the UV map the reference's reference_vertex_error.
double error_scale(const std::vector<double>& field);

// The legend: diverging map over [-100 s / d, +100 s / d] percent of the
// reference's diagonal d, labelled "signed error (% of diagonal)", ticks at
// the ends, the middle and the quarter points.
ColorBar error_color_bar(double scale, double diagonal);

// Boundary faces (4 triangles around the centre each, smooth colours) coloured
// by diverging_color(vertex_error / scale); boundary edges faint.
Scene build_boundary_error_scene(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_error,
                                 double scale);

// The front (view_direction) or back (its opposite) figure.
Image render_boundary_error_view(const HexMesh& mesh, const Topology& topology, const BoundaryError& error,
                                 const Vec3& view_direction, const BoundaryViewOptions& options, Renderer& renderer);

// F with --reference: the hex boundary (opaque light grey faces, dark edges)
// under the reference surface (translucent orange, flat shaded): reference
// parts the mesh leaves out show plain orange. Where the two surfaces coincide
// within depth precision the depth test picks either (grey speckles, not an
// error reading: the boundary_error views give the signed error). triangles[0] the hex boundary,
// lines[0] its edges, translucent[0] the reference.
inline constexpr Rgba8 kReferenceOverlayColor{235, 125, 35, 96};
Scene build_reference_overlay_scene(const HexMesh& mesh, const Topology& topology, const TriSurface& reference);

// One camera (view_direction) fitted to both the hex boundary and the reference.
Image render_reference_overlay(const HexMesh& mesh, const Topology& topology, const TriSurface& reference,
                               const Vec3& view_direction, const BoundaryViewOptions& options, Renderer& renderer);

// The UV map as a flat scene in the z = 0 plane (u, v in [0, 1]):
// triangles[0] unlit, corners coloured by the reference error; lines[0] the
// chart outlines (triangle edges not shared with a triangle of the same chart).
Scene build_uv_error_scene(const TriSurface& reference, const UvAtlas& atlas, const std::vector<double>& point_error,
                           double scale);

// The orthographic camera that frames the unit UV square (with a 3 % margin)
// in a view of the given aspect (width / height), v up.
Camera uv_map_camera(double aspect);

Image render_uv_error_map(const TriSurface& reference, const UvAtlas& atlas, const BoundaryError& error,
                          const BoundaryViewOptions& options, Renderer& renderer);

}  // namespace hq
