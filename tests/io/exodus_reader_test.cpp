// read_exodus on small Exodus II files written here with the netCDF C API
// (classic format): separate and combined coordinate variables, HEX8 and
// skipped blocks, and the error paths. Without netCDF, the reader's refusal.

#include "hqview/io/exodus_reader.h"

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#ifdef HQ_HAVE_NETCDF
#include <netcdf.h>
#endif

#include "error_text.h"
#include "hqview/io/mesh_reader.h"
#include "hybrid_mesh_files.h"
#include "temp_dir.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;
using test::TempDir;

#ifndef HQ_HAVE_NETCDF

TEST(ExodusReader, RefusedWithoutNetcdf) {
  EXPECT_FALSE(exodus_available());
  EXPECT_EQ(error_text<InputError>([] { read_exodus("CDF\x01", "m.e"); }),
            "m.e: this HQView was built without netCDF and cannot read Exodus II files");
}

#else

struct Block {
  std::string type;
  int nodes_per_element;
  std::vector<int> connectivity;  // 1-based
};

// Writes an Exodus-like classic netCDF file; returns its bytes. A non-empty
// elem_num_map is written as Exodus's element number map (dimension
// num_elem of its size).
std::string write_exodus(const TempDir& dir, const std::vector<double>& xyz, const std::vector<Block>& blocks,
                         bool combined_coord, bool with_num_nodes = true, int create_mode = NC_CLOBBER,
                         int num_steps = 0, const std::vector<int>& elem_num_map = {}) {
  const std::string path = (dir.path() / "m.e").string();
  int nc = 0;
  EXPECT_EQ(nc_create(path.c_str(), create_mode, &nc), NC_NOERR);
  int time_var = -1;
  if (num_steps > 0) {  // a record variable, as Exodus's time_whole
    int dim_time = 0;
    nc_def_dim(nc, "time_step", NC_UNLIMITED, &dim_time);
    nc_def_var(nc, "time_whole", NC_DOUBLE, 1, &dim_time, &time_var);
  }
  const auto n = xyz.size() / 3;
  int dim_nodes = 0, dim_dim = 0, dim_blocks = 0;
  nc_def_dim(nc, with_num_nodes ? "num_nodes" : "nodes", n, &dim_nodes);
  nc_def_dim(nc, "num_dim", 3, &dim_dim);
  nc_def_dim(nc, "num_el_blk", blocks.size(), &dim_blocks);
  std::vector<int> coord_vars;
  if (combined_coord) {
    int dims[2] = {dim_dim, dim_nodes};
    int var = 0;
    nc_def_var(nc, "coord", NC_DOUBLE, 2, dims, &var);
    coord_vars.push_back(var);
  } else {
    for (const char* name : {"coordx", "coordy", "coordz"}) {
      int var = 0;
      nc_def_var(nc, name, NC_DOUBLE, 1, &dim_nodes, &var);
      coord_vars.push_back(var);
    }
  }
  int map_var = -1;
  if (!elem_num_map.empty()) {
    int dim_elem = 0;
    nc_def_dim(nc, "num_elem", elem_num_map.size(), &dim_elem);
    nc_def_var(nc, "elem_num_map", NC_INT, 1, &dim_elem, &map_var);
  }
  std::vector<int> connect_vars;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const std::string suffix = std::to_string(b + 1);
    int dims[2];
    nc_def_dim(nc, ("num_el_in_blk" + suffix).c_str(),
               blocks[b].connectivity.size() / static_cast<std::size_t>(blocks[b].nodes_per_element), &dims[0]);
    nc_def_dim(nc, ("num_nod_per_el" + suffix).c_str(), static_cast<std::size_t>(blocks[b].nodes_per_element),
               &dims[1]);
    int var = 0;
    nc_def_var(nc, ("connect" + suffix).c_str(), NC_INT, 2, dims, &var);
    nc_put_att_text(nc, var, "elem_type", blocks[b].type.size(), blocks[b].type.c_str());
    connect_vars.push_back(var);
  }
  nc_enddef(nc);
  std::vector<double> by_dim(xyz.size());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 0; d < 3; ++d) by_dim[d * n + i] = xyz[3 * i + d];
  if (combined_coord) {
    nc_put_var_double(nc, coord_vars[0], by_dim.data());
  } else {
    for (std::size_t d = 0; d < 3; ++d) nc_put_var_double(nc, coord_vars[d], by_dim.data() + d * n);
  }
  for (std::size_t b = 0; b < blocks.size(); ++b) nc_put_var_int(nc, connect_vars[b], blocks[b].connectivity.data());
  if (map_var >= 0) nc_put_var_int(nc, map_var, elem_num_map.data());
  for (std::size_t step = 0; step < static_cast<std::size_t>(num_steps); ++step) {
    const double t = static_cast<double>(step);
    nc_put_var1_double(nc, time_var, &step, &t);
  }
  nc_close(nc);
  return read_file_bytes(path);
}

const std::vector<double> kCube = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};

TEST(ExodusReader, Hex8BlocksAndSkippedBlocks) {
  EXPECT_TRUE(exodus_available());
  TempDir dir("exodus");
  for (const bool combined : {false, true}) {
    const std::string bytes = write_exodus(
        dir, kCube,
        {{"QUAD4", 4, {1, 2, 3, 4, 5, 6, 7, 8}}, {"HEX8", 8, {1, 2, 3, 4, 5, 6, 7, 8, 5, 6, 7, 8, 1, 2, 3, 4}}},
        combined);
    const LoadedMesh loaded = read_exodus(bytes, "m.e");
    EXPECT_EQ(loaded.format, "exodus");
    ASSERT_EQ(loaded.mesh.points.size(), 8u);
    EXPECT_EQ(loaded.mesh.points[6].x, 1.0);
    EXPECT_EQ(loaded.mesh.points[6].z, 1.0);
    ASSERT_EQ(loaded.mesh.hexes.size(), 2u);
    EXPECT_EQ(loaded.mesh.hexes[0], (Hex{0, 1, 2, 3, 4, 5, 6, 7}));
    EXPECT_EQ(loaded.mesh.hexes[1], (Hex{4, 5, 6, 7, 0, 1, 2, 3}));
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_EQ(loaded.warnings[0], "m.e: 2 elements of unread types skipped (type QUAD4)");
  }
}

// The hybrid mesh of hybrid_mesh_files.h as Exodus blocks (HEX8, TETRA,
// WEDGE in Exodus's order, PYRAMID): the same VTK-order cells as every other
// format reads it to (cell_blocks_reading_test.cpp), each with a positive
// volume, and source_index the element's 1-based id over the blocks.
TEST(ExodusReader, HybridMeshReadsToTheSameCells) {
  const test::HybridMesh m = test::hybrid_mesh();
  std::vector<double> xyz;
  for (const auto& p : m.points) xyz.insert(xyz.end(), p.begin(), p.end());
  const std::vector<std::pair<int, std::string>> kinds = {{12, "HEX8"}, {10, "TETRA"}, {13, "WEDGE"}, {14, "PYRAMID"}};
  std::vector<Block> blocks;
  for (const auto& [type, name] : kinds) {
    Block block{name, 0, {}};
    for (const test::HybridCell& c : m.cells)
      if (c.vtk_type == type) {
        const std::vector<int> corners = test::file_order(c, true);
        block.nodes_per_element = static_cast<int>(corners.size());
        for (const int v : corners) block.connectivity.push_back(v + 1);
      }
    blocks.push_back(block);
  }
  TempDir dir("exodus_hybrid");
  const LoadedMesh loaded = read_exodus(write_exodus(dir, xyz, blocks, false), "m.e");
  std::vector<std::array<double, 3>> points;
  for (const Vec3& p : loaded.mesh.points) points.push_back({p.x, p.y, p.z});
  std::int64_t id = 0;
  for (const auto& [type, name] : kinds) {
    SCOPED_TRACE(name);
    std::vector<std::vector<int>> expected, read;
    for (const test::HybridCell& c : m.cells)
      if (c.vtk_type == type) expected.push_back(c.vtk);
    for_each_block(loaded.mesh, [&](auto kind, const auto& cells) {
      if (cell_kind_vtk_type(kind()) == type)
        for (const auto& cell : cells) read.emplace_back(cell.begin(), cell.end());
    });
    EXPECT_EQ(read, expected);
    std::vector<std::int64_t> ids;
    for (std::size_t i = 0; i < expected.size(); ++i) ids.push_back(++id);
    for (const CellKind kind : kCellKinds)
      if (cell_kind_vtk_type(kind) == type) {
        EXPECT_EQ(loaded.mesh.source_index[static_cast<std::size_t>(kind)], ids);
      }
    for (const auto& cell : read) EXPECT_GT(test::split_volume(points, type, cell).min_tet, 0.0);
  }
}

// Higher-order blocks (HEX20, TETRA10, WEDGE15, PYRAMID13; corners first,
// then new nodes at the edge midpoints) read to the hybrid mesh's cells with
// one warning, and with an elem_num_map the source index of each cell is
// its entry there (the user's element id), skipped blocks counted in.
TEST(ExodusReader, HigherOrderBlocksAndTheElementNumberMap) {
  const test::HybridMesh m = test::hybrid_mesh();
  std::vector<double> xyz;
  for (const auto& p : m.points) xyz.insert(xyz.end(), p.begin(), p.end());
  const std::vector<std::tuple<int, std::string, int>> kinds = {
      {12, "HEX20", 20}, {10, "TETRA10", 10}, {13, "WEDGE15", 15}, {14, "PYRAMID13", 13}};
  std::vector<Block> blocks = {{"QUAD4", 4, {1, 2, 5, 4}}};  // a skipped element first
  for (const auto& [type, name, num_nodes] : kinds) {
    Block block{name, num_nodes, {}};
    for (const test::HybridCell& c : m.cells)
      if (c.vtk_type == type) {
        const std::vector<int> corners = test::file_order(c, true);
        for (const int v : corners) block.connectivity.push_back(v + 1);
        for (int j = static_cast<int>(corners.size()); j < num_nodes; ++j) {  // a new node at an edge's midpoint
          const auto& a = m.points[static_cast<std::size_t>(corners[static_cast<std::size_t>(j % corners.size())])];
          const auto& b = m.points[static_cast<std::size_t>(corners[static_cast<std::size_t>((j + 1) % corners.size())])];
          for (int k = 0; k < 3; ++k) xyz.push_back((a[k] + b[k]) / 2);
          block.connectivity.push_back(static_cast<int>(xyz.size() / 3));
        }
      }
    blocks.push_back(block);
  }
  const std::vector<int> map = {7, 501, 502, 90, 91, 300, 301, 200};  // QUAD4, HEX20 x2, TETRA10 x2, WEDGE15 x2, PYRAMID13
  TempDir dir("exodus_higher_order");
  for (const bool with_map : {false, true}) {
    SCOPED_TRACE(with_map ? "elem_num_map" : "no map");
    const LoadedMesh loaded =
        read_exodus(write_exodus(dir, xyz, blocks, false, true, NC_CLOBBER, 0, with_map ? map : std::vector<int>{}), "m.e");
    std::vector<std::array<double, 3>> points;
    for (const Vec3& p : loaded.mesh.points) points.push_back({p.x, p.y, p.z});
    std::size_t position = 1;  // the QUAD4 is element 1
    for (const auto& [type, name, num_nodes] : kinds) {
      SCOPED_TRACE(name);
      std::vector<std::vector<int>> expected, read;
      for (const test::HybridCell& c : m.cells)
        if (c.vtk_type == type) expected.push_back(c.vtk);
      std::vector<std::int64_t> ids;
      for (std::size_t i = 0; i < expected.size(); ++i, ++position)
        ids.push_back(with_map ? map[position] : static_cast<std::int64_t>(position + 1));
      for (const CellKind kind : kCellKinds)
        if (cell_kind_vtk_type(kind) == type) {
          for_each_block(loaded.mesh, [&](auto k, const auto& cells) {
            if (k() == kind)
              for (const auto& cell : cells) read.emplace_back(cell.begin(), cell.end());
          });
          std::vector<std::int64_t> source;
          for (std::size_t i = 0; i < read.size(); ++i) source.push_back(cell_source_index(loaded.mesh, kind, i));
          EXPECT_EQ(source, ids);
        }
      EXPECT_EQ(read, expected);
      for (const auto& cell : read) EXPECT_GT(test::split_volume(points, type, cell).min_tet, 0.0);
    }
    EXPECT_EQ(loaded.warnings,
              (std::vector<std::string>{"m.e: 1 element of unread types skipped (type QUAD4)",
                                        "m.e: 7 higher-order elements read by their corner nodes only (2 of type "
                                        "HEX20, 1 of type PYRAMID13, 2 of type TETRA10, 2 of type WEDGE15): their "
                                        "other nodes are ignored, so curved cells are measured as straight-sided "
                                        "ones"}));
  }
  // A map shorter than the blocks' elements (num_elem too small) is refused.
  EXPECT_EQ(error_text<ParseError>([&] {
              read_exodus(write_exodus(dir, kCube, {{"HEX8", 8, {1, 2, 3, 4, 5, 6, 7, 8, 5, 6, 7, 8, 1, 2, 3, 4}}}, false,
                                       true, NC_CLOBBER, 0, {42}),
                          "m.e");
            }),
            "m.e: elem_num_map has 1 entries, fewer than the blocks' elements (connect1 element 2)");
}

// HEX8 elements with repeated nodes in the collapse patterns (1-based: a
// wedge 3=4, 7=8; a pyramid 5=6=7=8; a tetrahedron 3=4, 5=6=7=8) are read as
// their kind with their element ids, and a HEX27 block named "HEX" by its
// corners.
TEST(ExodusReader, CollapsedHexahedraAndAHexBlockOf27Nodes) {
  std::vector<double> xyz = kCube;
  std::vector<int> hex27 = {1, 2, 3, 4, 5, 6, 7, 8};
  for (int j = 8; j < 27; ++j) {  // the other nodes at the centre
    for (int k = 0; k < 3; ++k) xyz.push_back(0.5);
    hex27.push_back(static_cast<int>(xyz.size() / 3));
  }
  TempDir dir("exodus_collapsed");
  const LoadedMesh loaded = read_exodus(
      write_exodus(dir, xyz,
                   {{"HEX8", 8, {1, 2, 3, 3, 5, 6, 7, 7, 1, 2, 3, 4, 5, 5, 5, 5, 1, 2, 3, 3, 5, 5, 5, 5}},
                    {"HEX", 27, hex27}},
                   false, true, NC_CLOBBER, 0, {10, 20, 30, 40}),
      "m.e");
  ASSERT_EQ(loaded.mesh.wedges.size(), 1u);
  ASSERT_EQ(loaded.mesh.pyramids.size(), 1u);
  ASSERT_EQ(loaded.mesh.tets.size(), 1u);
  ASSERT_EQ(loaded.mesh.hexes.size(), 1u);
  EXPECT_EQ(loaded.mesh.wedges[0], (CellCorners<CellKind::wedge>{0, 2, 1, 4, 6, 5}));
  EXPECT_EQ(loaded.mesh.pyramids[0], (CellCorners<CellKind::pyramid>{0, 1, 2, 3, 4}));
  EXPECT_EQ(loaded.mesh.tets[0], (CellCorners<CellKind::tet>{0, 1, 2, 4}));
  EXPECT_EQ(loaded.mesh.hexes[0], (Hex{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::wedge, 0), 10);
  EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::pyramid, 0), 20);
  EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::tet, 0), 30);
  EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::hex, 0), 40);
  std::vector<std::array<double, 3>> points;
  for (const Vec3& p : loaded.mesh.points) points.push_back({p.x, p.y, p.z});
  EXPECT_GT(test::split_volume(points, 13, {0, 2, 1, 4, 6, 5}).min_tet, 0.0);
  EXPECT_EQ(loaded.warnings,
            (std::vector<std::string>{
                "m.e: 1 higher-order element read by its corner nodes only (1 of type HEX (27 nodes)): its other "
                "nodes are ignored, so curved cells are measured as straight-sided ones",
                "m.e: 3 hexahedra with repeated corners read as the cells they collapse to (1 wedge, 1 pyramid, 1 "
                "tetrahedron): elements 10, 20, 30"}));
}

// The header walk (netcdf_header.h) accepts what libnetcdf writes: classic,
// 64-bit offset and CDF-5 files, with records, in fill and no-fill mode; and
// refuses every truncation of them.
TEST(ExodusReader, HeaderCheckAcceptsEveryClassicVersion) {
  TempDir dir("exodus");
  for (const int mode : {NC_CLOBBER, NC_CLOBBER | NC_64BIT_OFFSET, NC_CLOBBER | NC_64BIT_DATA}) {
    const std::string bytes =
        write_exodus(dir, kCube, {{"HEX8", 8, {1, 2, 3, 4, 5, 6, 7, 8}}}, false, true, mode, /*num_steps=*/3);
    ASSERT_EQ(bytes[3], mode & NC_64BIT_DATA ? 5 : mode & NC_64BIT_OFFSET ? 2 : 1);
    EXPECT_EQ(read_exodus(bytes, "m.e").mesh.hexes.size(), 1u) << mode;
    for (std::size_t n = 0; n < bytes.size(); ++n)
      EXPECT_THROW(read_exodus(bytes.substr(0, n), "m.e"), ParseError) << mode << " " << n;
  }
}

TEST(ExodusReader, Errors) {
  TempDir dir("exodus");
  // The header is walked before libnetcdf sees it (netcdf_header_test.cpp).
  EXPECT_EQ(error_text<ParseError>([] { read_exodus("CDF\x01garbage", "m.e"); }),
            "m.e: exodus header claims 12 bytes for the list of dimensions but the file has 11");
  EXPECT_EQ(error_text<ParseError>([&] {
              read_exodus(write_exodus(dir, kCube, {{"HEX8", 8, {1, 2, 3, 4, 5, 6, 7, 8}}}, false, false), "m.e");
            }),
            "m.e: no dimension num_nodes (not an Exodus II file?)");
  EXPECT_EQ(error_text<ParseError>([&] {
              read_exodus(write_exodus(dir, kCube, {{"HEX8", 8, {1, 2, 3, 4, 5, 6, 7, 9}}}, false), "m.e");
            }),
            "m.e: node 9 out of range [1, 8] (connect1 element 1)");
  EXPECT_EQ(error_text<ParseError>([&] {
              read_exodus(write_exodus(dir, kCube, {{"HEX8", 8, {1, 2, 3, 4, 5, 6, 7, 1}}}, false), "m.e");
            }),
            "m.e: node 1 repeated (connect1 element 1)");
  EXPECT_EQ(error_text<ParseError>([&] {
              read_exodus(write_exodus(dir, kCube, {{"QUAD4", 4, {1, 2, 3, 4}}}, false), "m.e");
            }),
            "m.e: no volume elements (HEX8, TETRA, WEDGE or PYRAMID blocks) among 1 element of type QUAD4");
}

#endif

}  // namespace
}  // namespace hq
