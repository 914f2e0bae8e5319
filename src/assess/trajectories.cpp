#include "assess/trajectories.hpp"

#include <algorithm>

#include "random/stream.hpp"

namespace j232::assess {

void NotableNails::add(const MarkRow& row) {
  if (!row.mark.counted || !(row.mark.in_zone || row.mark.puncture)) return;
  const NailId id{row.replicate, static_cast<int>(row.nail)};
  if (id == last_) {
    // A further mark of the same nail: a zone mark promotes it to the zone kind.
    if (row.mark.in_zone && !last_in_zone_) {
      for (auto it = puncture_.begin(); it != puncture_.end(); ++it)
        if (it->second == id) {
          puncture_.erase(it);
          break;
        }
      keep(zone_, id);
      last_in_zone_ = true;
    }
    return;
  }
  last_ = id;
  last_in_zone_ = row.mark.in_zone;
  ++seen_;
  keep(row.mark.in_zone ? zone_ : puncture_, id);
}

void NotableNails::keep(Kept& kept, const NailId& id) {
  std::uint64_t state = id.first * 0x9E3779B97F4A7C15ULL ^ static_cast<std::uint64_t>(id.second);
  kept.emplace(random::splitmix64(state), id);
  if (kept.size() > cap_) kept.erase(std::prev(kept.end()));
}

std::vector<NotableNails::NailId> NotableNails::in_order(const Kept& kept) {
  std::vector<NailId> ids;
  for (const auto& entry : kept) ids.push_back(entry.second);
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<Trajectory> trace_nails(const Simulator& sim, std::size_t sampled, const NotableNails& notable) {
  std::vector<Trajectory> out;
  auto trace = [&](std::uint64_t replicate, int nail, const char* why) {
    Trajectory t;
    t.replicate = replicate;
    t.nail = nail;
    t.why = why;
    t.fate = sim.trace(replicate, nail, t.points).flight.fate;
    return t;
  };
  const int nails = sim.scenario().feed.nails;
  for (int n = 0; n < nails && out.size() < sampled; ++n) {
    Trajectory t = trace(0, n, "sample");
    if (t.fate != flight::Fate::NotStruck) out.push_back(std::move(t));
  }
  for (const auto& [r, n] : notable.zone()) out.push_back(trace(r, n, "operator zone"));
  for (const auto& [r, n] : notable.puncture()) out.push_back(trace(r, n, "puncture"));
  return out;
}

}  // namespace j232::assess
