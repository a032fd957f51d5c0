#include "hqview/views/surface_views.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <span>
#include <string>

#include "hqview/core/box3.h"
#include "hqview/glyph/glyph_ties.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/mesh_summary.h"
#include "hqview/mesh/planarity.h"
#include "hqview/quality/hex_metrics.h"
#include "hqview/render/camera.h"
#include "hqview/render/upright.h"
#include "hqview/views/main_views.h"
#include "hqview/views/overview_viewpoint.h"
#include "hqview/views/overview_views.h"
#include "hqview/views/structure_views.h"

namespace hq {
namespace {

// The fill's bins: upper bounds (inclusive), colours and legend text. A
// sequential ramp dark to light with a step in lightness between
// neighbours (CIE L* about 45, 67, 87, 97; ColorBrewer OrRd's hues), so a
// 0.3-0.6 face stands out among 0.9-1 faces in grey-scale too; inverted in
// the inverted colour (blue, apart from the ramp's hues).
struct FillBin {
  double upper;
  Rgba8 color;
  const char* text;
};
const std::array<FillBin, 5> kFillBins{{{0.0, to_rgba8(kInvertedColor), "inverted (<= 0)"},
                                        {0.3, Rgba8{179, 0, 0, 255}, "0 to 0.3"},
                                        {0.6, Rgba8{239, 101, 72, 255}, "0.3 to 0.6"},
                                        {0.9, Rgba8{253, 212, 158, 255}, "0.6 to 0.9"},
                                        {1.0, Rgba8{250, 247, 240, 255}, "0.9 to 1"}}};

// The bin of q, or -1 (undefined: NaN or Verdict's sentinel).
int fill_bin(double q) {
  if (std::isnan(q) || is_verdict_sentinel(q)) return -1;
  for (std::size_t b = 0; b < kFillBins.size(); ++b)
    if (q <= kFillBins[b].upper) return static_cast<int>(b);
  return static_cast<int>(kFillBins.size()) - 1;
}

// A face as 1 or 2 triangles in one colour, lit by one normal (a quad's
// diagonals' cross product: its area-weighted normal when not planar).
void add_flat_face(TriangleSet& set, const HexMesh& mesh, const BoundaryPolygon& face, const Rgba8& color,
                   const Vec3& origin) {
  std::array<Vec3, 4> p{};
  for (int i = 0; i < face.size; ++i)
    p[static_cast<std::size_t>(i)] = mesh.points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])];
  const Vec3 n = face.size == 4 ? cross(p[2] - p[0], p[3] - p[1]) : cross(p[1] - p[0], p[2] - p[0]);
  const Vec3f normal = norm(n) > 0.0 ? to_vec3f(normalized(n)) : Vec3f{0.0f, 0.0f, 1.0f};
  const auto base = static_cast<std::uint32_t>(set.positions.size());
  for (int i = 0; i < face.size; ++i) {
    set.positions.push_back(to_vec3f(p[static_cast<std::size_t>(i)] - origin));
    set.normals.push_back(normal);
    set.colors.push_back(color);
  }
  set.indices.insert(set.indices.end(), {base, base + 1, base + 2});
  if (face.size == 4) set.indices.insert(set.indices.end(), {base, base + 2, base + 3});
}

Rgba8 bin_color(int b) {
  return b < 0 ? to_rgba8(kUndefinedColor) : kFillBins[static_cast<std::size_t>(b)].color;
}

}  // namespace

bool is_surface_mesh_view(std::string_view id) {
  return id == "overview" || id == "main" || id == "histogram" || id == "histogram_log" || id == "sorted_quality" ||
         id == "structure" || id == "thumbnail" || id == "compare" || id == "boundary_error" ||
         id == "reference_error" || id == "uv_error" || id == "uv_key" || id == "reference_overlay" ||
         id == "boundary_error_sorted" || id == "boundary_area" || id == "clusters" || id == "local" ||
         id == "corners";
}

std::optional<Vec3> planar_view_direction(const Analysis& a) {
  if (!is_surface_mesh(a.mesh) || !a.mesh_summary.planarity || !a.mesh_summary.planarity->is_planar) return std::nullopt;
  return -1.0 * a.mesh_summary.planarity->normal;
}

std::vector<std::size_t> cluster_target_faces(const GlyphResult& glyphs, Index cluster,
                                              std::span<const BoundaryPolygon> faces,
                                              std::span<const double> cell_quality) {
  const auto c = static_cast<std::size_t>(cluster);
  if (c >= glyphs.clusters.size() || c + 1 >= glyphs.cluster_offsets.size()) return {};
  const std::span<const Index> members(glyphs.cluster_vertices.data() + glyphs.cluster_offsets[c],
                                       glyphs.cluster_vertices.data() + glyphs.cluster_offsets[c + 1]);
  auto at_member = [&](const BoundaryPolygon& f) {
    return std::any_of(f.v.begin(), f.v.begin() + f.size,
                       [&](Index v) { return std::binary_search(members.begin(), members.end(), v); });
  };
  const double worst = glyphs.clusters[c].min_quality + kGlyphTieTolerance;
  std::vector<std::size_t> all, worst_faces;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (!at_member(faces[i])) continue;
    all.push_back(i);
    const auto cell = static_cast<std::size_t>(faces[i].cell);
    if (cell < cell_quality.size() && cell_quality[cell] <= worst) worst_faces.push_back(i);
  }
  return worst_faces.empty() ? all : worst_faces;
}

namespace {

// A face's area vector (its normal times its area).
Vec3 area_vector(const HexMesh& mesh, const BoundaryPolygon& f) {
  auto p = [&](int i) { return mesh.points[static_cast<std::size_t>(f.v[static_cast<std::size_t>(i % f.size)])]; };
  return f.size == 3 ? 0.5 * cross(p(1) - p(0), p(2) - p(0)) : 0.5 * cross(p(2) - p(0), p(3) - p(1));
}

// The first allowed candidate scoring at least kNearBestFraction of the
// largest allowed score (candidates in order of preference: the upright
// ones first); score.size() when none scores.
std::size_t best_of(std::span<const double> score, const std::vector<bool>& allowed) {
  double top = 0.0;
  for (std::size_t i = 0; i < score.size(); ++i)
    if (allowed[i]) top = std::max(top, score[i]);
  for (std::size_t i = 0; i < score.size(); ++i)
    if (allowed[i] && top > 0.0 && score[i] >= kNearBestFraction * top) return i;
  return score.size();
}

}  // namespace

namespace {

// The points' principal axes: the eigenvalues of their covariance,
// ascending, and the unit eigenvectors; none for fewer than 3 points.
struct PrincipalAxes {
  std::array<double, 3> value{};
  std::array<Vec3, 3> axis{};
};

std::optional<PrincipalAxes> principal_axes(std::span<const Vec3> points) {
  if (points.size() < 3) return std::nullopt;
  Vec3 mean;
  for (const Vec3& p : points) mean = mean + p;
  mean = (1.0 / static_cast<double>(points.size())) * mean;
  std::array<std::array<double, 3>, 3> c{}, v{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  for (const Vec3& p : points) {
    const std::array<double, 3> d{p.x - mean.x, p.y - mean.y, p.z - mean.z};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[i][j] += d[i] * d[j];
  }
  // Cyclic Jacobi rotations: c becomes diagonal, v's columns its eigenvectors.
  for (int sweep = 0; sweep < 50; ++sweep)
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (std::abs(c[p][q]) <= 1e-15 * (std::abs(c[p][p]) + std::abs(c[q][q]))) continue;
        const double theta = 0.5 * std::atan2(2.0 * c[p][q], c[q][q] - c[p][p]);
        const double cs = std::cos(theta), sn = std::sin(theta);
        for (int k = 0; k < 3; ++k) {  // c <- c J
          const double a = c[k][p], b = c[k][q];
          c[k][p] = cs * a - sn * b;
          c[k][q] = sn * a + cs * b;
        }
        for (int k = 0; k < 3; ++k) {  // c <- J^T c
          const double a = c[p][k], b = c[q][k];
          c[p][k] = cs * a - sn * b;
          c[q][k] = sn * a + cs * b;
        }
        for (int k = 0; k < 3; ++k) {  // v <- v J
          const double a = v[k][p], b = v[k][q];
          v[k][p] = cs * a - sn * b;
          v[k][q] = sn * a + cs * b;
        }
      }
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return c[a][a] < c[b][b]; });
  PrincipalAxes out;
  for (int i = 0; i < 3; ++i) {
    const int k = order[static_cast<std::size_t>(i)];
    out.value[static_cast<std::size_t>(i)] = c[k][k];
    out.axis[static_cast<std::size_t>(i)] = Vec3{v[0][k], v[1][k], v[2][k]};
  }
  return out;
}

// model_axis's choice: the index (0 or 2) of the eigenvalue farther from
// the middle one, or none.
std::optional<std::size_t> axis_index(const PrincipalAxes& p) {
  const auto& l = p.value;
  if (!(l[2] > 0.0)) return std::nullopt;
  // The eigenvalue farther from the middle one: the longest axis (a vase)
  // or the shortest (a bell, a dish).
  const std::size_t k = l[2] - l[1] >= l[1] - l[0] ? 2 : 0;
  if (std::abs(l[k] - l[1]) < kAxisGap * l[2]) return std::nullopt;
  return k;
}

}  // namespace

std::optional<Vec3> model_axis(std::span<const Vec3> points) {
  const std::optional<PrincipalAxes> p = principal_axes(points);
  const std::optional<std::size_t> k = p ? axis_index(*p) : std::nullopt;
  if (!k) return std::nullopt;
  return p->axis[*k];
}

std::optional<Vec3> revolution_axis(std::span<const Vec3> points) {
  const std::optional<PrincipalAxes> p = principal_axes(points);
  const std::optional<std::size_t> k = p ? axis_index(*p) : std::nullopt;
  if (!k) return std::nullopt;
  // The two other eigenvalues: 0 and 1 about the longest axis, 1 and 2
  // about the shortest.
  const double a = p->value[*k == 2 ? 0 : 1], b = p->value[*k == 2 ? 1 : 2];
  if (b - a > kRevolutionAlike * b) return std::nullopt;
  return p->axis[*k];
}

Vec3 surface_view_up(const HexMesh& mesh, const Topology& topology, const Vec3& up) {
  if (!is_surface_mesh(mesh)) return up;
  const Box3 box = referenced_bounding_box(mesh, topology);
  if (measure_planarity(mesh, box.is_empty() ? 0.0 : norm(box.hi - box.lo)).is_planar) return up;
  std::vector<Vec3> points;
  points.reserve(mesh.points.size());
  for (std::size_t v = 0, u = 0; v < mesh.points.size(); ++v) {
    const auto& unused = topology.unreferenced_vertices;
    while (u < unused.size() && static_cast<std::size_t>(unused[u]) < v) ++u;
    if (u == unused.size() || static_cast<std::size_t>(unused[u]) != v) points.push_back(mesh.points[v]);
  }
  const std::optional<Vec3> axis = revolution_axis(points);
  if (!axis) return up;
  // An open end up: the half of the axis's extent holding at least
  // kOpenEndShare of the boundary's length (a cup's, a vase's rim).
  double low = INFINITY, high = -INFINITY;
  for (const Vec3& p : points) {
    low = std::min(low, dot(p, *axis));
    high = std::max(high, dot(p, *axis));
  }
  double above = 0.0, below = 0.0;
  const SurfaceTopology& surface = topology.surface;
  for (std::size_t e = 0; e < surface.edges.size(); ++e) {
    if (surface.edge_num_faces[e] != 1) continue;
    const Vec3& a = mesh.points[static_cast<std::size_t>(surface.edges[e][0])];
    const Vec3& b = mesh.points[static_cast<std::size_t>(surface.edges[e][1])];
    (dot(0.5 * (a + b), *axis) > 0.5 * (low + high) ? above : below) += norm(b - a);
  }
  if (above >= kOpenEndShare * (above + below) && above > 0.0) return *axis;
  if (below >= kOpenEndShare * (above + below) && below > 0.0) return -1.0 * *axis;
  // Else the file's up decides the sign; an axis across it, its largest component.
  double along = dot(*axis, up);
  if (std::abs(along) < 1e-9) {
    const Vec3& x = *axis;
    along = std::abs(x.x) >= std::abs(x.y) && std::abs(x.x) >= std::abs(x.z) ? x.x
            : std::abs(x.y) >= std::abs(x.z)                                   ? x.y
                                                                               : x.z;
  }
  return along < 0.0 ? -1.0 * *axis : *axis;
}

std::vector<Vec3> choose_surface_main_viewpoints(const HexMesh& mesh, const Topology& topology,
                                                 const GlyphResult& glyphs, std::span<const double> cell_quality,
                                                 std::span<const Vec3> points, double aspect, int count,
                                                 const Vec3& up, double fov_y_degrees) {
  const std::vector<BoundaryPolygon> faces = boundary_polygons(topology);
  std::vector<std::vector<std::size_t>> targets;
  for (Index k = 0; k < std::min<Index>(kSurfaceViewTargets, static_cast<Index>(glyphs.clusters.size())); ++k)
    targets.push_back(cluster_target_faces(glyphs, k, faces, cell_quality));
  std::vector<Vec3> candidates = upright_view_candidates(up);
  const std::vector<Vec3> below = below_view_candidates(up);
  candidates.insert(candidates.end(), below.begin(), below.end());
  for (const std::vector<std::size_t>& target : targets) {
    Vec3 largest, normal;
    for (std::size_t i : target)
      if (const Vec3 a = area_vector(mesh, faces[i]); norm(a) > norm(largest)) largest = a;
    for (std::size_t i : target) {
      const Vec3 a = area_vector(mesh, faces[i]);
      normal = normal + (dot(a, largest) < 0.0 ? -1.0 : 1.0) * a;
    }
    if (norm(normal) > 0.0) candidates.insert(candidates.end(), {-1.0 * normal, normal});
  }
  // f[c][k]: the area of target k's faces in sight from candidate c (one task a candidate).
  std::vector<std::vector<double>> f(candidates.size(), std::vector<double>(targets.size(), 0.0));
  tbb::parallel_for(std::size_t{0}, candidates.size(), [&](std::size_t c) {
    const Camera camera = fit_camera_to_points(
        points, candidates[c], aspect, {.up = up, .fov_y_degrees = fov_y_degrees, .is_perspective = false});
    const FaceDepthGrid grid(mesh, faces, camera, aspect);
    for (std::size_t k = 0; k < targets.size(); ++k)
      for (std::size_t i : targets[k])
        for (int corner = 0; corner < faces[i].size; ++corner)
          if (grid.in_sight(grid.corner_sample(faces[i], corner)))
            f[c][k] += grid.projected_area(faces[i]) / faces[i].size;
  });
  for (std::size_t k = 0; k < targets.size(); ++k) {
    double top = 0.0;
    for (const auto& row : f) top = std::max(top, row[k]);
    for (auto& row : f) row[k] = top > 0.0 ? row[k] / top : 0.0;
  }
  if (targets.empty() || count <= 0 || std::all_of(f.begin(), f.end(), [](const auto& row) { return row[0] <= 0.0; }))
    return choose_main_viewpoints(points, glyphs, aspect, count, up, fov_y_degrees);
  // View 1: #0's faces near their best, then the most of the others'.
  std::vector<double> score(candidates.size(), 0.0);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    for (std::size_t k = 1; k < targets.size(); ++k) score[c] += f[c][k];
    score[c] += 1e-9;  // a candidate with #0's faces alone still scores
  }
  std::vector<bool> above(candidates.size()), off_axis(candidates.size(), true);
  const std::optional<Vec3> axis = model_axis(points);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    above[c] = view_elevation_degrees(candidates[c], up) >= 0.0;
    if (axis)
      off_axis[c] = std::abs(dot(normalized(candidates[c]), normalized(*axis))) <= std::cos(kOffAxisDegrees * std::numbers::pi / 180.0) + 1e-9;
  }
  // The first tier any candidate is in: the model recognisable (an eye
  // above the horizon: a hill seen from underneath, the 47r fine bell, is
  // hard to read; off the model's axis: the 47c review's turned bell seen
  // 27 degrees off its axis read as a disc or a funnel) before #0's faces
  // at their very best.
  // An eye above the horizon that sees #0's faces at kInSightFraction
  // before any from below (the 47d review: the mirrored kitten from -25
  // read as a blob).
  struct Tier {
    bool above, off_axis;
    double least;
  };
  static constexpr Tier kTiers[] = {
      {true, true, kNearBestFraction},  {true, true, kRecognisableFraction},  {true, false, kNearBestFraction},
      {true, false, kRecognisableFraction}, {true, true, kInSightFraction},   {true, false, kInSightFraction},
      {false, true, kNearBestFraction}, {false, true, kRecognisableFraction}, {false, false, kNearBestFraction}};
  std::vector<bool> allowed(candidates.size(), false);
  std::size_t first = candidates.size();
  for (const Tier& tier : kTiers) {
    for (std::size_t c = 0; c < candidates.size(); ++c)
      allowed[c] = f[c][0] >= tier.least && (!tier.above || above[c]) && (!tier.off_axis || off_axis[c]);
    first = best_of(score, allowed);
    if (first != candidates.size()) break;
  }
  std::vector<Vec3> chosen{candidates[first]};
  if (count < 2) return chosen;
  // View 2: what view 1 shows least, from the model's other side when that
  // shows any; an eye below the horizon only when none above scores.
  const auto prefer_above = [&](std::vector<bool>& ok) {
    bool any = false;
    for (std::size_t c = 0; c < candidates.size(); ++c) any = any || (ok[c] && above[c] && score[c] > 0.0);
    if (any)
      for (std::size_t c = 0; c < candidates.size(); ++c) ok[c] = ok[c] && above[c];
  };
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    score[c] = 0.0;
    for (std::size_t k = 0; k < targets.size(); ++k) score[c] += (1.0 - f[first][k] + 0.1) * f[c][k];
    const double gap = std::abs(view_azimuth_degrees(candidates[c], up) - view_azimuth_degrees(candidates[first], up));
    allowed[c] = c != first && std::min(gap, 360.0 - gap) >= 90.0 - 1e-9;
  }
  prefer_above(allowed);
  std::size_t second = best_of(score, allowed);
  if (second == candidates.size()) {
    for (std::size_t c = 0; c < candidates.size(); ++c) allowed[c] = c != first;
    second = best_of(score, allowed);
  }
  if (second != candidates.size()) chosen.push_back(candidates[second]);
  return chosen;
}

Rgba8 surface_fill_color(double q) { return bin_color(fill_bin(q)); }

namespace {

// Per cell its bin: fill_bin of its quality, the inverted bin for the cells
// of `inverted` (a cell given with a positive value still counts as
// inverted).
// With `reversed`, the first bin holds the cells of `inverted` alone.
std::vector<int> cell_bins(const std::vector<double>& cell_quality, std::span<const Index> inverted, bool reversed) {
  std::vector<int> bins(cell_quality.size());
  for (std::size_t c = 0; c < cell_quality.size(); ++c) {
    bins[c] = fill_bin(cell_quality[c]);
    if (reversed && bins[c] == 0) bins[c] = 1;  // not reversed: a shape below 0.3
  }
  for (Index c : inverted)
    if (c >= 0 && static_cast<std::size_t>(c) < bins.size()) bins[static_cast<std::size_t>(c)] = 0;
  return bins;
}

}  // namespace

TriangleSet surface_fill_faces(const HexMesh& mesh, const Topology& topology, const std::vector<double>& cell_quality,
                               const Vec3& origin, std::span<const Index> inverted, bool reversed) {
  const std::vector<int> bins = cell_bins(cell_quality, inverted, reversed);
  TriangleSet set;
  set.ambient = kSurfaceFillAmbient;
  for (const BoundaryPolygon& face : boundary_polygons(topology)) {
    const auto cell = static_cast<std::size_t>(face.cell);
    add_flat_face(set, mesh, face, bin_color(cell < bins.size() ? bins[cell] : -1), origin);
  }
  return set;
}

std::vector<LegendLine> surface_fill_legend_lines(const std::vector<double>& cell_quality,
                                                  std::span<const Index> inverted, bool reversed) {
  std::array<std::size_t, kFillBins.size()> counts{};
  std::size_t undefined = 0;
  for (int b : cell_bins(cell_quality, inverted, reversed)) {
    if (b < 0)
      ++undefined;
    else
      ++counts[static_cast<std::size_t>(b)];
  }
  std::vector<LegendLine> lines;
  // Every bin, empty ones too (a reader sees that 0 to 0.3 was looked for).
  lines.push_back({std::nullopt, "faces: scaled Jacobian", 1});
  lines.push_back({std::nullopt, "(each face's lowest corner)"});
  for (std::size_t b = 0; b < kFillBins.size(); ++b) {
    lines.push_back({bin_color(static_cast<int>(b)),
                     std::string(reversed && b == 0   ? "reversed"
                                 : reversed && b == 1 ? "up to 0.3"
                                 : b == 0 && !inverted.empty() && counts[0] > 0 &&
                                         std::any_of(inverted.begin(), inverted.end(),
                                                     [&](Index c) {
                                                       return static_cast<std::size_t>(c) < cell_quality.size() &&
                                                              cell_quality[static_cast<std::size_t>(c)] > 0.0;
                                                     })
                                     ? "inverted or reversed"
                                     : kFillBins[b].text) +
                         ": " + std::to_string(counts[b])});
    if (reversed && b == 0) lines.push_back({std::nullopt, "  (orientation flipped)"});
  }
  if (undefined > 0) lines.push_back({bin_color(-1), "degenerate: " + std::to_string(undefined)});
  return lines;
}

namespace {

// The irregular vertices' classes, in legend order.
enum class IrregularClass { interior_3, interior_5, interior_6_plus, interior_1_2, boundary_below, boundary_above };
constexpr int kNumIrregularClasses = 6;

IrregularClass irregular_class(Index valence, int ideal, bool is_boundary) {
  if (is_boundary) return valence < ideal ? IrregularClass::boundary_below : IrregularClass::boundary_above;
  if (valence == 3) return IrregularClass::interior_3;
  if (valence == 5) return IrregularClass::interior_5;
  return valence >= 6 ? IrregularClass::interior_6_plus : IrregularClass::interior_1_2;
}

Rgba8 irregular_class_color(IrregularClass c) {
  // The hex structure view's palette (Okabe-Ito), class for class.
  switch (c) {
    case IrregularClass::interior_3: return singular_class_color(SingularClass::interior_3);
    case IrregularClass::interior_5: return singular_class_color(SingularClass::interior_5);
    case IrregularClass::interior_6_plus: return singular_class_color(SingularClass::interior_6_plus);
    case IrregularClass::interior_1_2: return singular_class_color(SingularClass::interior_other);
    case IrregularClass::boundary_below: return singular_class_color(SingularClass::boundary_1);
    case IrregularClass::boundary_above: return singular_class_color(SingularClass::boundary_3_plus);
  }
  return {0, 0, 0, 255};
}

const char* irregular_class_label(IrregularClass c) {
  switch (c) {
    case IrregularClass::interior_3: return "interior, valence 3";
    case IrregularClass::interior_5: return "interior, valence 5";
    case IrregularClass::interior_6_plus: return "interior, valence 6+";
    case IrregularClass::interior_1_2: return "interior, valence 1-2";
    case IrregularClass::boundary_below: return "boundary, below ideal";
    case IrregularClass::boundary_above: return "boundary, above ideal";
  }
  return "";
}

// Pale tints for the patches (light, unsaturated: the spheres and lines
// stay apart from them).
constexpr std::array<Rgba8, 8> kPatchTints{{{222, 232, 246, 255},
                                            {246, 228, 214, 255},
                                            {222, 240, 226, 255},
                                            {240, 226, 240, 255},
                                            {246, 240, 210, 255},
                                            {214, 238, 240, 255},
                                            {236, 232, 222, 255},
                                            {230, 230, 236, 255}}};
constexpr Rgba8 kSeparatrixColor{45, 45, 52, 255};
constexpr Rgba8 kFaintEdgeColor{150, 154, 162, 110};

// "1.2", "12": a ratio with one decimal below 10.
std::string ratio_text(double r) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, r < 10.0 ? "%.1f" : "%.0f", r);
  return buffer;
}

}  // namespace

Rgba8 irregular_vertex_color(Index valence, int ideal, bool is_boundary) {
  return irregular_class_color(irregular_class(valence, ideal, is_boundary));
}

Image render_quad_structure_view(const HexMesh& mesh, const Topology& topology, const QuadStructure& structure,
                                 double mean_edge_length, const Vec3& view_direction,
                                 const QuadStructureViewOptions& options, Renderer& renderer) {
  const std::vector<Vec3> points = boundary_points(mesh, topology);
  const FigureFrame3d f = figure_frame_3d(
      "structure view", options.width, options.height, Rgba8{255, 255, 255, 255},
      [&](const AnnotationStyle& style) {
        return figure_layout(options.width, options.height, !options.title.empty(),
                             static_cast<int>(std::lround(340 * style.scale)), style);
      },
      points, view_direction, options.up, 30.0);
  const Box3 box = boundary_bounding_box(mesh, topology);
  Scene scene;
  scene.origin = 0.5 * (box.lo + box.hi);
  scene.background = f.style.background;
  const auto local = [&](Index v) { return to_vec3f(mesh.points[static_cast<std::size_t>(v)] - scene.origin); };

  // Faces by patch (the quads; triangles and faces without a patch white).
  TriangleSet faces;
  faces.is_lit = options.is_lit;
  faces.ambient = kSurfaceFillAmbient;
  for (const BoundaryPolygon& face : boundary_polygons(topology)) {
    const auto cell = static_cast<std::size_t>(face.cell);
    const Rgba8 tint = face.size == 4 && cell < structure.quad_patch.size() && structure.quad_patch[cell] != kNoIndex
                           ? kPatchTints[static_cast<std::size_t>(structure.quad_patch[cell]) % kPatchTints.size()]
                           : Rgba8{255, 255, 255, 255};
    add_flat_face(faces, mesh, face, tint, scene.origin);
  }
  scene.triangles.push_back(std::move(faces));

  // Faint edges, then the separatrices.
  LineSet edges;
  edges.width = static_cast<float>(f.style.scale);
  for (const Edge& e : boundary_edges_all_kinds(topology))
    for (Index v : e) {
      edges.indices.push_back(static_cast<std::uint32_t>(edges.positions.size()));
      edges.positions.push_back(local(v));
      edges.colors.push_back(kFaintEdgeColor);
    }
  scene.lines.push_back(std::move(edges));
  // The boundary edges (used by one face), over the faint ones.
  LineSet boundary;
  boundary.width = static_cast<float>(std::max(2.0, 2.0 * f.style.scale));
  const SurfaceTopology& surface = topology.surface;
  for (std::size_t e = 0; e < surface.edges.size() && e < surface.edge_num_faces.size(); ++e)
    if (surface.edge_num_faces[e] == 1)
      for (Index v : surface.edges[e]) {
        boundary.indices.push_back(static_cast<std::uint32_t>(boundary.positions.size()));
        boundary.positions.push_back(local(v));
        boundary.colors.push_back(kSurfaceBoundaryEdgeColor);
      }
  const bool has_boundary = !boundary.positions.empty();
  scene.lines.push_back(std::move(boundary));
  LineSet separatrices;
  separatrices.width = static_cast<float>(3.0 * f.style.scale);
  for (Index s = 0; s < structure.num_separatrices; ++s) {
    const auto begin = structure.separatrix_offsets[static_cast<std::size_t>(s)];
    const auto end = structure.separatrix_offsets[static_cast<std::size_t>(s) + 1];
    for (auto i = begin; i + 1 < end; ++i)
      for (auto k : {i, i + 1}) {
        separatrices.indices.push_back(static_cast<std::uint32_t>(separatrices.positions.size()));
        separatrices.positions.push_back(local(structure.separatrix_vertices[static_cast<std::size_t>(k)]));
        separatrices.colors.push_back(kSeparatrixColor);
      }
  }
  scene.lines.push_back(std::move(separatrices));

  // Irregular vertices.
  std::array<Index, kNumIrregularClasses> counts{};
  SphereSet spheres;
  const double diagonal = box.is_empty() ? 1.0 : norm(box.hi - box.lo);
  const auto radius = static_cast<float>(std::max(0.3 * mean_edge_length, 0.006 * diagonal));
  for (Index v : structure.irregular_vertices) {
    const auto i = static_cast<std::size_t>(v);
    const IrregularClass c = irregular_class(structure.valence[i], structure.ideal_valence[i],
                                             structure.vertex_kind[i] == QuadVertexKind::boundary);
    ++counts[static_cast<std::size_t>(c)];
    spheres.centers.push_back(local(v));
    spheres.radii.push_back(radius);
    spheres.colors.push_back(irregular_class_color(c));
  }
  scene.spheres.push_back(std::move(spheres));

  Image figure = render_figure(renderer, scene, f.camera, options.width, options.height, f.layout, options.title, f.style);
  std::vector<LegendLine> lines{{std::nullopt, "irregular vertices: " + std::to_string(structure.num_irregular)},
                                {std::nullopt, "(valence = incident quads)"}};
  // Every class, zeros too: the reader sees each was looked for.
  for (int c = 0; c < kNumIrregularClasses; ++c)
    if (structure.num_irregular > 0)
      lines.push_back({irregular_class_color(static_cast<IrregularClass>(c)),
                       std::string(irregular_class_label(static_cast<IrregularClass>(c))) + ": " +
                           std::to_string(counts[static_cast<std::size_t>(c)])});
  if (structure.num_irregular == 0) lines.push_back({std::nullopt, "none: every vertex is regular"});
  // The separatrices with their edges' share, the patches with their mean
  // size: on an unstructured mesh nearly every edge is traced and a patch
  // is a quad or two, which the numbers say (the layout is not simplified).
  const double edge_share = structure.num_edges > 0 ? 100.0 * static_cast<double>(structure.num_traced_edges) /
                                                          static_cast<double>(structure.num_edges)
                                                    : 0.0;
  lines.push_back({kSeparatrixColor,
                   "separatrices: " + std::to_string(structure.num_separatrices) +
                       (structure.is_capped ? " (capped)" : ""),
                   1, SwatchShape::thick_line});
  lines.push_back({std::nullopt, "  " + std::to_string(structure.num_traced_edges) + " edges, " +
                                     std::to_string(static_cast<long long>(std::lround(edge_share))) + "% of all"});
  const std::size_t num_quads = mesh.quads.size();
  std::string patches = "patches: " + std::to_string(structure.num_patches);
  if (structure.num_patches == 1)
    patches += " (all " + std::to_string(num_quads) + " quads)";
  else if (structure.num_patches > 1)
    patches += ", " + ratio_text(static_cast<double>(num_quads) / static_cast<double>(structure.num_patches)) +
               " quads each";
  lines.push_back({kPatchTints[0], patches});
  if (structure.num_patches > static_cast<Index>(kPatchTints.size()))
    lines.push_back({std::nullopt, "  (8 tints, repeating)"});
  lines.push_back({std::nullopt, "not simplified: traced as is"});
  if (structure.num_unclassified > 0)
    lines.push_back({std::nullopt, "unclassified vertices: " + std::to_string(structure.num_unclassified)});
  if (has_boundary) lines.push_back({kSurfaceBoundaryEdgeColor, "mesh boundary", 0, SwatchShape::thick_line});
  lines.push_back({Rgba8{150, 154, 162, 255}, "edges", 0, SwatchShape::thick_line});
  draw_legend(figure, f.layout.legend, lines, f.style);
  return figure;
}

}  // namespace hq
