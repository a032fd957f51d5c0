// The whole analyze pipeline without OpenGL: a mock renderer records every
// scene and returns a plain image. Every view of kViews is produced for a
// small mesh with and without a reference and a compare mesh, and the scenes
// hold what the analysis says they must.
#include "hqview/pipeline/analyze.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/image/colormap.h"
#include "hqview/render/scene.h"
#include "hqview/views/views.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

class RecordingRenderer final : public Renderer {
 public:
  Image render(const Scene& scene, const Camera&, int width, int height) override {
    scenes.push_back(scene);
    sizes.emplace_back(width, height);
    return {width, height, std::vector<std::uint8_t>(4 * static_cast<std::size_t>(width) * height, 200)};
  }
  std::vector<Scene> scenes;
  std::vector<std::pair<int, int>> sizes;
};

AnalyzeOptions small_run() {
  AnalyzeOptions options;
  options.mesh_path = test::source_dir() / "examples/ball.mesh";
  options.tool_version = "test";
  options.views.width = 320;
  options.views.height = 240;
  return options;
}

std::vector<std::string> ids_of(const AnalyzeResult& result) {
  std::vector<std::string> ids;
  for (const ViewEntry& v : result.model.views) ids.push_back(v.id);
  return ids;
}

// The ids of kViews whose needs the run meets, in table order.
std::vector<std::string> expected_ids(bool with_reference, bool with_compare) {
  std::vector<std::string> ids;
  for (const ViewSpec& spec : kViews)
    if (spec.needs == ViewNeeds::mesh ||
        ((spec.needs == ViewNeeds::reference || spec.needs == ViewNeeds::uv_atlas) && with_reference) ||
        (spec.needs == ViewNeeds::compare && with_compare))
      ids.emplace_back(spec.id);
  return ids;
}

// The first frame each 3D view drew: with one render thread, frames come in
// view order, except that the views that need the UV atlas come last (it is
// built beside the others); one per PNG file of a view that is not a chart
// (charts have an SVG twin), two for the compare view (one per half, one
// camera).
// An overview inset's picture (views/inverted_inset.h): its faces are all
// in the inverted colour. The overview draws its insets' pictures before
// its own frame.
bool is_inset_picture(const Scene& scene) {
  bool any = false;
  for (const TriangleSet& t : scene.triangles)
    for (const Rgba8& c : t.colors) {
      if (c != to_rgba8(kInvertedColor)) return false;
      any = true;
    }
  return any;
}

std::size_t count_inset_pictures(const RecordingRenderer& renderer) {
  return static_cast<std::size_t>(std::count_if(renderer.scenes.begin(), renderer.scenes.end(), is_inset_picture));
}

std::map<std::string, std::size_t> first_frames(const AnalyzeResult& result, std::size_t overview_insets) {
  std::map<std::string, std::size_t> first;
  std::size_t frame = 0;
  std::vector<ViewEntry> drawn = result.model.views;
  std::stable_partition(drawn.begin(), drawn.end(),
                        [](const ViewEntry& v) { return find_view(v.id)->needs != ViewNeeds::uv_atlas; });
  for (const ViewEntry& v : drawn) {
    const bool is_chart =
        std::any_of(v.files.begin(), v.files.end(), [](const std::string& f) { return f.ends_with(".svg"); });
    if (is_chart) continue;
    if (v.id == "overview") frame += overview_insets;  // the insets' pictures come first
    first[v.id] = frame;
    // compare: two meshes; uv_key: front, back and the atlas, each then
    // again in chart-id colours (where its numbers may go).
    frame += v.id == "compare" ? 2 : v.id == "uv_key" ? 6 : v.files.size();
  }
  first["(end)"] = frame;
  return first;
}

TEST(AnalyzePipeline, EveryMeshViewWithAMockRenderer) {
  RecordingRenderer renderer;
  const AnalyzeResult result = analyze(small_run(), &renderer);
  const Analysis& a = result.model.analysis;
  ASSERT_TRUE(a.glyphs);
  ASSERT_GT(a.glyphs->clusters.size(), 0u) << "ball.mesh has bad vertices: C, D, E need clusters";
  EXPECT_EQ(ids_of(result), expected_ids(false, false));

  const auto first = first_frames(result, count_inset_pictures(renderer));
  ASSERT_EQ(renderer.scenes.size(), first.at("(end)")) << "one frame per 3D image";
  for (const auto& [w, h] : renderer.sizes) EXPECT_TRUE(w > 0 && w <= 320 && h > 0 && h <= 240);
  // Overview: 4 triangles per boundary quad, coloured by vertex quality.
  const Scene& overview = renderer.scenes[first.at("overview")];
  EXPECT_EQ(triangle_count(overview), 4 * a.topology.boundary_faces.size());
  // Main view (two viewpoints): one aggregated glyph per cluster, less
  // those left out where they pile up on screen (issue 44 part T): each
  // sphere at a distinct cluster's position, #0's always drawn.
  const std::size_t main = first.at("main");
  EXPECT_EQ(first.at("clusters") - main, 2u);
  for (std::size_t f = main; f < main + 2; ++f) {
    const Scene& scene = renderer.scenes[f];
    ASSERT_FALSE(scene.spheres.empty());
    std::set<std::size_t> matched;  // grey ones and ranked ones (drawn over them)
    std::size_t glyphs = 0;
    for (const SphereSet& set : scene.spheres)
      for (const Vec3f& c : set.centers) {
        ++glyphs;
        for (std::size_t k = 0; k < a.glyphs->clusters.size(); ++k)
          if (norm(scene.origin + Vec3{c.x, c.y, c.z} - a.glyphs->clusters[k].position) < 1e-4) matched.insert(k);
      }
    EXPECT_LE(glyphs, a.glyphs->clusters.size());
    EXPECT_EQ(matched.size(), glyphs);
    EXPECT_TRUE(matched.count(0));
  }
  // Local views: one marker per corner at the vertex, coloured from the field.
  const ViewEntry& local = result.model.views[3];
  ASSERT_EQ(local.id, "local");
  const Index v = local.links[0].vertex;
  const std::size_t corners =
      static_cast<std::size_t>(a.topology.vertex_hex_offsets[v + 1] - a.topology.vertex_hex_offsets[v]);
  // Drawn as flat discs over the veil (a rim and a disc of 1 + 32 points
  // each), then the vertex's dot (a black ring disc and its white centre)
  // on top of them.
  const Scene& local_scene = renderer.scenes[first.at("local")];
  EXPECT_TRUE(local_scene.spheres[0].centers.empty());
  EXPECT_TRUE(local_scene.spheres[1].centers.empty());
  ASSERT_EQ(local_scene.overlay.size(), 1u);
  EXPECT_EQ(local_scene.overlay[0].positions.size(), (corners * 2 + 2) * 33);
  // Every file of every view is a bundle image.
  std::size_t files = 0;
  for (const ViewEntry& view : result.model.views) files += view.files.size();
  EXPECT_EQ(result.images.size(), files);
  // The document holds the views as report.json lists them.
  ASSERT_EQ(result.document["views"].size(), result.model.views.size());
  EXPECT_EQ(result.document["views"][0]["id"], "overview");
}

TEST(AnalyzePipeline, ReferenceAndCompareViewsWithAMockRenderer) {
  AnalyzeOptions options = small_run();
  options.reference_path = test::source_dir() / "examples/ball.off";
  options.compare_path = test::source_dir() / "examples/twisted_bar.mesh";
  RecordingRenderer renderer;
  const AnalyzeResult result = analyze(options, &renderer);
  const Analysis& a = result.model.analysis;
  ASSERT_TRUE(a.reference_surface && a.boundary_error && a.uv_atlas && a.compare);
  EXPECT_EQ(ids_of(result), expected_ids(true, true));
  // Every view of the table but panel P's three, which need a solved
  // finite-element check (--simulate; the ball's inverted hexes skip it).
  EXPECT_EQ(ids_of(result).size(), std::size(kViews) - 3) << "every view of the table";
  EXPECT_EQ(std::count_if(std::begin(kViews), std::end(kViews),
                          [](const ViewSpec& v) { return v.needs == ViewNeeds::simulation; }),
            3);

  const auto first = first_frames(result, count_inset_pictures(renderer));
  ASSERT_EQ(renderer.scenes.size(), first.at("(end)"));
  // Boundary error: front and back, the hex boundary's sampled patches; then
  // the reference error, front and back, the reference's patches.
  EXPECT_EQ(first.at("reference_error") - first.at("boundary_error"), 2u);
  EXPECT_EQ(first.at("reference_overlay") - first.at("reference_error"), 2u);
  EXPECT_EQ(renderer.scenes[first.at("boundary_error")].triangles.at(0).indices.size() / 3,
            a.boundary_error->mesh_patches.size());
  EXPECT_EQ(renderer.scenes[first.at("reference_error")].triangles.at(0).indices.size() / 3,
            a.boundary_error->reference_patches.size());
  EXPECT_GT(a.boundary_error->reference_patches.size(), a.reference_surface->triangles.size() / 2);
  // The UV key: the reference twice in 3D, every triangle tinted by its
  // chart, then the atlas with the UV error map's triangles.
  const std::size_t key = first.at("uv_key");
  for (std::size_t f = key; f < key + 3; ++f) EXPECT_EQ(triangle_count(renderer.scenes[f]), a.reference_surface->triangles.size());
  EXPECT_EQ(triangle_count(renderer.scenes[key + 2]), triangle_count(renderer.scenes[first.at("uv_error")]));
  // The reference overlay draws the reference's triangles translucent.
  const Scene& overlay = renderer.scenes[first.at("reference_overlay")];
  std::size_t translucent = 0;
  for (const TriangleSet& t : overlay.translucent) translucent += t.indices.size() / 3;
  EXPECT_EQ(translucent, a.reference_surface->triangles.size());
  // Compare: the two boundaries, one half each, 4 triangles per quad.
  const std::size_t compare = first.at("compare");
  EXPECT_EQ(triangle_count(renderer.scenes[compare]), 4 * a.topology.boundary_faces.size());
  EXPECT_EQ(triangle_count(renderer.scenes[compare + 1]), 4 * a.compare->topology.boundary_faces.size());
  EXPECT_TRUE(result.document["compare"].is_object());
  EXPECT_TRUE(result.document["boundary_error"].is_object());
}

TEST(AnalyzePipeline, NoRendererNoViewsSameNumbers) {
  RecordingRenderer renderer;
  const AnalyzeResult drawn = analyze(small_run(), &renderer);
  const AnalyzeResult plain = analyze(small_run(), nullptr);
  EXPECT_TRUE(plain.model.views.empty());
  EXPECT_TRUE(plain.images.empty());
  EXPECT_EQ(plain.document["quality"], drawn.document["quality"]);
  EXPECT_EQ(plain.document["glyphs"], drawn.document["glyphs"]);
}

TEST(AnalyzePipeline, TopClustersChoosesTheDetailViews) {
  // --top-clusters reaches the views through the glyph result: K clusters
  // get a C view, their K worst vertices D and E (plus a focus vertex).
  for (const int k : {0, 1, 3}) {
    AnalyzeOptions options = small_run();
    options.glyphs.rmax = 0.3;  // x the mean edge length: several clusters on the ball
    options.glyphs.top_clusters = k;
    options.views.focus_vertices = {0};
    RecordingRenderer renderer;
    const AnalyzeResult result = analyze(options, &renderer);
    ASSERT_GE(result.model.analysis.glyphs->clusters.size(), 3u);
    std::map<std::string, std::size_t> files;
    for (const ViewEntry& v : result.model.views) files[v.id] = v.files.size();
    EXPECT_EQ(files.count("clusters") ? files["clusters"] : 0u, static_cast<std::size_t>(k)) << k;
    EXPECT_EQ(files["local"], static_cast<std::size_t>(k) + 1) << k;  // vertex 0 is no cluster's worst here
  }
}

// A mock renderer with a sibling (Renderer::sibling): every frame's image is
// made from the scene and the camera alone, so any renderer of the family
// draws it alike; the family counts the frames each member drew, and on
// which threads.
struct FamilyLog {
  std::mutex mutex;
  std::map<int, std::size_t> frames;  // by member: 0 the first, 1 its sibling
  std::set<std::thread::id> threads;
  bool sibling_fails = false;
};

class FamilyRenderer final : public Renderer {
 public:
  FamilyRenderer(std::shared_ptr<FamilyLog> log, int member) : log_(std::move(log)), member_(member) {}
  Image render(const Scene& scene, const Camera& camera, int width, int height) override {
    {
      const std::lock_guard<std::mutex> guard(log_->mutex);
      ++log_->frames[member_];
      log_->threads.insert(std::this_thread::get_id());
      if (member_ == 1 && log_->sibling_fails) throw RenderError("the sibling broke");
    }
    // Pixels from what is drawn and from where.
    std::size_t spheres = 0;
    for (const SphereSet& set : scene.spheres) spheres += set.centers.size();
    const auto seed = static_cast<std::uint8_t>(triangle_count(scene) * 7 + spheres * 13 +
                                                static_cast<std::size_t>(std::abs(camera.eye.x) * 1000.0));
    Image image{width, height, std::vector<std::uint8_t>(4 * static_cast<std::size_t>(width) * height)};
    for (std::size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<std::uint8_t>(seed + i % 251);
    return image;
  }
  std::unique_ptr<Renderer> sibling() const override { return std::make_unique<FamilyRenderer>(log_, 1); }

 private:
  std::shared_ptr<FamilyLog> log_;
  int member_;
};

TEST(AnalyzePipeline, TwoRenderThreadsDrawWhatOneDraws) {
  const tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
  if (tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) < 2)
    GTEST_SKIP() << "TBB allows one thread here";
  AnalyzeOptions options = small_run();
  options.reference_path = test::source_dir() / "examples/ball.off";
  std::vector<AnalyzeResult> results;
  std::vector<std::shared_ptr<FamilyLog>> logs;
  for (const int threads : {1, 2}) {
    options.views.render_threads = threads;
    logs.push_back(std::make_shared<FamilyLog>());
    FamilyRenderer renderer(logs.back(), 0);
    results.push_back(analyze(options, &renderer));
  }
  EXPECT_EQ(logs[0]->frames[1], 0u) << "one thread: no sibling";
  EXPECT_GT(logs[1]->frames[0], 0u);
  EXPECT_GT(logs[1]->frames[1], 0u) << "two threads: the sibling draws some views";
  EXPECT_EQ(logs[1]->threads.size(), 2u);
  EXPECT_EQ(logs[0]->frames[0], logs[1]->frames[0] + logs[1]->frames[1]) << "every frame drawn once";
  // The same views, files, cameras and image bytes, in the same order.
  EXPECT_EQ(ids_of(results[0]), expected_ids(true, false));
  EXPECT_EQ(ids_of(results[0]), ids_of(results[1]));
  EXPECT_EQ(results[0].document["views"], results[1].document["views"]);
  ASSERT_EQ(results[0].images.size(), results[1].images.size());
  for (std::size_t i = 0; i < results[0].images.size(); ++i) {
    const BundleImage &a = results[0].images[i], &b = results[1].images[i];
    EXPECT_EQ(a.relative_path, b.relative_path);
    EXPECT_EQ(a.text, b.text) << a.relative_path;
    EXPECT_EQ(a.image.rgba, b.image.rgba) << a.relative_path;
  }
}

TEST(AnalyzePipeline, AFailureOnTheSecondRenderThreadReachesTheCaller) {
  const tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
  if (tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) < 2)
    GTEST_SKIP() << "TBB allows one thread here";
  auto log = std::make_shared<FamilyLog>();
  log->sibling_fails = true;
  FamilyRenderer renderer(log, 0);
  try {
    (void)analyze(small_run(), &renderer);
    FAIL() << "no error";
  } catch (const RenderError& e) {
    EXPECT_STREQ(e.what(), "the sibling broke");
  }
  EXPECT_EQ(log->frames[1], 1u) << "the sibling stopped at its failure";
}

TEST(AnalyzePipeline, GatesReadTheDocument) {
  AnalyzeOptions options = small_run();
  options.gates = {parse_gate_rule("quality.scaled_jacobian.min>=2"), parse_gate_rule("mesh.num_hexes>0")};
  const AnalyzeResult result = analyze(options, nullptr);
  ASSERT_EQ(result.model.gates.results.size(), 2u);
  EXPECT_FALSE(result.model.gates.passed);
  EXPECT_EQ(result.model.gates.results[0].value, result.document["quality"]["scaled_jacobian"]["min"].get<double>());
  EXPECT_EQ(result.model.gates.results[1].value, result.model.analysis.mesh_summary.num_hexes);
  EXPECT_EQ(result.document["gates"]["passed"], false);
  EXPECT_EQ(result.document["gates"]["results"].size(), 2u);
}

}  // namespace
}  // namespace hq
