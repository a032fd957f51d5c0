// check_netcdf_classic_header on headers built byte by byte here from the
// netCDF classic / 64-bit offset / CDF-5 specification, each with one thing
// wrong, and on the fuzz finding that made libnetcdf allocate 16 GiB.

#include "hqview/io/netcdf_header.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "error_text.h"
#include "hqview/io/mesh_reader.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

using detail::check_netcdf_classic_header;
using test::error_text;

// A classic netCDF file written by hand: big-endian fields, names padded to 4.
class CdfWriter {
 public:
  explicit CdfWriter(int version) : version_(version) { bytes_ = std::string("CDF") + static_cast<char>(version); }
  CdfWriter& u32(std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) bytes_ += static_cast<char>(v >> s & 0xFF);
    return *this;
  }
  CdfWriter& u64(std::uint64_t v) {
    for (int s = 56; s >= 0; s -= 8) bytes_ += static_cast<char>(v >> s & 0xFF);
    return *this;
  }
  CdfWriter& count(std::uint64_t v) { return version_ == 5 ? u64(v) : u32(static_cast<std::uint32_t>(v)); }
  CdfWriter& offset(std::uint64_t v) { return version_ == 1 ? u32(static_cast<std::uint32_t>(v)) : u64(v); }
  CdfWriter& name(const std::string& text) {
    count(text.size());
    bytes_ += text;
    while (bytes_.size() % 4 != 0) bytes_ += '\0';
    return *this;
  }
  CdfWriter& zeros(std::size_t n) {
    bytes_.append(n, '\0');
    return *this;
  }
  std::size_t size() const { return bytes_.size(); }
  const std::string& bytes() const { return bytes_; }

 private:
  int version_;
  std::string bytes_;
};

struct Layout {
  int version = 1;
  std::uint64_t numrecs = 0;
  std::uint64_t num_nodes = 2;         // length of dimension num_nodes
  std::uint32_t dim_id = 0;            // the dimension coordx uses
  std::uint64_t name_length = 0;       // 0: the real length of "coordx"
  std::uint64_t attribute_values = 3;  // of the text attribute "units"
  bool is_record = false;              // coordx over (time, num_nodes)
  std::int64_t data_delta = 0;         // bytes added to (removed from) the data
};

// dims: num_nodes (and time, the record dimension, with is_record), one
// global text attribute, one double variable coordx; data after the header.
std::string make_file(const Layout& l) {
  auto header = [&](std::uint64_t begin) {
    CdfWriter w(l.version);
    (l.version == 5 ? w.u64(l.numrecs) : w.u32(static_cast<std::uint32_t>(l.numrecs)));
    w.u32(0x0A).count(2).name("num_nodes").count(l.num_nodes).name("time").count(0);
    w.u32(0x0C).count(1).name("title").u32(2).count(l.attribute_values).zeros(4);
    w.u32(0x0B).count(1);
    if (l.name_length == 0) {
      w.name("coordx");
    } else {
      w.count(l.name_length).zeros(8);
    }
    if (l.is_record)
      w.count(2).count(1).count(l.dim_id);
    else
      w.count(1).count(l.dim_id);
    w.u32(0).count(0);  // no variable attributes
    w.u32(6).count(8 * l.num_nodes).offset(begin);
    return w;
  };
  CdfWriter w = header(0);
  w = header(w.size());
  const std::uint64_t records = l.is_record ? l.numrecs : 1;
  const std::int64_t data = static_cast<std::int64_t>(8 * l.num_nodes * records) + l.data_delta;
  std::string bytes = w.bytes();
  bytes.append(static_cast<std::size_t>(std::max<std::int64_t>(data, 0)), '\0');
  return bytes;
}

TEST(NetcdfHeader, WellFormedHeadersOfEveryVersionPass) {
  for (const int version : {1, 2, 5}) {
    const std::string bytes = make_file({.version = version});
    EXPECT_NO_THROW(check_netcdf_classic_header(bytes, "m.e")) << version;
    const std::string records = make_file({.version = version, .numrecs = 3, .is_record = true});
    EXPECT_NO_THROW(check_netcdf_classic_header(records, "m.e")) << version;
  }
}

TEST(NetcdfHeader, VariablePastTheEndOfTheFile) {
  const std::string bytes = make_file({.data_delta = -1});
  const std::size_t header = bytes.size() + 1 - 16;
  EXPECT_EQ(error_text<ParseError>([&] { check_netcdf_classic_header(bytes, "m.e"); }),
            "m.e: exodus header claims " + std::to_string(header + 16) +
                " bytes for variable 'coordx' (16 bytes at offset " + std::to_string(header) + ") but the file has " +
                std::to_string(bytes.size()));
}

TEST(NetcdfHeader, HugeDimensionLength) {
  // 10^12 nodes: CDF-5 stores 64-bit lengths.
  const std::string bytes = make_file({.version = 5, .num_nodes = 1000000000000, .data_delta = -8000000000000});
  EXPECT_EQ(error_text<ParseError>([&] { check_netcdf_classic_header(bytes, "m.e"); }),
            "m.e: exodus header claims 1000000000000 bytes for dimension 'num_nodes' of length 1000000000000 but the "
            "file has " +
                std::to_string(bytes.size()));
}

TEST(NetcdfHeader, HugeCountsOfDimensionsAttributesAndNames) {
  CdfWriter dims(1);
  dims.u32(0).u32(0x0A).u32(0xFFFFFFFF);
  EXPECT_EQ(error_text<ParseError>([&] { check_netcdf_classic_header(dims.bytes(), "m.e"); }),
            "m.e: exodus header claims " + std::to_string(16 + 12ull * 0xFFFFFFFF) +
                " bytes for 4294967295 dimensions but the file has 16");
  const std::string name = make_file({.name_length = 1u << 30});
  EXPECT_NE(error_text<ParseError>([&] {
              check_netcdf_classic_header(name, "m.e");
            }).find("bytes for the name of variable 0 but the file has"),
            std::string::npos);
  const std::string attribute = make_file({.attribute_values = 100000});
  EXPECT_NE(error_text<ParseError>([&] {
              check_netcdf_classic_header(attribute, "m.e");
            }).find("bytes for global attribute 'title' (100000 values) but the file has"),
            std::string::npos);
}

TEST(NetcdfHeader, RecordsPastTheEndOfTheFile) {
  // numrecs x recsize: 1000 records of 2 doubles in a file holding 3.
  const std::string bytes = make_file({.numrecs = 1000, .is_record = true, .data_delta = -8 * 2 * 997});
  EXPECT_EQ(error_text<ParseError>([&] { check_netcdf_classic_header(bytes, "m.e"); }),
            "m.e: exodus header claims " + std::to_string(bytes.size() - 48 + 16000) +
                " bytes for 1000 records of 16 bytes from offset " + std::to_string(bytes.size() - 48) +
                " but the file has " + std::to_string(bytes.size()));
}

TEST(NetcdfHeader, MalformedHeaders) {
  EXPECT_EQ(error_text<ParseError>([] { check_netcdf_classic_header("CDF\x01garbage", "m.e"); }),
            "m.e: exodus header claims 12 bytes for the list of dimensions but the file has 11");
  EXPECT_EQ(error_text<ParseError>([] { check_netcdf_classic_header(make_file({.dim_id = 7}), "m.e"); }),
            "m.e: not an Exodus II (netCDF) file: variable 'coordx' uses dimension id 7 of 2");
  EXPECT_EQ(error_text<ParseError>([] { check_netcdf_classic_header("HDF5", "m.e"); }),
            "m.e: not an Exodus II (netCDF) file: no CDF signature");
}

// Every prefix of a well-formed file is refused: the data of its variable
// (or the header itself) is cut.
TEST(NetcdfHeader, EveryTruncationIsRefused) {
  for (const int version : {1, 2, 5}) {
    const std::string bytes = make_file({.version = version, .numrecs = 2, .is_record = true});
    for (std::size_t n = 0; n < bytes.size(); ++n)
      EXPECT_THROW(check_netcdf_classic_header(bytes.substr(0, n), "m.e"), ParseError) << version << " " << n;
  }
}

// Fuzz finding exodus-oom-6f9e6fbb (scripts/fuzz, fuzz_exodus): a variable
// claiming 2^32-1 dimensions made nc_open_mem allocate 16 GiB. Now refused
// before libnetcdf reads the header.
TEST(NetcdfHeader, FuzzFindingOomDimensionIds6f9e6fbb) {
  const std::string path = (test::source_dir() / "tests/bad_inputs/exodus_fuzz_oom_6f9e6fbb.e").string();
  const std::string bytes = read_file_bytes(path);
  ASSERT_EQ(bytes.size(), 552u);
  EXPECT_EQ(error_text<ParseError>([&] { check_netcdf_classic_header(bytes, "f.e"); }),
            "f.e: exodus header claims 17179869412 bytes for 4294967295 dimensions of variable 'cogrd\\x86' but the "
            "file has 552");
  if (!has_exodus_support()) return;
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(path); }).substr(path.size()),
            ": exodus header claims 17179869412 bytes for 4294967295 dimensions of variable 'cogrd\\x86' but the file "
            "has 552");
}

// Fuzz finding exodus-timeout-2a40bb80 (session 2, fuzz_exodus): num_el_blk
// was the record dimension, 1,112,831 records long in a 665-byte file, and the
// reader looked up connectN/num_el_in_blkN for every one of them (2 s in a
// release build, > 10 s under ASan). The block count is now bounded by the
// file's variables.
TEST(NetcdfHeader, FuzzFindingTimeoutRecordBlockCount2a40bb80) {
  if (!has_exodus_support()) GTEST_SKIP() << "built without netCDF";
  const std::string path = (test::source_dir() / "tests/bad_inputs/exodus_fuzz_timeout_2a40bb80.e").string();
  ASSERT_EQ(read_file_bytes(path).size(), 665u);
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(path); }).substr(path.size()),
            ": num_el_blk is 1112831 but the file has only 2 variables");
}

}  // namespace
}  // namespace hq
