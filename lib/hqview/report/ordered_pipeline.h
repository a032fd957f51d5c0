#pragma once
// A three-stage TBB pipeline over numbered items whose results must come out
// in order: start(i, item) hands item i out (serial, in order), work(item)
// runs on any thread (parallel), finish(item) takes it in (serial, in order).
// At most `tokens` items are in flight.
//
// The items live in slots owned here, one per token, never in the pipeline's
// tokens: a stage that throws cancels the pipeline, and TBB leaves the items
// it holds then undestroyed (LeakSanitizer found shared pointers leaked that
// way). finish is serial in order, so when item i is handed out, item
// i - tokens has been finished and its slot i % tokens is free. A slot is
// reused as it was left: start must reset what it needs.

#include <tbb/parallel_pipeline.h>

#include <cstddef>
#include <vector>

namespace hq {

template <class Item, class Start, class Work, class Finish>
void run_ordered_pipeline(std::size_t num_items, std::size_t tokens, Start&& start, Work&& work, Finish&& finish) {
  if (num_items == 0 || tokens == 0) return;
  std::vector<Item> slots(tokens);
  std::size_t next = 0;
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, Item*>(tbb::filter_mode::serial_in_order,
                                    [&](tbb::flow_control& fc) -> Item* {
                                      if (next == num_items) {
                                        fc.stop();
                                        return nullptr;
                                      }
                                      Item* item = &slots[next % tokens];
                                      start(next++, *item);
                                      return item;
                                    }) &
          tbb::make_filter<Item*, Item*>(tbb::filter_mode::parallel,
                                         [&](Item* item) {
                                           work(*item);
                                           return item;
                                         }) &
          tbb::make_filter<Item*, void>(tbb::filter_mode::serial_in_order, [&](Item* item) { finish(*item); }));
}

}  // namespace hq
