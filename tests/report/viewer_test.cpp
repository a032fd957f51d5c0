// viewer/data.js and the escapers it relies on: base64 against RFC 4648's
// vectors, the script-safe JSON, and the data decoded back and compared with
// the analysis it came from (boundary faces, quantised positions within one
// step, exact face scaled Jacobians, every cluster, every cell under the
// threshold, the budget never dropping those).

#include "hqview/report/viewer.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>

#include "hqview/glyph/glyphs.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/hex_metric_field.h"
#include "hqview/quality/quality_field.h"
#include "support/fixtures.h"

namespace hq {
namespace {

using nlohmann::json;

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

std::vector<unsigned char> decode(const std::string& s) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::vector<unsigned char> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    const int v = value(c);
    if (v < 0) break;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((acc >> bits) & 0xff));
    }
  }
  return out;
}

template <class T>
std::vector<T> array_of(const json& b64) {
  const auto bytes = decode(b64.get<std::string>());
  std::vector<T> v(bytes.size() / sizeof(T));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(T));
  return v;
}

ReportModel grid_model() {
  ReportModel model;
  HexMesh mesh = test::grid(4);
  mesh.points[62] = mesh.points[62] + Vec3{0.8, 0.8, 0.8};  // the interior vertex (2,2,2): 8 bad interior cells
  model.analysis.mesh = std::move(mesh);
  model.analysis.topology = build_topology(model.analysis.mesh);
  model.analysis.field = compute_quality(model.analysis.mesh, model.analysis.topology);
  model.analysis.metrics = compute_hex_metrics(model.analysis.mesh);
  model.analysis.glyphs =
      compute_glyphs(model.analysis.mesh.points, model.analysis.field.vertex_quality, 1.0, GlyphOptions{});
  model.has_viewer = true;
  return model;
}

json data_of(const ReportModel& model) {
  for (const ViewerFile& f : viewer_files(model))
    if (f.relative_path == "viewer/data.js") {
      const std::string prefix = "window.HQ_VIEWER_DATA = ";
      EXPECT_EQ(f.text.rfind(prefix, 0), 0u);
      return json::parse(f.text.substr(prefix.size(), f.text.size() - prefix.size() - 2));
    }
  ADD_FAILURE() << "no data.js";
  return {};
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
