#pragma once
// The structure views (index.html's panel S, after A): the singularity graph
// and the size gradation.
//   - Singularity graph: the singular edges (HexStructure) as thick lines
//     coloured by their class (a fixed palette, one legend entry each, with
//     its count), the singularity nodes as small dark spheres, inside the
//     boundary drawn as a translucent grey veil; orthographic and upright,
//     from the viewpoints that show the most singular edges (choose_viewpoints
//     with a sphere on each singular edge).
//   - Size gradation: every boundary face coloured by its hex's gradation on
//     a fixed log scale from 1 (pale: equal neighbours) to 4 and more (red),
//     grey where undefined; upright, from the viewpoint that shows the most
//     faces above 2 (the three-quarter view when there are none).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hqview/image/image.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/render/camera.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"
#include "hqview/structure/structure.h"

namespace hq {

// The classes of singular edges, in legend order.
enum class SingularClass { interior_3, interior_5, interior_6_plus, interior_other, boundary_1, boundary_3_plus };
inline constexpr int kNumSingularClasses = 6;
SingularClass singular_class(const StructureEdge& e);
// Okabe-Ito colours (told apart with colour-blindness too), never grey.
Rgba8 singular_class_color(SingularClass c);
const char* singular_class_label(SingularClass c);  // "interior valence 3", ...

struct StructureViewOptions {
  int width = 1600;  // figure size in pixels, legend and title included
  int height = 1200;
  std::string title;  // empty: no title band
  Rgba8 background{255, 255, 255, 255};
  float edge_width = 4.0f;       // singular edges, output pixels at 1200 pixels of height
  Vec3 up{0.0, 0.0, 1.0};        // the model axis drawn upwards (--up)
  double fov_y_degrees = 30.0;
};

// The radius of the node spheres: 0.2 of the median singular edge length,
// at most 0.02 of the boundary's bounding-box diagonal (model units).
double node_radius(const HexMesh& mesh, const Topology& topology, const HexStructure& structure);

// A hybrid mesh: the vertices where a singular curve of the hex part is cut
// by non-hex cells (one singular edge there, on an edge that touches a
// non-hex cell; HexStructure::num_interface_ends of them), ascending.
std::vector<Index> interface_curve_ends(const HexStructure& structure);

// A hollow ring (outer radius `radius`, inner kCurveEndRingInner of it, in
// model units) facing the camera at each of `ends`, unlit, in the node
// colour: what view S draws over everything at the curve ends, with a ring
// swatch on the legend's "curve ends at non-hex cells" line.
inline constexpr double kCurveEndRingRadius = 0.8;  // of node_radius
inline constexpr double kCurveEndRingInner = 0.6;
TriangleSet curve_end_rings(const HexMesh& mesh, std::span<const Index> ends, const Vec3& origin, const Camera& camera,
                            double radius);

// The non-conforming faces' opacity in view S (a flat, half-transparent
// brown drawn after the veil: nodes and curves behind it show through).
inline constexpr std::uint8_t kNonConformingFaceAlpha = 128;

// The singularity graph's scene: translucent boundary, lines, node spheres
// (radius node_radius); on a mesh with non-conforming faces, those faces
// (translucent[1], unlit, kNonConformingFaceAlpha) and their diagonals dashed
// in white (overlay[0]).
Scene build_singularity_scene(const HexMesh& mesh, const Topology& topology, const HexStructure& structure,
                              const StructureViewOptions& options);

// Width / height of the 3D area of a structure figure.
double structure_view_aspect(const StructureViewOptions& options);

// The count upright directions that show the most of the singular edges
// (each a sphere of half its length); the three-quarter views without any.
std::vector<Vec3> choose_singularity_viewpoints(const HexMesh& mesh, const Topology& topology,
                                                const HexStructure& structure, int count,
                                                const StructureViewOptions& options);

Image render_singularity_view(const HexMesh& mesh, const Topology& topology, const HexStructure& structure,
                              const Vec3& view_direction, const StructureViewOptions& options, Renderer& renderer);

// The colour of a size gradation g (a length ratio): sample_quality_map(1 -
// log2(g) / 2) (g = 1 pale, 2 orange, g >= 4 red), kUndefinedColor for NaN.
Color gradation_color(double g);
// The gradation view looks at the cells grading above this (length ratio).
inline constexpr double kGradationOfInterest = 1.5;

// The gradation view's direction: of the four upright three-quarter poses
// (azimuth kThreeQuarterAzimuth + k 90 degrees, elevation
// kThreeQuarterElevation: the overview's pose, first, and its turns about
// up), the one that sees the largest projected area of the boundary faces
// (every kind) of cells grading above kGradationOfInterest facing it; ties
// and none: the overview's pose (issue 46 part T: a free choice among the
// upright candidates gave the tower a head-on view that read as a flat
// rectangle). The view is drawn in perspective, as the overview.
Vec3 choose_gradation_viewpoint(const HexMesh& mesh, const Topology& topology, const HexStructure& structure,
                                const StructureViewOptions& options);

// The cell of the largest finite gradation (the lowest id on ties), which
// the gradation view outlines (its edges in magenta on a white halo, drawn
// over every nearer cell; legend "max cell: its edges") and labels with
// gradation_max_label ("max 1.71  tet 123", then " (inside)" when it has no
// boundary face) on a leader; kNoIndex when no
// value is finite.
Index gradation_max_cell(std::span<const double> cell_gradation);
// Whether `cell` is in sight from `camera` (46w review C4: cyl's max cell was
// on the far side, its solid outline over nearer cells of ~1.05): seen when
// some boundary face of it (boundary: boundary_polygons, outward) faces the
// eye and a segment from one of its samples (the face's centre and the
// points 0.6 of the way to its corners) to the eye (orthographic: along the
// view direction) crosses no other boundary face; far_side when it has
// boundary faces but none so; inside without one. The gradation view draws a
// cell not seen dashed (legend `max cell: its edges` / `(dashed: not in
// sight)`) and ends its label with ` (far side)` or ` (inside)`.
enum class CellSight { seen, far_side, inside };
CellSight cell_sight(const HexMesh& mesh, std::span<const BoundaryPolygon> boundary, Index cell, const Camera& camera);
std::string gradation_max_label(std::span<const double> cell_gradation, const HexMesh& mesh, Index cell);

Image render_gradation_view(const HexMesh& mesh, const Topology& topology, const HexStructure& structure,
                            const Vec3& view_direction, const StructureViewOptions& options, Renderer& renderer);

}  // namespace hq
