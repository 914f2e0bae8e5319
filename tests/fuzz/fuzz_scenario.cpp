// libFuzzer target: the scenario reader, through to a built simulator and a tiny run.
// Bad input must end in an InputError (exit 2 for a user); any other exception, crash,
// hang or non-finite result is a bug.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <toml++/toml.h>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "report/result_files.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace j232;
  const std::string text(reinterpret_cast<const char*>(data), size);
  toml::table document;
  try {
    document = toml::parse(std::string_view(text), std::string_view("fuzz.toml"));
  } catch (const toml::parse_error&) {
    return 0;
  }
  try {
    scenario::Scenario s = scenario::read_scenario(document, "fuzz.toml");
    s.run.replicates = 1;
    s.run.target_half_width.reset();
    s.feed.nails = std::min(s.feed.nails, 4);
    const assess::Simulator sim(s);
    const assess::Assessment a = assess::run_assessment(sim, 1);
    const assess::Summary sum = assess::summarise(a, s);
    report::require_finite(report::result_json(s, a, sum, {}));
  } catch (const scenario::InputError&) {
  }
  return 0;
}
