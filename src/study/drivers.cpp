#include "study/drivers.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "pipeline/pipeline.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/toml_reader.hpp"
#include "study/uncertainty.hpp"

namespace j232::study {

Drivers deciding_drivers(const std::string& file, int criterion, int threads, const std::function<void(std::size_t, std::size_t)>& on_run) {
  const toml::table base = scenario::parse_toml_file(file);
  scenario::Scenario nominal = scenario::read_scenario(base, file);
  if (const std::string why = pipeline::pipeline_of(nominal).refuse_drivers(); !why.empty()) throw std::invalid_argument(why);
  const UncertaintyPlan plan = uncertainty_plan(nominal);
  nominal.run.replicates = plan.replicates;
  nominal.run.until_settled = false;
  nominal.run.target_half_width.reset();

  // Every end of every input, as a scenario of its own (checked as the study checks them).
  std::vector<scenario::Scenario> designs = {nominal};
  std::vector<std::pair<std::size_t, std::string>> ends;  // (input, value) per design after the first
  for (std::size_t i = 0; i < plan.inputs.size(); ++i) {
    const auto& in = plan.inputs[i];
    const std::vector<std::string> values = in.values.empty() ? std::vector<std::string>{in.low, in.high} : in.values;
    const std::string key = plan.defaults ? fmt::format("(default) {}", in.parameter) : fmt::format("uncertainty.inputs[{}]", i + 1);
    for (const auto& v : values) {
      designs.push_back(scenario_with(base, file, in, v, key));
      ends.emplace_back(i, v);
    }
  }
  const Comparison c = compare_designs(std::move(designs), threads, nullptr, [&](std::size_t d, const scenario::Scenario&) {
    if (on_run) on_run(d, ends.size() + 1);
  });

  const auto k = static_cast<std::size_t>(criterion);
  const auto exact = [](const DesignResult& d) { return d.exact.computed ? d.exact.value : d.pass.estimate; };
  Drivers out;
  out.criterion = criterion;
  out.replicates = c.replicates;
  out.seed = c.seed;
  out.share = c.designs.front().shares[k].mean;
  out.p_pass_exact = exact(c.designs.front());
  out.default_inputs = plan.defaults;
  for (const auto& in : plan.inputs) out.ranked.push_back({in.parameter, in.basis, {}, 0.0});
  for (std::size_t e = 0; e < ends.size(); ++e) {
    const DesignResult& d = c.designs[e + 1];
    Driver& driver = out.ranked[ends[e].first];
    driver.ends.push_back({ends[e].second, d.verdict, d.shares[k].mean, c.versus_first[e].shares[k], exact(d)});
    if (d.verdict != "invalid") driver.largest_change = std::max(driver.largest_change, std::abs(c.versus_first[e].shares[k].mean));
  }
  // Largest change first; ties (inputs that change nothing) keep the set's order.
  std::stable_sort(out.ranked.begin(), out.ranked.end(), [](const Driver& a, const Driver& b) { return a.largest_change > b.largest_change; });
  return out;
}

}  // namespace j232::study
