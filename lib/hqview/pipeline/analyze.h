#pragma once
// The `analyze` pipeline: read -> topology -> quality -> views -> ReportModel.
// The one place that knows the order of the stages. Touches no output file:
// main() hands the result to write_bundle().

#include <filesystem>
#include <string>
#include <vector>

#include "hqview/report/bundle_writer.h"
#include "hqview/report/report_model.h"

namespace hq {

struct AnalyzeOptions {
  std::filesystem::path mesh_path;
  std::string tool_version;
  bool render = true;
  int image_width = 1600;
  int image_height = 1200;
  int worst_count = 20;  // entries in worst_vertices / worst_cells
};

struct Analysis {
  ReportModel model;
  std::vector<BundleImage> images;
};

// Throws InputError/ParseError for unreadable or malformed input,
// InvalidMeshError for a mesh that cannot be analysed, RenderError when the
// offscreen context fails.
Analysis analyze(const AnalyzeOptions& options);

// The summary parts, exposed for tests.
MeshSummary summarize_mesh(const HexMesh& mesh, const Topology& topo);
QualitySummary summarize_quality(const HexMesh& mesh, const QualityField& field, int worst_count);

}  // namespace hq
