// consumer SCENARIO REPLICATES SEED: one assessment through the installed library, its
// counts printed as JSON (package_check.sh compares them with `j232 run`'s result.json).
#include <cstdint>
#include <iostream>
#include <j232/assess/runner.hpp>
#include <j232/assess/summary.hpp>
#include <j232/scenario/scenario_reader.hpp>
#include <j232/version.hpp>
#include <nlohmann/json.hpp>
#include <string>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: consumer SCENARIO REPLICATES SEED\n";
    return 2;
  }
  j232::scenario::Scenario s = j232::scenario::read_scenario(argv[1]);
  s.run.replicates = std::stoll(argv[2]);
  s.run.seed = std::stoull(argv[3]);
  const j232::assess::Simulator simulator(s);
  const j232::assess::Assessment a = j232::assess::run_assessment(simulator, 2);
  const j232::assess::Summary sum = j232::assess::summarise(a, s);
  nlohmann::json out = {
      {"version", j232::version}, {"replicates", a.replicates}, {"replicates_passed", a.passed},        {"nails_fed", a.nails},
      {"nails_struck", a.struck}, {"marks", a.marks},           {"pass_probability", sum.pass.estimate}};
  std::cout << out.dump() << "\n";
}
