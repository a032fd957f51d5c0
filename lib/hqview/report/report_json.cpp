#include "hqview/report/report_json.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace hq {
namespace {

using Json = nlohmann::ordered_json;

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json vec3(const Vec3& v) { return Json::array({number(v.x), number(v.y), number(v.z)}); }

Json stats_json(const Statistics& s, bool with_inverted) {
  Json j;
  j["count"] = s.count;
  j["min"] = number(s.min);
  j["max"] = number(s.max);
  j["mean"] = number(s.mean);
  j["std"] = number(s.std);
  j["p01"] = number(s.p01);
  j["p05"] = number(s.p05);
  j["p50"] = number(s.p50);
  j["p95"] = number(s.p95);
  j["p99"] = number(s.p99);
  if (with_inverted) j["num_inverted"] = s.num_inverted;
  j["num_degenerate"] = s.num_degenerate;
  Json edges = Json::array();
  for (double e : s.histogram.edges) edges.push_back(number(e));
  j["histogram"] = {{"edges", edges}, {"counts", s.histogram.counts}};
  return j;
}

Json mesh_json(const MeshSummary& m) {
  Json j;
  j["num_vertices"] = m.num_vertices;
  j["num_hexes"] = m.num_hexes;
  j["num_unreferenced_vertices"] = m.num_unreferenced_vertices;
  j["num_boundary_faces"] = m.num_boundary_faces;
  j["num_boundary_vertices"] = m.num_boundary_vertices;
  j["num_non_manifold_faces"] = m.num_non_manifold_faces;
  j["bbox"] = {{"min", vec3(m.bbox_min)}, {"max", vec3(m.bbox_max)}, {"diagonal", number(m.bbox_diagonal)}};
  j["edge_length"] = {
      {"min", number(m.edge_length_min)}, {"mean", number(m.edge_length_mean)}, {"max", number(m.edge_length_max)}};
  return j;
}

Json quality_json(const QualitySummary& q) {
  Json j;
  j["scaled_jacobian"] = stats_json(q.scaled_jacobian, true);
  j["corner_scaled_jacobian"] = stats_json(q.corner_scaled_jacobian, true);
  j["vertex_quality"] = stats_json(q.vertex_quality, true);
  Json metrics = Json::object();
  for (const MetricSummary& m : q.metrics) {
    Json mj = stats_json(m.stats, m.name == "scaled_jacobian");
    mj["acceptable"] = Json::array({number(m.acceptable_min), number(m.acceptable_max)});
    mj["fraction_acceptable"] = number(m.fraction_acceptable);
    metrics[m.name] = std::move(mj);
  }
  j["metrics"] = std::move(metrics);
  Json worst_vertices = Json::array();
  for (const WorstVertex& w : q.worst_vertices)
    worst_vertices.push_back({{"vertex", w.vertex}, {"quality", number(w.quality)}, {"position", vec3(w.position)}});
  j["worst_vertices"] = std::move(worst_vertices);
  Json worst_cells = Json::array();
  for (const WorstCell& w : q.worst_cells)
    worst_cells.push_back({{"cell", w.cell}, {"scaled_jacobian", number(w.scaled_jacobian)}});
  j["worst_cells"] = std::move(worst_cells);
  return j;
}

}  // namespace

std::string report_json(const ReportModel& model) {
  Json j;
  j["schema_version"] = kSchemaVersion;
  j["tool"] = {{"name", "hqview"}, {"version", model.tool_version}};
  j["input"] = {
      {"mesh",
       {{"path", model.mesh_input.path}, {"format", model.mesh_input.format}, {"sha256", model.mesh_input.sha256}}},
      {"reference", nullptr},
      {"compare", nullptr}};
  j["mesh"] = mesh_json(model.mesh_summary);
  j["quality"] = quality_json(model.quality);
  // Stages of later releases; null until computed.
  j["glyphs"] = nullptr;
  j["overlap"] = nullptr;
  j["boundary_error"] = nullptr;
  j["compare"] = nullptr;
  Json views = Json::array();
  for (const ViewEntry& v : model.views) views.push_back({{"id", v.id}, {"title", v.title}, {"files", v.files}});
  j["views"] = std::move(views);
  j["gates"] = {{"passed", true}, {"results", Json::array()}};
  j["warnings"] = model.warnings;
  // Invalid UTF-8 in names from input is replaced, never thrown on.
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace hq
