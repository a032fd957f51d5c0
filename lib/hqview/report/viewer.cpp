#include "hqview/report/viewer.h"

#include <kainjow/mustache.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "hqview/core/box3.h"
#include "hqview/core/message_text.h"
#include "hqview/core/number_format.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/quality/corner_jacobian.h"
#include "hqview/quality/kind_vertex_quality.h"
#include "hqview/glyph/glyph_ties.h"
#include "hqview/report/cluster_color.h"
#include "hqview/report/escape.h"
#include "hqview/report/report_templates.h"
#include "hqview/report/viewer_boundary.h"
#include "hqview/views/boundary_views.h"
#include "hqview/views/error_density_views.h"
#include "hqview/views/main_views.h"
#include "hqview/views/overview_views.h"

namespace hq {

using Json = nlohmann::ordered_json;

std::string base64_encode(const void* bytes, std::size_t size) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(bytes);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const std::uint32_t v = (std::uint32_t{p[i]} << 16) | (std::uint32_t{p[i + 1]} << 8) | p[i + 2];
    for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
  }
  if (i < size) {
    const std::uint32_t v = (std::uint32_t{p[i]} << 16) | (i + 1 < size ? std::uint32_t{p[i + 1]} << 8 : 0);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < size ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string script_safe_json(std::string text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '<') {
      out += "\\u003c";
    } else if (c == '>') {
      out += "\\u003e";
    } else if (c == '&') {
      out += "\\u0026";
    } else if (c == '\xE2' && i + 2 < text.size() && text[i + 1] == '\x80' && (text[i + 2] == '\xA8' || text[i + 2] == '\xA9')) {
      out += text[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

namespace {

// "data/cells.csv has", or what the bundle has instead (--data).
std::string where_cell_values(const ReportModel& model) {
  const std::string path = cell_data_path(model.data);
  return path.empty() ? "a bundle written with --data csv has" : path + " has";
}

template <class T>
std::string b64(const std::vector<T>& v) {
  return base64_encode(v.data(), v.size() * sizeof(T));
}

Json vec(const Vec3& p) { return Json::array({p.x, p.y, p.z}); }

std::string hex_color(const Rgba8& c) {
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c.r, c.g, c.b);
  return text;
}

// The colours of the viewer's overlays, read from the constants the PNG
// views draw with (views/main_views.h, views/overview_views.h, view A's
// ring in AnnotationStyle's text colour), so the viewer keeps no copy.
Json overlay_colors() {
  return {{"coincident", hex_color(kCoincidentArrowColor)},
          {"intersection", hex_color(kIntersectionArrowColor)},
          {"intersecting_cells", hex_color(kIntersectingCellColor)},
          {"non_conforming", hex_color(kNonConformingColor)},
          {"worst_ring", hex_color(AnnotationStyle{}.text_color)}};
}

// The faces of each volume kind (CellKindTable, outward), by CellKind
// number: local corner numbers, 3 or 4 per face; and each kind's corner
// count and name. The viewer draws a cell of any kind from its corners with these.
Json kind_faces_json() {
  Json faces = Json::array(), corners = Json::array(), names = Json::array();
  for_each_cell_kind([&](auto kind) {
    if constexpr (CellKindTable<kind()>::dimension == 3) {
      Json list = Json::array();
      for (const CellFace& f : CellKindTable<kind()>::faces) {
        Json face = Json::array();
        for (int i = 0; i < f.size; ++i) face.push_back(f.v[static_cast<std::size_t>(i)]);
        list.push_back(std::move(face));
      }
      faces.push_back(std::move(list));
      corners.push_back(CellKindTable<kind()>::num_corners);
      names.push_back(std::string(cell_kind_name(kind())));
    }
  });
  return {{"faces", std::move(faces)}, {"corners", std::move(corners)}, {"names", std::move(names)}};
}

// The non-conforming faces (Topology::non_conforming_faces): each quad's 4
// corners and its two triangles' 3 corners (float32 xyz), so the viewer
// draws the frame the overview draws and the triangles' diagonal.
Json non_conforming_json(const Analysis& a) {
  std::vector<float> quads, triangles;
  const auto put = [&](std::vector<float>& out, Index v) {
    for (int c = 0; c < 3; ++c) out.push_back(static_cast<float>(a.mesh.points[static_cast<std::size_t>(v)][c]));
  };
  for (const NonConformingFace& nc : a.topology.non_conforming_faces) {
    for (Index v : nc.quad) put(quads, v);
    for (const Tri& t : nc.triangles)
      for (Index v : t) put(triangles, v);
  }
  return {{"count", a.topology.non_conforming_faces.size()}, {"quads", b64(quads)}, {"triangles", b64(triangles)}};
}

// Colour tables: 256 RGB triples; index 255 is "no value".
constexpr std::uint8_t kNoValue = 255;

std::vector<std::uint8_t> lut_of(auto&& color_of_index) {
  std::vector<std::uint8_t> rgb;
  for (int i = 0; i < 256; ++i) {
    const Color c = color_of_index(i);
    for (float f : {c.r, c.g, c.b}) rgb.push_back(static_cast<std::uint8_t>(std::lround(std::clamp(f, 0.0f, 1.0f) * 255.0f)));
  }
  return rgb;
}

// Quality in [-1, 1] on indices 0..254 (the colour map of the PNG views):
// 127 is 0; a quality below 0 takes at most 126, so a barely inverted vertex
// (-0.002 would round to 127) keeps the inverted colour.
std::uint8_t quality_index(double q) {
  if (!std::isfinite(q) || std::abs(q) >= kVerdictDegenerate) return kNoValue;
  const long i = std::lround((std::clamp(q, -1.0, 1.0) + 1.0) / 2.0 * 254.0);
  return static_cast<std::uint8_t>(q < 0.0 ? std::min(i, 126L) : i);
}
double quality_of_index(int i) { return -1.0 + 2.0 * i / 254.0; }

Json field_json(std::string id, std::string label, const char* per, const std::vector<std::uint8_t>& values,
                const std::vector<std::uint8_t>& lut, double lo, double hi, Json legend) {
  return {{"id", std::move(id)}, {"label", std::move(label)}, {"per", per}, {"min", lo}, {"max", hi},
          {"values", b64(values)}, {"lut", b64(lut)}, {"legend", std::move(legend)}};
}

// Positions quantised to 16 bits per axis over the bounding box.
Json quantised_positions(const std::vector<Vec3>& points) {
  Box3 box;
  for (const Vec3& p : points) box.add(p);
  if (box.is_empty()) box.add({0, 0, 0});
  std::vector<std::uint16_t> q;
  q.reserve(points.size() * 3);
  Vec3 step;
  for (int k = 0; k < 3; ++k) step[k] = box.hi[k] > box.lo[k] ? (box.hi[k] - box.lo[k]) / 65535.0 : 1.0;
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k)
      q.push_back(static_cast<std::uint16_t>(std::lround(std::clamp((p[k] - box.lo[k]) / step[k], 0.0, 65535.0))));
  return {{"count", points.size()}, {"lo", vec(box.lo)}, {"step", vec(step)}, {"quantised", b64(q)}};
}

Json camera_of_view_a(const ReportModel& model) {
  for (const ViewEntry& v : model.views)
    if (v.id == "main")
      for (const auto& c : v.cameras)
        if (c) return {{"eye", vec(c->eye)}, {"target", vec(c->target)}, {"up", vec(c->up)}, {"height", c->height},
                       {"aspect", c->aspect}, {"orthographic", !c->is_perspective}};
  return nullptr;
}

// The boundary's part of data.js: positions, faces, the exact scaled
// Jacobian and corners of each face's hex, and the colour fields.
struct BoundaryData {
  Json vertices, faces, face_scaled_jacobian, fields = Json::array();
  std::string face_corners;                  // base64 float32, 8 per face
  Json metric_fields = Json::array();        // the other Verdict metrics (dropped first)
  std::size_t metric_bytes = 0;
  std::size_t size() const { return vertices.dump().size() + faces.dump().size() + face_scaled_jacobian.dump().size() + fields.dump().size(); }
};

BoundaryData boundary_data(const Analysis& a, const ViewerBoundary& b, bool with_metrics, double density_reference) {
  BoundaryData out;
  std::vector<Vec3> points;
  for (Index v : b.vertices) points.push_back(a.mesh.points[static_cast<std::size_t>(v)]);
  out.vertices = quantised_positions(points);
  std::vector<std::uint32_t> face_hex(b.face_hex.begin(), b.face_hex.end());
  out.faces = {{"count", b.face_hex.size()}, {"quads", b64(b.quads)}, {"hex", b64(face_hex)}};
  // On a mesh of several kinds, each face's cell kind (CellKind number) and
  // the kinds' names: the click names the cell ("tet 70"). Absent on a
  // pure-hex mesh, whose data keeps its bytes.
  // A surface mesh's faces are its quads and triangles (issue 47).
  const bool surface = is_surface_mesh(a.mesh);
  if (a.topology.across_kinds || surface) {
    const auto quads = static_cast<Index>(a.mesh.quads.size());
    std::vector<std::uint8_t> kinds;
    for (Index h : b.face_hex)
      kinds.push_back(static_cast<std::uint8_t>(surface               ? (h < quads ? CellKind::quad : CellKind::triangle)
                                                : h < a.mesh.num_hexes() ? CellKind::hex
                                                                         : volume_cell(a.mesh, h).kind));
    out.faces["kind"] = b64(kinds);
    Json names = Json::array();
    for (CellKind kind : kCellKinds) names.push_back(std::string(cell_kind_name(kind)));
    out.faces["kind_names"] = std::move(names);
  }
  // Exact cell scaled Jacobian of each face's hex (the click shows it); NaN
  // for a cell the quality field does not cover (a non-hex cell while only
  // hexes are analysed).
  const auto of_cell = [](const std::vector<double>& values, Index cell, std::size_t per_cell, int k) {
    const std::size_t i = per_cell * static_cast<std::size_t>(cell) + static_cast<std::size_t>(k);
    return i < values.size() && static_cast<std::size_t>(cell) < values.size() / per_cell ? values[i] : std::nan("");
  };
  std::vector<double> face_sj;
  for (Index h : b.face_hex) face_sj.push_back(of_cell(a.field.cell_scaled_jacobian, h, 1, 0));
  out.face_scaled_jacobian = b64(face_sj);
  // The 8 corner scaled Jacobians of each face's hex (kCornerFrames order);
  // NaN for a cell of another kind.
  std::vector<float> face_corners;
  for (Index h : b.face_hex)
    for (int c = 0; c < 8; ++c)
      face_corners.push_back(static_cast<float>(h < a.mesh.num_hexes() ? of_cell(a.field.corner_scaled_jacobian, h, 8, c)
                                                                       : std::nan("")));
  out.face_corners = b64(face_corners);

  // Fields: vertex quality, the cell scaled Jacobian, the boundary error,
  // then every other Verdict metric of the faces' cells.
  const std::vector<std::uint8_t> quality_lut = lut_of([](int i) {
    return i == kNoValue ? kUndefinedColor : quality_color(quality_of_index(i));
  });
  {
    // On a mesh of several kinds each face's corners take the vertex
    // quality of its own cell's kind (kind_vertex_quality.h, as the overview
    // colours them; issue 44 part P: the viewer blended a perfect hex's
    // face with its tet neighbours' corners): 4 values per face ("per":
    // "corner", in the face's quads order); a pure-hex mesh keeps one value
    // per vertex and its bytes.
    const KindVertexQuality kinds = kind_vertex_quality(a.mesh, a.field);
    // A curved surface's quality fields say what their values below 0 are
    // (the overview's swatch); the viewer names the swatch "inverted (< 0)"
    // otherwise.
    const bool curved = is_curved_surface(a.mesh_summary);
    const auto quality_field = [&](std::string id, std::string label, const char* per,
                                   const std::vector<std::uint8_t>& values) {
      Json field = field_json(std::move(id), std::move(label), per, values, quality_lut, -1.0, 1.0, Json::array());
      if (curved) field["below_zero"] = std::string(kCurvedBelowZeroLabel) + " " + kCurvedBelowZeroNote;
      return field;
    };
    std::vector<std::uint8_t> vq;
    if (kinds.empty()) {
      for (Index v : b.vertices) vq.push_back(quality_index(a.field.vertex_quality[static_cast<std::size_t>(v)]));
      out.fields.push_back(
          quality_field("vertex_quality", "vertex quality (min corner scaled Jacobian)", "vertex", vq));
    } else {
      for (std::size_t f = 0; f < b.face_hex.size(); ++f) {
        const auto kind = static_cast<std::size_t>(
            b.face_hex[f] < a.mesh.num_hexes() ? CellKind::hex : volume_cell(a.mesh, b.face_hex[f]).kind);
        for (int c = 0; c < 4; ++c) {
          const auto v = static_cast<std::size_t>(b.vertices[b.quads[4 * f + static_cast<std::size_t>(c)]]);
          const std::vector<double>& own = kinds.by_kind[kind];
          const double q = v < own.size() && !std::isnan(own[v]) ? own[v] : a.field.vertex_quality[v];
          vq.push_back(quality_index(q));
        }
      }
      out.fields.push_back(quality_field(
          "vertex_quality", "vertex quality (min corner scaled Jacobian over the face's own cell kind)", "corner", vq));
    }
    std::vector<std::uint8_t> sj;
    for (double s : face_sj) sj.push_back(quality_index(s));
    out.fields.push_back(quality_field("scaled_jacobian", "cell scaled Jacobian (Verdict)", "face", sj));
  }
  if (a.boundary_error) {
    const double s = error_scale(a.boundary_error->vertex_error);
    std::vector<std::uint8_t> e;
    for (Index v : b.vertices) {
      const double x = a.boundary_error->vertex_error[static_cast<std::size_t>(v)];
      e.push_back(std::isfinite(x) ? static_cast<std::uint8_t>(std::lround((std::clamp(x / s, -1.0, 1.0) + 1.0) / 2.0 * 254.0))
                                   : kNoValue);
    }
    const auto lut = lut_of([](int i) { return i == kNoValue ? kUndefinedColor : diverging_color(-1.0 + 2.0 * i / 254.0); });
    out.fields.push_back(field_json("boundary_error", "signed boundary error (+ outside the reference), model units",
                                    "vertex", e, lut, -s, s, Json::array()));
  }
  if (a.poisson && a.poisson->cell_error_density.size() == a.mesh.hexes.size()) {
    // --simulate: the error density of each face's hex, indices 0..253 on
    // the log scale of view fem_error_density (error_density_views.h).
    const std::vector<double>& density = a.poisson->cell_error_density;
    const ErrorDensityScale scale = error_density_scale(density, density_reference);
    const double span = std::log10(scale.hi) - std::log10(scale.lo);
    std::vector<std::uint8_t> e;
    for (Index h : b.face_hex) {
      const double x = density[static_cast<std::size_t>(h)];
      e.push_back(std::isfinite(x) && x > 0
                      ? static_cast<std::uint8_t>(std::lround(
                            std::clamp((std::log10(x) - std::log10(scale.lo)) / span, 0.0, 1.0) * 253.0))
                      : kNoValue);
    }
    const auto lut = lut_of([&](int i) {
      return i == kNoValue ? kUndefinedColor
                           : error_density_color(std::pow(10.0, std::log10(scale.lo) + span * i / 253.0), scale);
    });
    out.fields.push_back(field_json("fem_error_density",
                                    "FEM error density of the face's hex (normalised H1 error, no unit; log scale)",
                                    "face", e, lut, scale.lo, scale.hi, Json::array()));
  }
  if (!with_metrics) return out;
  // Metrics: indices 0..253 over [min, max] of the faces' cells, 254 outside
  // Verdict's acceptable range, 255 no value (a sentinel).
  for (int m = 0; m < kNumHexMetrics; ++m) {
    const auto metric = static_cast<HexMetric>(m);
    if (metric == HexMetric::scaled_jacobian || !a.metrics.computed.test(static_cast<std::size_t>(m))) continue;
    const std::vector<double>& values = a.metrics.of(metric);
    const HexMetricInfo& info = hex_metric_info(metric);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (Index h : b.face_hex) {
      const double x = of_cell(values, h, 1, 0);
      if (std::isfinite(x) && std::abs(x) < kVerdictDegenerate) lo = std::min(lo, x), hi = std::max(hi, x);
    }
    if (!(lo <= hi)) continue;
    std::vector<std::uint8_t> idx;
    for (Index h : b.face_hex) {
      const double x = of_cell(values, h, 1, 0);
      if (!std::isfinite(x) || std::abs(x) >= kVerdictDegenerate) idx.push_back(kNoValue);
      else if (x < info.acceptable_min || x > info.acceptable_max) idx.push_back(254);
      else idx.push_back(static_cast<std::uint8_t>(hi > lo ? std::lround((x - lo) / (hi - lo) * 253.0) : 0));
    }
    const auto lut = lut_of([](int i) {
      if (i == kNoValue) return kUndefinedColor;
      if (i == 254) return Color{0.80f, 0.10f, 0.10f, 1.0f};
      const float t = static_cast<float>(i) / 253.0f;  // light to dark blue
      return Color{0.93f - 0.80f * t, 0.95f - 0.65f * t, 0.98f - 0.35f * t, 1.0f};
    });
    out.metric_bytes += idx.size();
    out.metric_fields.push_back(field_json(std::string(info.name), std::string(info.name) + " (Verdict, per cell)",
                                           "face", idx, lut, lo, hi,
                                           Json::array({{{"label", "outside Verdict's acceptable range"}, {"index", 254}}})));
  }
  return out;
}

// A reduced boundary keeps at least this many faces (the model stays
// recognisable) even when the glyphs and cells alone fill the budget.
constexpr std::size_t kMinViewerFaces = 2000;

}  // namespace

std::vector<ViewerFile> viewer_files(const ReportModel& model) {
  const Analysis& a = model.analysis;
  const ViewerBoundary full = viewer_boundary(a);
  const double budget = model.viewer_max_mb * 1e6;
  const std::string budget_flag =
      "--viewer-max-mb " + display_number(model.viewer_max_mb);
  Json reduced = Json::array();

  Json d;
  d["name"] = message_text(a.mesh_name());  // the only text from input (docs/contract.md, "Messages are text")
  d["num_vertices"] = a.mesh_summary.num_vertices;
  d["num_hexes"] = a.mesh_summary.num_hexes;
  // What a face's cell is called in the click's text: "hex", or a surface
  // mesh's "face" (issue 47; absent: "hex", the bytes of a volume mesh's data).
  if (is_surface_mesh(a.mesh)) d["cell_word"] = "face";
  d["cell_data"] = cell_data_path(model.data);  // where every value of a hex is ("": --data none)
  d["up"] = vec(model.viewer_up);
  d["boundary_reduced"] = nullptr;  // or what the budget did to the boundary

  // Glyph clusters (every listed one: never reduced).
  Json clusters = Json::array();
  if (a.glyphs) {
    const std::int64_t k = a.glyphs->options.top_clusters;
    const std::size_t listed = std::min<std::size_t>(a.glyphs->clusters.size(), 1000);
    const std::vector<Index> ties = glyph_tie_classes(a.glyphs->clusters);
    const std::vector<Index> tie_sizes = tie_class_sizes(ties);
    const Index coloured = coloured_tie_classes(tie_sizes, static_cast<Index>(labelled_cluster_count(k)));
    d["coloured_classes"] = coloured;  // tie classes wearing a cluster colour (glyph_ties.h)
    for (std::size_t i = 0; i < listed; ++i) {
      const AggregatedGlyph& g = a.glyphs->clusters[i];
      clusters.push_back({{"id", g.id}, {"size", g.size}, {"min_quality", g.min_quality},
                          {"vertex", g.representative_vertex}, {"position", vec(g.position)}, {"radius", g.radius},
                          {"color", cluster_color_hex(ties[i] < coloured ? ties[i] : -1, k)}, {"is_top", static_cast<std::int64_t>(i) < k},
                          {"tie_class", ties[i]}, {"tied", tie_sizes[static_cast<std::size_t>(ties[i])]}});
    }
    d["top_clusters"] = k;
    d["labelled_clusters"] = labelled_cluster_count(k);  // #k labels, as view A's
    d["glyph_threshold"] = a.glyphs->options.threshold;
    d["tie_tolerance"] = kGlyphTieTolerance;  // clusters[].tie_class / tied (glyph_ties.h)
  }
  d["clusters"] = std::move(clusters);

  // Overlap markers and the edges of intersecting cells.
  Json markers = Json::array();
  std::vector<float> intersecting;
  if (a.overlap) {
    for (const OverlapMarker& m : a.overlap->markers)
      markers.push_back({{"kind", m.kind == MarkerKind::coincident ? "coincident" : "intersection"},
                         {"position", vec(m.position)}, {"count", m.count}});
    // A surface mesh's intersecting cells are faces (overlap.h): their edges.
    for (std::size_t f = 0; a.overlap->is_surface && f < a.overlap->cell_intersecting.size(); ++f) {
      if (!a.overlap->cell_intersecting[f]) continue;
      const std::size_t quads = a.mesh.quads.size();
      if (f >= quads + a.mesh.triangles.size()) break;
      const Index* v = f < quads ? a.mesh.quads[f].data() : a.mesh.triangles[f - quads].data();
      const int n = f < quads ? 4 : 3;
      for (int i = 0; i < n; ++i)
        for (Index w : {v[i], v[(i + 1) % n]})
          for (int c = 0; c < 3; ++c) intersecting.push_back(static_cast<float>(a.mesh.points[static_cast<std::size_t>(w)][c]));
    }
    for (std::size_t h = 0; h < std::min(a.overlap->cell_intersecting.size(), a.mesh.hexes.size()); ++h) {
      if (!a.overlap->cell_intersecting[h]) continue;
      if (h >= a.mesh.hexes.size()) {  // a tet, wedge or pyramid: its CellKindTable edges
        if (static_cast<Index>(h) >= num_volume_cells(a.mesh)) break;
        for_each_edge_of(volume_cell(a.mesh, static_cast<Index>(h)), [&](Index p, Index q) {
          for (Index v : {p, q})
            for (int c = 0; c < 3; ++c) intersecting.push_back(static_cast<float>(a.mesh.points[static_cast<std::size_t>(v)][c]));
        });
        continue;
      }
      const Hex& hex = a.mesh.hexes[h];
      static constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                           {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
      for (const auto& e : kEdges)
        for (int k : e)
          for (int c = 0; c < 3; ++c)
            intersecting.push_back(static_cast<float>(a.mesh.points[static_cast<std::size_t>(hex[k])][c]));
    }
  }
  d["markers"] = std::move(markers);
  d["intersecting_edges"] = b64(intersecting);
  d["num_intersecting_cells"] = a.overlap ? a.overlap->num_intersecting_cells : 0;
  d["non_conforming"] = non_conforming_json(a);
  d["colors"] = overlay_colors();

  // Cells under the glyph threshold (cell scaled Jacobian below 1 - T), of
  // every kind: drawn by the cut, never reduced.
  {
    const double t = a.glyphs ? a.glyphs->options.threshold : 0.5;
    std::vector<std::uint32_t> ids;
    std::vector<std::uint8_t> kinds, worst;  // worst: 1 for a cell with a vertex of cluster #0
    std::vector<float> corners;
    std::vector<double> sj;
    const Index cells = std::min<Index>(num_volume_cells(a.mesh), static_cast<Index>(a.field.cell_scaled_jacobian.size()));
    for (Index h = 0; h < cells; ++h) {
      const double s = a.field.cell_scaled_jacobian[static_cast<std::size_t>(h)];
      if (!(s < 1.0 - t) && std::abs(s) < kVerdictDegenerate) continue;
      const CellRef cell = volume_cell(a.mesh, h);
      ids.push_back(static_cast<std::uint32_t>(h));
      kinds.push_back(static_cast<std::uint8_t>(cell.kind));
      sj.push_back(s);
      std::uint8_t in_worst = 0;
      for (int i = 0; i < cell.num_corners; ++i) {
        const auto v = static_cast<std::size_t>(cell.corners[static_cast<std::size_t>(i)]);
        if (a.glyphs && v < a.glyphs->vertex_cluster.size() && a.glyphs->vertex_cluster[v] == 0) in_worst = 1;
        for (int c = 0; c < 3; ++c) corners.push_back(static_cast<float>(a.mesh.points[v][c]));
      }
      worst.push_back(in_worst);
    }
    d["low_cells"] = {{"count", ids.size()}, {"threshold", 1.0 - t}, {"ids", b64(ids)}, {"kinds", b64(kinds)},
                      {"worst", b64(worst)}, {"corners", b64(corners)}, {"scaled_jacobian", b64(sj)}, {"kind_faces", kind_faces_json()}};
  }
  d["camera"] = camera_of_view_a(model);

  // The budget (base64 is 4/3 of the bytes): the metric colourings go first,
  // then the corner values of a click, then the boundary is reduced.
  const double rest = static_cast<double>(d.dump().size());
  BoundaryData bd = boundary_data(a, full, true, model.viewer_error_density_reference);
  const double boundary_size = static_cast<double>(bd.size());
  if (rest + boundary_size + static_cast<double>(bd.metric_bytes * 4 / 3) > budget && !bd.metric_fields.empty()) {
    reduced.push_back("the " + std::to_string(bd.metric_fields.size()) +
                      " Verdict metric colourings other than the scaled Jacobian were left out (" + budget_flag +
                      "); " + where_cell_values(model) + " every value");
    bd.metric_fields = Json::array();
  }
  if (rest + boundary_size + static_cast<double>(bd.face_corners.size()) > budget) {
    reduced.push_back("the corner scaled Jacobians shown when a face is clicked were left out; " +
                      where_cell_values(model) + " them");
    bd.face_corners.clear();
  }
  if (rest + boundary_size > budget && full.face_hex.size() > kMinViewerFaces) {
    const double share = std::max(0.0, budget - rest) / boundary_size;
    const auto target = std::max(kMinViewerFaces, static_cast<std::size_t>(0.9 * share * static_cast<double>(full.face_hex.size())));
    const ViewerBoundary drawn = reduce_boundary(full, a.mesh.points, a.field.vertex_quality, a.field.cell_scaled_jacobian, target);
    if (drawn.face_hex.size() < full.face_hex.size()) {
      bd = boundary_data(a, drawn, false, model.viewer_error_density_reference);
      d["boundary_reduced"] = {{"faces", full.face_hex.size()}, {"cell_size", drawn.cell_size}};
      reduced.push_back("the boundary is drawn with " + display_count(static_cast<long long>(drawn.face_hex.size())) + " of its " +
                        display_count(static_cast<long long>(full.face_hex.size())) + " faces (vertex clustering on a grid of " +
                        display_number(drawn.cell_size, 3) + " model units, keeping each cell's worst vertex and "
                        "each face's worst hex; " + budget_flag + "); a click on a face still shows its hex's exact "
                        "values, and every glyph and cell under the threshold is drawn");
    }
  }
  if (rest > budget)
    reduced.push_back("the glyphs and the cells under the threshold alone exceed " + budget_flag +
                      "; all of them are drawn");
  d["vertices"] = std::move(bd.vertices);
  d["faces"] = std::move(bd.faces);
  d["face_scaled_jacobian"] = std::move(bd.face_scaled_jacobian);
  if (!bd.face_corners.empty()) d["face_corners"] = std::move(bd.face_corners);
  for (Json& f : bd.metric_fields) bd.fields.push_back(std::move(f));
  d["fields"] = std::move(bd.fields);
  d["reduced"] = std::move(reduced);

  // The data, the scripts (embedded at build time) and the page.
  std::vector<ViewerFile> files;
  files.push_back({"viewer/data.js", "window.HQ_VIEWER_DATA = " + script_safe_json(d.dump()) + ";\n"});
  files.push_back({"viewer/three.min.js", std::string(report_template("three.min.js"))});
  files.push_back({"viewer/OrbitControls.js", std::string(report_template("OrbitControls.js"))});
  files.push_back({"viewer/viewer.js", std::string(report_template("viewer.js"))});
  kainjow::mustache::mustache page{std::string(report_template("viewer.html.mustache"))};
  page.set_custom_escape([](const std::string& s) { return html_escape(s); });
  kainjow::mustache::data data;
  data.set("name", a.mesh_name());
  data.set("tool_version", model.tool_version);
  data.set("surface", is_surface_mesh(a.mesh));  // a surface mesh's faces are all drawn: no "boundary"
  files.push_back({"viewer.html", page.render(data)});
  return files;
}

}  // namespace hq
