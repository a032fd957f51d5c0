#pragma once
// A bounds check of a classic netCDF header (the container of Exodus II
// files) before the netCDF library reads it. libnetcdf's nc_open_mem
// allocates whatever the header claims (dimension ids, attribute values,
// variable shapes); a 552-byte file can make it ask for gigabytes. This walk
// reads the header as the "NetCDF Classic and 64-bit Offset Format" and
// "CDF-5" specifications define it (Unidata, netCDF Users Guide, File Format
// Specifications) and refuses every count, length, shape and offset that
// the file's byte count cannot hold.
//
// Checked: the magic 'C' 'D' 'F' 1|2|5; numrecs (or streaming); the
// dimension, global attribute and variable lists (tags, counts, names up to
// 256 bytes, attribute types and value lengths, dimension ids, one record
// dimension, first only); every dimension length and every fixed-size
// variable (begin + product of its dimensions x type size) against the file
// size, the sum of the fixed-size variables too, and numrecs x recsize (the
// bytes of one record of every record variable) against the file size.
//
// Not a classic header (HDF5-based netCDF-4 starts with "\x89HDF"): not
// checked here; the Exodus reader bounds what it reads from such a file.

#include <cstdint>
#include <string>
#include <string_view>

namespace hq::detail {

// True when bytes start with a classic netCDF magic: "CDF\x01", "CDF\x02"
// or "CDF\x05".
bool is_netcdf_classic(std::string_view bytes);

// Throws ParseError (line 0: "name: message") for a classic header that
// does not fit the file: "exodus header claims N bytes for WHAT but the
// file has M" (M = bytes.size()), or "not an Exodus II (netCDF) file: ..."
// for a malformed one (bad tag, type, name or dimension id). Returns the
// header's length in bytes.
std::uint64_t check_netcdf_classic_header(std::string_view bytes, const std::string& name);

}  // namespace hq::detail
