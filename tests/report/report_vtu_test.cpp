// data/annotated.vtu: the file is parsed back here by a reader written for
// the test (header, appended offsets, sizes, values), read by io's own .vtu
// reader, and compared with the model and with the CSV columns it mirrors.
// VTK's own reader checks it in tests/e2e/check_vtu.py.

#include "hqview/report/report_vtu.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <streambuf>
#include <string>
#include <system_error>
#include <vector>

#include "hqview/boundary/boundary_error.h"
#include "hqview/core/error.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/io/vtu_reader.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/overlap.h"
#include "hqview/quality/corner_jacobian.h"
#include "hqview/fem/poisson_check.h"
#include "hqview/quality/hex_metric_field.h"
#include "hqview/quality/quality_field.h"
#include "hqview/report/ordered_chunks.h"
#include "hqview/report/report_csv.h"
#include "support/fixtures.h"
#include "support/surface_fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

struct ModelParts {
  HexMetricSet metrics = all_hex_metrics();
  bool glyphs = true;
  bool overlap = true;
  bool simulate = false;  // the finite-element check (element conditioning and Poisson)
  const TriSurface* reference = nullptr;
};

ReportModel make_model(HexMesh mesh, const ModelParts& parts = {}) {
  ReportModel model;
  model.analysis.mesh = std::move(mesh);
  model.analysis.topology = build_topology(model.analysis.mesh);
  model.analysis.field = compute_quality(model.analysis.mesh, model.analysis.topology);
  model.analysis.structure = compute_structure(model.analysis.mesh, model.analysis.topology);
  model.analysis.metrics = compute_hex_metrics(model.analysis.mesh, parts.metrics);
  if (parts.glyphs)
    model.analysis.glyphs =
        compute_glyphs(model.analysis.mesh.points, model.analysis.field.vertex_quality, 1.0, GlyphOptions{});
  if (parts.overlap)
    model.analysis.overlap = check_overlap(model.analysis.mesh, model.analysis.topology, OverlapOptions{});
  if (parts.reference)
    model.analysis.boundary_error =
        compute_boundary_error(model.analysis.mesh, model.analysis.topology, *parts.reference);
  if (parts.simulate) {
    model.analysis.fem_elements = compute_fem_elements(model.analysis.mesh);
    model.analysis.poisson =
        run_poisson_check(model.analysis.mesh, model.analysis.topology, *model.analysis.fem_elements,
                          PoissonOptions{.min_free_vertices = 1});  // small fixtures solve too
  }
  return model;
}

// A 3x3x3 grid with moved points (varied metric values, a tangled corner)
// and one point no hex uses.
HexMesh perturbed_grid() {
  HexMesh mesh = test::grid(3);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    const double t = static_cast<double>(v);
    mesh.points[v] =
        mesh.points[v] + Vec3{0.13 * std::sin(1.7 * t), 0.11 * std::cos(2.3 * t), 0.09 * std::sin(0.7 * t + 1.0)};
  }
  mesh.points[21] = mesh.points[21] + Vec3{0.9, 0.8, 0.0};  // an interior vertex pulled far: inverted corners
  mesh.points.push_back({7.0, 7.0, 7.0});
  return mesh;
}

// The file as a reader that knows only the format sees it.
struct ParsedArray {
  std::string section, name, type;
  int components = 1;
  std::uint64_t offset = 0;
};

struct ParsedVtu {
  std::map<std::string, std::string> root;  // <VTKFile> attributes
  std::map<std::string, std::string> piece;
  std::map<std::string, std::string> scalars;  // section -> Scalars attribute
  std::vector<ParsedArray> arrays;
  std::string data;  // the AppendedData bytes after '_', up to the closing tail
  std::string tail;

  const ParsedArray* find(const std::string& section, const std::string& name) const {
    for (const ParsedArray& a : arrays)
      if (a.section == section && a.name == name) return &a;
    return nullptr;
  }
};

std::map<std::string, std::string> attributes(const std::string& element) {
  std::map<std::string, std::string> out;
  static const std::regex attribute(R"re(([A-Za-z_]+)="([^"]*)")re");
  for (auto it = std::sregex_iterator(element.begin(), element.end(), attribute); it != std::sregex_iterator(); ++it)
    out[(*it)[1]] = (*it)[2];
  return out;
}

ParsedVtu parse(const std::string& bytes) {
  ParsedVtu p;
  const std::string marker = "<AppendedData encoding=\"raw\">";
  const std::size_t appended = bytes.find(marker);
  EXPECT_NE(appended, std::string::npos);
  const std::size_t underscore = bytes.find('_', appended + marker.size());
  EXPECT_NE(underscore, std::string::npos);
  // Only whitespace between the element and its '_'.
  for (std::size_t i = appended + marker.size(); i < underscore; ++i) EXPECT_TRUE(std::isspace(bytes[i]));
  const std::string header = bytes.substr(0, appended);
  p.tail = "\n  </AppendedData>\n</VTKFile>\n";
  EXPECT_TRUE(bytes.ends_with(p.tail));
  p.data = bytes.substr(underscore + 1, bytes.size() - p.tail.size() - underscore - 1);

  static const std::regex element(R"re(<(/?)([A-Za-z]+)([^>]*)>)re");
  std::string section;
  for (auto it = std::sregex_iterator(header.begin(), header.end(), element); it != std::sregex_iterator(); ++it) {
    const std::string name = (*it)[2];
    const bool closing = (*it)[1] == "/";
    const auto attrs = attributes((*it)[3]);
    if (name == "VTKFile") {
      if (!closing) p.root = attrs;
    } else if (name == "Piece") {
      if (!closing) p.piece = attrs;
    } else if (name == "PointData" || name == "CellData" || name == "Points" || name == "Cells") {
      section = closing ? "" : name;
      if (!closing && attrs.count("Scalars")) p.scalars[name] = attrs.at("Scalars");
    } else if (name == "DataArray") {
      EXPECT_FALSE(section.empty()) << "DataArray outside a section";
      EXPECT_EQ(attrs.at("format"), "appended");
      ParsedArray a;
      a.section = section;
      a.name = attrs.at("Name");
      a.type = attrs.at("type");
      if (attrs.count("NumberOfComponents")) a.components = std::stoi(attrs.at("NumberOfComponents"));
      a.offset = std::stoull(attrs.at("offset"));
      p.arrays.push_back(a);
    }
  }
  return p;
}

std::size_t type_size(const std::string& type) {
  if (type == "Float64" || type == "Int64" || type == "UInt64") return 8;
  if (type == "Int32" || type == "UInt32" || type == "Float32") return 4;
  if (type == "UInt8" || type == "Int8") return 1;
  ADD_FAILURE() << "unexpected type " << type;
  return 1;
}

std::uint64_t block_bytes(const ParsedVtu& p, const ParsedArray& a) {
  std::uint64_t n = 0;
  EXPECT_LE(a.offset + 8, p.data.size());
  std::memcpy(&n, p.data.data() + a.offset, 8);  // little-endian host (x86-64, aarch64)
  return n;
}

template <class T>
std::vector<T> values(const ParsedVtu& p, const std::string& section, const std::string& name) {
  const ParsedArray* a = p.find(section, name);
  if (a == nullptr) {
    ADD_FAILURE() << section << "/" << name << " missing";
    return {};
  }
  EXPECT_EQ(type_size(a->type), sizeof(T)) << name;
  const std::uint64_t n = block_bytes(p, *a);
  std::vector<T> out(n / sizeof(T));
  if (n > 0) std::memcpy(out.data(), p.data.data() + a->offset + 8, n);  // an empty vector's data() may be null
  return out;
}

std::string vtu_bytes(const ReportModel& model) {
  std::ostringstream out(std::ios::binary);
  write_annotated_vtu(model, out);
  return out.str();
}

std::vector<std::string> csv_header(const std::string& csv) {
  std::vector<std::string> columns;
  std::istringstream line(csv.substr(0, csv.find('\n')));
  for (std::string column; std::getline(line, column, ',');) columns.push_back(column);
  return columns;
}

// Bitwise equality, NaN == NaN.
bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(AnnotatedVtu, HeaderOffsetsAndSizesAreConsistent) {
  const ReportModel model = make_model(perturbed_grid());
  const ParsedVtu p = parse(vtu_bytes(model));
  EXPECT_EQ(p.root.at("type"), "UnstructuredGrid");
  EXPECT_EQ(p.root.at("version"), "1.0");
  EXPECT_EQ(p.root.at("byte_order"), "LittleEndian");
  EXPECT_EQ(p.root.at("header_type"), "UInt64");
  EXPECT_EQ(p.root.count("compressor"), 0u);
  const std::size_t nv = model.analysis.mesh.points.size(), nc = model.analysis.mesh.hexes.size();
  EXPECT_EQ(p.piece.at("NumberOfPoints"), std::to_string(nv));
  EXPECT_EQ(p.piece.at("NumberOfCells"), std::to_string(nc));
  EXPECT_EQ(p.scalars.at("PointData"), "quality");
  EXPECT_EQ(p.scalars.at("CellData"), "scaled_jacobian");

  // The blocks tile the appended data: each starts where the previous ends,
  // the last one ends at the closing tags; every block holds one value per
  // point (PointData, Points) or cell (CellData, Cells) and component.
  std::uint64_t expected_offset = 0;
  for (const ParsedArray& a : p.arrays) {
    SCOPED_TRACE(a.section + "/" + a.name);
    EXPECT_EQ(a.offset, expected_offset);
    std::uint64_t tuples = a.section == "PointData" || a.section == "Points" ? nv : nc;
    if (a.name == "connectivity") tuples = 8 * nc;
    EXPECT_EQ(block_bytes(p, a), tuples * static_cast<std::uint64_t>(a.components) * type_size(a.type));
    expected_offset = a.offset + 8 + block_bytes(p, a);
  }
  EXPECT_EQ(expected_offset, p.data.size());

  // The layout the writer reports is the one in the file.
  const std::vector<VtuArrayInfo> layout = annotated_vtu_layout(model);
  ASSERT_EQ(layout.size(), p.arrays.size());
  for (std::size_t i = 0; i < layout.size(); ++i) {
    EXPECT_EQ(layout[i].name, p.arrays[i].name);
    EXPECT_EQ(layout[i].section, p.arrays[i].section);
    EXPECT_EQ(layout[i].offset, p.arrays[i].offset);
    EXPECT_EQ(layout[i].type, p.arrays[i].type);
  }
}

TEST(AnnotatedVtu, ArraysMirrorTheCsvColumns) {
  // Every stage run, so that every CSV column is filled.
  const TriSurface sphere = test::icosphere(2, 1.02);
  ModelParts parts;
  parts.reference = &sphere;
  parts.simulate = true;
  const ReportModel model = make_model(test::hex_ball(3, [](const Vec3&) { return 1.0; }), parts);
  ASSERT_TRUE(model.analysis.poisson && model.analysis.poisson->skipped.empty()) << model.analysis.poisson->skipped;
  const ParsedVtu p = parse(vtu_bytes(model));
  std::ostringstream cells, vertices;
  write_cells_csv(model, cells);
  write_vertices_csv(model, vertices);

  std::set<std::string> cell_arrays, point_arrays, geometry_arrays;
  for (const ParsedArray& a : p.arrays) {
    if (a.section == "CellData") cell_arrays.insert(a.name);
    if (a.section == "PointData") point_arrays.insert(a.name);
    if (a.section == "Points" || a.section == "Cells") geometry_arrays.insert(a.section + "/" + a.name);
  }
  EXPECT_EQ(geometry_arrays,
            (std::set<std::string>{"Points/Points", "Cells/connectivity", "Cells/offsets", "Cells/types"}));
  std::set<std::string> expected_cells = {"min_corner_sj"};
  // cell_type is Cells/types (the native VTK cell type).
  for (const std::string& c : csv_header(cells.str()))
    if (c != "cell" && c != "cell_type") expected_cells.insert(c);
  EXPECT_EQ(cell_arrays, expected_cells);
  std::set<std::string> expected_points;
  for (const std::string& c : csv_header(vertices.str()))
    if (c != "vertex" && c != "x" && c != "y" && c != "z") expected_points.insert(c);
  EXPECT_EQ(point_arrays, expected_points);

  for (const ParsedArray& a : p.arrays) {
    std::string type = "Float64";
    if (a.name == "cluster" || a.name == "coincident_group") type = "Int32";
    if (a.name == "inverted" || a.name == "degenerate" || a.name == "intersecting" || a.name == "boundary" ||
        a.name == "singular" || a.name == "types")
      type = "UInt8";
    if (a.name == "connectivity" || a.name == "offsets" || a.name == "source_index") type = "Int64";
    EXPECT_EQ(a.type, type) << a.name;
  }
}

TEST(AnnotatedVtu, ValuesAreTheModels) {
  const ReportModel model = make_model(perturbed_grid());
  const ParsedVtu p = parse(vtu_bytes(model));
  const std::size_t nv = model.analysis.mesh.points.size(), nc = model.analysis.mesh.hexes.size();

  const auto points = values<double>(p, "Points", "Points");
  ASSERT_EQ(points.size(), 3 * nv);
  for (std::size_t v = 0; v < nv; ++v) {
    EXPECT_EQ(points[3 * v], model.analysis.mesh.points[v].x);
    EXPECT_EQ(points[3 * v + 1], model.analysis.mesh.points[v].y);
    EXPECT_EQ(points[3 * v + 2], model.analysis.mesh.points[v].z);
  }
  const auto connectivity = values<std::int64_t>(p, "Cells", "connectivity");
  const auto offsets = values<std::int64_t>(p, "Cells", "offsets");
  const auto types = values<std::uint8_t>(p, "Cells", "types");
  ASSERT_EQ(connectivity.size(), 8 * nc);
  ASSERT_EQ(offsets.size(), nc);
  ASSERT_EQ(types.size(), nc);
  for (std::size_t h = 0; h < nc; ++h) {
    EXPECT_EQ(offsets[h], static_cast<std::int64_t>(8 * (h + 1)));
    EXPECT_EQ(types[h], 12);  // VTK_HEXAHEDRON
    for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(connectivity[8 * h + i], model.analysis.mesh.hexes[h][i]);
  }

  const auto sj = values<double>(p, "CellData", "scaled_jacobian");
  const auto min_corner = values<double>(p, "CellData", "min_corner_sj");
  ASSERT_EQ(sj.size(), nc);
  ASSERT_EQ(min_corner.size(), nc);
  std::vector<std::vector<double>> corners;
  for (int i = 0; i < 8; ++i) corners.push_back(values<double>(p, "CellData", "corner_sj_" + std::to_string(i)));
  bool any_negative_corner = false;
  for (std::size_t h = 0; h < nc; ++h) {
    EXPECT_EQ(sj[h], model.analysis.field.cell_scaled_jacobian[h]);
    double lowest = corners[0][h];
    for (std::size_t i = 0; i < 8; ++i) {
      EXPECT_EQ(corners[i][h], model.analysis.field.corner_scaled_jacobian[8 * h + i]);
      lowest = std::min(lowest, corners[i][h]);
    }
    EXPECT_EQ(min_corner[h], lowest);
    any_negative_corner |= lowest < 0;
  }
  EXPECT_TRUE(any_negative_corner) << "the fixture should have a tangled corner";
  for (int m = 0; m < kNumHexMetrics; ++m) {
    const auto metric = static_cast<HexMetric>(m);
    if (metric == HexMetric::scaled_jacobian) continue;
    const auto column = values<double>(p, "CellData", std::string(hex_metric_name(metric)));
    ASSERT_EQ(column.size(), nc) << hex_metric_name(metric);
    for (std::size_t h = 0; h < nc; ++h) EXPECT_TRUE(same(column[h], model.analysis.metrics.of(metric)[h]));
  }
  const auto intersecting = values<std::uint8_t>(p, "CellData", "intersecting");
  for (std::size_t h = 0; h < nc; ++h) EXPECT_EQ(intersecting[h], model.analysis.overlap->cell_intersecting[h] ? 1 : 0);
  const auto gradation = values<double>(p, "CellData", "size_gradation");
  ASSERT_EQ(gradation.size(), nc);
  for (std::size_t h = 0; h < nc; ++h) EXPECT_TRUE(same(gradation[h], model.analysis.structure.cell_gradation[h]));
  const auto singular = values<std::uint8_t>(p, "PointData", "singular");
  ASSERT_EQ(singular.size(), nv);
  for (std::size_t v = 0; v < nv; ++v) EXPECT_EQ(singular[v], model.analysis.structure.vertex_singular[v]);

  const auto quality = values<double>(p, "PointData", "quality");
  const auto radius = values<double>(p, "PointData", "glyph_radius");
  const auto cluster = values<std::int32_t>(p, "PointData", "cluster");
  const auto group = values<std::int32_t>(p, "PointData", "coincident_group");
  const auto boundary = values<std::uint8_t>(p, "PointData", "boundary");
  ASSERT_EQ(quality.size(), nv);
  std::size_t num_glyphs = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    EXPECT_TRUE(same(quality[v], model.analysis.field.vertex_quality[v]));
    EXPECT_EQ(cluster[v], model.analysis.glyphs->vertex_cluster[v]);
    EXPECT_EQ(group[v], -1);  // no two points coincide
    EXPECT_EQ(boundary[v], model.analysis.topology.is_boundary_vertex[v] ? 1 : 0);
    if (v + 1 == nv) {
      EXPECT_TRUE(std::isnan(quality[v])) << "the unreferenced point";
      EXPECT_TRUE(std::isnan(radius[v]));
      EXPECT_EQ(cluster[v], -1);
    } else {
      EXPECT_EQ(radius[v], model.analysis.glyphs->vertex_radius[v]);
      num_glyphs += radius[v] > 0;
      EXPECT_EQ(radius[v] > 0, cluster[v] >= 0);
    }
  }
  EXPECT_GT(num_glyphs, 0u);
}

TEST(AnnotatedVtu, IoReaderReadsTheMeshBack) {
  const ReportModel model = make_model(perturbed_grid());
  const LoadedMesh loaded = read_vtu(vtu_bytes(model), "annotated.vtu");
  EXPECT_EQ(loaded.format, "vtu-appended");
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_EQ(loaded.mesh.points.size(), model.analysis.mesh.points.size());
  for (std::size_t v = 0; v < model.analysis.mesh.points.size(); ++v) {
    EXPECT_EQ(loaded.mesh.points[v].x, model.analysis.mesh.points[v].x);
    EXPECT_EQ(loaded.mesh.points[v].y, model.analysis.mesh.points[v].y);
    EXPECT_EQ(loaded.mesh.points[v].z, model.analysis.mesh.points[v].z);
  }
  EXPECT_EQ(loaded.mesh.hexes, model.analysis.mesh.hexes);
}

TEST(AnnotatedVtu, LeavesOutStagesThatDidNotRun) {
  ModelParts parts;
  parts.metrics = HexMetricSet{};
  insert(parts.metrics, HexMetric::skew);
  insert(parts.metrics, HexMetric::volume);
  parts.glyphs = false;
  parts.overlap = false;
  const ReportModel model = make_model(test::grid(2), parts);
  const ParsedVtu p = parse(vtu_bytes(model));
  std::set<std::string> names;
  for (const ParsedArray& a : p.arrays) names.insert(a.name);
  for (const char* present : {"scaled_jacobian", "min_corner_sj", "skew", "volume", "inverted", "degenerate", "quality",
                              "boundary", "singular", "size_gradation", "Points", "connectivity"})
    EXPECT_TRUE(names.count(present)) << present;
  for (const char* absent : {"edge_ratio", "taper", "shape", "equiangle_skew", "intersecting", "glyph_radius",
                             "cluster", "coincident_group", "boundary_error"})
    EXPECT_FALSE(names.count(absent)) << absent;
  // A unit grid: every volume is 1 (hand computation), skew 0.
  for (double volume : values<double>(p, "CellData", "volume")) EXPECT_NEAR(volume, 1.0, 1e-14);
  for (double skew : values<double>(p, "CellData", "skew")) EXPECT_NEAR(skew, 0.0, 1e-14);
}

TEST(AnnotatedVtu, FlagsAndSentinels) {
  // Cell 0: the unit cube; 1: inside out (every frame left-handed); 2: node 1
  // collapsed onto node 0 (Verdict's 1e30); the three share no point.
  HexMesh mesh;
  const std::array<std::array<Vec3, 8>, 3> cells = {test::cube_corners(), test::inverted_hex(), [] {
                                                      auto c = test::cube_corners();
                                                      c[1] = c[0];
                                                      return c;
                                                    }()};
  for (std::size_t h = 0; h < cells.size(); ++h) {
    Hex hex;
    for (int i = 0; i < 8; ++i) {
      hex[i] = static_cast<Index>(mesh.points.size());
      mesh.points.push_back(cells[h][i] + Vec3{3.0 * static_cast<double>(h), 0, 0});
    }
    mesh.hexes.push_back(hex);
  }
  const ReportModel model = make_model(mesh);
  const ParsedVtu p = parse(vtu_bytes(model));
  const auto sj = values<double>(p, "CellData", "scaled_jacobian");
  EXPECT_EQ(sj[0], 1.0);
  EXPECT_EQ(sj[1], -1.0);
  EXPECT_EQ(sj[2], 1e30);  // the sentinel, written as it is
  EXPECT_EQ(values<std::uint8_t>(p, "CellData", "inverted"), (std::vector<std::uint8_t>{0, 1, 0}));
  EXPECT_EQ(values<std::uint8_t>(p, "CellData", "degenerate"), (std::vector<std::uint8_t>{0, 0, 1}));
  // Points 16 and 17 (cell 2's corners 0 and 1) coincide: one group.
  const auto group = values<std::int32_t>(p, "PointData", "coincident_group");
  for (std::size_t v = 0; v < group.size(); ++v) EXPECT_EQ(group[v], v == 16 || v == 17 ? 0 : -1) << v;
}

TEST(AnnotatedVtu, BoundaryErrorIsNaNInside) {
  const HexMesh ball = test::hex_ball(4, [](const Vec3&) { return 1.0; });
  const TriSurface sphere = test::icosphere(3, 1.02);
  ModelParts parts;
  parts.reference = &sphere;
  const ReportModel model = make_model(ball, parts);
  const ParsedVtu p = parse(vtu_bytes(model));
  const auto error = values<double>(p, "PointData", "boundary_error");
  ASSERT_EQ(error.size(), model.analysis.mesh.points.size());
  std::size_t num_boundary = 0;
  for (std::size_t v = 0; v < error.size(); ++v) {
    EXPECT_TRUE(same(error[v], model.analysis.boundary_error->vertex_error[v]));
    if (model.analysis.topology.is_boundary_vertex[v]) {
      ++num_boundary;
      // Boundary points lie on the unit sphere, inside the reference
      // (radius 1.02 faceted): the mesh is inside, within 0.02.
      EXPECT_TRUE(std::isfinite(error[v]));
      EXPECT_LE(std::abs(error[v]), 0.021);
    } else {
      EXPECT_TRUE(std::isnan(error[v])) << v;
    }
  }
  EXPECT_GT(num_boundary, 0u);
}

TEST(AnnotatedVtu, MeshWithoutHexesGivesEmptyCellArrays) {
  HexMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 2, 3}};
  const ReportModel model = make_model(mesh);
  const std::string bytes = vtu_bytes(model);
  const ParsedVtu p = parse(bytes);
  EXPECT_EQ(p.piece.at("NumberOfCells"), "0");
  EXPECT_EQ(p.piece.at("NumberOfPoints"), "2");
  EXPECT_TRUE(values<std::int64_t>(p, "Cells", "connectivity").empty());
  EXPECT_EQ(values<double>(p, "Points", "Points"), (std::vector<double>{0, 0, 0, 1, 2, 3}));
  const auto quality = values<double>(p, "PointData", "quality");
  ASSERT_EQ(quality.size(), 2u);
  EXPECT_TRUE(std::isnan(quality[0]) && std::isnan(quality[1]));
}

TEST(AnnotatedVtu, FieldOfTheWrongLengthIsAnInternalError) {
  ReportModel model = make_model(test::grid(2));
  model.analysis.field.vertex_quality.pop_back();
  try {
    vtu_bytes(model);
    ADD_FAILURE() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("internal: annotated.vtu: vertex_quality has 26 entries, expected 27"),
              std::string::npos)
        << e.what();
  }
}

TEST(AnnotatedVtu, SameModelSameBytes) {
  const ReportModel model = make_model(perturbed_grid());
  EXPECT_EQ(vtu_bytes(model), vtu_bytes(model));
}

// A stream buffer that takes `room` bytes, then fails as a full disk does:
// the write returns short with errno ENOSPC, on whichever thread wrote.
class FullDisk : public std::streambuf {
 public:
  explicit FullDisk(std::size_t room) : room_(room) {}

 protected:
  std::streamsize xsputn(const char*, std::streamsize n) override {
    if (static_cast<std::size_t>(n) <= room_) {
      room_ -= static_cast<std::size_t>(n);
      return n;
    }
    errno = ENOSPC;
    return 0;
  }
  int_type overflow(int_type c) override { return xsputn(nullptr, 1) == 1 ? c : traits_type::eof(); }

 private:
  std::size_t room_;
};

// The pipelines' writing stage runs on any thread and errno is per thread:
// the cause of a failed write must come from where it failed (a file size
// limit was once reported as "No such file or directory", the main
// thread's errno). Run with a stale errno on this thread, 2 threads.
TEST(AnnotatedVtu, AFailedWriteKeepsItsCause) {
  const ReportModel model = make_model(perturbed_grid());
  const std::size_t size = vtu_bytes(model).size();
  // Rooms that end inside the arrays' blocks, which a pipeline stage writes
  // (the header and tail are written on the calling thread, whose errno
  // the bundle writer reads after its flush).
  for (const std::size_t room : {std::size_t{0}, size / 3, 2 * size / 3}) {
    FullDisk disk(room);
    std::ostream out(&disk);
    errno = ENOENT;
    try {
      write_annotated_vtu(model, out, VtuData::zlib);
      ADD_FAILURE() << "no error with room for " << room << " of " << size << " bytes";
    } catch (const std::system_error& e) {
      EXPECT_EQ(e.code().value(), ENOSPC) << e.what();
    }
  }
  // Chunks written in order by a pipeline: the same.
  FullDisk disk(10);
  std::ostream out(&disk);
  errno = ENOENT;
  try {
    write_ordered_chunks(out, 64, [](std::size_t i, std::string& text) { text.assign(100 + i, 'x'); });
    ADD_FAILURE() << "no error";
  } catch (const std::system_error& e) {
    EXPECT_EQ(e.code().value(), ENOSPC);
  }
}

}  // namespace
}  // namespace hq
