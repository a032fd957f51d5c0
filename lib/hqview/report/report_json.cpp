#include "hqview/report/report_json.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "hqview/glyph/glyph_ties.h"
#include "hqview/render/upright.h"
#include "hqview/report/cluster_color.h"
#include "hqview/report/escape.h"

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
  j["num_non_conforming_faces"] = m.num_non_conforming_faces;
  j["bbox"] = {{"min", vec3(m.bbox_min)}, {"max", vec3(m.bbox_max)}, {"diagonal", number(m.bbox_diagonal)}};
  j["edge_length"] = {
      {"min", number(m.edge_length_min)}, {"mean", number(m.edge_length_mean)}, {"max", number(m.edge_length_max)}};
  // Surface meshes (issue 47); null for a volume mesh's surface-only keys.
  j["dimension"] = m.is_surface ? "surface" : "volume";
  j["planar"] = m.planarity ? Json(m.planarity->is_planar) : Json(nullptr);
  j["planarity"] = m.planarity ? number(m.planarity->planarity) : Json(nullptr);
  j["plane_normal"] = m.planarity && m.planarity->is_planar ? vec3(m.planarity->normal) : Json(nullptr);
  j["num_boundary_edges"] = m.is_surface ? Json(m.num_boundary_edges) : Json(nullptr);
  j["num_non_manifold_edges"] = m.is_surface ? Json(m.num_non_manifold_edges) : Json(nullptr);
  j["num_reversed_faces"] = m.is_surface ? Json(m.num_reversed_faces) : Json(nullptr);
  return j;
}

// CONTRACT.md glyphs, with extensions before `clusters`: how rmax was given,
// top_clusters, and how many clusters the list leaves out (it holds the
// kMaxListedClusters worst; vertices.csv has every vertex's cluster).
constexpr std::size_t kMaxListedClusters = 1000;

Json glyphs_json(const GlyphResult& g) {
  Json j;
  j["rmax"] = number(g.rmax);
  j["threshold"] = number(g.options.threshold);
  j["num_glyphs"] = g.num_glyphs;
  j["num_clusters"] = g.clusters.size();
  const bool is_relative = g.options.rmax_unit == RmaxUnit::kMeanEdgeLength;
  j["rmax_mode"] = is_relative ? "mean_edge_length" : "model_units";
  j["rmax_factor"] = is_relative ? number(g.options.rmax) : Json(nullptr);
  j["top_clusters"] = g.options.top_clusters;
  j["size_rule"] = glyph_size_rule_name(g.options.size_rule);
  const std::size_t listed = std::min(g.clusters.size(), kMaxListedClusters);
  j["num_clusters_omitted"] = g.clusters.size() - listed;
  j["tie_tolerance"] = number(kGlyphTieTolerance);
  const std::vector<Index> ties = glyph_tie_classes(g.clusters);
  const std::vector<Index> slots =
      glyph_colour_slots(g.clusters, static_cast<Index>(labelled_cluster_count(g.options.top_clusters)));
  Json clusters = Json::array();
  for (std::size_t i = 0; i < listed; ++i) {
    const AggregatedGlyph& c = g.clusters[i];
    clusters.push_back({{"id", c.id},
                        {"size", c.size},
                        {"representative_vertex", c.representative_vertex},
                        {"position", vec3(c.position)},
                        {"min_quality", number(c.min_quality)},
                        {"ratio", number(c.ratio)},
                        {"radius", number(c.radius)},
                        {"color", cluster_color_hex(slots[i], g.options.top_clusters)},
                        {"tie_class", ties[i]}});
  }
  j["clusters"] = std::move(clusters);
  return j;
}

// quality.by_kind: hex, tet, wedge, pyramid, each with its count and every
// Verdict metric of the kind (null statistics when the kind has no cell).
Json by_kind_json(const std::vector<KindQualitySummary>& by_kind) {
  Json j = Json::object();
  for (const KindQualitySummary& k : by_kind) {
    Json kj;
    kj["count"] = k.count;
    kj["num_inverted"] = k.num_inverted;
    kj["num_flat"] = k.num_flat;
    Json metrics = Json::object();
    if (k.count == 0)
      for (const std::string_view name : volume_kind_metric_names(k.kind)) metrics[std::string(name)] = nullptr;
    for (const MetricSummary& m : k.metrics)
      metrics[m.name] = stats_json(m.stats, m.name == "scaled_jacobian" || m.name == "corner_scaled_jacobian");
    kj["metrics"] = std::move(metrics);
    j[std::string(cell_kind_name(k.kind))] = std::move(kj);
  }
  return j;
}

Json quality_json(const QualitySummary& q) {
  Json j;
  // Cell counts first: the numbers CI gates read most (`quality.num_inverted==0`).
  j["num_inverted"] = q.num_inverted;
  j["num_degenerate"] = q.num_degenerate;
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
    worst_cells.push_back({{"cell", w.cell},
                           {"scaled_jacobian", number(w.scaled_jacobian)},
                           {"kind", cell_kind_name(w.kind)},
                           {"source_index", w.source_index}});
  j["worst_cells"] = std::move(worst_cells);
  j["by_kind"] = by_kind_json(q.by_kind);
  return j;
}

// structure: counts of the singularity graph and the size gradation.
Json structure_json(const HexStructure& s) {
  auto by_valence = [](const std::map<Index, Index>& m) {
    Json j = Json::object();
    for (const auto& [valence, count] : m) j[std::to_string(valence)] = count;
    return j;
  };
  Json lengths = {{"min", 0}, {"mean", 0.0}, {"max", 0}};
  if (!s.curve_lengths.empty()) {
    double sum = 0;
    for (Index l : s.curve_lengths) sum += static_cast<double>(l);
    lengths = {{"min", *std::min_element(s.curve_lengths.begin(), s.curve_lengths.end())},
               {"mean", number(sum / static_cast<double>(s.curve_lengths.size()))},
               {"max", *std::max_element(s.curve_lengths.begin(), s.curve_lengths.end())}};
  }
  return {{"num_edges", s.num_edges},
          {"num_singular_edges_interior", s.num_singular_edges_interior},
          {"num_singular_edges_boundary", s.num_singular_edges_boundary},
          {"num_irregular_edges_boundary", s.num_irregular_edges_boundary},
          {"num_nonmanifold_edges", s.num_nonmanifold_edges},
          {"num_edges_touching_non_hex", s.num_edges_touching_non_hex},
          {"singular_edges_by_valence", {{"interior", by_valence(s.interior_by_valence)},
                                         {"boundary", by_valence(s.boundary_by_valence)}}},
          {"num_singular_vertices", s.num_singular_vertices},
          {"num_singularity_nodes", static_cast<Index>(s.nodes.size())},
          {"num_singular_curves", s.num_curves},
          {"curve_length", std::move(lengths)},
          {"size_gradation", stats_json(s.gradation, false)},
          {"num_gradation_above_2", s.num_gradation_above_2},
          {"num_gradation_above_4", s.num_gradation_above_4}};
}

// structure of a surface mesh: its quad structure (docs/contract.md
// "structure (surface meshes)").
Json quad_structure_json(const QuadStructure& s) {
  auto by_valence = [](const std::map<Index, Index>& m) {
    Json j = Json::object();
    for (const auto& [valence, count] : m) j[std::to_string(valence)] = count;
    return j;
  };
  std::array<Index, 5> ends{};
  for (SeparatrixEnd e : s.separatrix_end) ++ends[static_cast<std::size_t>(e)];
  return {{"valence", "incident quads"},
          {"num_edges", s.num_edges},
          {"num_boundary_edges", s.num_boundary_edges},
          {"num_nonmanifold_edges", s.num_nonmanifold_edges},
          {"num_irregular_vertices", s.num_irregular},
          {"num_irregular_vertices_interior", s.num_irregular_interior},
          {"num_irregular_vertices_boundary", s.num_irregular_boundary},
          {"irregular_vertices_by_valence",
           {{"interior", by_valence(s.interior_by_valence)}, {"boundary", by_valence(s.boundary_by_valence)}}},
          {"num_unclassified_vertices", s.num_unclassified},
          {"num_separatrices", s.num_separatrices},
          {"separatrix_ends",
           {{"irregular_vertex", ends[static_cast<std::size_t>(SeparatrixEnd::irregular_vertex)]},
            {"boundary", ends[static_cast<std::size_t>(SeparatrixEnd::boundary)]},
            {"unclassified_vertex", ends[static_cast<std::size_t>(SeparatrixEnd::unclassified_vertex)]},
            {"traced_edge", ends[static_cast<std::size_t>(SeparatrixEnd::traced_edge)]},
            {"cap", ends[static_cast<std::size_t>(SeparatrixEnd::cap)]}}},
          {"num_traced_edges", s.num_traced_edges},
          {"num_patches", s.num_patches}};
}

// fem.poisson.normalization: the frame of the manufactured solutions
// (principal_frame.h; issue 48: was the model axes and their bounding box).
Json normalization_json(const Normalization& n) {
  const auto& v = n.principal_variances;
  return {{"center", vec3(n.center)},
          {"diagonal", number(n.diagonal)},
          {"axes", Json::array({vec3(n.axes[0]), vec3(n.axes[1]), vec3(n.axes[2])})},
          {"principal_variances", Json::array({number(v[0]), number(v[1]), number(v[2])})},
          {"axes_from_input", n.axes_from_input},
          {"signs_from_input", n.signs_from_input},
          {"placement_independent", n.axes_from_input == 0 && n.signs_from_input == 0}};
}

// fem: the element conditioning, and with --simulate the Poisson check
// (docs/contract.md "fem"). A skipped check keeps every key, null.
Json fem_poisson_json(const PoissonCheck& p, const std::vector<MetricCorrelation>& correlations) {
  const bool solved = p.skipped.empty();
  auto value = [&](double v) { return solved ? number(v) : Json(nullptr); };
  Json solutions = Json::object();
  for (const PoissonSolutionResult& s : p.solutions)
    solutions[s.name] = {{"l2_error", number(s.l2_error)},
                         {"h1_error", number(s.h1_error)},
                         {"nodal_error", number(s.nodal_error)},
                         {"iterations", s.iterations},
                         {"lanczos_steps", s.lanczos_steps},
                         {"converged", s.converged},
                         {"relative_residual", number(s.relative_residual)}};
  Json correlation = Json::object(), given_size = Json::object(), interval = Json::object(), adjusted = Json::object();
  for (const MetricCorrelation& c : correlations) {
    correlation[c.metric] = number(c.correlation.rho);
    given_size[c.metric] = number(c.rho_given_size);
    interval[c.metric] = std::isfinite(c.interval.lo) ? Json::array({number(c.interval.lo), number(c.interval.hi)})
                                                      : Json(nullptr);
    adjusted[c.metric] = std::isfinite(c.adjusted_interval.lo)
                             ? Json::array({number(c.adjusted_interval.lo), number(c.adjusted_interval.hi)})
                             : Json(nullptr);
  }
  return {{"skipped", solved ? Json(nullptr) : Json(p.skipped)},
          {"num_free_vertices", p.num_free_vertices},
          {"min_free_vertices", p.min_free_vertices},
          {"normalization", normalization_json(p.normalization)},
          {"solver", {{"method", "cg"}, {"preconditioner", "jacobi"}, {"tolerance", 1e-10}}},
          {"solutions", solved ? std::move(solutions) : Json(nullptr)},
          {"mean",
           {{"l2_error", value(p.mean_l2_error)},
            {"h1_error", value(p.mean_h1_error)},
            {"nodal_error", value(p.mean_nodal_error)},
            {"iterations", value(p.mean_iterations)}}},
          {"scaled_matrix",
           {{"lambda_min", value(p.scaled_lambda_min)},
            {"lambda_max", value(p.scaled_lambda_max)},
            {"condition", value(p.scaled_condition)}}},
          {"stiffness",
           {{"lambda_max", value(p.stiffness_lambda_max)},
            {"lanczos_steps", solved ? Json(p.stiffness_lanczos_steps) : Json(nullptr)},
            {"fried_bound", value(p.fried_bound)},
            {"max_hexes_at_vertex", solved ? Json(p.max_hexes_at_vertex) : Json(nullptr)}}},
          {"error_density", solved ? stats_json(p.error_density_stats, false) : Json(nullptr)},
          {"correlation", solved ? std::move(correlation) : Json(nullptr)},
          {"size_correlation", value(p.size_correlation)},
          {"correlation_given_size", solved ? std::move(given_size) : Json(nullptr)},
          {"correlation_interval", solved ? std::move(interval) : Json(nullptr)},
          {"correlation_interval_adjusted", solved ? std::move(adjusted) : Json(nullptr)},
          {"correlation_verdict_family", solved ? Json(verdict_family_size(correlations)) : Json(nullptr)}};
}

Json fem_json(const Analysis& a) {
  const FemElementField& e = *a.fem_elements;
  Json element = {{"num_invalid", e.num_invalid},
                  {"num_not_invertible", e.num_not_invertible},
                  {"kappa", stats_json(e.kappa_stats, false)},
                  {"lambda_max", stats_json(e.lambda_max_stats, false)},
                  {"det_j_min", stats_json(e.det_j_min_stats, true)},
                  {"det_j_max", stats_json(e.det_j_max_stats, true)}};
  Json poisson = a.poisson ? fem_poisson_json(*a.poisson, a.fem_correlations) : Json(nullptr);
  // The placement-free length (fem/moment_length.h): the batch's h/L. Only
  // for a solved check.
  if (a.poisson && a.poisson->skipped.empty()) poisson["mesh_length"] = number(a.poisson->mesh_length);
  return {{"element", std::move(element)}, {"poisson", std::move(poisson)}};
}

// compare.alignment, boundary_error.reference_alignment.
// The rotation keys are added after the box rule's (auto's search: null
// distances for none and bbox).
// --up auto: the chosen axis and every candidate's numbers.
Json up_auto_json(const RestingUp& r) {
  Json candidates = Json::array();
  for (const RestingCandidate& c : r.candidates)
    candidates.push_back({{"up", up_axis_name(c.up)},
                          {"support_area", number(c.support_area)},
                          {"tip", number(c.tip)},
                          {"rests", c.rests}});
  return {{"axis", up_axis_name(r.up)}, {"from_data", r.from_data}, {"candidates", std::move(candidates)}};
}

Json alignment_json(const CompareAlignment& a) {
  const auto matrix = [](const Matrix3& m) {
    Json rows = Json::array();
    for (const auto& row : m) rows.push_back({number(row[0]), number(row[1]), number(row[2])});
    return rows;
  };
  const auto searched = [&](double v) { return a.searched ? number(v) : Json(nullptr); };
  const bool turned = a.aligned && rotation_angle_degrees(a.rotation) > 1e-6;
  return {{"requested", compare_align_name(a.requested)},
          {"mode", !a.aligned ? "none" : turned ? "rotation" : "bbox"},
          {"scale", number(a.scale)},
          {"translation", vec3(a.translation)},
          {"diagonal_ratio", number(a.diagonal_ratio)},
          {"boxes_overlap", a.boxes_overlap},
          {"rotation", matrix(a.aligned ? a.rotation : kIdentity3)},
          {"rotation_name", rotation_name(a.aligned ? a.rotation : kIdentity3)},
          {"axis_rotation", rotation_name(a.axis_rotation)},
          {"icp", {{"applied", a.icp_applied}, {"iterations", a.icp_iterations}}},
          {"mean_distance_identity", searched(a.identity_distance)},
          {"mean_distance", searched(a.distance)},
          {"mirrored", a.mirrored},
          {"mean_distance_mirror", searched(a.mirror_distance)},
          {"description", alignment_description(a)}};
}

// CONTRACT.md boundary_error, then extensions (after uv_atlas).
Json boundary_error_json(const ReportModel& model) {
  const BoundaryError& e = *model.analysis.boundary_error;
  Json j;
  j["reference"] = model.analysis.reference_input ? Json(model.analysis.reference_input->path) : Json(nullptr);
  j["bbox_diagonal"] = number(e.reference_bbox_diagonal);
  j["normalization"] = "reference_bbox_diagonal";
  j["hausdorff"] = {{"mesh_to_reference", number(e.hausdorff_mesh_to_reference)},
                    {"reference_to_mesh", number(e.hausdorff_reference_to_mesh)},
                    {"symmetric", number(e.hausdorff_symmetric)},
                    {"relative", number(e.hausdorff_relative)},
                    {"relative_mesh_to_reference", number(e.relative_mesh_to_reference)},
                    {"relative_reference_to_mesh", number(e.relative_reference_to_mesh)}};
  j["signed"] = stats_json(e.signed_stats, false);
  j["fraction_outside"] = number(e.fraction_outside);
  j["fraction_inside"] = number(e.fraction_inside);
  j["sign_method"] = sign_method_name(e.sign_method);
  if (model.analysis.uv_atlas) {
    const UvAtlas& a = *model.analysis.uv_atlas;
    auto quantiles = [&](const UvDistortionStats& d) {
      return ReportDocument{{"min", number(d.min)}, {"p5", number(d.p5)},   {"p50", number(d.p50)},
                            {"p95", number(d.p95)}, {"max", number(d.max)}};
    };
    j["uv_atlas"] = {{"num_charts", a.num_charts},
                     {"num_flipped", a.num_flipped},
                     {"num_overlaps", a.num_overlaps},
                     {"num_splits", a.num_splits},
                     {"num_lscm_charts", a.num_lscm_charts},
                     {"packing_efficiency", number(a.packing_efficiency)},
                     {"area_fraction_largest_chart", number(a.area_fraction_largest_chart)},
                     {"area_fraction_top_4_charts", number(a.area_fraction_top_4_charts)},
                     {"area_fraction_top_8_charts", number(a.area_fraction_top_8_charts)},
                     {"area_ratio", quantiles(a.area_ratio)},
                     {"area_fraction_area_ratio_within_2", number(a.area_fraction_area_ratio_within_2)},
                     {"conformal_distortion", quantiles(a.conformal_distortion)}};
  } else {
    j["uv_atlas"] = nullptr;
  }
  j["num_uncertain_signs"] = e.num_uncertain_signs;
  j["area_weighted"] = {{"mean", number(e.area_weighted_mean)},
                        {"mean_abs", number(e.area_weighted_mean_abs)},
                        {"rms", number(e.area_weighted_rms)}};
  j["reference_triangles"] = {{"num_read", e.num_reference_triangles},
                              {"num_removed_by_repair", e.num_repaired_triangles},
                              {"num_zero_area", e.num_zero_area_triangles}};
  j["reference_alignment"] = alignment_json(model.analysis.reference_alignment);
  // Sampled over the surfaces (issue 43): certified maxima both ways.
  const double d = e.reference_bbox_diagonal;
  auto relative = [d](double v) { return number(d > 0 ? v / d : 0.0); };
  const auto &m = e.sampled_mesh_to_reference, &r = e.sampled_reference_to_mesh;
  j["hausdorff_sampled"] = {
      {"mesh_to_reference", number(m.max)},
      {"reference_to_mesh", number(r.max)},
      {"symmetric", number(e.sampled_symmetric)},
      {"relative", relative(e.sampled_symmetric)},
      {"relative_mesh_to_reference", relative(m.max)},
      {"relative_reference_to_mesh", relative(r.max)},
      {"upper_bound",
       {{"mesh_to_reference", number(m.upper_bound)},
        {"reference_to_mesh", number(r.upper_bound)},
        {"symmetric", number(e.sampled_upper_bound)},
        {"relative", relative(e.sampled_upper_bound)}}},
      {"tolerance", number(e.sampling_tolerance)},
      {"relative_tolerance", relative(e.sampling_tolerance)},
      {"num_samples", m.num_samples + r.num_samples}};
  auto means = [](const BoundaryError::SampledSide& s) {
    return ReportDocument{{"mean", number(s.mean)}, {"mean_abs", number(s.mean_abs)}, {"rms", number(s.rms)}};
  };
  j["area_weighted_sampled"] = {{"mesh_to_reference", means(m)}, {"reference_to_mesh", means(r)}};
  j["fraction_on_surface"] = number(e.fraction_on_surface);
  j["on_surface_tolerance_relative"] = relative(e.on_surface_tolerance);
  // A planar mesh (issue 47): its boundary polylines against the reference's outline.
  if (e.planar) {
    auto length = [](const std::vector<BoundaryError::ErrorPatch>& patches) {
      double sum = 0;
      for (const auto& p : patches) sum += p.area;
      return sum;
    };
    j["planar"] = {{"num_reference_outline_segments", e.reference_outline.segments.size()},
                   {"reference_outline_length", number(length(e.reference_patches))},
                   {"mesh_boundary_length", number(length(e.mesh_patches))}};
  } else {
    j["planar"] = nullptr;
  }
  return j;
}

// CONTRACT.md overlap, then extensions. Each list stops after
// kMaxListedOverlap entries (`lists_truncated` says when); counts are always
// complete.
constexpr std::size_t kMaxListedOverlap = 1000;

Json overlap_json(const OverlapReport& o) {
  bool truncated = false;
  auto listed = [&](std::size_t n) {
    truncated = truncated || n > kMaxListedOverlap;
    return std::min(n, kMaxListedOverlap);
  };
  auto ids = [&](const std::vector<Index>& v) {
    return std::vector<Index>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(listed(v.size())));
  };
  Json j;
  j["num_coincident_vertices"] = o.num_coincident_vertices;
  Json groups = Json::array();
  for (std::size_t i = 0; i < listed(o.coincident_groups.size()); ++i)
    groups.push_back(
        {{"vertices", ids(o.coincident_groups[i].vertices)}, {"position", vec3(o.coincident_groups[i].position)}});
  j["coincident_groups"] = std::move(groups);
  j["num_zero_length_edges"] = o.zero_length_edges.size();
  j["num_inverted_cells"] = o.inverted_cells.size();
  j["num_non_manifold_faces"] = o.non_manifold_faces.size();
  j["num_duplicate_cells"] = o.duplicate_cells.size();
  j["num_intersecting_cells"] = o.num_intersecting_cells;
  Json pairs = Json::array(), detail = Json::array();
  for (std::size_t i = 0; i < listed(o.intersecting_pairs.size()); ++i) {
    const IntersectingPair& p = o.intersecting_pairs[i];
    pairs.push_back(p.cells);
    detail.push_back({{"cells", p.cells},
                      {"inside_vertex", p.inside_vertex == kNoIndex ? Json(nullptr) : Json(p.inside_vertex)},
                      {"kinds", {cell_kind_name(p.kinds[0]), cell_kind_name(p.kinds[1])}},
                      {"source_indices", p.source_indices}});
  }
  j["intersecting_pairs"] = std::move(pairs);
  Json markers = Json::array();
  for (std::size_t i = 0; i < listed(o.markers.size()); ++i) {
    const OverlapMarker& m = o.markers[i];
    markers.push_back({{"kind", marker_kind_name(m.kind)}, {"position", vec3(m.position)}, {"count", m.count}});
  }
  j["markers"] = std::move(markers);
  // Extensions.
  j["mode"] = overlap_mode_name(o.mode);
  j["certified_clean"] = o.certified_clean;
  j["coincident_tolerance"] = number(o.coincident_tolerance);
  j["num_intersecting_pairs"] = o.intersecting_pairs.size();
  j["intersecting_pairs_detail"] = std::move(detail);
  j["num_degenerate_cells"] = o.degenerate_cells.size();
  j["num_nonpositive_tet_cells"] = o.nonpositive_tet_cells.size();
  j["num_same_winding_faces"] = o.same_winding_faces.size();
  j["num_boundary_self_intersections"] = o.boundary_self_intersections.size();
  j["num_nested_shells"] = o.num_nested_shells;
  Json edges = Json::array();
  for (std::size_t i = 0; i < listed(o.zero_length_edges.size()); ++i) edges.push_back(o.zero_length_edges[i]);
  j["zero_length_edges"] = std::move(edges);
  j["inverted_cells"] = ids(o.inverted_cells);
  j["degenerate_cells"] = ids(o.degenerate_cells);
  j["nonpositive_tet_cells"] = ids(o.nonpositive_tet_cells);
  j["duplicate_cells"] = ids(o.duplicate_cells);
  j["num_flagged_cells"] = o.num_flagged_cells;
  j["num_candidate_pairs"] = o.num_candidate_pairs;
  j["certificate_rounds"] = o.certificate_rounds;
  j["max_listed"] = kMaxListedOverlap;
  j["lists_truncated"] = truncated;
  // The work budget (issue 22): a pair stage that stopped, and what it left untested.
  j["budget_exceeded"] = o.is_over_budget;
  j["untested_pairs"] = o.is_over_budget ? Json{{"stage", o.over_budget_stage},
                                                {"budget", o.pair_budget},
                                                {"count", o.num_untested_pairs},
                                                {"count_is_lower_bound", !o.is_untested_count_exact}}
                                         : Json(nullptr);
  // A surface mesh's check (issue 47): how quads were split into the
  // triangles tested, and the faces folded onto themselves.
  if (o.is_surface) {
    j["quad_split"] = "unfolded_else_shorter_diagonal";
    j["decided_in_plane"] = o.is_decided_in_plane;
    j["num_self_intersecting_faces"] = o.self_intersecting_faces.size();
    j["self_intersecting_faces"] = ids(o.self_intersecting_faces);
  }
  return j;
}

// Every number under from (objects only, arrays skipped) as "a.b.c" -> value.
void numeric_leaves(const Json& from, const std::string& prefix, std::vector<std::pair<std::string, double>>& out) {
  if (from.is_object()) {
    for (auto it = from.begin(); it != from.end(); ++it)
      numeric_leaves(it.value(), prefix.empty() ? it.key() : prefix + "." + it.key(), out);
  } else if (from.is_number()) {
    out.push_back({prefix, from.get<double>()});
  }
}

// headline additions: cells by kind and the hex fractions.
void add_composition(Json& headline, const CellComposition& c) {
  headline["num_cells"] = c.num_cells;
  headline["num_cells_by_kind"] = {{"hex", c.count[0]},     {"tet", c.count[1]},           {"wedge", c.count[2]},
                                   {"pyramid", c.count[3]}, {"quad", c.num_quads}, {"triangle", c.num_triangles}};
  headline["hex_fraction"] = c.hex_fraction ? number(*c.hex_fraction) : Json(nullptr);
  headline["hex_volume_fraction"] = c.hex_volume_fraction ? number(*c.hex_volume_fraction) : Json(nullptr);
}

// compare: MESH2's headline, mesh and quality summaries (as for MESH), and
// differences{key: MESH2 - MESH} for every number both have (keys as in gates).
Json compare_json(const Json& report, const Analysis::Compared& c) {
  Json j;
  j["headline"] = {{"num_vertices", c.mesh_summary.num_vertices},
                   {"num_hexes", c.mesh_summary.num_hexes},
                   {"min_scaled_jacobian", number(c.quality.scaled_jacobian.min)},
                   {"mean_scaled_jacobian", number(c.quality.scaled_jacobian.mean)},
                   {"num_inverted", c.quality.num_inverted}};
  add_composition(j["headline"], c.composition);
  j["mesh"] = mesh_json(c.mesh_summary);
  j["quality"] = quality_json(c.quality);
  Json differences = Json::object();
  for (const char* part : {"headline", "mesh", "quality"}) {
    std::vector<std::pair<std::string, double>> mine, theirs;
    numeric_leaves(report[part], part, mine);
    numeric_leaves(j[part], part, theirs);
    std::map<std::string, double> base(mine.begin(), mine.end());
    for (const auto& [key, value] : theirs)
      if (const auto it = base.find(key); it != base.end()) differences[key] = number(value - it->second);
  }
  j["differences"] = std::move(differences);
  j["alignment"] = alignment_json(c.alignment);
  return j;
}

Json gates_json(const GateSummary& gates) {
  Json results = Json::array();
  for (const GateResult& g : gates.results) {
    results.push_back({{"rule", g.rule}, {"value", number(g.value)}, {"passed", g.passed}});
    if (!g.note.empty()) results.back()["note"] = g.note;
  }
  return {{"passed", gates.passed}, {"results", std::move(results)}};
}

}  // namespace

ReportDocument report_document(const ReportModel& model) {
  Json j;
  j["schema_version"] = kSchemaVersion;
  j["tool"] = {{"name", "hqview"}, {"version", model.tool_version}};
  // The papers' headline first (an extension of the contract): #V, #H, min
  // and mean cell scaled Jacobian, #inverted.
  j["headline"] = {{"num_vertices", model.analysis.mesh_summary.num_vertices},
                   {"num_hexes", model.analysis.mesh_summary.num_hexes},
                   {"min_scaled_jacobian", number(model.analysis.quality.scaled_jacobian.min)},
                   {"mean_scaled_jacobian", number(model.analysis.quality.scaled_jacobian.mean)},
                   {"num_inverted", model.analysis.quality.num_inverted}};
  add_composition(j["headline"], model.analysis.composition);
  j["input"] = {{"mesh",
                 {{"path", model.analysis.mesh_input.path},
                  {"format", model.analysis.mesh_input.format},
                  {"sha256", model.analysis.mesh_input.sha256}}},
                {"reference", model.analysis.reference_input ? Json{{"path", model.analysis.reference_input->path},
                                                                    {"format", model.analysis.reference_input->format},
                                                                    {"sha256", model.analysis.reference_input->sha256}}
                                                             : Json(nullptr)},
                {"compare", model.analysis.compare ? Json{{"path", model.analysis.compare->input.path},
                                                          {"format", model.analysis.compare->input.format},
                                                          {"sha256", model.analysis.compare->input.sha256}}
                                                   : Json(nullptr)}};
  j["mesh"] = mesh_json(model.analysis.mesh_summary);
  j["quality"] = quality_json(model.analysis.quality);
  // Stages of later releases; null until computed.
  j["glyphs"] = model.analysis.glyphs ? glyphs_json(*model.analysis.glyphs) : Json(nullptr);
  j["overlap"] = model.analysis.overlap ? overlap_json(*model.analysis.overlap) : Json(nullptr);
  // A surface mesh's structure is its quad structure (irregular vertices,
  // separatrices, patches).
  const Analysis& analysis = model.analysis;
  j["structure"] = !analysis.mesh_summary.is_surface ? structure_json(analysis.structure)
                   : analysis.quad_structure        ? quad_structure_json(*analysis.quad_structure)
                                                    : Json(nullptr);
  // Only when asked for (--simulate, --metrics fem_element): other reports keep their bytes.
  if (model.analysis.fem_elements) j["fem"] = fem_json(model.analysis);
  j["boundary_error"] = model.analysis.boundary_error ? boundary_error_json(model) : Json(nullptr);
  j["compare"] = model.analysis.compare ? compare_json(j, *model.analysis.compare) : Json(nullptr);
  // Only with --up auto: other reports keep their bytes.
  if (model.analysis.resting_up) j["up_auto"] = up_auto_json(*model.analysis.resting_up);
  Json views = Json::array();
  for (const ViewEntry& v : model.views) {
    Json cameras = Json::array();
    for (const std::optional<ViewCameraEntry>& c : v.cameras)
      cameras.push_back(c ? Json{{"eye", vec3(c->eye)},
                                 {"target", vec3(c->target)},
                                 {"up", vec3(c->up)},
                                 {"elevation_degrees", number(c->elevation_degrees)},
                                 {"azimuth_degrees", number(c->azimuth_degrees)},
                                 {"projection", c->is_perspective ? "perspective" : "orthographic"},
                                 {"height", number(c->height)},
                                 {"aspect", number(c->aspect)},
                                 {"pixels", Json::array({c->pixel_width, c->pixel_height})}}
                          : Json(nullptr));
    if (cameras.empty()) cameras = Json(std::vector<std::nullptr_t>(v.files.size(), nullptr));
    views.push_back({{"id", v.id}, {"title", v.title}, {"files", v.files}, {"cameras", std::move(cameras)}});
  }
  j["views"] = std::move(views);
  // The data files of the bundle (--data), schema_version 2.
  Json files = Json::array();
  for (const DataFile& f : data_files(model.data)) files.push_back({{"path", f.path}, {"format", f.format}});
  j["data_files"] = std::move(files);
  j["gates"] = gates_json(model.gates);
  // The readers' notes (information: lower-dimensional cells skipped) apart
  // from the warnings, so that a pipeline or the batch index acting on
  // warnings does not act on them.
  j["notes"] = model.analysis.notes;
  j["warnings"] = model.analysis.warnings;
  return j;
}

void set_report_gates(ReportDocument& document, const GateSummary& gates) { document["gates"] = gates_json(gates); }

std::string report_json_text(const ReportDocument& document) {
  return json_message_text(document).dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string report_json(const ReportModel& model) { return report_json_text(report_document(model)); }

}  // namespace hq
