// viewer/data.js and the escapers it relies on: base64 against RFC 4648's
// vectors, the script-safe JSON, and the data decoded back and compared with
// the analysis it came from (boundary faces, quantised positions within one
// step, exact face scaled Jacobians, every cluster, every cell under the
// threshold, the budget never dropping those).

#include "hqview/report/viewer.h"
#include "hqview/report/viewer_boundary.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>

#include "hqview/glyph/glyph_ties.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/views/main_views.h"
#include "hqview/views/overview_views.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/hex_metric_field.h"
#include "hqview/quality/quality_field.h"
#include "hqview/report/cluster_color.h"
#include "support/fixtures.h"
#include "support/viewer_data.h"

namespace hq {
namespace HQ_TEST_UNIT {

using nlohmann::json;
using test::array_of;
using test::data_of;

std::string b64(std::string_view s) { return base64_encode(s.data(), s.size()); }

TEST(Viewer, Base64MatchesRfc4648) {
  EXPECT_EQ(b64(""), "");
  EXPECT_EQ(b64("f"), "Zg==");
  EXPECT_EQ(b64("fo"), "Zm8=");
  EXPECT_EQ(b64("foo"), "Zm9v");
  EXPECT_EQ(b64("foob"), "Zm9vYg==");
  EXPECT_EQ(b64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(b64("foobar"), "Zm9vYmFy");
  const unsigned char high[] = {0xff, 0xfe, 0x00};
  EXPECT_EQ(base64_encode(high, 3), "//4A");
}

TEST(Viewer, ScriptSafeJsonHasNoMarkupAndParsesBack) {
  const json original = {{"name", "</script><script>alert(1)</script>&amp;\xE2\x80\xA8\xE2\x80\xA9 ok"}};
  const std::string safe = script_safe_json(original.dump());
  for (const char* bad : {"<", ">", "&", "\xE2\x80\xA8", "\xE2\x80\xA9"}) EXPECT_EQ(safe.find(bad), std::string::npos) << bad;
  EXPECT_EQ(json::parse(safe), original);
}

// A grid of n^3 cells whose centre vertex is pulled (8 bad interior cells);
// `dent` also pushes a vertex at the middle of the face x = 0 inwards.
ReportModel grid_model(int n = 4, bool dent = false) {
  ReportModel model;
  HexMesh mesh = test::grid(n);
  const auto at = [n](int i, int j, int k) { return static_cast<std::size_t>(i + (n + 1) * (j + (n + 1) * k)); };
  mesh.points[at(n / 2, n / 2, n / 2)] = mesh.points[at(n / 2, n / 2, n / 2)] + Vec3{0.8, 0.8, 0.8};
  if (dent) mesh.points[at(0, n / 2, n / 2)] = mesh.points[at(0, n / 2, n / 2)] + Vec3{0.9, 0.3, 0};
  model.analysis.mesh = std::move(mesh);
  model.analysis.topology = build_topology(model.analysis.mesh);
  model.analysis.field = compute_quality(model.analysis.mesh, model.analysis.topology);
  model.analysis.metrics = compute_hex_metrics(model.analysis.mesh);
  model.analysis.glyphs =
      compute_glyphs(model.analysis.mesh.points, model.analysis.field.vertex_quality, 1.0, GlyphOptions{});
  model.has_viewer = true;
  return model;
}

TEST(Viewer, DataDecodesToTheAnalysis) {
  const ReportModel model = grid_model();
  const Analysis& a = model.analysis;
  const json d = data_of(model);
  const std::size_t nf = a.topology.boundary_faces.size();
  ASSERT_EQ(d["faces"]["count"].get<std::size_t>(), nf);
  const auto quads = array_of<std::uint32_t>(d["faces"]["quads"]);
  const auto hexes = array_of<std::uint32_t>(d["faces"]["hex"]);
  const auto sj = array_of<double>(d["face_scaled_jacobian"]);
  const auto q = array_of<std::uint16_t>(d["vertices"]["quantised"]);
  ASSERT_EQ(quads.size(), 4 * nf);
  ASSERT_EQ(q.size(), 3 * a.topology.boundary_vertices.size());
  const auto lo = d["vertices"]["lo"].get<std::vector<double>>(), step = d["vertices"]["step"].get<std::vector<double>>();
  for (std::size_t f = 0; f < nf; ++f) {
    const Index face = a.topology.boundary_faces[f];
    const Index hex = a.topology.face_hexes[static_cast<std::size_t>(a.topology.face_hex_offsets[static_cast<std::size_t>(face)])];
    EXPECT_EQ(hexes[f], static_cast<std::uint32_t>(hex));
    EXPECT_EQ(sj[f], a.field.cell_scaled_jacobian[static_cast<std::size_t>(hex)]);  // exact
    for (int c = 0; c < 4; ++c) {
      const std::uint32_t slot = quads[4 * f + c];
      const Index v = a.topology.faces[static_cast<std::size_t>(face)][static_cast<std::size_t>(c)];
      EXPECT_EQ(a.topology.boundary_vertices[slot], v);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(lo[k] + q[3 * slot + k] * step[k], a.mesh.points[static_cast<std::size_t>(v)][k], 0.5 * step[k] + 1e-12);
    }
  }
  // Every cluster, and the 8 interior cells around the pulled vertex.
  EXPECT_EQ(d["clusters"].size(), a.glyphs->clusters.size());
  EXPECT_EQ(d["clusters"][0]["size"].get<Index>(), a.glyphs->clusters[0].size);
  std::size_t under = 0;
  for (double s : a.field.cell_scaled_jacobian) under += s < 1.0 - a.glyphs->options.threshold;
  EXPECT_EQ(d["low_cells"]["count"].get<std::size_t>(), under);
  EXPECT_GE(under, 8u);
  EXPECT_TRUE(d["reduced"].empty());
  EXPECT_EQ(d["fields"].size(), 2u + kNumHexMetrics - 1);  // quality, scaled Jacobian, the other metrics
}

// Ties (issue 44 part T): clusters whose min quality ties #0's wear its
// colour and carry their class and its size, so the viewer draws them alike
// and labels the tie once; the report.json colour is the same.
TEST(Viewer, TiedClustersShareTheirClassColour) {
  ReportModel model = grid_model(6, true);
  std::vector<AggregatedGlyph>& clusters = model.analysis.glyphs->clusters;
  ASSERT_GE(clusters.size(), 1u);
  while (clusters.size() < 3) {  // copies of the last (the viewer lists clusters as given)
    AggregatedGlyph extra = clusters.back();
    extra.id = static_cast<Index>(clusters.size());
    clusters.push_back(extra);
  }
  // #0 and #1 tie (0.0004 apart), #2 does not.
  clusters[0].min_quality = 0.1;
  clusters[1].min_quality = 0.1004;
  clusters[2].min_quality = 0.3;
  const json d = data_of(model);
  EXPECT_EQ(d["tie_tolerance"].get<double>(), kGlyphTieTolerance);
  EXPECT_EQ(d["clusters"][0]["tie_class"].get<Index>(), 0);
  EXPECT_EQ(d["clusters"][1]["tie_class"].get<Index>(), 0);
  EXPECT_EQ(d["clusters"][2]["tie_class"].get<Index>(), 1);
  EXPECT_EQ(d["clusters"][0]["tied"].get<Index>(), 2);
  EXPECT_EQ(d["clusters"][2]["tied"].get<Index>(), 1);
  EXPECT_EQ(d["clusters"][1]["color"], d["clusters"][0]["color"]);
  EXPECT_EQ(d["clusters"][2]["color"].get<std::string>(), cluster_color_hex(1, model.analysis.glyphs->options.top_clusters));
  EXPECT_NE(d["clusters"][2]["color"], d["clusters"][0]["color"]);
}

TEST(Viewer, TheBudgetDropsMetricColouringsNeverGlyphsOrBadCells) {
  ReportModel model = grid_model();
  const json full = data_of(model);
  model.viewer_max_mb = 1e-4;
  const json tiny = data_of(model);
  EXPECT_EQ(tiny["fields"].size(), 2u);
  EXPECT_EQ(tiny["clusters"], full["clusters"]);
  EXPECT_EQ(tiny["low_cells"], full["low_cells"]);
  EXPECT_EQ(tiny["faces"], full["faces"]);
  ASSERT_FALSE(tiny["reduced"].empty());
  // Deterministic: the same model gives the same bytes.
  EXPECT_EQ(viewer_files(model).back().text, viewer_files(model).back().text);
  EXPECT_EQ(data_of(model), tiny);
}

// The boundary reduced under the budget: at most the asked faces, real
// vertices at their own positions, the worst boundary vertex kept, every
// face a boundary face's hex, and the same result every time.
TEST(Viewer, TheReducedBoundaryKeepsTheWorstVertexAndRealHexes) {
  const ReportModel model = grid_model(24, true);
  const Analysis& a = model.analysis;
  const ViewerBoundary full = viewer_boundary(a);
  ASSERT_EQ(full.face_hex.size(), 6u * 24 * 24);
  const ViewerBoundary r = reduce_boundary(full, a.mesh.points, a.field.vertex_quality, a.field.cell_scaled_jacobian, 600);
  EXPECT_LE(r.face_hex.size(), 600u);
  EXPECT_GE(r.face_hex.size(), 100u);  // not reduced to nothing
  EXPECT_GT(r.cell_size, 0);
  EXPECT_EQ(r.num_source_faces, full.face_hex.size());
  const std::set<Index> boundary_vertices(full.vertices.begin(), full.vertices.end());
  const std::set<Index> boundary_hexes(full.face_hex.begin(), full.face_hex.end());
  for (Index v : r.vertices) EXPECT_TRUE(boundary_vertices.count(v)) << v;
  for (Index h : r.face_hex) EXPECT_TRUE(boundary_hexes.count(h)) << h;
  ASSERT_EQ(r.quads.size(), 4 * r.face_hex.size());
  for (std::size_t f = 0; f < r.face_hex.size(); ++f) {
    std::set<std::uint32_t> distinct;
    for (int c = 0; c < 4; ++c) {
      ASSERT_LT(r.quads[4 * f + c], r.vertices.size());
      distinct.insert(r.quads[4 * f + c]);
    }
    EXPECT_GE(distinct.size(), 3u);
  }
  // The dented vertex is the boundary's worst, and it is drawn.
  Index worst = full.vertices[0];
  for (Index v : full.vertices)
    if (a.field.vertex_quality[static_cast<std::size_t>(v)] < a.field.vertex_quality[static_cast<std::size_t>(worst)]) worst = v;
  EXPECT_EQ(worst, static_cast<Index>(25 * (12 + 25 * 12)));
  EXPECT_NE(std::find(r.vertices.begin(), r.vertices.end(), worst), r.vertices.end());
  // Faces on the same cells keep the worst hex: the lowest scaled Jacobian
  // of the boundary hexes is drawn.
  double lowest = 2, lowest_drawn = 2;
  for (Index h : full.face_hex) lowest = std::min(lowest, a.field.cell_scaled_jacobian[static_cast<std::size_t>(h)]);
  for (Index h : r.face_hex) lowest_drawn = std::min(lowest_drawn, a.field.cell_scaled_jacobian[static_cast<std::size_t>(h)]);
  EXPECT_EQ(lowest_drawn, lowest);
  const ViewerBoundary again = reduce_boundary(full, a.mesh.points, a.field.vertex_quality, a.field.cell_scaled_jacobian, 600);
  EXPECT_EQ(again.vertices, r.vertices);
  EXPECT_EQ(again.quads, r.quads);
  EXPECT_EQ(again.face_hex, r.face_hex);
  // A budget that fits changes nothing.
  const ViewerBoundary same = reduce_boundary(full, a.mesh.points, a.field.vertex_quality, a.field.cell_scaled_jacobian, full.face_hex.size());
  EXPECT_EQ(same.quads, full.quads);
  EXPECT_EQ(same.cell_size, 0);
}

TEST(Viewer, OverTheBudgetTheBoundaryIsReducedNeverGlyphsOrBadCells) {
  ReportModel model = grid_model(40);
  const json full = data_of(model);
  model.viewer_max_mb = 0.05;
  const json tiny = data_of(model);
  EXPECT_EQ(full["faces"]["count"].get<std::size_t>(), 6u * 40 * 40);
  EXPECT_LT(tiny["faces"]["count"].get<std::size_t>(), full["faces"]["count"].get<std::size_t>());
  EXPECT_LE(tiny["faces"]["count"].get<std::size_t>(), 2000u);  // kMinViewerFaces: the floor of the target
  EXPECT_GE(tiny["faces"]["count"].get<std::size_t>(), 1000u);
  EXPECT_EQ(tiny["clusters"], full["clusters"]);
  EXPECT_EQ(tiny["low_cells"], full["low_cells"]);
  // Each drawn face's scaled Jacobian is its hex's exact value.
  const auto hex = array_of<std::uint32_t>(tiny["faces"]["hex"]);
  const auto sj = array_of<double>(tiny["face_scaled_jacobian"]);
  ASSERT_EQ(hex.size(), sj.size());
  for (std::size_t f = 0; f < hex.size(); ++f) EXPECT_EQ(sj[f], model.analysis.field.cell_scaled_jacobian[hex[f]]);
  bool says = false;
  for (const json& r : tiny["reduced"]) says |= r.get<std::string>().find("the boundary is drawn with") != std::string::npos;
  EXPECT_TRUE(says) << tiny["reduced"].dump();
  EXPECT_EQ(data_of(model), tiny);
}

// Issue 44: a hex with two tets against its x = 1 quad (a non-conforming
// face), and apart a flat wedge and a flat pyramid. data.js has every kind's
// cell under the threshold with its own corners and its kind's faces, the
// non-conforming face's quad and triangles, and the overlay colours of the
// PNG views' constants.
TEST(Viewer, CellsOfEveryKindTheNonConformingFaceAndTheViewsColours) {
  ReportModel model;
  Mesh& mesh = model.analysis.mesh;
  const auto add = [&](Vec3 p) { mesh.points.push_back(p); return static_cast<Index>(mesh.points.size() - 1); };
  mesh.hexes.push_back({add({0, 0, 0}), add({1, 0, 0}), add({1, 1, 0}), add({0, 1, 0}), add({0, 0, 1}), add({1, 0, 1}),
                        add({1, 1, 1}), add({0, 1, 1})});
  const Index apex = add({2, 0.5, 0.5});
  const auto tet = [&](Index a, Index b, Index c) {
    const Vec3 u = mesh.points[static_cast<std::size_t>(b)] - mesh.points[static_cast<std::size_t>(a)],
               v = mesh.points[static_cast<std::size_t>(c)] - mesh.points[static_cast<std::size_t>(a)],
               w = mesh.points[static_cast<std::size_t>(apex)] - mesh.points[static_cast<std::size_t>(a)];
    const double det = dot(u, cross(v, w));
    mesh.tets.push_back(det > 0 ? CellCorners<CellKind::tet>{a, b, c, apex} : CellCorners<CellKind::tet>{a, c, b, apex});
  };
  tet(1, 2, 6);  // the quad 1 2 6 5 split along 1-6
  tet(1, 6, 5);
  mesh.wedges.push_back({add({6, 0, 0}), add({7, 0, 0}), add({6, 1, 0}), add({6, 0, 1}), add({7, 0, 1}), add({6.1, 0.9, 0.1})});
  mesh.pyramids.push_back({add({9, 0, 0}), add({10, 0, 0}), add({10, 1, 0}), add({9, 1, 0}), add({9.5, 0.5, 0.05})});
  Analysis& a = model.analysis;
  a.topology = build_topology(mesh);
  a.field = compute_quality(mesh, a.topology);
  a.glyphs = compute_glyphs(mesh.points, a.field.vertex_quality, 1.0, GlyphOptions{});
  model.has_viewer = true;
  ASSERT_EQ(a.topology.non_conforming_faces.size(), 1u);
  const json d = data_of(model);

  const json& low = d["low_cells"];
  const auto ids = array_of<std::uint32_t>(low["ids"]);
  const auto kinds = array_of<std::uint8_t>(low["kinds"]);
  const auto corners = array_of<float>(low["corners"]);
  const auto worst = array_of<std::uint8_t>(low["worst"]);
  ASSERT_EQ(ids.size(), low["count"].get<std::size_t>());
  ASSERT_EQ(kinds.size(), ids.size());
  ASSERT_EQ(worst.size(), ids.size());
  std::set<int> seen;
  std::size_t o = 0, in_worst = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const CellRef cell = volume_cell(mesh, static_cast<Index>(ids[i]));
    EXPECT_EQ(kinds[i], static_cast<std::uint8_t>(cell.kind));
    // 1 exactly for a cell with a member of cluster #0 among its corners.
    bool has = false;
    for (int c = 0; c < cell.num_corners; ++c)
      for (std::size_t m = static_cast<std::size_t>(a.glyphs->cluster_offsets[0]); m < static_cast<std::size_t>(a.glyphs->cluster_offsets[1]); ++m)
        has = has || a.glyphs->cluster_vertices[m] == cell.corners[static_cast<std::size_t>(c)];
    EXPECT_EQ(worst[i], has ? 1 : 0) << "low cell " << i;
    in_worst += has;
    EXPECT_LT(a.field.cell_scaled_jacobian[ids[i]], 1.0 - a.glyphs->options.threshold);
    seen.insert(kinds[i]);
    ASSERT_EQ(low["kind_faces"]["corners"][kinds[i]].get<int>(), cell.num_corners);
    for (int c = 0; c < cell.num_corners; ++c)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(corners[o + 3 * static_cast<std::size_t>(c) + static_cast<std::size_t>(k)],
                  static_cast<float>(mesh.points[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>(c)])][k]));
    o += 3 * static_cast<std::size_t>(cell.num_corners);
  }
  EXPECT_EQ(o, corners.size());
  EXPECT_GE(in_worst, 1u);
  EXPECT_TRUE(seen.count(static_cast<int>(CellKind::wedge)) && seen.count(static_cast<int>(CellKind::pyramid)));
  // The face tables: the kinds' faces as CellKindTable has them (a hex's 6 quads, a pyramid's 4 triangles and base).
  EXPECT_EQ(low["kind_faces"]["faces"][0].size(), 6u);
  EXPECT_EQ(low["kind_faces"]["faces"][1].size(), 4u);
  EXPECT_EQ(low["kind_faces"]["faces"][2].size(), 5u);
  EXPECT_EQ(low["kind_faces"]["faces"][3].size(), 5u);
  EXPECT_EQ(low["kind_faces"]["faces"][0][0], json::array({0, 3, 2, 1}));
  EXPECT_EQ(low["kind_faces"]["names"][3], "pyramid");

  ASSERT_EQ(d["non_conforming"]["count"].get<std::size_t>(), 1u);
  const auto quad = array_of<float>(d["non_conforming"]["quads"]);
  const auto tris = array_of<float>(d["non_conforming"]["triangles"]);
  ASSERT_EQ(quad.size(), 12u);
  ASSERT_EQ(tris.size(), 18u);
  for (float x : quad) EXPECT_TRUE(x == 0.0f || x == 1.0f);
  for (std::size_t c = 0; c < 4; ++c) EXPECT_EQ(quad[3 * c], 1.0f);  // the x = 1 face
  for (std::size_t c = 0; c < 6; ++c) EXPECT_EQ(tris[3 * c], 1.0f);

  const auto hex = [](Rgba8 c) {
    char t[8];
    std::snprintf(t, sizeof t, "#%02x%02x%02x", c.r, c.g, c.b);
    return std::string(t);
  };
  EXPECT_EQ(d["colors"]["coincident"], hex(kCoincidentArrowColor));
  EXPECT_EQ(d["colors"]["intersection"], hex(kIntersectionArrowColor));
  EXPECT_EQ(d["colors"]["intersecting_cells"], hex(kIntersectingCellColor));
  EXPECT_EQ(d["colors"]["non_conforming"], hex(kNonConformingColor));
  EXPECT_EQ(d["colors"]["worst_ring"], hex(AnnotationStyle{}.text_color));
  EXPECT_EQ(d["labelled_clusters"].get<std::int64_t>(), labelled_cluster_count(a.glyphs->options.top_clusters));
}

TEST(Viewer, TheNameReachesThePageOnlyEscaped) {
  ReportModel model = grid_model();
  model.analysis.mesh_input.path = "/x/<script>alert(1)<b>.mesh";
  for (const ViewerFile& f : viewer_files(model)) {
    if (f.relative_path == "viewer.html") {
      EXPECT_EQ(f.text.find("<script>alert"), std::string::npos);
      EXPECT_NE(f.text.find("&lt;script&gt;alert(1)"), std::string::npos);
    }
    if (f.relative_path == "viewer/data.js") {
      EXPECT_EQ(f.text.find("<script>"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace hq
