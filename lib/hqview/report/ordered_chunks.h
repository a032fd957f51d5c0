#pragma once
// Writing a large file as numbered chunks made in parallel and written in
// order: chunk i is made by produce(i, text) on any thread, then written to
// `out` after chunks 0 ... i-1. At most a few chunks per thread are in memory
// at once. The chunks (and so the bytes) are fixed by the caller, never by
// the thread count.

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <system_error>

namespace hq {

using ChunkProducer = std::function<void(std::size_t index, std::string& text)>;

void write_ordered_chunks(std::ostream& out, std::size_t num_chunks, const ChunkProducer& produce);

// Throws std::system_error with this thread's errno (EIO when it is 0) when
// `out` has failed. For the writing stage of a pipeline, which runs on any
// thread: errno is per thread, so a write that failed there (a full disk, a
// file size limit) keeps its cause only if it is read there; the caller
// (the bundle writer) turns the error into "path: write failed: cause".
void throw_if_failed(const std::ostream& out);

}  // namespace hq
