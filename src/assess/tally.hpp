#pragma once
// One replicate is one whole J232 test: its nails' marks counted in four categories,
// turned into shares and judged against the criteria (docs/model.md §5.6).
#include <array>
#include <cstdint>

#include "flight/nail_flight.hpp"
#include "scenario/scenario.hpp"

namespace j232::assess {

enum Category { HitsZone = 0, PuncturesZone = 1, HitsOutside = 2, PuncturesOutside = 3 };
inline constexpr int kCategories = 4;
const char* category_name(int c);  // "hits_zone", ...
double category_limit(const scenario::CriteriaSpec& c, int category);

struct ReplicateTally {
  std::array<std::uint32_t, kCategories> counts{};
  std::uint32_t nails = 0;
  std::uint32_t marks = 0;            // counted marks
  std::uint32_t uncounted_marks = 0;  // below the counted height
  std::array<std::uint32_t, flight::kFates> fates{};

  void add(const flight::FlightResult& nail);
};

struct Judgement {
  std::array<double, kCategories> shares{};
  std::array<bool, kCategories> passes{};
  bool pass = false;
};

// Shares use the scenario's denominator: nails fed, or all marks (the report's literal
// wording; with no marks every share is zero).
Judgement judge(const ReplicateTally& tally, const scenario::CriteriaSpec& criteria);

}  // namespace j232::assess
