#include "hqview/views/inverted_inset.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "hqview/core/box3.h"
#include "hqview/core/cell_kinds.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/cell_faces.h"

namespace hq {
namespace {

constexpr Rgba8 kInsetEdgeColor{30, 30, 40, 255};  // the inverted cells' edges

// The caption: at the legend's size (issue 45f: was three quarters of the
// labels', about 10 px on the page), three lines.
int caption_size(int text_size) { return std::max(9, static_cast<int>(std::lround(0.92 * text_size))); }
constexpr int kCaptionLines = 4;
int caption_height(int text_size) { return kCaptionLines * static_cast<int>(std::lround(1.3 * caption_size(text_size))) + 8; }

}  // namespace

InsetStrip inset_strip(const PixelRect& view, double silhouette_width, double silhouette_height, int count, int margin) {
  InsetStrip out{view, {}};
  if (count <= 0 || view.width <= 0 || view.height <= 0) return out;
  const double bw = std::max(1.0, silhouette_width), bh = std::max(1.0, silhouette_height);
  const int full_w = static_cast<int>(std::lround(kInsetWidthFraction * view.width));
  const int full_h = static_cast<int>(std::lround(kInsetHeightFraction * view.height));
  // The column on the right.
  const int col_h = std::min(full_h, (view.height - (count + 1) * margin) / count);
  const PixelRect col_model{view.x, view.y, view.width - full_w - 2 * margin, view.height};
  // The row at the bottom.
  const int row_w = std::min(full_w, (view.width - (count + 1) * margin) / count);
  const PixelRect row_model{view.x, view.y, view.width, view.height - full_h - 2 * margin};
  const double col_scale = std::min(col_model.width / bw, col_model.height / bh);
  const double row_scale = std::min(row_model.width / bw, row_model.height / bh);
  if (col_scale >= row_scale) {
    out.model = col_model;
    for (int i = 0; i < count; ++i)
      out.slots.push_back({view.x + view.width - margin - full_w, view.y + margin + i * (col_h + margin), full_w, col_h});
  } else {
    out.model = row_model;
    // Right-aligned, A on the left.
    const int x0 = view.x + view.width - count * (row_w + margin);
    for (int i = 0; i < count; ++i)
      out.slots.push_back({x0 + i * (row_w + margin), view.y + view.height - margin - full_h, row_w, full_h});
  }
  return out;
}

std::vector<Index> cells_touching(const HexMesh& mesh, std::span<const Index> cells) {
  const Index num_cells = num_volume_cells(mesh);
  std::vector<char> is_cell(static_cast<std::size_t>(num_cells), 0);
  std::vector<char> is_vertex(mesh.points.size(), 0);
  for (Index c : cells) {
    if (c < 0 || c >= num_cells) continue;
    is_cell[static_cast<std::size_t>(c)] = 1;
    const CellRef ref = volume_cell(mesh, c);
    for (int k = 0; k < ref.num_corners; ++k) is_vertex[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])] = 1;
  }
  std::vector<Index> out;
  for (Index c = 0; c < num_cells; ++c) {
    if (is_cell[static_cast<std::size_t>(c)]) continue;
    const CellRef ref = volume_cell(mesh, c);
    for (int k = 0; k < ref.num_corners; ++k)
      if (is_vertex[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])]) {
        out.push_back(c);
        break;
      }
  }
  return out;
}

namespace {

template <CellKind K>
void add_negative_frames(const Mesh& mesh, const CellRef& cell, std::vector<std::array<Index, 4>>& out) {
  for (const auto& f : CellKindTable<K>::corner_frames) {
    const std::size_t i = static_cast<std::size_t>(&f - CellKindTable<K>::corner_frames.data());
    const Index v = cell.corners[i];
    const Vec3& p = mesh.points[static_cast<std::size_t>(v)];
    std::array<Vec3, 3> e;
    for (std::size_t k = 0; k < 3; ++k)
      e[k] = mesh.points[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>(f[k])])] - p;
    if (dot(cross(e[0], e[1]), e[2]) < 0.0)
      out.push_back({v, cell.corners[static_cast<std::size_t>(f[0])], cell.corners[static_cast<std::size_t>(f[1])],
                     cell.corners[static_cast<std::size_t>(f[2])]});
  }
}

}  // namespace

std::vector<std::array<Index, 4>> negative_corner_frames(const Mesh& mesh, const CellRef& cell) {
  std::vector<std::array<Index, 4>> out;
  switch (cell.kind) {
    case CellKind::hex: add_negative_frames<CellKind::hex>(mesh, cell, out); break;
    case CellKind::tet: add_negative_frames<CellKind::tet>(mesh, cell, out); break;
    case CellKind::wedge: add_negative_frames<CellKind::wedge>(mesh, cell, out); break;
    case CellKind::pyramid: add_negative_frames<CellKind::pyramid>(mesh, cell, out); break;
    default: break;
  }
  return out;
}

Scene inverted_inset_scene(const HexMesh& mesh, std::span<const Index> cells, std::span<const Index> neighbours,
                           std::span<const double> vertex_quality) {
  const Index num_cells = num_volume_cells(mesh);
  Box3 box;
  bool any = false;
  auto each_corner = [&](std::span<const Index> ids, auto&& f) {
    for (Index c : ids) {
      if (c < 0 || c >= num_cells) continue;
      const CellRef ref = volume_cell(mesh, c);
      for (int k = 0; k < ref.num_corners; ++k) f(mesh.points[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])]);
    }
  };
  auto grow = [&](const Vec3& p) {
    if (!any) box.lo = box.hi = p;
    any = true;
    box.lo = {std::min(box.lo.x, p.x), std::min(box.lo.y, p.y), std::min(box.lo.z, p.z)};
    box.hi = {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y), std::max(box.hi.z, p.z)};
  };
  each_corner(cells, grow);
  each_corner(neighbours, grow);
  Scene scene;
  scene.origin = any ? 0.5 * (box.lo + box.hi) : Vec3{};
  const Vec3 origin = scene.origin;

  TriangleSet faces;  // the inverted cells, every face (two triangles per quad)
  LineSet edges;      // their edges
  edges.width = 2.0f;
  LineSet cage;       // the neighbours' edges
  cage.width = 1.0f;
  const Rgba8 blue = to_rgba8(kInvertedColor);
  SphereSet dots;  // the negative corners, over the cells
  dots.over_other_spheres = true;
  std::vector<char> dotted(mesh.points.size(), 0);
  // The dots' radius: a sixth of the inverted cells' mean edge.
  double edge_sum = 0.0;
  int edge_count = 0;
  for (Index c : cells)
    if (c >= 0 && c < num_cells)
      for_each_edge_of(volume_cell(mesh, c), [&](Index a, Index b) {
        edge_sum += norm(mesh.points[static_cast<std::size_t>(a)] - mesh.points[static_cast<std::size_t>(b)]);
        ++edge_count;
      });
  const double dot_radius = edge_count > 0 ? edge_sum / edge_count / 6.0 : 0.0;
  for (Index c : cells) {
    if (c < 0 || c >= num_cells) continue;
    const CellRef ref = volume_cell(mesh, c);
    Vec3 centre;
    for (int k = 0; k < ref.num_corners; ++k) centre = centre + mesh.points[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])];
    centre = (1.0 / ref.num_corners) * centre;
    // A corner of the shrunk cell.
    const auto at = [&](Index v) {
      return to_vec3f(centre + kInsetShrink * (mesh.points[static_cast<std::size_t>(v)] - centre) - origin);
    };
    for_each_face_of(ref, [&](const std::array<Index, 4>& v, int size) {
      const auto base = static_cast<std::uint32_t>(faces.positions.size());
      for (int i = 0; i < size; ++i) {
        faces.positions.push_back(at(v[static_cast<std::size_t>(i)]));
        faces.colors.push_back(blue);
      }
      faces.indices.insert(faces.indices.end(), {base, base + 1, base + 2});
      if (size == 4) faces.indices.insert(faces.indices.end(), {base, base + 2, base + 3});
    });
    for_each_edge_of(ref, [&](Index a, Index b) {
      const auto base = static_cast<std::uint32_t>(edges.positions.size());
      for (Index v : {a, b}) {
        edges.positions.push_back(at(v));
        edges.colors.push_back(kInsetEdgeColor);
      }
      edges.indices.insert(edges.indices.end(), {base, base + 1});
    });
    for (int k = 0; k < ref.num_corners; ++k) {
      const auto v = static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)]);
      if (v >= vertex_quality.size() || !(vertex_quality[v] < 0.0) || dotted[v]) continue;
      dotted[v] = 1;
      dots.centers.push_back(to_vec3f(mesh.points[v] - origin));
      dots.radii.push_back(static_cast<float>(dot_radius));
      dots.colors.push_back(kInsetCornerColor);
    }
  }
  for (Index c : neighbours) {
    if (c < 0 || c >= num_cells) continue;
    for_each_edge_of(volume_cell(mesh, c), [&](Index a, Index b) {
      const auto base = static_cast<std::uint32_t>(cage.positions.size());
      for (Index v : {a, b}) {
        cage.positions.push_back(to_vec3f(mesh.points[static_cast<std::size_t>(v)] - origin));
        cage.colors.push_back(kInsetNeighbourColor);
      }
      cage.indices.insert(cage.indices.end(), {base, base + 1});
    });
  }
  // The fold (issue 45g: a single shrunk cell read as a thin cell, not an
  // inverted one): each corner whose frame is left-handed in its cell
  // (det J < 0) has its three frame edges drawn from the vertex
  // kInsetFoldReach of the way to their other ends, over everything.
  LineSet fold_halo, fold;
  fold_halo.width = 6.0f;
  fold.width = 3.0f;
  fold_halo.in_overlay = fold.in_overlay = true;
  for (Index c : cells) {
    if (c < 0 || c >= num_cells) continue;
    for (const std::array<Index, 4>& frame : negative_corner_frames(mesh, volume_cell(mesh, c))) {
      const Vec3& p = mesh.points[static_cast<std::size_t>(frame[0])];
      for (int k = 1; k < 4; ++k) {
        const Vec3 q = p + kInsetFoldReach * (mesh.points[static_cast<std::size_t>(frame[static_cast<std::size_t>(k)])] - p);
        for (LineSet* set : {&fold_halo, &fold}) {
          const auto base = static_cast<std::uint32_t>(set->positions.size());
          set->positions.push_back(to_vec3f(p - origin));
          set->positions.push_back(to_vec3f(q - origin));
          const Rgba8 color = set == &fold ? kInsetCornerColor : Rgba8{255, 255, 255, 255};
          set->colors.insert(set->colors.end(), {color, color});
          set->indices.insert(set->indices.end(), {base, base + 1});
        }
      }
    }
  }
  scene.triangles.push_back(std::move(faces));
  scene.lines.push_back(std::move(cage));
  scene.lines.push_back(std::move(edges));
  if (!fold.positions.empty()) {
    scene.lines.push_back(std::move(fold_halo));
    scene.lines.push_back(std::move(fold));
  }
  if (!dots.centers.empty()) scene.spheres.push_back(std::move(dots));
  return scene;
}

InvertedCallout inset_part(const InvertedCallout& c) {
  if (c.hidden_cells.empty()) return c;
  InvertedCallout part = c;
  part.cells = c.hidden_cells;
  part.num_cells = static_cast<int>(c.hidden_cells.size());
  part.num_groups = c.num_hidden_groups;
  part.visible_pixels = 0;
  part.on_boundary = c.hidden_on_boundary;
  part.hidden_cells.clear();
  part.hidden_radius = 0.0;
  return part;
}

std::vector<std::size_t> inset_callouts(std::span<const InvertedCallout> callouts, std::span<const PixelRect> slots,
                                        int text_size, double view_area) {
  const int caption = caption_height(text_size);
  std::vector<std::size_t> chosen;
  for (int small = 0; small < 2; ++small)
    for (std::size_t i = 0; i < callouts.size(); ++i)
      if (callout_wants_inset(callouts[i], view_area) && callout_has_hidden(callouts[i]) == (small == 0)) {
        if (chosen.size() >= slots.size()) return chosen;
        const PixelRect& slot = slots[chosen.size()];
        if (slot.width < 40 || slot.height < caption + 40) return chosen;
        chosen.push_back(i);
      }
  return chosen;
}

std::vector<InvertedInset> plan_inverted_insets(const HexMesh& mesh, std::vector<InvertedCallout>& callouts,
                                                std::span<const PixelRect> slots, const Camera& view_camera,
                                                int text_size, double view_area) {
  std::vector<InvertedInset> insets;
  const int caption = caption_height(text_size);
  for (std::size_t i : inset_callouts(callouts, slots, text_size, view_area)) {
    const PixelRect& slot = slots[insets.size()];
    InvertedInset inset;
    inset.callout = i;
    inset.letter = std::string(1, static_cast<char>('A' + insets.size()));
    inset.rect = slot;
    inset.picture = {slot.x + 2, slot.y + caption, slot.width - 4, slot.height - caption - 2};
    inset.cells = inset_part(callouts[i]).cells;
    std::sort(inset.cells.begin(), inset.cells.end());
    inset.neighbours = cells_touching(mesh, inset.cells);
    std::vector<Vec3> points;
    for (std::span<const Index> ids : {std::span<const Index>(inset.cells), std::span<const Index>(inset.neighbours)})
      for (Index c : ids) {
        const CellRef ref = volume_cell(mesh, c);
        for (int k = 0; k < ref.num_corners; ++k) points.push_back(mesh.points[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])]);
      }
    inset.camera = fit_camera_to_points(points, view_camera.target - view_camera.eye,
                                        static_cast<double>(inset.picture.width) / inset.picture.height,
                                        {.up = view_camera.up, .fov_y_degrees = view_camera.fov_y_degrees,
                                         .margin = 0.1, .is_perspective = view_camera.is_perspective});
    callouts[i].inset = inset.letter;
    insets.push_back(std::move(inset));
  }
  return insets;
}

std::vector<Image> render_inverted_insets(const HexMesh& mesh, std::span<const InvertedInset> insets,
                                          std::span<const double> vertex_quality, Renderer& renderer) {
  std::vector<Image> pictures;
  for (const InvertedInset& inset : insets)
    pictures.push_back(renderer.render(inverted_inset_scene(mesh, inset.cells, inset.neighbours, vertex_quality),
                                       inset.camera, inset.picture.width, inset.picture.height));
  return pictures;
}

void draw_inverted_insets(Image& figure, std::span<const InvertedInset> insets, std::span<const Image> pictures,
                          std::span<const InvertedCallout> callouts, const std::string& noun, int text_size,
                          const AnnotationStyle& style) {
  const int caption = caption_size(text_size);
  const int pitch = static_cast<int>(std::lround(1.3 * caption));
  for (std::size_t i = 0; i < insets.size() && i < pictures.size(); ++i) {
    const InvertedInset& inset = insets[i];
    const PixelRect& r = inset.rect;
    fill_rect(figure, r, {255, 255, 255, 255});
    paste(figure, pictures[i], inset.picture.x, inset.picture.y);
    // The caption: what it shows and what the colours are.
    InvertedCallout named = inset_part(callouts[inset.callout]);
    named.inset.clear();
    named.num_more_cells = 0;
    // The label split after its noun ("A: 14 inverted hexes" / "in 3
    // groups, inside"), so that neither line is cut at an inset's width.
    std::string label = inverted_callout_label(named, noun, 1.0);
    std::string rest;
    const std::size_t noun_end = noun.empty() ? std::string::npos : label.find(' ', label.find(noun));
    if (noun_end != std::string::npos) {
      rest = label.substr(noun_end + 1);
      label.resize(noun_end);
      if (label.ends_with(",")) label.pop_back();
    }
    if (rest.empty() && callout_in_sight(named)) rest = "small, in sight";  // only small groups in sight get one
    const std::string lines[kCaptionLines] = {inset.letter + ": " + label, rest, "blue: shrunk · grey: nearby",
                                              "crimson: det J < 0 corners"};
    const int max_width = r.width - 12;
    for (int k = 0; k < kCaptionLines; ++k)
      draw_text(figure, r.x + 6, r.y + 4 + (k + 1) * pitch - caption / 4, ellipsize(lines[k], caption, max_width, style),
                caption, style);
    fill_rect(figure, {r.x, inset.picture.y - 2, r.width, 1}, kInsetFrameColor);
    for (int t = 0; t < 2; ++t) {
      fill_rect(figure, {r.x + t, r.y, 1, r.height}, kInsetFrameColor);
      fill_rect(figure, {r.x + r.width - 1 - t, r.y, 1, r.height}, kInsetFrameColor);
      fill_rect(figure, {r.x, r.y + t, r.width, 1}, kInsetFrameColor);
      fill_rect(figure, {r.x, r.y + r.height - 1 - t, r.width, 1}, kInsetFrameColor);
    }
  }
}

}  // namespace hq
