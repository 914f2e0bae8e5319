#include "assess/chunk_runner.hpp"

#include <algorithm>
#include <optional>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "assess/cluster.hpp"
#include "invariant/check.hpp"

namespace j232::assess {

namespace {
// Chunks per wave: as many as a rank may hold alone, or in an MPI job fewer, so that every
// rank gets some. Chunks are merged in index order whatever the waves, so their size
// changes nothing in the result.
std::uint64_t wave_of(const ChunkWork& work, std::uint64_t ranks) {
  const std::uint64_t most = std::max<std::uint64_t>(work.most_slots, 1);
  return ranks == 1 ? most : std::clamp<std::uint64_t>((work.chunks + 2 * ranks - 1) / (2 * ranks), 1, most);
}
}  // namespace

std::uint64_t wave_size(const ChunkWork& work) {
  return std::min(work.chunks, wave_of(work, static_cast<std::uint64_t>(cluster::size())));
}

void run_chunks(const ChunkWork& work) {
  const auto ranks = static_cast<std::uint64_t>(cluster::size());
  const auto rank = static_cast<std::uint64_t>(cluster::rank());
  const std::uint64_t wave = wave_of(work, ranks);
  const auto count = [&](std::uint64_t chunk) {
    if (work.progress && work.items) work.progress->done += static_cast<long long>(work.items(chunk));
  };
  for (std::uint64_t w = 0, w0 = 0; w0 < work.chunks; ++w, w0 += wave) {
    const std::uint64_t in_wave = std::min(wave, work.chunks - w0);
    const std::uint64_t owner = w % ranks;
    if (owner == rank) {
      tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, in_wave, 1), [&](const tbb::blocked_range<std::uint64_t>& range) {
        for (std::uint64_t c = range.begin(); c != range.end(); ++c) {
          work.run(w0 + c, static_cast<std::size_t>(c));
          count(w0 + c);
        }
      });
      if (rank == 0)
        for (std::uint64_t c = 0; c < in_wave; ++c) work.merge(w0 + c, static_cast<std::size_t>(c));  // in chunk order
      else
        cluster::send(0, work.pack(static_cast<std::size_t>(in_wave)));
    } else if (rank == 0) {
      work.unpack(cluster::receive(static_cast<int>(owner)), static_cast<std::size_t>(in_wave));
      for (std::uint64_t c = 0; c < in_wave; ++c) {
        work.merge(w0 + c, static_cast<std::size_t>(c));
        count(w0 + c);
      }
    }
  }
}

int thread_count(int threads) { return threads > 0 ? threads : static_cast<int>(tbb::this_task_arena::max_concurrency()); }

int on_threads(int threads, const std::function<void()>& f) {
  const int available = static_cast<int>(tbb::this_task_arena::max_concurrency());
  const int used = thread_count(threads);
  J232_CHECK(used > 0);
  tbb::task_arena arena(used);
  std::optional<tbb::global_control> oversubscribe;
  if (used > available) oversubscribe.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(used));
  arena.execute(f);
  return used;
}

}  // namespace j232::assess
