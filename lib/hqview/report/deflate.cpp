#include "hqview/report/deflate.h"

#include <libdeflate.h>

#include <memory>

#include "hqview/core/error.h"

namespace hq {
namespace {

// Level 1: the data files are written on every run; a higher level costs
// 2-4x the time for a few percent (docs/performance.md).
constexpr int kLevel = 1;

struct CompressorDeleter {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

// One compressor per thread and level (libdeflate's are not shareable),
// made once.
libdeflate_compressor* thread_compressor(bool stored) {
  using Owned = std::unique_ptr<libdeflate_compressor, CompressorDeleter>;
  thread_local Owned fast(libdeflate_alloc_compressor(kLevel));
  thread_local Owned none(libdeflate_alloc_compressor(0));
  libdeflate_compressor* c = stored ? none.get() : fast.get();
  if (c == nullptr) throw Error("internal: libdeflate_alloc_compressor failed");
  return c;
}

// Appends what `compress` writes into at most `bound` bytes past out's end.
template <class Buffer, class Bound, class Compress>
void append_compressed(const void* data, std::size_t size, Buffer& out, Bound bound, Compress compress,
                       bool stored = false) {
  libdeflate_compressor* c = thread_compressor(stored);
  const std::size_t old_size = out.size();
  out.resize(old_size + bound(c, size));
  const std::size_t written = compress(c, data, size, out.data() + old_size, out.size() - old_size);
  if (written == 0) throw Error("internal: libdeflate: output larger than its bound");
  out.resize(old_size + written);
}

}  // namespace

void append_gzip_member(std::string_view data, std::string& out) {
  append_compressed(data.data(), data.size(), out, libdeflate_gzip_compress_bound, libdeflate_gzip_compress);
}

void append_zlib_stream(std::span<const unsigned char> data, std::vector<unsigned char>& out, bool stored) {
  append_compressed(data.data(), data.size(), out, libdeflate_zlib_compress_bound, libdeflate_zlib_compress, stored);
}

}  // namespace hq
