#pragma once
// Analysis: every result one `analyze` run computes, as plain data. The
// pipeline fills it in stage order (pipeline/analyze.h); the views and the
// report read it and never recompute what it holds.

#include <optional>
#include <string>
#include <vector>

#include "hqview/core/stage_times.h"

#include "hqview/analysis/compare_alignment.h"
#include "hqview/analysis/resting_up.h"
#include "hqview/boundary/boundary_error.h"
#include "hqview/fem/fem_element_field.h"
#include "hqview/fem/metric_correlation.h"
#include "hqview/fem/poisson_check.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/io/mesh_source.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/mesh_summary.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/overlap.h"
#include "hqview/quality/cell_composition.h"
#include "hqview/quality/cell_metric_field.h"
#include "hqview/quality/hex_metric_field.h"
#include "hqview/quality/quality_field.h"
#include "hqview/quality/quality_summary.h"
#include "hqview/structure/quad_structure.h"
#include "hqview/structure/structure.h"
#include "hqview/uv/uv_atlas.h"

namespace hq {

struct Analysis {
  InputFile mesh_input;
  std::vector<std::string> warnings;  // from the readers and the analysis, in stage order
  // The readers' notes (LoadedMesh::notes: lower-dimensional cells skipped):
  // information, shown apart from the warnings on the pages; report.json
  // lists them first under `warnings`.
  std::vector<std::string> notes;
  std::vector<StageTime> timings;     // wall times of the stages run (timings.json; never in report.json)

  HexMesh mesh;
  Topology topology;
  QualityField field;      // corner scaled Jacobians, vertex quality, cell scaled Jacobian
  HexMetricField metrics;  // the Verdict metrics per hex (cells.csv columns)
  // The other volume blocks' Verdict metrics (tets, wedges, pyramids with
  // cells, in CellKind order), summarised as they were computed
  // (quality.by_kind): only the metrics that have a cells.csv column (a hex
  // metric's name) keep their values; the corner values and validity are
  // `field`'s.
  std::vector<CellBlockMetricField> cell_metrics;
  MeshSummary mesh_summary;
  CellComposition composition;  // cells and volume by kind, hex fractions (headline)
  QualitySummary quality;
  // Edge valences, singular edges and vertices, the singularity graph, size gradation.
  HexStructure structure;
  // A surface mesh's quad structure (irregular vertices, separatrices,
  // patches: structure/quad_structure.h); none for a volume mesh.
  std::optional<QuadStructure> quad_structure;
  // The edges of the polygons the reader skipped (LoadedMesh::hole_edges,
  // a < b): holes, not boundary, for the quad structure.
  std::vector<std::array<Index, 2>> hole_edges;
  // The finite-element check (--simulate, or fem_element in --metrics for
  // the element conditioning alone); empty when not asked for.
  std::optional<FemElementField> fem_elements;
  std::optional<PoissonCheck> poisson;
  // Spearman rho over the hexes of the error density and each metric (solved checks only).
  std::vector<MetricCorrelation> fem_correlations;

  // Vertex glyphs and their clusters; empty when the stage did not run.
  std::optional<GlyphResult> glyphs;
  // Overlapping vertices and intersecting cells; empty with --no-overlap.
  std::optional<OverlapReport> overlap;

  // With --reference: the reference file and surface (as read), the boundary
  // error and the reference's UV atlas (all four or none).
  std::optional<InputFile> reference_input;
  std::optional<TriSurface> reference_surface;
  std::optional<BoundaryError> boundary_error;
  std::optional<UvAtlas> uv_atlas;
  // --reference-align: how the reference was moved into the mesh's frame
  // before the boundary error (reference_surface is the moved surface).
  CompareAlignment reference_alignment{.requested = CompareAlign::none};

  // --up auto: the resting up axis and its candidates (the views use its up).
  std::optional<RestingUp> resting_up;

  // With --compare MESH2: MESH2 analysed the same way (quality only).
  struct Compared {
    InputFile input;
    MeshSummary mesh_summary;
    CellComposition composition;
    QualitySummary quality;
    HexMesh mesh;
    Topology topology;
    QualityField field;
    CompareAlignment alignment;  // how the views place MESH2 (numbers stay in its own units)
  };
  std::optional<Compared> compare;

  // The mesh's file name, for titles ("kitten_1.mesh").
  std::string mesh_name() const;
};

}  // namespace hq
