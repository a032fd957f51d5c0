#include "hqview/report/ordered_chunks.h"

#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <cerrno>
#include <string>
#include <vector>

#include "hqview/core/progress.h"

namespace hq {

void write_ordered_chunks(std::ostream& out, std::size_t num_chunks, const ChunkProducer& produce) {
  if (num_chunks == 0) return;
  throw_if_failed(out);  // a stream already failed: its cause is this thread's errno
  progress::set_total(num_chunks);
  std::size_t next = 0;
  // Two chunks in flight per thread keep both the producers and the writer busy.
  const auto tokens = static_cast<std::size_t>(2 * tbb::this_task_arena::max_concurrency());
  struct Chunk {
    std::size_t index = 0;
    std::string text;
  };
  // The chunks live here, one slot per token, not in the pipeline's tokens:
  // a writer that throws cancels the pipeline, and TBB leaves the items it
  // holds then undestroyed (LeakSanitizer found the shared pointers that
  // were here). The last filter is serial in order, so when chunk i enters,
  // chunk i - tokens has left and its slot i % tokens is free.
  std::vector<Chunk> slots(tokens);
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, Chunk*>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& fc) -> Chunk* {
        if (next == num_chunks) {
          fc.stop();
          return nullptr;
        }
        Chunk* c = &slots[next % tokens];
        c->index = next++;
        c->text.clear();
        return c;
      }) & tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::parallel, [&](Chunk* c) {
        produce(c->index, c->text);
        return c;
      }) & tbb::make_filter<Chunk*, void>(tbb::filter_mode::serial_in_order, [&](Chunk* c) {
        out.write(c->text.data(), static_cast<std::streamsize>(c->text.size()));
        throw_if_failed(out);
        progress::add_done(1);
      }));
}

void throw_if_failed(const std::ostream& out) {
  if (out) return;
  const int cause = errno != 0 ? errno : EIO;
  throw std::system_error(cause, std::generic_category(), "write");
}

}  // namespace hq
