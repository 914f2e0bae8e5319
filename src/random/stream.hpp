#pragma once
// Random numbers as a pure function of indices (docs/model.md §5.7, after pbrt-v4 and
// OpenMC): every nail's stream is keyed by (scenario seed, replicate, nail, purpose),
// so results are bit-identical for any thread count and any order of work. In flight each
// random event has its own stream, keyed further by its number among the nail's events of
// that purpose (EventDraws), so that two designs compared with common random numbers draw
// the same numbers for the same event even after an earlier event has gone differently.
//
// Engine: xoshiro256++ (Blackman & Vigna, 2019), 256-bit state seeded through
// SplitMix64 from the key. Distributions come from Boost.Random, whose algorithms are
// fixed (std:: distributions differ between standard libraries).
#include <cstdint>
#include <limits>

namespace j232::random {

inline constexpr std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// What a stream is used for; separate purposes never share numbers.
enum class Purpose : std::uint64_t { Feed = 1, Estimator = 3, GuardPass = 4, Roughness = 5, FieldObject = 6, Recheck = 7, BoardFit = 8, Test = 99 };

class Stream {
 public:
  using result_type = std::uint64_t;
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }

  Stream(std::uint64_t seed, std::uint64_t replicate, std::uint64_t nail, Purpose purpose) {
    std::uint64_t s = seed;
    std::uint64_t key = splitmix64(s);
    key ^= replicate * 0xD1B54A32D192ED03ULL;
    s = key;
    key = splitmix64(s) ^ (nail * 0x8CB92BA72F3D8DD7ULL);
    s = key;
    key = splitmix64(s) ^ static_cast<std::uint64_t>(purpose);
    s = key;
    for (auto& word : state_) word = splitmix64(s);
  }
  // The stream of one event: the key above, and the event's number.
  Stream(std::uint64_t seed, std::uint64_t replicate, std::uint64_t nail, Purpose purpose, std::uint64_t event)
      : Stream(seed, replicate, nail, purpose) {
    std::uint64_t s = state_[0] ^ state_[3] ^ (event * 0x9FB21C651E98DF25ULL);
    for (auto& word : state_) word ^= splitmix64(s);
  }

  result_type operator()() {
    const std::uint64_t result = rotl(state_[0] + state_[3], 23) + state_[0];
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>((*this)() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

// One nail's random events in flight: the n-th event of a purpose draws from the stream
// keyed (seed, replicate, nail, purpose, n), whatever came before it.
class EventDraws {
 public:
  EventDraws(std::uint64_t seed, std::uint64_t replicate, std::uint64_t nail) : seed_(seed), replicate_(replicate), nail_(nail) {}
  Stream next(Purpose purpose) {
    std::uint64_t& n = purpose == Purpose::GuardPass ? guard_passes_ : purpose == Purpose::Roughness ? rough_facets_ : others_;
    return Stream(seed_, replicate_, nail_, purpose, n++);
  }

 private:
  std::uint64_t seed_, replicate_, nail_;
  std::uint64_t guard_passes_ = 0, rough_facets_ = 0, others_ = 0;
};

}  // namespace j232::random
