#pragma once
// The one parallel runner of every pipeline (a J232 assessment's replicates, a field's
// objects, designs compared object by object): work cut into fixed chunks, run in waves on
// the threads of each MPI rank, and merged by rank 0 in chunk order. Wave w is run by rank
// w mod N, each of its chunks into a slot of its own; rank 0 merges its own waves' slots and
// unpacks the others' in wave order, so every chunk is merged in index order whatever the
// threads and ranks: the result is bit-identical on any number of either (docs/model.md §5.7).
// A slot holds one chunk's result until it is merged; slots are reused wave after wave, so
// memory is bounded by the wave, not the run.
#include <cstdint>
#include <functional>
#include <string>

#include "assess/runner.hpp"  // Progress

namespace j232::assess {

struct ChunkWork {
  std::uint64_t chunks = 0;      // how many, run and merged as 0 .. chunks - 1
  std::uint64_t most_slots = 1;  // chunks in flight at once on a rank (the wave's size at most)
  // Runs chunk `chunk` into slot `slot` (cleared by `run` itself): called on the threads of
  // the rank that owns the chunk's wave, each slot by one thread at a time.
  std::function<void(std::uint64_t chunk, std::size_t slot)> run;
  // Rank 0 only, in chunk order: merges slot `slot`, holding chunk `chunk`.
  std::function<void(std::uint64_t chunk, std::size_t slot)> merge;
  // Under MPI: slots [0, n) as bytes (a rank's wave, sent to rank 0), and those bytes back
  // into slots [0, n) of rank 0.
  std::function<std::string(std::size_t n)> pack;
  std::function<void(const std::string& bytes, std::size_t n)> unpack;
  // Items (replicates, objects) in a chunk, for progress: counted when a rank runs the chunk
  // and, on rank 0, when it merges another rank's.
  std::function<std::uint64_t(std::uint64_t chunk)> items;
  Progress* progress = nullptr;
};

// How many slots a run of `work` needs: the largest wave any rank runs.
std::uint64_t wave_size(const ChunkWork& work);

// Runs and merges every chunk (slots 0 .. wave_size(work) - 1 must exist). Call inside
// on_threads().
void run_chunks(const ChunkWork& work);

// Runs `f` on `threads` threads (0: every core) in an arena of its own, not a process-wide
// limit: a program embedding the library keeps its other TBB work as it was. Only more
// threads than cores, asked for explicitly, raises the process-wide ceiling. Returns the
// number of threads used.
int on_threads(int threads, const std::function<void()>& f);
// The threads on_threads(threads, ...) runs on.
int thread_count(int threads);

}  // namespace j232::assess
