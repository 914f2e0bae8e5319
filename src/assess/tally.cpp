#include "assess/tally.hpp"

namespace j232::assess {

const char* category_name(int c) {
  static const char* names[kCategories] = {"hits_zone", "punctures_zone", "hits_outside", "punctures_outside"};
  return names[c];
}

double category_limit(const scenario::CriteriaSpec& c, int category) {
  switch (category) {
    case HitsZone: return c.hits_zone;
    case PuncturesZone: return c.punctures_zone;
    case HitsOutside: return c.hits_outside;
    default: return c.punctures_outside;
  }
}

void ReplicateTally::add(const flight::FlightResult& nail) {
  ++nails;
  counts[HitsZone] += static_cast<std::uint32_t>(nail.hits_zone);
  counts[PuncturesZone] += static_cast<std::uint32_t>(nail.punctures_zone);
  counts[HitsOutside] += static_cast<std::uint32_t>(nail.hits_outside);
  counts[PuncturesOutside] += static_cast<std::uint32_t>(nail.punctures_outside);
  marks += static_cast<std::uint32_t>(nail.mark_count - nail.uncounted_marks);
  uncounted_marks += static_cast<std::uint32_t>(nail.uncounted_marks);
  ++fates[static_cast<std::size_t>(nail.fate)];
}

Judgement judge(const ReplicateTally& t, const scenario::CriteriaSpec& criteria) {
  Judgement j;
  const double denominator = criteria.denominator == scenario::CriteriaSpec::Denominator::Marks ? t.marks : t.nails;
  j.pass = true;
  for (int c = 0; c < kCategories; ++c) {
    j.shares[c] = denominator > 0 ? t.counts[c] / denominator : 0.0;
    // A tiny slack so that 30 of 150 (exactly 20 %) passes a 20 % limit despite rounding.
    j.passes[c] = j.shares[c] <= category_limit(criteria, c) + 1e-12;
    j.pass = j.pass && j.passes[c];
  }
  return j;
}

}  // namespace j232::assess
