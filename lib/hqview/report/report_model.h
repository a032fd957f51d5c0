#pragma once
// ReportModel: what the writers (report.json, CSV, VTU, pages) are written
// from: the Analysis, the views rendered from it and the gates' outcome.
// Plain data; the writers never recompute analysis.

#include <optional>
#include <string>
#include <vector>

#include "hqview/analysis/analysis.h"
#include "hqview/chart/chart.h"
#include "hqview/report/data_files.h"

namespace hq {

// One `--gate` rule's outcome (report.json `gates.results`).
struct GateResult {
  std::string rule;
  double value = 0;  // the report value the rule read; NaN (null) when it has none
  bool passed = true;
  // Why a rule passed without a value: it reads quality.by_kind.<kind> of a
  // kind the mesh has no cell of ("no tet in the mesh"); empty otherwise.
  std::string note;
};

struct GateSummary {
  bool passed = true;  // every rule passed (true when there are none)
  std::vector<GateResult> results;
};

// What one file of a view shows, for the links between panels in
// index.html (not written to report.json).
struct ViewFileLinks {
  Index cluster = kNoIndex;  // C: its cluster; D, E: the cluster of its vertex (kNoIndex: none)
  Index vertex = kNoIndex;   // D, E: its vertex
  // Chart B: one region per bar, in fractions of the image, key = vertex id.
  std::vector<ChartHotspot> hotspots;
};

// Where a 3D view's camera looked from (report.json views[].cameras).
struct ViewCameraEntry {
  Vec3 eye, target, up;                 // model units; up: the image's up direction (--up made orthogonal)
  double elevation_degrees = 0;         // of the eye above the horizontal plane of up
  double azimuth_degrees = 0;           // around up, from the front (render/upright.h), in (-180, 180]
  bool is_perspective = true;
  double height = 0;  // orthographic: the view's height in model units; perspective: its vertical field of view, degrees
  double aspect = 1;  // the 3D area's width / height, pixels
  int pixel_width = 0, pixel_height = 0;  // the 3D area in the image: its bottom-left corner (below the title, left of the legend)
};

struct ViewEntry {
  std::string id;
  std::string title;
  std::vector<std::string> files;    // relative to the bundle root
  std::vector<ViewFileLinks> links;  // one per file, or empty (no links)
  std::vector<std::optional<ViewCameraEntry>> cameras{};  // one per file (none: not a 3D view), or empty
};

struct ReportModel {
  std::string tool_version;
  Analysis analysis;
  std::vector<ViewEntry> views;
  GateSummary gates;
  // The per-cell and per-vertex data files of the bundle (--data); the
  // pages link the ones there are.
  DataFormats data;
  // viewer.html and viewer/ are part of the bundle (--no-viewer: not).
  bool has_viewer = false;
  double viewer_max_mb = 25;  // --viewer-max-mb
  Vec3 viewer_up{0.0, 0.0, 1.0};  // --up
  bool up_auto = false;           // --up auto (the default): viewer_up chosen per mesh
  double viewer_error_density_reference = 0;  // --error-density-reference
};

}  // namespace hq
