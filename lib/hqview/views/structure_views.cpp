#include "hqview/views/structure_views.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <span>

#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/label_layout.h"
#include "hqview/render/upright.h"
#include "hqview/views/main_views.h"
#include "hqview/views/overview_views.h"

namespace hq {
namespace {

constexpr double kNodeRadius = 0.2;  // of the median singular edge length
constexpr double kMaxNodeRadius = 0.02;  // of the boundary's bounding-box diagonal
constexpr Rgba8 kVeilColor{176, 182, 194, 56};     // the translucent boundary
constexpr Rgba8 kNodeColor{40, 40, 46, 255};        // singularity nodes
constexpr Rgba8 kGradationEdgeColor{40, 40, 46, 70};  // boundary edges over the gradation
// The gradation's max cell's edges: the error-density view's max-hex magenta
// (on none of the gradation map's pale-orange-red colours).
constexpr Rgba8 kGradationMaxEdgeColor{204, 0, 204, 255};
constexpr Rgba8 kNonConformingDiagonalColor{255, 255, 255, 255};  // dashed over the brown face
// The dashes stop this fraction of the diagonal short of its corners, so the
// curve-end rings there stay whole (46r review).
constexpr double kDiagonalEndMargin = 0.07;
// The non-conforming face as drawn: its colour at kNonConformingFaceAlpha
// over the veiled boundary on white (213, 214, 218: measured on the
// rendered view), so the legend swatch matches the face (46r review: the
// swatch was the saturated brown, the face tan).
constexpr Rgba8 kVeiledBoundary{213, 214, 218, 255};
constexpr Rgba8 non_conforming_face_as_drawn() {
  const auto mix = [](int c, int under) {
    return static_cast<std::uint8_t>((c * kNonConformingFaceAlpha + under * (255 - kNonConformingFaceAlpha) + 127) / 255);
  };
  return {mix(kNonConformingColor.r, kVeiledBoundary.r), mix(kNonConformingColor.g, kVeiledBoundary.g),
          mix(kNonConformingColor.b, kVeiledBoundary.b), 255};
}

const Vec3& point(const HexMesh& mesh, Index v) { return mesh.points[static_cast<std::size_t>(v)]; }

FigureLayout structure_layout(const StructureViewOptions& options, const AnnotationStyle& style) {
  const int legend_width = static_cast<int>(std::lround(360 * style.scale));
  return figure_layout(options.width, options.height, !options.title.empty(), legend_width, style);
}

Camera structure_camera(std::span<const Vec3> points, const Vec3& direction, double aspect,
                        const StructureViewOptions& options) {
  return fit_camera_to_points(points, direction, aspect,
                              {.up = options.up, .fov_y_degrees = options.fov_y_degrees, .is_perspective = false});
}

void check_size(const StructureViewOptions& options) {
  if (options.width <= 0 || options.height <= 0)
    throw RenderError("structure view size must be positive, got " + std::to_string(options.width) + "x" +
                      std::to_string(options.height));
}

// The boundary faces over all kinds (boundary_polygons), a quad as two
// triangles, a triangle as itself, one colour per face (color_of_cell of the
// face's cell id), flat.
TriangleSet boundary_faces(const HexMesh& mesh, const Topology& topology, const Vec3& origin, auto color_of_cell) {
  TriangleSet set;
  const std::vector<BoundaryPolygon> polygons = boundary_polygons(topology);
  const std::size_t n = polygons.size();
  set.positions.reserve(4 * n);
  set.colors.reserve(4 * n);
  set.indices.reserve(6 * n);
  for (const BoundaryPolygon& face : polygons) {
    const auto base = static_cast<std::uint32_t>(set.positions.size());
    const Rgba8 color = color_of_cell(face.cell);
    for (int i = 0; i < face.size; ++i) {
      set.positions.push_back(to_vec3f(point(mesh, face.v[static_cast<std::size_t>(i)]) - origin));
      set.colors.push_back(color);
    }
    for (std::uint32_t i : {0u, 1u, 2u}) set.indices.push_back(base + i);
    if (face.size == 4)
      for (std::uint32_t i : {0u, 2u, 3u}) set.indices.push_back(base + i);
  }
  return set;
}

double median_singular_edge_length(const HexMesh& mesh, const HexStructure& s) {
  std::vector<double> lengths;
  for (const StructureEdge& e : s.edges)
    if (e.singular) lengths.push_back(norm(point(mesh, e.vertices[1]) - point(mesh, e.vertices[0])));
  if (lengths.empty()) return 0.0;
  const auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  return *middle;
}

}  // namespace

double node_radius(const HexMesh& mesh, const Topology& topology, const HexStructure& structure) {
  // At most kMaxNodeRadius of the boundary's diagonal: on a coarse mesh (a
  // few hexes beside many tets) a fifth of an edge hid the graph.
  const Box3 box = boundary_bounding_box(mesh, topology);
  return std::min(kNodeRadius * median_singular_edge_length(mesh, structure), kMaxNodeRadius * norm(box.hi - box.lo));
}

std::vector<Index> interface_curve_ends(const HexStructure& structure) {
  std::map<Index, int> degree;
  std::set<Index> on_interface;
  for (const StructureEdge& e : structure.edges) {
    if (e.singular)
      for (Index v : e.vertices) ++degree[v];
    if (e.touches_non_hex) on_interface.insert(e.vertices.begin(), e.vertices.end());
  }
  std::vector<Index> ends;
  for (const auto& [v, d] : degree)
    if (d == 1 && on_interface.count(v)) ends.push_back(v);
  return ends;
}

TriangleSet curve_end_rings(const HexMesh& mesh, std::span<const Index> ends, const Vec3& origin, const Camera& camera,
                            double radius) {
  TriangleSet set;
  set.is_lit = false;
  const auto [right, up] = screen_axes(camera);
  constexpr int kSegments = 24;
  for (Index v : ends) {
    const Vec3 c = point(mesh, v) - origin;
    const auto base = static_cast<std::uint32_t>(set.positions.size());
    for (int k = 0; k < kSegments; ++k) {
      const double a = 2.0 * std::numbers::pi * k / kSegments;
      const Vec3 u = std::cos(a) * right + std::sin(a) * up;
      set.positions.push_back(to_vec3f(c + radius * u));
      set.positions.push_back(to_vec3f(c + kCurveEndRingInner * radius * u));
    }
    for (std::uint32_t k = 0; k < kSegments; ++k) {
      const std::uint32_t o0 = base + 2 * k, i0 = o0 + 1, o1 = base + 2 * ((k + 1) % kSegments), i1 = o1 + 1;
      set.indices.insert(set.indices.end(), {o0, o1, i1, o0, i1, i0});
    }
  }
  set.colors.assign(set.positions.size(), kNodeColor);
  return set;
}

SingularClass singular_class(const StructureEdge& e) {
  if (e.kind == EdgeKind::boundary) return e.valence <= 1 ? SingularClass::boundary_1 : SingularClass::boundary_3_plus;
  if (e.valence == 3) return SingularClass::interior_3;
  if (e.valence == 5) return SingularClass::interior_5;
  if (e.valence >= 6) return SingularClass::interior_6_plus;
  return SingularClass::interior_other;
}

Rgba8 singular_class_color(SingularClass c) {
  switch (c) {
    case SingularClass::interior_3: return {0, 114, 178, 255};       // blue
    case SingularClass::interior_5: return {213, 94, 0, 255};        // vermillion
    case SingularClass::interior_6_plus: return {204, 121, 167, 255};  // reddish purple
    case SingularClass::interior_other: return {86, 180, 233, 255};  // sky blue
    case SingularClass::boundary_1: return {0, 158, 115, 255};       // bluish green
    case SingularClass::boundary_3_plus: return {230, 159, 0, 255};  // orange
  }
  return {0, 0, 0, 255};
}

const char* singular_class_label(SingularClass c) {
  switch (c) {
    case SingularClass::interior_3: return "interior, valence 3";
    case SingularClass::interior_5: return "interior, valence 5";
    case SingularClass::interior_6_plus: return "interior, valence 6+";
    case SingularClass::interior_other: return "interior, valence 1-2";
    case SingularClass::boundary_1: return "boundary, valence 1";
    case SingularClass::boundary_3_plus: return "boundary, valence 3+";
  }
  return "";
}

Scene build_singularity_scene(const HexMesh& mesh, const Topology& topology, const HexStructure& structure,
                              const StructureViewOptions& options) {
  const Box3 box = boundary_bounding_box(mesh, topology);
  Scene scene;
  scene.origin = 0.5 * (box.lo + box.hi);
  scene.background = options.background;
  LineSet lines;
  lines.width = options.edge_width;
  for (const StructureEdge& e : structure.edges) {
    if (!e.singular) continue;
    const Rgba8 color = singular_class_color(singular_class(e));
    for (Index v : e.vertices) {
      lines.indices.push_back(static_cast<std::uint32_t>(lines.positions.size()));
      lines.positions.push_back(to_vec3f(point(mesh, v) - scene.origin));
      lines.colors.push_back(color);
    }
  }
  scene.lines.push_back(std::move(lines));
  SphereSet nodes;
  const auto radius = static_cast<float>(node_radius(mesh, topology, structure));
  if (radius > 0.0f)
    for (Index v : structure.nodes) {
      nodes.centers.push_back(to_vec3f(point(mesh, v) - scene.origin));
      nodes.radii.push_back(radius);
      nodes.colors.push_back(kNodeColor);
    }
  scene.spheres.push_back(std::move(nodes));
  scene.translucent.push_back(boundary_faces(mesh, topology, scene.origin, [](Index) { return kVeilColor; }));
  // Non-conforming interfaces (inside the mesh): flat, half transparent,
  // after the veil (one shade; the curves and nodes behind show through).
  if (!topology.non_conforming_faces.empty()) {
    TriangleSet faces;
    faces.is_lit = false;
    for (const NonConformingFace& nc : topology.non_conforming_faces) {
      const auto base = static_cast<std::uint32_t>(faces.positions.size());
      for (Index v : nc.quad) {
        faces.positions.push_back(to_vec3f(point(mesh, v) - scene.origin));
        faces.colors.push_back({kNonConformingColor.r, kNonConformingColor.g, kNonConformingColor.b, kNonConformingFaceAlpha});
      }
      faces.indices.insert(faces.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    scene.translucent.push_back(std::move(faces));
    // The triangles' diagonal, dashed in white over everything (the face is
    // under the veil; the split is what makes it non-conforming).
    TriangleSet diagonals;
    diagonals.is_lit = false;
    for (const NonConformingFace& nc : topology.non_conforming_faces)
      add_non_conforming_diagonal(mesh, nc, scene.origin, kNonConformingDiagonalColor, diagonals, kDiagonalEndMargin);
    scene.overlay.push_back(std::move(diagonals));
  }
  return scene;
}

double structure_view_aspect(const StructureViewOptions& options) {
  const FigureLayout layout = structure_layout(options, annotation_style_for(options.height));
  return static_cast<double>(std::max(1, layout.view.width)) / std::max(1, layout.view.height);
}

std::vector<Vec3> choose_singularity_viewpoints(const HexMesh& mesh, const Topology& topology,
                                                const HexStructure& structure, int count,
                                                const StructureViewOptions& options) {
  std::vector<Vec3> centers;
  std::vector<double> radii;
  for (const StructureEdge& e : structure.edges)
    if (e.singular) {
      const Vec3 a = point(mesh, e.vertices[0]), b = point(mesh, e.vertices[1]);
      centers.push_back(0.5 * (a + b));
      radii.push_back(0.5 * norm(b - a));
    }
  return choose_viewpoints(boundary_points(mesh, topology), centers, radii, structure_view_aspect(options), count,
                           options.up, options.fov_y_degrees);
}

Image render_singularity_view(const HexMesh& mesh, const Topology& topology, const HexStructure& structure,
                              const Vec3& view_direction, const StructureViewOptions& options, Renderer& renderer) {
  check_size(options);
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  const FigureLayout layout = structure_layout(options, style);
  const double aspect = static_cast<double>(layout.view.width) / std::max(1, layout.view.height);
  const Camera camera = structure_camera(boundary_points(mesh, topology), view_direction, aspect, options);
  StructureViewOptions scaled = options;
  scaled.edge_width = static_cast<float>(options.edge_width * style.scale);
  Scene scene = build_singularity_scene(mesh, topology, structure, scaled);
  // Where a curve of the hex part is cut by non-hex cells: a hollow ring
  // over everything (46q review Q-M3: the ends looked like dropouts).
  const std::vector<Index> ends = interface_curve_ends(structure);
  if (!ends.empty())
    scene.overlay.push_back(
        curve_end_rings(mesh, ends, scene.origin, camera, kCurveEndRingRadius * node_radius(mesh, topology, structure)));

  Image figure = render_figure(renderer, scene, camera, options.width, options.height, layout, options.title, style);

  std::array<Index, kNumSingularClasses> counts{};
  for (const StructureEdge& e : structure.edges)
    if (e.singular) ++counts[static_cast<std::size_t>(singular_class(e))];
  std::vector<LegendLine> lines{{std::nullopt, "singular edges"}};
  for (int c = 0; c < kNumSingularClasses; ++c)
    if (counts[static_cast<std::size_t>(c)] > 0)
      lines.push_back({singular_class_color(static_cast<SingularClass>(c)),
                       std::string(singular_class_label(static_cast<SingularClass>(c))) + ": " +
                           std::to_string(counts[static_cast<std::size_t>(c)])});
  if (structure.num_singular_edges_interior + structure.num_singular_edges_boundary == 0)
    lines.push_back({std::nullopt, "none: every edge is regular"});
  lines.push_back({kNodeColor, "nodes: " + std::to_string(structure.nodes.size()), 1});
  lines.push_back({std::nullopt, "curves: " + std::to_string(structure.num_curves)});
  lines.push_back({std::nullopt, "irregular boundary edges: " + std::to_string(structure.num_irregular_edges_boundary)});
  if (structure.num_nonmanifold_edges > 0)
    lines.push_back({std::nullopt, "non-manifold edges: " + std::to_string(structure.num_nonmanifold_edges)});
  lines.push_back({Rgba8{176, 182, 194, 255}, "boundary (translucent)", 1});
  if (!topology.non_conforming_faces.empty()) {
    lines.push_back({non_conforming_face_as_drawn(),
                     "non-conforming faces: " + std::to_string(topology.non_conforming_faces.size())});
    lines.push_back({std::nullopt, "white dashes: the split diagonal"});
  }
  if (const std::string kinds = mesh_kinds_text(mesh); !kinds.empty()) {
    lines.push_back({std::nullopt, kinds, 1});
    lines.push_back({std::nullopt, "graph of the hex part"});
    if (structure.num_interface_ends > 0)
      lines.push_back({kNodeColor, std::to_string(structure.num_interface_ends) + " curve ends at non-hex cells", 0, SwatchShape::solid_ring});
  }
  draw_legend(figure, layout.legend, lines, style);
  return figure;
}

Color gradation_color(double g) {
  if (std::isnan(g)) return kUndefinedColor;
  return sample_quality_map(1.0 - std::clamp(std::log2(std::max(g, 1.0)) / 2.0, 0.0, 1.0));
}

Vec3 choose_gradation_viewpoint(const HexMesh& mesh, const Topology& topology, const HexStructure& structure,
                                const StructureViewOptions& options) {
  // The four upright three-quarter poses, the overview's first.
  std::vector<Vec3> poses;
  for (int k = 0; k < 4; ++k)
    poses.push_back(upright_view_direction(options.up, kThreeQuarterAzimuth + 90.0 * k, kThreeQuarterElevation));
  // Each pose's score: the area, projected on its view plane, of the
  // boundary faces (every kind) of cells grading above
  // kGradationOfInterest that face its eye (their outward vector areas
  // against the direction to the eye).
  std::vector<double> score(poses.size(), 0.0);
  for (const BoundaryPolygon& face : boundary_polygons(topology)) {
    const auto cell = static_cast<std::size_t>(face.cell);
    if (cell >= structure.cell_gradation.size() || !(structure.cell_gradation[cell] > kGradationOfInterest)) continue;
    const auto p = [&](int i) { return point(mesh, face.v[static_cast<std::size_t>(i)]); };
    Vec3 area = 0.5 * cross(p(1) - p(0), p(2) - p(0));
    if (face.size == 4) area = area + 0.5 * cross(p(2) - p(0), p(3) - p(0));
    for (std::size_t k = 0; k < poses.size(); ++k) score[k] += std::max(0.0, -dot(area, poses[k]));
  }
  // The first best (a tie, or no such face: the overview's pose).
  std::size_t best = 0;
  for (std::size_t k = 1; k < poses.size(); ++k)
    if (score[k] > score[best] * (1.0 + 1e-9)) best = k;
  return poses[best];
}

Image render_gradation_view(const HexMesh& mesh, const Topology& topology, const HexStructure& structure,
                            const Vec3& view_direction, const StructureViewOptions& options, Renderer& renderer) {
  check_size(options);
  if (structure.cell_gradation.size() != static_cast<std::size_t>(num_volume_cells(mesh)))
    throw Error("size gradation has " + std::to_string(structure.cell_gradation.size()) + " values for " +
                std::to_string(num_volume_cells(mesh)) + " cells");
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  ColorBar bar;
  bar.label = "size gradation:\nedge length (cube root of\nvolume) ratio to a face\nneighbour (max)";
  bar.min_value = 0.0;
  bar.max_value = 2.0;  // log2 of the gradation
  for (int i = 0; i <= 32; ++i) bar.colors.push_back(gradation_color(std::exp2(2.0 * i / 32.0)));
  bar.ticks = {{0.0, "1"}, {std::log2(1.5), "1.5"}, {1.0, "2"}, {std::log2(3.0), "3"}, {2.0, ">= 4"}};
  // "undefined" only when a boundary cell has no gradation.
  for (const BoundaryPolygon& face : boundary_polygons(topology))
    if (static_cast<std::size_t>(face.cell) < structure.cell_gradation.size() &&
        std::isnan(structure.cell_gradation[static_cast<std::size_t>(face.cell)])) {
      bar.swatches = {{kUndefinedColor, "undefined"}};
      break;
    }
  // Several kinds: sizes are equivalent edge lengths (the regular cell of
  // the kind with the cell's volume; structure.h).
  if (const std::string kinds = mesh_kinds_text(mesh); !kinds.empty())
    bar.label = "size gradation: ratio of\nequivalent edge lengths\n(regular cell of its kind\nwith its volume) to a face\nneighbour's (max)\n" + kinds;
  const FigureLayout layout =
      figure_layout(options.width, options.height, !options.title.empty(), color_bar_width(bar, style), style);
  const double aspect = static_cast<double>(layout.view.width) / std::max(1, layout.view.height);
  // In perspective, as the overview (a boundary coloured by a field, seen
  // from its upright three-quarter pose): an orthographic view along a
  // side read as a flat rectangle (46r review M4).
  const Camera camera = fit_camera_to_points(
      boundary_points(mesh, topology), view_direction, aspect,
      {.up = options.up, .fov_y_degrees = options.fov_y_degrees, .is_perspective = true});

  const Box3 box = boundary_bounding_box(mesh, topology);
  Scene scene;
  scene.origin = 0.5 * (box.lo + box.hi);
  scene.background = options.background;
  scene.triangles.push_back(boundary_faces(mesh, topology, scene.origin, [&](Index cell) {
    return to_rgba8(gradation_color(structure.cell_gradation[static_cast<std::size_t>(cell)]));
  }));
  // Flat, as the colour bar: lit side faces took colours the bar has not
  // (46t review); the edges give the shape.
  scene.triangles.back().is_lit = false;
  LineSet edges;
  edges.width = static_cast<float>(std::max(1.0, style.scale));
  for (const Edge& e : boundary_edges_all_kinds(topology))
    for (Index v : e) {
      edges.indices.push_back(static_cast<std::uint32_t>(edges.positions.size()));
      edges.positions.push_back(to_vec3f(point(mesh, v) - scene.origin));
      edges.colors.push_back(kGradationEdgeColor);
    }
  scene.lines.push_back(std::move(edges));

  // The max cell (46t2 review: the title's max was hidden and unmarked):
  // its whole wireframe over everything (nearer cells do not hide it), in
  // kGradationMaxEdgeColor on a white halo, and a label with its value,
  // kind and id at its centre, with a leader.
  const Index max_cell = gradation_max_cell(structure.cell_gradation);
  const std::vector<BoundaryPolygon> polygons = boundary_polygons(topology);
  const CellSight sight = max_cell != kNoIndex ? cell_sight(mesh, polygons, max_cell, camera) : CellSight::inside;
  if (max_cell != kNoIndex) {
    LineSet halo, core;
    halo.width = static_cast<float>(std::max(4.0, 6.0 * style.scale));
    core.width = static_cast<float>(std::max(2.0, 2.5 * style.scale));
    halo.over_all = core.over_all = true;
    // Not seen from the camera (on the far side, or inside): dashed, 5
    // dashes an edge (46w review C4: a hidden max cell's solid outline
    // read as the nearer cells under it).
    const bool dashed = sight != CellSight::seen;
    const int pieces = dashed ? 9 : 1;
    for_each_edge_of(volume_cell(mesh, max_cell), [&](Index a, Index b) {
      const Vec3 pa = point(mesh, a) - scene.origin, pb = point(mesh, b) - scene.origin;
      for (int k = 0; k < pieces; k += 2)
        for (int end : {k, k + 1}) {
          const Vec3 q = pa + (static_cast<double>(end) / pieces) * (pb - pa);
          for (LineSet* set : {&halo, &core}) {
            set->indices.push_back(static_cast<std::uint32_t>(set->positions.size()));
            set->positions.push_back(to_vec3f(q));
          }
          halo.colors.push_back({255, 255, 255, 255});
          core.colors.push_back(kGradationMaxEdgeColor);
        }
    });
    scene.lines.push_back(std::move(halo));
    scene.lines.push_back(std::move(core));
    bar.swatches.push_back({to_color(kGradationMaxEdgeColor),
                            dashed ? "max cell: its edges\n(dashed: not in sight)" : "max cell: its edges",
                            dashed ? SwatchShape::dashed_line : SwatchShape::thick_line});
  }
  Image figure = render_figure(renderer, scene, camera, options.width, options.height, layout, options.title, style);
  draw_color_bar(figure, layout.legend, bar, style);
  if (max_cell != kNoIndex) {
    const CellRef cell = volume_cell(mesh, max_cell);
    Vec3 centre{};
    for (int i = 0; i < cell.num_corners; ++i) centre = centre + point(mesh, cell.corners[static_cast<std::size_t>(i)]);
    centre = centre / static_cast<double>(cell.num_corners);
    const PixelRect& view = layout.view;
    const auto to_screen = [&](const Vec3& p) {
      const Vec3 ndc = project_to_ndc(camera, aspect, p);
      return std::array<double, 2>{view.x + 0.5 * (ndc.x + 1.0) * view.width, view.y + 0.5 * (1.0 - ndc.y) * view.height};
    };
    // The anchor: a disc over the cell's corners on screen (the label stays
    // off the outline), at most a tenth of the view's height.
    const auto [cx, cy] = to_screen(centre);
    double reach = 3.0 * style.scale;
    for (int i = 0; i < cell.num_corners; ++i) {
      const auto [x, y] = to_screen(point(mesh, cell.corners[static_cast<std::size_t>(i)]));
      reach = std::max(reach, std::hypot(x - cx, y - cy));
    }
    const ScreenDisc anchor{cx, cy, std::min(reach, 0.1 * view.height), 0};
    // Inside (no boundary face) or on the far side (none of its boundary
    // faces in sight): its outline is seen through the boundary.
    const std::string text = gradation_max_label(structure.cell_gradation, mesh, max_cell) +
                             (sight == CellSight::inside     ? " (inside)"
                              : sight == CellSight::far_side ? " (far side)"
                                                             : "");
    const int text_size = std::max(style.min_text_size, static_cast<int>(std::lround(22 * style.scale)));
    const PixelRect extent = text_extent(text, text_size, style);
    LabelLayoutOptions placement;
    placement.bounds = view;
    placement.gap = 6.0 * style.scale;
    placement.ring_step = 14.0 * style.scale;
    placement.leader_distance = 0.0;  // always a leader: the label names the outlined cell
    LabelRequest request{anchor, extent.width + 8, static_cast<int>(std::lround(1.3 * text_size))};
    request.always_leader = true;
    request.leader_from = ScreenDisc{cx, cy, 2.0 * style.scale, 0};  // from the cell's centre
    const std::optional<PlacedLabel> p = LabelPlacer({}, placement).place(request, {});
    if (p) {
      const double width = std::max(1.0, 1.5 * style.scale);
      draw_line(figure, p->leader_x0, p->leader_y0, p->leader_x1, p->leader_y1, {255, 255, 255, 255}, 3.0 * width);
      draw_line(figure, p->leader_x0, p->leader_y0, p->leader_x1, p->leader_y1, kGradationMaxEdgeColor, width);
      fill_rect(figure, p->box, options.background);
      AnnotationStyle ink = style;
      ink.text_color = {30, 30, 30, 255};
      draw_text(figure, p->box.x + 4, p->box.y + static_cast<int>(std::lround(1.0 * text_size)), text, text_size, ink);
      // Its frame in the outline's colour: the label and the outlined cell read as one.
      for (const auto& [x0, y0, x1, y1] : std::array<std::array<int, 4>, 4>{
               {{p->box.x, p->box.y, p->box.x + p->box.width, p->box.y},
                {p->box.x, p->box.y + p->box.height, p->box.x + p->box.width, p->box.y + p->box.height},
                {p->box.x, p->box.y, p->box.x, p->box.y + p->box.height},
                {p->box.x + p->box.width, p->box.y, p->box.x + p->box.width, p->box.y + p->box.height}}})
        draw_line(figure, x0, y0, x1, y1, kGradationMaxEdgeColor, width);
    }
  }
  return figure;
}

CellSight cell_sight(const HexMesh& mesh, std::span<const BoundaryPolygon> boundary, Index cell, const Camera& camera) {
  const auto corner = [&](const BoundaryPolygon& f, int i) { return point(mesh, f.v[static_cast<std::size_t>(i)]); };
  const auto normal_of = [&](const BoundaryPolygon& f) {
    Vec3 n = cross(corner(f, 1) - corner(f, 0), corner(f, 2) - corner(f, 0));
    if (f.size == 4) n = n + cross(corner(f, 2) - corner(f, 0), corner(f, 3) - corner(f, 0));
    return n;
  };
  // Whether the segment p -> eye passes through a triangle (Moller-Trumbore).
  const auto blocks = [](const Vec3& p, const Vec3& e, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 d = e - p, ab = b - a, ac = c - a, h = cross(d, ac);
    const double det = dot(ab, h);
    if (std::abs(det) < 1e-300) return false;
    const Vec3 s = p - a;
    const double u = dot(s, h) / det;
    if (u < 0.0 || u > 1.0) return false;
    const Vec3 q = cross(s, ab);
    const double v = dot(d, q) / det;
    if (v < 0.0 || u + v > 1.0) return false;
    const double t = dot(ac, q) / det;
    return t > 1e-9 && t < 1.0;
  };
  bool on_boundary = false;
  double scale = 0.0;
  for (const BoundaryPolygon& f : boundary)
    if (f.cell == cell) scale = std::max(scale, norm(corner(f, 1) - corner(f, 0)));
  for (const BoundaryPolygon& f : boundary) {
    if (f.cell != cell) continue;
    on_boundary = true;
    const Vec3 n = normal_of(f);
    if (!(norm(n) > 0.0)) continue;
    Vec3 centre{};
    for (int i = 0; i < f.size; ++i) centre = centre + corner(f, i);
    centre = centre / static_cast<double>(f.size);
    // The centre and points 0.6 of the way to each corner, lifted off the face.
    std::vector<Vec3> samples{centre};
    for (int i = 0; i < f.size; ++i) samples.push_back(centre + 0.6 * (corner(f, i) - centre));
    for (Vec3 p : samples) {
      const Vec3 eye = camera.is_perspective ? camera.eye : p + (camera.eye - camera.target);
      if (!(dot(n, eye - p) > 0.0)) break;  // faces away (or edge-on)
      p = p + (1e-6 * scale / norm(n)) * n;
      bool hidden = false;
      for (const BoundaryPolygon& g : boundary) {
        if (&g == &f) continue;
        if (blocks(p, eye, corner(g, 0), corner(g, 1), corner(g, 2)) ||
            (g.size == 4 && blocks(p, eye, corner(g, 0), corner(g, 2), corner(g, 3)))) {
          hidden = true;
          break;
        }
      }
      if (!hidden) return CellSight::seen;
    }
  }
  return on_boundary ? CellSight::far_side : CellSight::inside;
}

Index gradation_max_cell(std::span<const double> cell_gradation) {
  Index best = kNoIndex;
  for (std::size_t i = 0; i < cell_gradation.size(); ++i)
    if (std::isfinite(cell_gradation[i]) && (best == kNoIndex || cell_gradation[i] > cell_gradation[static_cast<std::size_t>(best)]))
      best = static_cast<Index>(i);
  return best;
}

std::string gradation_max_label(std::span<const double> cell_gradation, const HexMesh& mesh, Index cell) {
  return "max " + display_number(cell_gradation[static_cast<std::size_t>(cell)], 3) + "  " +
         std::string(cell_kind_name(volume_cell(mesh, cell).kind)) + " " + std::to_string(cell);
}

}  // namespace hq
