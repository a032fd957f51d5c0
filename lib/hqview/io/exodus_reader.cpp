#include "hqview/io/exodus_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <initializer_list>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#ifdef HQ_HAVE_NETCDF
#include <netcdf.h>
#include <netcdf_mem.h>
#endif

#include "hqview/core/shared_library.h"
#include "hqview/core/types.h"
#include "hqview/io/cell_reading.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/io/netcdf_header.h"

namespace hq {

#ifndef HQ_HAVE_NETCDF

bool exodus_available() { return false; }

LoadedMesh read_exodus(std::string_view, const std::string& name, const ReadLimits&) {
  throw InputError(name + ": this HQView was built without netCDF and cannot read Exodus II files");
}

#else

namespace {

// netCDF-4 (HDF5) variables may be compressed: allow zlib's largest
// expansion (1032:1) over the file's size before allocating from a
// dimension the file claims; classic files store values uncompressed.
constexpr std::uint64_t kMaxExpansion = 1032;

// The netCDF functions the reader calls, looked up in libnetcdf when the
// first Exodus II file is read (hq::SharedLibrary), not linked: a run on
// any other format never loads netCDF and HDF5 (about 17 ms at every start).
#define HQ_NETCDF_FUNCTIONS(X)                                                                                    \
  X(open_mem) X(close) X(strerror) X(inq_dimid) X(inq_dimlen) X(inq_nvars) X(inq_varid) X(inq_varndims)          \
  X(inq_vardimid) X(get_var_double) X(get_var_longlong) X(inq_attlen) X(inq_atttype) X(get_att_text)

struct NetcdfApi {
#define HQ_NETCDF_MEMBER(name) decltype(&::nc_##name) name = nullptr;
  HQ_NETCDF_FUNCTIONS(HQ_NETCDF_MEMBER)
#undef HQ_NETCDF_MEMBER
};

// Loaded once per process; throws InputError naming `file` when libnetcdf
// cannot be loaded or lacks a function.
const NetcdfApi& netcdf_api(const std::string& file) {
  static const auto loaded = [] {
    std::pair<NetcdfApi, std::string> result;  // the functions, the error
    const SharedLibrary library({"libnetcdf.so.19", "libnetcdf.so"});
    if (!library.is_open()) {
      result.second = "cannot load libnetcdf (Debian package libnetcdf19) to read Exodus II: " + library.error();
      return result;
    }
#define HQ_LOAD_NETCDF(f) \
  if (!library.load(result.first.f, "nc_" #f) && result.second.empty()) result.second = library.name() + " has no nc_" #f;
    HQ_NETCDF_FUNCTIONS(HQ_LOAD_NETCDF)
#undef HQ_LOAD_NETCDF
    return result;
  }();
  if (!loaded.second.empty()) throw InputError(file + ": " + loaded.second);
  return loaded.first;
}

class NcFile {
 public:
  NcFile(std::string_view bytes, const std::string& name)
      : nc_(netcdf_api(name)), name_(name), memory_(bytes.begin(), bytes.end()) {
    is_classic_ = detail::is_netcdf_classic(bytes);
    // libnetcdf allocates what a classic header claims: bound it first.
    if (is_classic_) detail::check_netcdf_classic_header(bytes, name);
    const int status = nc_.open_mem(name.c_str(), NC_NOWRITE, memory_.size(), memory_.data(), &id_);
    if (status != NC_NOERR) fail("not an Exodus II (netCDF) file: " + std::string(nc_.strerror(status)));
  }
  ~NcFile() { nc_.close(id_); }
  NcFile(const NcFile&) = delete;
  NcFile& operator=(const NcFile&) = delete;

  [[noreturn]] void fail(const std::string& message) const { throw ParseError(name_, 0, message); }

  // A dimension's length; -1 when absent.
  std::int64_t dimension(const std::string& dim_name) const {
    int dim = 0;
    if (nc_.inq_dimid(id_, dim_name.c_str(), &dim) != NC_NOERR) return -1;
    std::size_t length = 0;
    check(nc_.inq_dimlen(id_, dim, &length), "dimension " + dim_name);
    return static_cast<std::int64_t>(length);
  }
  std::int64_t required_dimension(const std::string& dim_name) const {
    const std::int64_t n = dimension(dim_name);
    if (n < 0) fail("no dimension " + dim_name + " (not an Exodus II file?)");
    return n;
  }
  // How many variables the file has.
  int num_variables() const {
    int n = 0;
    check(nc_.inq_nvars(id_, &n), "variables");
    return n;
  }
  // A variable's id; -1 when absent.
  int variable(const std::string& var_name) const {
    int var = 0;
    return nc_.inq_varid(id_, var_name.c_str(), &var) == NC_NOERR ? var : -1;
  }
  // The total number of values of a variable (product of its dimensions).
  std::uint64_t size(int var, const std::string& var_name) const {
    int num_dims = 0;
    check(nc_.inq_varndims(id_, var, &num_dims), "variable " + var_name);
    std::vector<int> dims(static_cast<std::size_t>(num_dims));
    check(nc_.inq_vardimid(id_, var, dims.data()), "variable " + var_name);
    std::uint64_t total = 1;
    for (const int dim : dims) {
      std::size_t length = 0;
      check(nc_.inq_dimlen(id_, dim, &length), "variable " + var_name);
      if (length != 0 && total > std::numeric_limits<std::uint64_t>::max() / length)
        fail("variable " + var_name + " is too large");
      total *= length;
    }
    return total;
  }
  void check_room(std::uint64_t values, const std::string& what) const {
    const std::uint64_t room = is_classic_ ? memory_.size() / 4 : memory_.size() * kMaxExpansion;
    if (values > room)
      fail(what + " claims " + std::to_string(values) + " values, more than the " + std::to_string(memory_.size()) +
           "-byte file can hold");
  }
  std::vector<double> doubles(int var, const std::string& var_name, std::uint64_t expected) const {
    const std::uint64_t n = size(var, var_name);
    if (n != expected)
      fail("variable " + var_name + " has " + std::to_string(n) + " values, expected " + std::to_string(expected));
    check_room(n, "variable " + var_name);
    std::vector<double> values(static_cast<std::size_t>(n));
    if (n > 0) check(nc_.get_var_double(id_, var, values.data()), "reading " + var_name);
    return values;
  }
  std::vector<long long> integers(int var, const std::string& var_name, std::uint64_t expected) const {
    const std::uint64_t n = size(var, var_name);
    if (n != expected)
      fail("variable " + var_name + " has " + std::to_string(n) + " values, expected " + std::to_string(expected));
    check_room(n, "variable " + var_name);
    std::vector<long long> values(static_cast<std::size_t>(n));
    if (n > 0) check(nc_.get_var_longlong(id_, var, values.data()), "reading " + var_name);
    return values;
  }
  std::string text_attribute(int var, const char* attribute) const {
    std::size_t length = 0;
    if (nc_.inq_attlen(id_, var, attribute, &length) != NC_NOERR) return {};
    nc_type type = NC_NAT;
    if (nc_.inq_atttype(id_, var, attribute, &type) != NC_NOERR || type != NC_CHAR || length > 4096) return {};
    std::string text(length, '\0');
    check(nc_.get_att_text(id_, var, attribute, text.data()), std::string("attribute ") + attribute);
    while (!text.empty() && (text.back() == '\0' || text.back() == ' ')) text.pop_back();
    return text;
  }

 private:
  void check(int status, const std::string& what) const {
    if (status != NC_NOERR) fail(what + ": " + nc_.strerror(status));
  }

  const NetcdfApi& nc_;
  const std::string& name_;
  std::vector<char> memory_;  // nc_open_mem reads from it until nc_close
  bool is_classic_ = false;
  int id_ = -1;
};

std::string upper(std::string text) {
  for (char& c : text)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return text;
}

// The kind of a block's elements: the elem_type names Exodus writers use
// (HEX, HEX8; TETRA, TET4, TETRA4; WEDGE, WEDGE6; PYRAMID, PYRAMID5, PYRA)
// with a node count Exodus and IOSS define for that shape (SEACAS'
// "Exodus Element Types"): hexahedra of 8, 9, 20 or 27 nodes,
// tetrahedra of 4, 5, 8, 10, 11, 14 or 15, wedges of 6, 12, 15, 16, 18, 20
// or 21 and pyramids of 5, 13, 14, 18 or 19; none for every other block.
// The corners are listed first (Exodus follows PATRAN's element library).
// Exodus lists a WEDGE's first triangle with its normal towards the second
// (side 4 is 1-3-2): such wedges are permuted to VTK's order by the caller.
std::optional<CellKind> exodus_volume_kind(const std::string& type, std::int64_t per_element) {
  const auto one_of = [&](std::initializer_list<std::int64_t> counts) {
    return std::find(counts.begin(), counts.end(), per_element) != counts.end();
  };
  if (type.starts_with("HEX") && one_of({8, 9, 20, 27})) return CellKind::hex;
  if (type.starts_with("TET") && one_of({4, 5, 8, 10, 11, 14, 15})) return CellKind::tet;
  if (type.starts_with("WEDGE") && one_of({6, 12, 15, 16, 18, 20, 21})) return CellKind::wedge;
  if (type.starts_with("PYR") && one_of({5, 13, 14, 18, 19})) return CellKind::pyramid;
  return std::nullopt;
}

}  // namespace

bool exodus_available() { return true; }

// netCDF-C is not thread-safe (its open-file table and HDF5 underneath are
// global): a batch reads meshes on several threads, and two Exodus files read
// at once crashed it (e2e.MessagesAreText, about 1 run in 40 under load). One
// netCDF use at a time, from open to close.
static std::mutex& netcdf_mutex() {
  static std::mutex mutex;
  return mutex;
}

LoadedMesh read_exodus(std::string_view bytes, const std::string& name, const ReadLimits& limits) {
  const std::lock_guard lock(netcdf_mutex());
  const NcFile file(bytes, name);
  const std::int64_t num_nodes = file.required_dimension("num_nodes");
  const std::int64_t num_dim = file.required_dimension("num_dim");
  if (num_nodes > kMaxIndexCount)
    file.fail("num_nodes " + std::to_string(num_nodes) + " exceeds the limit of " + std::to_string(kMaxIndexCount));
  if (num_dim < 1 || num_dim > 3) file.fail("num_dim is " + std::to_string(num_dim) + ", expected 1 to 3");

  check_mesh_memory(limits, name, 0, bytes.size(), num_nodes, -1);
  LoadedMesh loaded;
  loaded.format = "exodus";
  file.check_room(static_cast<std::uint64_t>(num_nodes) * static_cast<std::uint64_t>(num_dim), "num_nodes");
  // Coordinates by component (x of every node, then y, then z).
  std::vector<double> xyz_by_dim(static_cast<std::size_t>(3 * num_nodes), 0.0);
  const auto n = static_cast<std::uint64_t>(num_nodes);
  if (const int coord = file.variable("coord"); coord >= 0) {
    const std::vector<double> xyz = file.doubles(coord, "coord", n * static_cast<std::uint64_t>(num_dim));
    for (std::int64_t d = 0; d < num_dim; ++d)
      for (std::int64_t i = 0; i < num_nodes; ++i)
        xyz_by_dim[static_cast<std::size_t>(d * num_nodes + i)] = xyz[static_cast<std::size_t>(d * num_nodes + i)];
  } else {
    const char* names[3] = {"coordx", "coordy", "coordz"};
    for (std::int64_t d = 0; d < num_dim; ++d) {
      const int var = file.variable(names[d]);
      if (var < 0) file.fail(std::string("no coordinate variable ") + names[d] + " (nor coord)");
      const std::vector<double> values = file.doubles(var, names[d], n);
      for (std::int64_t i = 0; i < num_nodes; ++i)
        xyz_by_dim[static_cast<std::size_t>(d * num_nodes + i)] = values[static_cast<std::size_t>(i)];
    }
  }
  std::vector<Vec3>& points = loaded.mesh.points;
  points.resize(static_cast<std::size_t>(num_nodes));
  for (std::int64_t i = 0; i < num_nodes; ++i) {
    double p[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = xyz_by_dim[static_cast<std::size_t>(k * num_nodes + i)];
      if (!std::isfinite(p[k])) file.fail("non-finite coordinate (node " + std::to_string(i + 1) + ")");
    }
    points[static_cast<std::size_t>(i)] = {p[0], p[1], p[2]};
  }

  const std::int64_t num_blocks = std::max<std::int64_t>(file.dimension("num_el_blk"), 0);
  // Each block has its own connectN variable: a count beyond the file's
  // variables (e.g. num_el_blk made the record dimension) is a lie, and looking
  // up that many names would take minutes.
  if (num_blocks > file.num_variables())
    file.fail("num_el_blk is " + std::to_string(num_blocks) + " but the file has only " +
              std::to_string(file.num_variables()) + " variables");
  std::int64_t num_elements_declared = 0;  // every block's, an upper bound of the hexes
  for (std::int64_t b = 1; b <= num_blocks; ++b)
    num_elements_declared +=
        std::clamp<std::int64_t>(file.dimension("num_el_in_blk" + std::to_string(b)), 0, kMaxIndexCount);
  check_mesh_memory(limits, name, 0, bytes.size(), num_nodes, num_elements_declared, "element");
  // The user's element ids: elem_num_map, when the file has one, maps the
  // 1-based element number over the blocks to the id (Exodus II, "Element
  // Number Map"); without it the id is that number.
  std::vector<long long> id_map;
  const int map = file.variable("elem_num_map");
  if (map >= 0) {
    const std::int64_t num_elem = std::max<std::int64_t>(file.dimension("num_elem"), 0);
    id_map = file.integers(map, "elem_num_map", static_cast<std::uint64_t>(num_elem));
  }
  std::map<std::string, std::int64_t> skipped_by_type;
  detail::CellNotes notes;
  std::int64_t element_number = 0;  // 1-based over the blocks in order: Exodus's implicit element id
  const auto element_id = [&](const std::string& connect, std::int64_t e) -> std::int64_t {
    if (map < 0) return element_number;
    if (element_number > static_cast<std::int64_t>(id_map.size()))
      file.fail("elem_num_map has " + std::to_string(id_map.size()) + " entries, fewer than the blocks' elements (" +
                connect + " element " + std::to_string(e + 1) + ")");
    return id_map[static_cast<std::size_t>(element_number - 1)];
  };
  for (std::int64_t b = 1; b <= num_blocks; ++b) {
    const std::string connect = "connect" + std::to_string(b);
    const int var = file.variable(connect);
    const std::int64_t num_elements = file.dimension("num_el_in_blk" + std::to_string(b));
    const std::int64_t per_element = file.dimension("num_nod_per_el" + std::to_string(b));
    if (var < 0 || num_elements <= 0) continue;  // an empty block has no connectivity
    const std::string type = upper(file.text_attribute(var, "elem_type"));
    const std::optional<CellKind> kind = exodus_volume_kind(type, per_element);
    const std::string count = std::to_string(per_element);
    const std::string type_name = type.empty() || type.ends_with(count) ? type : type + " (" + count + " nodes)";
    if (!kind) {
      skipped_by_type[type.empty() ? "?" : type_name] += num_elements;
      element_number += num_elements;
      continue;
    }
    // Every node is checked; the corners, listed first, are kept.
    const int n = static_cast<int>(per_element);
    const int num_corners = cell_kind_num_corners(*kind);
    const bool is_higher_order = n > num_corners;
    const int* to_vtk = *kind == CellKind::wedge ? detail::kWedgeFlippedToVtk.data() : nullptr;
    const std::vector<long long> ids =
        file.integers(var, connect, static_cast<std::uint64_t>(num_elements) * static_cast<std::uint64_t>(n));
    if (is_higher_order) notes.add_higher_order(type_name, num_elements);
    for (std::int64_t e = 0; e < num_elements; ++e) {
      std::array<Index, 8> corners{};
      for (int j = 0; j < n; ++j) {
        const long long id = ids[static_cast<std::size_t>(e * n + j)];
        if (id < 1 || id > num_nodes)
          file.fail("node " + std::to_string(id) + " out of range [1, " + std::to_string(num_nodes) + "] (" + connect +
                    " element " + std::to_string(e + 1) + ")");
        if (j < num_corners) corners[static_cast<std::size_t>(j)] = static_cast<Index>(id - 1);
      }
      ++element_number;
      const std::int64_t source = element_id(connect, e);
      if (const int j = detail::first_repeated(corners.data(), num_corners); j >= 0) {
        if (*kind == CellKind::hex && detail::append_collapsed_hex(loaded.mesh, corners.data(), nullptr, source, notes))
          continue;
        file.fail("node " + std::to_string(corners[static_cast<std::size_t>(j)] + 1) + " repeated (" + connect +
                  " element " + std::to_string(e + 1) + ")");
      }
      detail::append_cell(loaded.mesh, *kind, corners.data(), to_vtk, source);
    }
  }
  const SkippedCells skipped(skipped_by_type);
  if (num_volume_cells(loaded.mesh) == 0)
    file.fail("no volume elements (HEX8, TETRA, WEDGE or PYRAMID blocks)" +
              (skipped.count > 0 ? " among " + skipped.counted("element") : std::string()));
  if (skipped.count > 0) loaded.warnings.push_back(skipped.warning(name, "element"));
  notes.append_warnings(name, "element", loaded.warnings);
  return loaded;
}

#endif

}  // namespace hq
