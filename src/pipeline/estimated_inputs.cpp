#include "pipeline/estimated_inputs.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "scenario/ground_kinds.hpp"

namespace j232::pipeline {

scenario::UncertainInput estimated(std::string parameter, std::string low, std::string high, std::string basis, std::string distribution) {
  scenario::UncertainInput in;
  in.parameter = std::move(parameter), in.low = std::move(low), in.high = std::move(high), in.basis = std::move(basis);
  in.distribution = std::move(distribution);
  return in;
}

scenario::UncertainInput model_form(std::string parameter, std::vector<std::string> values, std::string basis) {
  scenario::UncertainInput in;
  in.parameter = std::move(parameter), in.values = std::move(values), in.basis = std::move(basis);
  return in;
}

scenario::UncertainInput contact_model_form() {
  return model_form("contacts.model", {"sequential", "simultaneous"},
                    "model form: the contacts of one instant one after another, or together (Moreau's impact); neither is exact "
                    "for a rod's multiple impacts (Stoianovici and Hurmuzlu 1996)");
}

scenario::UncertainInput restitution_law_form() {
  return model_form("run.restitution_law", {"energetic", "poisson"},
                    "model form: Stronge's energetic restitution, or Poisson's (the earlier law); the two agree without "
                    "friction and differ where the slip halts or reverses within an impact");
}

// What the test's mower stands on: the test's text is not to hand, so every kind of the
// table is drawn. Each kind carries its own restitution, friction, roughness and
// penetrability (docs/model.md §5.3a), so neither its restitution nor the angle law's cap is
// drawn beside it (a drawn value would override every kind's own, and a cap below a hard
// kind's restitution is refused).
scenario::UncertainInput ground_kind_form() {
  std::vector<std::string> kinds;
  for (const auto& k : scenario::kGroundKinds) kinds.emplace_back(k.name);
  return model_form("ground.kind", kinds,
                    "set-up: what the test ground is (SAE J232's text on it not to hand); each kind with its own restitution, friction "
                    "and penetrability (recalled tables and estimates)");
}

std::vector<scenario::UncertainInput> guard_openness(const scenario::Scenario& s) {
  const auto& guards = s.housing.guards;
  const auto chains = static_cast<std::size_t>(std::count_if(guards.begin(), guards.end(), [](const auto& g) { return g.kind == scenario::GuardSpec::Kind::Chains; }));
  const char* basis = "estimate: single row 0.3-0.5 open, double row 0.1-0.25";
  if (chains == 0) return {};
  if (chains == guards.size()) return {estimated("housing.guards.openness", "0.1", "0.4", basis)};
  std::vector<scenario::UncertainInput> out;
  for (std::size_t k = 0; k < guards.size(); ++k)
    if (guards[k].kind == scenario::GuardSpec::Kind::Chains)
      out.push_back(estimated(fmt::format("housing.guards[{}].openness", k + 1), "0.1", "0.4", basis));
  return out;
}

int commonest_cut_off(const std::array<std::uint64_t, flight::kCutOffReasons>& by) {
  int most = 0;
  for (int why = 1; why < flight::kCutOffReasons; ++why)
    if (by[static_cast<std::size_t>(why)] > by[static_cast<std::size_t>(most)]) most = why;
  return most;
}

}  // namespace j232::pipeline
