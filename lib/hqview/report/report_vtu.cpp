#include "hqview/report/report_vtu.h"

#include "hqview/report/ordered_chunks.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/core/progress.h"
#include "hqview/io/vtk_cells.h"
#include "hqview/quality/hex_metrics.h"
#include "hqview/report/deflate.h"
#include "hqview/report/ordered_pipeline.h"
#include "hqview/report/cell_rows.h"
#include "hqview/report/report_csv.h"

#include <tbb/task_arena.h>

namespace hq {
namespace {

// Values converted per chunk: 64 Ki values, at most 512 KiB of buffer.
constexpr std::size_t kChunkValues = std::size_t{1} << 16;

template <class T>
constexpr const char* vtk_type_name() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::int64_t> || std::is_same_v<T, std::int32_t> ||
                std::is_same_v<T, std::uint8_t>);
}

template <class T>
void store_little_endian(T value, unsigned char* out) {
  std::memcpy(out, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(out, out + sizeof(T));
}

// An array of the file: its header entry and a function that writes values
// [first, first + count) little-endian into a buffer.
struct VtuArray {
  VtuArrayInfo info;
  std::size_t value_size = 0;
  std::function<void(std::size_t first, std::size_t count, unsigned char* out)> fill;
};

template <class T, class Get>
VtuArray make_array(const char* section, std::string name, int components, std::size_t num_values, Get get) {
  VtuArray a;
  a.info.section = section;
  a.info.name = std::move(name);
  a.info.type = vtk_type_name<T>();
  a.info.components = components;
  a.info.num_values = num_values;
  a.value_size = sizeof(T);
  a.fill = [get](std::size_t first, std::size_t count, unsigned char* out) {
    for (std::size_t i = 0; i < count; ++i) store_little_endian(static_cast<T>(get(first + i)), out + i * sizeof(T));
  };
  return a;
}

template <class T>
VtuArray copy_array(const char* section, std::string name, const std::vector<T>& values) {
  return make_array<T>(section, std::move(name), 1, values.size(), [&values](std::size_t i) { return values[i]; });
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A per-element input with the wrong length is a bug upstream: refuse it
// rather than write a file VTK rejects (or read past a vector).
template <class Vector>
void require_size(const Vector& v, std::size_t expected, const char* what) {
  if (v.size() != expected)
    throw Error(std::string("internal: annotated.vtu: ") + what + " has " + std::to_string(v.size()) +
                " entries, expected " + std::to_string(expected));
}

void check_sizes(const ReportModel& model) {
  const std::size_t nv = model.analysis.mesh.points.size(), nc = model.analysis.mesh.hexes.size();
  const auto num_cells = static_cast<std::size_t>(hq::num_cells(model.analysis.mesh));
  const QualityField& q = model.analysis.field;
  require_size(q.vertex_quality, nv, "vertex_quality");
  require_size(q.cell_scaled_jacobian, num_cells, "cell_scaled_jacobian");
  require_size(q.corner_scaled_jacobian, q.corner_begin[kNumCellKinds], "corner_scaled_jacobian");
  require_size(q.corner_degenerate_mask, num_cells, "corner_degenerate_mask");
  require_size(model.analysis.topology.is_boundary_vertex, nv, "is_boundary_vertex");
  for (const std::vector<double>& values : model.analysis.metrics.values)
    if (!values.empty()) require_size(values, nc, "a metric");
  if (model.analysis.glyphs) {
    require_size(model.analysis.glyphs->vertex_radius, nv, "glyph vertex_radius");
    require_size(model.analysis.glyphs->vertex_cluster, nv, "glyph vertex_cluster");
  }
  if (model.analysis.overlap) {
    require_size(model.analysis.overlap->vertex_coincident_group, nv, "vertex_coincident_group");
    if (model.analysis.overlap->cell_intersecting.size() < nc)  // one per volume cell, hexes first: at least nc
      require_size(model.analysis.overlap->cell_intersecting, nc, "cell_intersecting");
  }
  if (model.analysis.boundary_error)
    require_size(model.analysis.boundary_error->vertex_error, nv, "boundary vertex_error");
  require_size(model.analysis.structure.vertex_singular, nv, "vertex_singular");
  require_size(model.analysis.structure.cell_gradation, num_cells, "cell_gradation");
  if (model.analysis.fem_elements) require_size(model.analysis.fem_elements->kappa, nc, "fem kappa");
  if (model.analysis.poisson && model.analysis.poisson->skipped.empty())
    require_size(model.analysis.poisson->cell_error_density, nc, "fem error density");
}

// Every array, in file order (PointData, CellData, Points, Cells, the order
// of VTK's own writer), offsets filled in.
std::vector<VtuArray> build_arrays(const ReportModel& model) {
  check_sizes(model);
  const std::size_t num_points = model.analysis.mesh.points.size();
  const QualityField& q = model.analysis.field;
  std::vector<VtuArray> arrays;

  // PointData: the columns of vertices.csv (x, y, z are the points).
  arrays.push_back(copy_array("PointData", "quality", q.vertex_quality));
  if (model.analysis.glyphs) {
    const GlyphResult& g = *model.analysis.glyphs;
    arrays.push_back(make_array<double>("PointData", "glyph_radius", 1, num_points, [&g, &q](std::size_t v) {
      return std::isnan(q.vertex_quality[v]) ? kNaN : g.vertex_radius[v];
    }));
    arrays.push_back(copy_array<std::int32_t>("PointData", "cluster", g.vertex_cluster));
  }
  if (model.analysis.overlap)
    arrays.push_back(
        copy_array<std::int32_t>("PointData", "coincident_group", model.analysis.overlap->vertex_coincident_group));
  arrays.push_back(make_array<std::uint8_t>("PointData", "boundary", 1, num_points, [&model](std::size_t v) {
    return model.analysis.topology.is_boundary_vertex[v] != 0 ? 1 : 0;
  }));
  if (model.analysis.boundary_error)
    arrays.push_back(copy_array("PointData", "boundary_error", model.analysis.boundary_error->vertex_error));
  arrays.push_back(make_array<std::uint8_t>("PointData", "singular", 1, num_points, [&model](std::size_t v) {
    return model.analysis.structure.vertex_singular[v] != 0 ? 1 : 0;
  }));

  // CellData: the columns of cells.csv, plus min_corner_sj, for every
  // volume cell (hexes, then tets, wedges, pyramids); a value a cell's kind
  // does not have is NaN (cell_rows.h).
  // Shared by the arrays' fill functions, which run after this returns.
  const auto rows = std::make_shared<const CellRows>(model.analysis);
  const std::size_t num_cells = rows->num_cells();
  const std::size_t nh = rows->num_hexes();
  arrays.push_back(copy_array("CellData", "scaled_jacobian", q.cell_scaled_jacobian));
  for (int i = 0; i < 8; ++i) {
    arrays.push_back(make_array<double>("CellData", "corner_sj_" + std::to_string(i), 1, num_cells,
                                        [rows, i](std::size_t c) { return rows->corner(c, i); }));
  }
  arrays.push_back(make_array<double>("CellData", "min_corner_sj", 1, num_cells, [rows](std::size_t c) {
    double lowest = rows->corner(c, 0);
    for (int i = 1; i < rows->num_corner_values(c); ++i) lowest = std::min(lowest, rows->corner(c, i));
    return lowest;
  }));
  for (int m = 0; m < kNumHexMetrics; ++m) {
    const auto metric = static_cast<HexMetric>(m);
    if (metric == HexMetric::scaled_jacobian || model.analysis.metrics.of(metric).empty()) continue;
    arrays.push_back(make_array<double>("CellData", std::string(hex_metric_name(metric)), 1, num_cells,
                                        [rows, m](std::size_t c) { return rows->metric(m, c); }));
  }
  arrays.push_back(make_array<std::uint8_t>("CellData", "inverted", 1, num_cells,
                                            [&q](std::size_t c) { return cell_is_inverted(q, c) ? 1 : 0; }));
  arrays.push_back(make_array<std::uint8_t>("CellData", "degenerate", 1, num_cells,
                                            [&q](std::size_t c) { return cell_is_degenerate(q, c) ? 1 : 0; }));
  if (model.analysis.overlap) {
    // A volume mesh's hexes (0 for its other cells); every face of a surface mesh.
    const std::vector<char>& intersecting = model.analysis.overlap->cell_intersecting;
    const std::size_t checked = model.analysis.overlap->is_surface ? intersecting.size() : nh;
    arrays.push_back(make_array<std::uint8_t>("CellData", "intersecting", 1, num_cells, [&intersecting, checked](std::size_t c) {
      return c < checked && intersecting[c] != 0 ? 1 : 0;
    }));
  }
  const auto hex_only = [&](const char* name, const std::vector<double>& values) {
    return make_array<double>("CellData", name, 1, num_cells,
                              [&values, nh](std::size_t c) { return CellRows::hex_only(values, c, nh); });
  };
  // Every kind (check_sizes: one value per volume cell).
  const std::vector<double>& gradation = model.analysis.structure.cell_gradation;
  arrays.push_back(
      make_array<double>("CellData", "size_gradation", 1, num_cells, [&gradation](std::size_t c) { return gradation[c]; }));
  if (const auto& fem = model.analysis.fem_elements) {
    arrays.push_back(hex_only("fem_kappa", fem->kappa));
    arrays.push_back(hex_only("fem_lambda_max", fem->lambda_max));
    arrays.push_back(hex_only("fem_det_j_min", fem->det_j_min));
    arrays.push_back(hex_only("fem_det_j_max", fem->det_j_max));
  }
  if (const auto& poisson = model.analysis.poisson; poisson && poisson->skipped.empty()) {
    arrays.push_back(hex_only("fem_l2_error_share", poisson->cell_l2_share));
    arrays.push_back(hex_only("fem_h1_error_share", poisson->cell_h1_share));
    arrays.push_back(hex_only("fem_error_density", poisson->cell_error_density));
  }
  // Where each cell is in its file (mesh.h, source_index); its kind is
  // Cells/types (cells.csv cell_type).
  arrays.push_back(make_array<std::int64_t>("CellData", "source_index", 1, num_cells,
                                              [rows](std::size_t c) { return rows->source_index(c); }));

  // Points and Cells, each cell with its native VTK type and corners (VTK order).
  const std::vector<Vec3>& points = model.analysis.mesh.points;
  arrays.push_back(make_array<double>("Points", "Points", 3, 3 * num_points, [&points](std::size_t i) {
    const Vec3& p = points[i / 3];
    return i % 3 == 0 ? p.x : i % 3 == 1 ? p.y : p.z;
  }));
  const Mesh& mesh = model.analysis.mesh;
  if (num_cells == nh) {
    const std::vector<Hex>& hexes = mesh.hexes;
    arrays.push_back(make_array<std::int64_t>("Cells", "connectivity", 1, 8 * num_cells,
                                              [&hexes](std::size_t i) { return hexes[i / 8][i % 8]; }));
    arrays.push_back(make_array<std::int64_t>("Cells", "offsets", 1, num_cells,
                                              [](std::size_t h) { return static_cast<std::int64_t>(8 * (h + 1)); }));
    arrays.push_back(make_array<std::uint8_t>("Cells", "types", 1, num_cells,
                                              [](std::size_t) { return static_cast<std::uint8_t>(vtk::kHexahedron); }));
  } else {
    // Mixed: the flat connectivity, offsets and types read from the blocks
    // as they are written (one run per block, in block order), not laid
    // out in arrays beside everything else (2.18 M tets: 89 MB).
    struct Run {
      std::size_t first_cell = 0, first_value = 0, num_cells = 0;
      std::size_t corners = 0;
      std::uint8_t type = 0;
      std::function<Index(std::size_t, std::size_t)> corner;  // (cell in the block, corner)
    };
    auto runs = std::make_shared<std::vector<Run>>();
    std::size_t cells_before = 0, values_before = 0;
    for_each_block(mesh, [&](auto kind, const auto& cells) {
      if (cells.empty()) return;
      using Cell = typename std::decay_t<decltype(cells)>::value_type;
      runs->push_back({cells_before, values_before, cells.size(), std::tuple_size_v<Cell>,
                       static_cast<std::uint8_t>(CellKindTable<kind()>::vtk_type),
                       [&cells](std::size_t c, std::size_t j) { return cells[c][j]; }});
      cells_before += cells.size();
      values_before += cells.size() * std::tuple_size_v<Cell>;
    });
    const auto run_of_value = [runs](std::size_t i) -> const Run& {
      std::size_t r = 0;
      while (r + 1 < runs->size() && (*runs)[r + 1].first_value <= i) ++r;
      return (*runs)[r];
    };
    const auto run_of_cell = [runs](std::size_t c) -> const Run& {
      std::size_t r = 0;
      while (r + 1 < runs->size() && (*runs)[r + 1].first_cell <= c) ++r;
      return (*runs)[r];
    };
    arrays.push_back(make_array<std::int64_t>("Cells", "connectivity", 1, values_before, [run_of_value](std::size_t i) {
      const Run& r = run_of_value(i);
      const std::size_t k = i - r.first_value;
      return static_cast<std::int64_t>(r.corner(k / r.corners, k % r.corners));
    }));
    arrays.push_back(make_array<std::int64_t>("Cells", "offsets", 1, cells_before, [run_of_cell](std::size_t c) {
      const Run& r = run_of_cell(c);
      return static_cast<std::int64_t>(r.first_value + (c - r.first_cell + 1) * r.corners);
    }));
    arrays.push_back(make_array<std::uint8_t>("Cells", "types", 1, cells_before,
                                              [run_of_cell](std::size_t c) { return run_of_cell(c).type; }));
  }

  std::uint64_t offset = 0;
  for (VtuArray& a : arrays) {
    a.info.offset = offset;
    offset += sizeof(std::uint64_t) + a.info.num_values * a.value_size;
  }
  return arrays;
}

void append_data_array(std::string& xml, const VtuArrayInfo& info, std::string_view indent) {
  xml += indent;
  xml += "<DataArray type=\"";
  xml += info.type;
  xml += "\" Name=\"";
  xml += info.name;  // HQView's own identifiers: nothing to escape
  xml += '"';
  if (info.components != 1) {
    xml += " NumberOfComponents=\"";
    xml += std::to_string(info.components);
    xml += '"';
  }
  xml += " format=\"appended\" offset=\"";
  xml += std::to_string(info.offset);
  xml += "\"/>\n";
}

std::string xml_header(const ReportModel& model, const std::vector<VtuArray>& arrays, VtuData encoding) {
  std::string xml =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"";
  if (encoding == VtuData::zlib) xml += " compressor=\"vtkZLibDataCompressor\"";
  xml +=
      ">\n"
      "  <UnstructuredGrid>\n";
  xml += "    <Piece NumberOfPoints=\"" + std::to_string(model.analysis.mesh.points.size()) + "\" NumberOfCells=\"" +
         std::to_string(hq::num_cells(model.analysis.mesh)) + "\">\n";
  // ParaView colours by the active scalars when a file is opened.
  const std::pair<const char*, const char*> sections[] = {{"PointData", " Scalars=\"quality\""},
                                                          {"CellData", " Scalars=\"scaled_jacobian\""},
                                                          {"Points", ""},
                                                          {"Cells", ""}};
  for (const auto& [section, attributes] : sections) {
    xml += "      <";
    xml += section;
    xml += attributes;
    xml += ">\n";
    for (const VtuArray& a : arrays)
      if (a.info.section == section) append_data_array(xml, a.info, "        ");
    xml += "      </";
    xml += section;
    xml += ">\n";
  }
  xml +=
      "    </Piece>\n"
      "  </UnstructuredGrid>\n"
      "  <AppendedData encoding=\"raw\">\n"
      "   _";
  return xml;
}

constexpr std::string_view kTail = "\n  </AppendedData>\n</VTKFile>\n";

// Compressed (VTK's vtkZLibDataCompressor with UInt64 headers): each array
// is split into kZlibBlockBytes blocks (the last one shorter), each an
// independent zlib stream, preceded by the header [number of blocks, block
// size, last block size (0: full), compressed size of each block]. The block
// size is fixed, so the bytes do not depend on the thread count. The blocks
// of every array go through one pipeline: handed out in file order (an
// array's first block compressed there, as it decides how the rest are
// written), compressed in parallel, and gathered in order, an array written
// once its last block is in; so the compression of one array overlaps the
// writing of the one before, and at most one array's compressed blocks wait
// in memory. Offsets are known only once the arrays are written: the XML
// header is written last, over a placeholder as long as its longest form
// (20-digit offsets), any shortfall made up with spaces before the '_' (blank
// text that VTK, ParaView and meshio skip).
constexpr std::size_t kZlibBlockBytes = std::size_t{1} << 17;
constexpr double kStoreAbove = 0.75;

// The last block of one repeated value a thread compressed, and its zlib
// stream. Columns of one value (a tet's corner values 4-7, the cell types of
// a mesh of one kind, flags that are all 0) give the same raw block again
// and again: the same bytes in, the same stream out (libdeflate is
// deterministic), so the stream is copied instead of compressed again (on
// 2.18 M tets, 4 NaN columns of 17 MB: a quarter of the file's deflate
// time). A block is of one value when it equals itself shifted by one value
// (memcmp stops at the first difference: at once, for most data).
class ConstantBlock {
 public:
  void append_zlib_stream(std::span<const unsigned char> raw, std::size_t value_size, bool stored,
                          std::vector<unsigned char>& out) {
    const bool is_constant =
        raw.size() > value_size && std::memcmp(raw.data(), raw.data() + value_size, raw.size() - value_size) == 0;
    if (!is_constant) {
      hq::append_zlib_stream(raw, out, stored);
      return;
    }
    if (stored != stored_ || !std::equal(raw.begin(), raw.end(), raw_.begin(), raw_.end())) {
      raw_.assign(raw.begin(), raw.end());
      stored_ = stored;
      stream_.clear();
      hq::append_zlib_stream(raw, stream_, stored);
    }
    out.insert(out.end(), stream_.begin(), stream_.end());
  }

 private:
  std::vector<unsigned char> raw_, stream_;
  bool stored_ = false;
};

// One block of one array, and what the pipeline made of it.
struct VtuBlock {
  std::size_t array = 0, block = 0;
  bool compressed = false;              // block 0: compressed when handed out
  std::vector<unsigned char> data;      // the zlib stream
};

void write_compressed(const ReportModel& model, std::vector<VtuArray> arrays, std::ostream& out) {
  for (VtuArray& a : arrays) a.info.offset = std::numeric_limits<std::uint64_t>::max();
  const std::size_t placeholder = xml_header(model, arrays, VtuData::zlib).size();
  const std::streampos start = out.tellp();
  out << std::string(placeholder, ' ');
  throw_if_failed(out);  // here, on the calling thread, before the pipeline's stages
  std::uint64_t total_bytes = 0;
  for (const VtuArray& a : arrays) total_bytes += a.info.num_values * a.value_size;
  progress::set_total(total_bytes);

  const auto num_blocks = [&](std::size_t i) {
    return (arrays[i].info.num_values * arrays[i].value_size + kZlibBlockBytes - 1) / kZlibBlockBytes;
  };
  std::vector<char> stored(arrays.size(), 0);  // set with an array's first block, before the others exist
  const auto compress = [&](VtuBlock& b) {
    thread_local std::vector<unsigned char> raw;
    thread_local ConstantBlock last_constant;
    const VtuArray& a = arrays[b.array];
    const std::size_t values_per_block = kZlibBlockBytes / a.value_size;
    const std::size_t first = b.block * values_per_block;
    const std::size_t count = std::min<std::size_t>(values_per_block, a.info.num_values - first);
    raw.resize(count * a.value_size);
    a.fill(first, count, raw.data());
    last_constant.append_zlib_stream(raw, a.value_size, stored[b.array] != 0, b.data);
    b.compressed = true;
    progress::add_done(raw.size());
    return static_cast<double>(b.data.size()) / static_cast<double>(std::max<std::size_t>(raw.size(), 1));
  };

  // Handed out: array by array, block by block; an array without values
  // still passes as one empty token, for its header.
  std::vector<std::pair<std::size_t, std::size_t>> order;  // (array, block), in file order
  for (std::size_t i = 0; i < arrays.size(); ++i)
    for (std::size_t k = 0; k < std::max<std::size_t>(num_blocks(i), 1); ++k) order.emplace_back(i, k);
  // Four blocks in flight per thread: the compressors never wait on the writer.
  const auto tokens = static_cast<std::size_t>(4 * tbb::this_task_arena::max_concurrency());
  const auto hand_out = [&](std::size_t i, VtuBlock& b) {
    b.compressed = false;
    b.data.clear();
    std::tie(b.array, b.block) = order[i];
    // The first block decides for the rest of the array: the measured
    // values (doubles with noisy low bits) shrink by 6-8 % for most of the
    // time of the whole file, and the coordinates by 16-22 % (at 363k hexes,
    // 1.4 MB saved for 30 ms), so an array whose first block keeps more than
    // kStoreAbove of its size is stored (zlib streams of stored blocks). The
    // choice depends on the data only, never on the thread count.
    if (num_blocks(b.array) == 0)
      b.compressed = true;
    else if (b.block == 0)
      stored[b.array] = compress(b) > kStoreAbove;
  };

  // Gathered in order; an array is written when its last block is in.
  std::uint64_t offset = 0;
  std::vector<std::vector<unsigned char>> blocks;
  std::vector<unsigned char> block_header;
  const auto gather = [&](VtuBlock& b) {
    const std::size_t n = num_blocks(b.array);
    if (n > 0) blocks.push_back(std::move(b.data));
    if (b.block + 1 < n) return;
    VtuArray& a = arrays[b.array];
    a.info.offset = offset;
    block_header.assign((3 + n) * sizeof(std::uint64_t), 0);
    const auto put = [&](std::size_t i, std::uint64_t v) { store_little_endian(v, &block_header[8 * i]); };
    put(0, n);
    put(1, kZlibBlockBytes);
    put(2, (a.info.num_values * a.value_size) % kZlibBlockBytes);
    for (std::size_t k = 0; k < n; ++k) put(3 + k, blocks[k].size());
    out.write(reinterpret_cast<const char*>(block_header.data()), static_cast<std::streamsize>(block_header.size()));
    offset += block_header.size();
    for (const std::vector<unsigned char>& block : blocks) {
      out.write(reinterpret_cast<const char*>(block.data()), static_cast<std::streamsize>(block.size()));
      offset += block.size();
    }
    throw_if_failed(out);  // on this (worker) thread, where errno tells why
    blocks.clear();
  };

  run_ordered_pipeline<VtuBlock>(
      order.size(), tokens, hand_out,
      [&](VtuBlock& b) {
        if (!b.compressed) compress(b);
      },
      gather);

  out.write(kTail.data(), static_cast<std::streamsize>(kTail.size()));
  const std::streampos end = out.tellp();
  std::string header = xml_header(model, arrays, VtuData::zlib);
  if (header.size() > placeholder || header.back() != '_') throw Error("internal: annotated.vtu header overflow");
  header.insert(header.size() - 1, placeholder - header.size(), ' ');
  out.seekp(start);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.seekp(end);
}

// Uncompressed: each array is its UInt64 byte count and its values,
// streamed through a fixed-size buffer.
void write_raw(const ReportModel& model, const std::vector<VtuArray>& arrays, std::ostream& out) {
  const std::string header = xml_header(model, arrays, VtuData::raw);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  std::vector<unsigned char> buffer(kChunkValues * sizeof(double));
  progress::set_total(arrays.size());
  for (const VtuArray& a : arrays) {
    progress::add_done(1);
    unsigned char count[sizeof(std::uint64_t)];
    store_little_endian<std::uint64_t>(a.info.num_values * a.value_size, count);
    out.write(reinterpret_cast<const char*>(count), sizeof count);
    for (std::size_t first = 0; first < a.info.num_values; first += kChunkValues) {
      const std::size_t n = std::min<std::size_t>(kChunkValues, a.info.num_values - first);
      a.fill(first, n, buffer.data());
      out.write(reinterpret_cast<const char*>(buffer.data()), static_cast<std::streamsize>(n * a.value_size));
    }
  }
  out.write(kTail.data(), static_cast<std::streamsize>(kTail.size()));
}

}  // namespace

std::vector<VtuArrayInfo> annotated_vtu_layout(const ReportModel& model) {
  std::vector<VtuArrayInfo> layout;
  for (VtuArray& a : build_arrays(model)) layout.push_back(std::move(a.info));
  return layout;
}

void write_annotated_vtu(const ReportModel& model, std::ostream& out, VtuData encoding) {
  if (encoding == VtuData::zlib)
    write_compressed(model, build_arrays(model), out);
  else
    write_raw(model, build_arrays(model), out);
}

}  // namespace hq
