#pragma once
// Parameter studies: one base file (an impact case or a J232 scenario), one parameter
// along the x axis and any number of series parameters (one curve per combination).
//
// Over an impact case each point is one impact (report 445-1, Appendix A, first
// program): the object's speed after impact, dimensional and in the report's
// dimensionless form
//     mass ratio  = object mass / blade mass,
//     velocity    = (v' - v0) / (omega L),
// v' the speed after impact, v0 the object's speed toward the blade before it, omega L
// the blade's tip speed (the Fortran's Z = (VA2 - 440) / (4 pi rpm) for a 2 ft blade).
// Over a J232 scenario each point is a full Monte Carlo assessment: P(pass) with its
// 95 % interval, and the four mean shares. Over a field scenario each point is a hazard
// run (j232 hazard): objects thrown per km, each plane's hazardous flux with its 95 %
// interval, and the hazard distance each way (estimate and conservative).
//
// Sweep file (TOML):
//   title = "..."              base = "path/relative/to/this/file.toml"
//   [set]       blade_speed = "700 rpm"      (fixed at every point; any parameter)
//   [x]         parameter = "object_mass"   values = ["0.25 lb", "1 lb"]
//               (or from = "0.25 lb"  to = "22 lb"  steps = 8)
//   [[series]]  parameter = "restitution"   values = [0.3, 0.5, 0.7, 0.9]
//   [run]       replicates = 200            (J232 scenarios only)
//               objects = 50000             (field scenarios only)
// Parameters: study/parameters.hpp.
#include <optional>
#include <string>
#include <vector>

#include "study/parameters.hpp"

namespace j232::study {

struct Axis {
  ParameterInfo info;
  std::vector<Setting> values;
};

struct SweepSpec {
  std::string source;  // the sweep file, or "command line"
  std::string name;    // stem of the output files
  std::string title;
  std::string base;            // base file, as a path from the working directory
  std::vector<Setting> fixed;  // applied first, at every point
  Axis x;
  std::vector<Axis> series;
  long long replicates = 0;  // J232 scenarios: replicates per point (0: the scenario's)
  long long objects = 0;     // field scenarios: objects per point (0: the scenario's field.objects_simulated)
  std::optional<unsigned long long> seed;
};

// Throws scenario::InputError naming file, line, key and value.
SweepSpec read_sweep_file(const std::string& file);
// "PARAMETER=V1,V2,..." (values with units: "blade_speed=700 rpm,800 rpm").
Axis parse_axis(const std::string& text, const std::string& option);

// A finished sweep: one row per point, in series-major order.
struct SweepTable {
  enum class Kind { Impact, Assessment, Hazard } kind = Kind::Impact;  // an impact case, a J232 scenario, a field scenario
  std::vector<std::string> columns;  // CSV header after the label columns
  struct Row {
    std::size_t series = 0;
    std::string series_label;  // "700 rpm, 16 lb" ("" with no series)
    std::string x_text;
    double x = 0;  // in the axis' display unit
    std::vector<double> values;  // empty at a point not assessed
    // Why the point has no values (a J232 or field sweep's point the reader refused, or whose
    // run was invalid: too many nails or objects cut off); empty: assessed. The sweep goes on.
    std::string invalid;
  };
  std::vector<Row> rows;
  bool any_invalid() const {
    for (const auto& r : rows)
      if (!r.invalid.empty()) return true;
    return false;
  }
  std::vector<std::string> series_labels;
  double required_pass_probability = 0;
  // Hazard sweeps: the planes' names and the directions, in their columns' order.
  std::vector<std::string> planes, directions;
};
// How the kinds are named in messages ("J232 assessments").
const char* points_name(SweepTable::Kind kind);

struct SweepProgress {
  virtual ~SweepProgress() = default;
  virtual void point(std::size_t done, std::size_t total) = 0;
};

// Runs every point. `threads`: for J232 scenarios (0: all cores).
SweepTable run_sweep(const SweepSpec& spec, int threads, SweepProgress* progress);

// Column index by name (for charts and tests); throws std::out_of_range.
std::size_t column(const SweepTable& t, const std::string& name);

// Its CSV and charts: report/sweep_report.hpp.

}  // namespace j232::study
