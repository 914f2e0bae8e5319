// The one parallel runner (assess/chunk_runner.hpp): every chunk runs once, into a slot no
// other thread holds at the time, and rank 0 merges the chunks in index order, whatever
// the threads and however the chunks split into waves.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include <oneapi/tbb/task_arena.h>

#include "assess/chunk_runner.hpp"

using namespace j232;

namespace {
// Runs `chunks` chunks whose slot holds the chunk's index (and a marker that the slot is
// busy); returns the indices in the order merged.
std::vector<std::uint64_t> merged_order(std::uint64_t chunks, std::uint64_t most_slots, int threads, std::atomic<int>& clashes,
                                        assess::Progress& progress) {
  std::vector<std::uint64_t> order;
  std::vector<std::uint64_t> slot_chunk;
  std::vector<std::atomic<int>> busy;
  assess::ChunkWork work;
  work.chunks = chunks;
  work.most_slots = most_slots;
  work.items = [](std::uint64_t chunk) { return chunk + 1; };
  work.run = [&](std::uint64_t chunk, std::size_t slot) {
    if (busy[slot].fetch_add(1) != 0) ++clashes;
    // Uneven work, so that threads finish out of order.
    std::this_thread::sleep_for(std::chrono::microseconds((chunk * 7919) % 13 * 50));
    slot_chunk[slot] = chunk;
    busy[slot].fetch_sub(1);
  };
  work.merge = [&](std::uint64_t chunk, std::size_t slot) {
    CHECK(slot_chunk[slot] == chunk);
    order.push_back(slot_chunk[slot]);
  };
  work.progress = &progress;
  const std::size_t slots = static_cast<std::size_t>(assess::wave_size(work));
  slot_chunk.assign(slots, ~std::uint64_t{0});
  busy = std::vector<std::atomic<int>>(slots);
  int arena = 0;
  assess::on_threads(threads, [&] {
    arena = tbb::this_task_arena::max_concurrency();
    assess::run_chunks(work);
  });
  CHECK(arena == threads);  // the run's own arena, of the threads asked for
  return order;
}
}  // namespace

TEST_CASE("the runner merges every chunk once, in index order, on any number of threads and waves", "[runner]") {
  for (const int threads : {1, 2, 4})
    for (const std::uint64_t most_slots : {1, 3, 128})
      for (const std::uint64_t chunks : {0, 1, 5, 64}) {
        CAPTURE(threads, most_slots, chunks);
        std::atomic<int> clashes{0};
        assess::Progress progress;
        const auto order = merged_order(chunks, most_slots, threads, clashes, progress);
        REQUIRE(order.size() == chunks);
        for (std::uint64_t c = 0; c < chunks; ++c) CHECK(order[c] == c);
        CHECK(clashes == 0);
        CHECK(progress.done == static_cast<long long>(chunks * (chunks + 1) / 2));  // every chunk's items, once
      }
}
