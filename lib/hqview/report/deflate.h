#pragma once
// Deflate for the bundle's data files (libdeflate, level 1: about 3x faster
// than zlib's level 1 at the same ratio). Deterministic: the same input gives
// the same bytes on any machine and for any thread count (no timestamps,
// no file names). Safe to call from several threads at once.

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hq {

// Appends one complete gzip member (RFC 1952: mtime 0, no name) holding
// `data`. Members concatenate into one valid .gz file (RFC 1952 §2.2): zcat,
// Python's gzip, pandas, R and polars read them as one stream.
void append_gzip_member(std::string_view data, std::string& out);

// Appends one zlib stream (RFC 1950) holding `data`: a block of VTK's
// vtkZLibDataCompressor. stored: deflate's stored blocks (no compression,
// a copy and a checksum), for data that compresses by a few percent only.
void append_zlib_stream(std::span<const unsigned char> data, std::vector<unsigned char>& out, bool stored = false);

}  // namespace hq
