#pragma once
// Whole paths of chosen nails, for pictures (docs/model.md §5.8): a run keeps no paths
// (the per-nail path allocates nothing), so the chosen nails are simulated again with
// their paths recorded - deterministic, they do exactly what they did in the run.
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "assess/runner.hpp"

namespace j232::assess {

// Collects, from a run's marks, the nails worth drawing: those with a counted mark in the
// operator zone, and those with a counted puncture elsewhere. Of each kind at most `cap`
// are kept, chosen uniformly at random (the ones with the smallest hash of their replicate
// and nail, so the choice is the same on any thread count and spread over the whole run
// rather than its first replicates); the rest are counted. Rows come as the run's mark
// sink gives them: a nail's marks one after another.
class NotableNails {
 public:
  using NailId = std::pair<std::uint64_t, int>;  // replicate, nail
  explicit NotableNails(std::size_t cap_per_kind = 100) : cap_(cap_per_kind) {}
  void add(const MarkRow& row);
  // The kept nails in (replicate, nail) order.
  std::vector<NailId> zone() const { return in_order(zone_); }
  std::vector<NailId> puncture() const { return in_order(puncture_); }
  std::uint64_t seen() const { return seen_; }
  std::uint64_t not_kept() const { return seen_ - zone_.size() - puncture_.size(); }

 private:
  using Kept = std::set<std::pair<std::uint64_t, NailId>>;  // (hash, nail)
  static std::vector<NailId> in_order(const Kept& kept);
  void keep(Kept& kept, const NailId& id);
  std::size_t cap_;
  Kept zone_, puncture_;
  std::uint64_t seen_ = 0;
  NailId last_{~0ull, -1};
  bool last_in_zone_ = false;
};

// The first `sampled` struck nails of replicate 0, then the notable ones, traced again.
std::vector<Trajectory> trace_nails(const Simulator& sim, std::size_t sampled, const NotableNails& notable);

}  // namespace j232::assess
