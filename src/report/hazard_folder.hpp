#pragma once
// One field scenario's hazard run into an output folder (`j232 hazard`, and a field
// scenario in `j232 batch`): hazard.csv, hazard.html and hazard.json written as a set by
// rank 0 of an MPI job (every rank simulates its share).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "report/display_units.hpp"

namespace j232::report {

struct HazardOverrides {
  long long objects = 0;  // 0: the scenario's field.objects_simulated
  std::optional<unsigned long long> seed;
  int threads = -1;       // -1: the scenario's
  DisplayUnits units;     // of hazard.html and the terminal's summary (the JSON and CSV keep SI)
};

struct HazardOutcome {
  nlohmann::ordered_json result;  // hazard.json (empty on ranks other than 0)
  std::string summary_text;       // the terminal's summary
  bool valid = false;
  bool writer = true;             // this process wrote the folder
};

// Throws scenario::InputError for a bad scenario, report::FileError for a folder that
// cannot be written (checked before the simulation).
HazardOutcome hazard_to_folder(const std::string& scenario_file, const HazardOverrides& o, const std::string& out);

}  // namespace j232::report
