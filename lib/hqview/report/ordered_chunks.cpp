#include "hqview/report/ordered_chunks.h"

#include <tbb/task_arena.h>

#include <cerrno>
#include <string>

#include "hqview/core/progress.h"
#include "hqview/report/ordered_pipeline.h"

namespace hq {

void write_ordered_chunks(std::ostream& out, std::size_t num_chunks, const ChunkProducer& produce) {
  if (num_chunks == 0) return;
  throw_if_failed(out);  // a stream already failed: its cause is this thread's errno
  progress::set_total(num_chunks);
  // Two chunks in flight per thread keep both the producers and the writer busy.
  const auto tokens = static_cast<std::size_t>(2 * tbb::this_task_arena::max_concurrency());
  struct Chunk {
    std::size_t index = 0;
    std::string text;
  };
  run_ordered_pipeline<Chunk>(
      num_chunks, tokens,
      [](std::size_t i, Chunk& c) {
        c.index = i;
        c.text.clear();
      },
      [&](Chunk& c) { produce(c.index, c.text); },
      [&](Chunk& c) {
        out.write(c.text.data(), static_cast<std::streamsize>(c.text.size()));
        throw_if_failed(out);
        progress::add_done(1);
      });
}

void throw_if_failed(const std::ostream& out) {
  if (out) return;
  const int cause = errno != 0 ? errno : EIO;
  throw std::system_error(cause, std::generic_category(), "write");
}

}  // namespace hq
