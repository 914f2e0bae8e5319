// The Python module `j232` (its compiled part, j232._j232): load a scenario from a file
// or a dict, set keys and parameters as sweeps do, run an assessment or a single impact.
// Results come back as plain dicts (the same content as result.json) with NumPy arrays for
// the marks and histograms. The GIL is released while the simulation runs.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "blade/blade_model.hpp"
#include "blade/impact.hpp"
#include "j232/version.hpp"
#include "report/atomic_file.hpp"
#include "report/impact_report.hpp"
#include "report/result_files.hpp"
#include "report/scenario_json.hpp"
#include "scenario/impact_input.hpp"
#include "scenario/input_error.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/toml_reader.hpp"
#include "study/parameters.hpp"

namespace py = pybind11;
using namespace j232;

namespace {

// Through the text the program writes (json_text: numbers to 12 significant digits), so a dict
// holds the same numbers as the program's files.
py::object from_json(const nlohmann::ordered_json& j) { return py::module_::import("json").attr("loads")(report::json_text(j, -1)); }

// A Python value as a TOML node: bool, int, float, str, list/tuple, dict.
std::unique_ptr<toml::node> to_toml(const py::handle& v, const std::string& key);

toml::table to_toml_table(const py::dict& d, const std::string& prefix) {
  toml::table t;
  for (const auto& [k, v] : d) {
    if (!py::isinstance<py::str>(k)) throw py::type_error("scenario keys are strings; got " + py::repr(k).cast<std::string>());
    const std::string key = k.cast<std::string>();
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    if (py::isinstance<py::dict>(v))
      t.insert(key, to_toml_table(v.cast<py::dict>(), path));
    else
      t.insert(key, std::move(*to_toml(v, path)));
  }
  return t;
}

std::unique_ptr<toml::node> to_toml(const py::handle& v, const std::string& key) {
  if (py::isinstance<py::bool_>(v)) return std::make_unique<toml::value<bool>>(v.cast<bool>());
  if (py::isinstance<py::int_>(v)) return std::make_unique<toml::value<std::int64_t>>(v.cast<std::int64_t>());
  if (py::isinstance<py::float_>(v)) return std::make_unique<toml::value<double>>(v.cast<double>());
  if (py::isinstance<py::str>(v)) return std::make_unique<toml::value<std::string>>(v.cast<std::string>());
  if (py::isinstance<py::dict>(v)) return std::make_unique<toml::table>(to_toml_table(v.cast<py::dict>(), key));
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    auto a = std::make_unique<toml::array>();
    for (const auto& item : v) {
      if (py::isinstance<py::dict>(item))
        a->push_back(to_toml_table(item.cast<py::dict>(), key));
      else
        a->push_back(std::move(*to_toml(item, key)));
    }
    return a;
  }
  throw py::type_error("scenario key " + key + ": expected a bool, number, string, list or dict, got " + py::repr(v).cast<std::string>());
}

// How a setting's value is written: text as it is ("2500 rpm"), numbers in full precision.
std::string setting_text(const py::handle& v, const std::string& name) {
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)) return py::repr(v).cast<std::string>();
  throw py::type_error("setting " + name + ": expected a string such as \"2500 rpm\" or a number, got " + py::repr(v).cast<std::string>());
}

std::vector<study::Setting> read_settings(const py::dict& settings, const std::string& origin) {
  std::vector<study::Setting> out;
  for (const auto& [k, v] : settings) {
    const std::string name = k.cast<std::string>();
    out.push_back(study::make_setting(study::parameter_info(name), setting_text(v, name), origin, std::nullopt, name));
  }
  return out;
}

// A parsed scenario document, where it came from (errors name it; relative mesh paths are
// anchored there) and what it reads as.
struct PyScenario {
  toml::table document;
  std::string file;
  py::dict settings;  // applied on top of `document`
  scenario::Scenario scenario;
};

// Bad input given from Python; raised as j232.InputError, as scenario::InputError is.
struct PythonInputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Values that come from Python (settings, a dict) have no place in a file; the reader
// blames "the command line" for them, which here means the caller's settings or dict.
template <class F>
auto from_python(F&& f) {
  try {
    return f();
  } catch (const scenario::InputError& e) {
    if (!e.file().empty()) throw;
    std::string text = e.what();
    for (const std::string prefix : {"command line: option for ", "command line: "})
      if (text.rfind(prefix, 0) == 0) {
        text = "Python settings or dict: " + text.substr(prefix.size());
        break;
      }
    throw PythonInputError(text);
  }
}

PyScenario make_scenario(toml::table document, std::string file, const py::dict& settings) {
  return from_python([&] {
    PyScenario p{std::move(document), std::move(file), settings, {}};
    // As a sweep point is made: file keys into the document, the document read with every
    // check, then the named parameters (blade_speed, bevel_angle, ...) onto the result.
    const auto parsed = read_settings(settings, p.file);
    toml::table doc = p.document;
    for (const auto& s : parsed) study::apply_to_document(s, doc, p.file);
    p.scenario = scenario::read_scenario(doc, p.file);
    for (const auto& s : parsed) study::apply(s, p.scenario);
    return p;
  });
}

PyScenario load_scenario(const py::object& source, const py::dict& settings, const std::string& base_dir) {
  if (py::isinstance<py::dict>(source)) {
    // A dict has no file: `base_dir` anchors relative mesh paths (a file name inside it
    // names the scenario in messages).
    return make_scenario(to_toml_table(source.cast<py::dict>(), ""), base_dir + "/<dict>", settings);
  }
  const std::string file = py::str(source).cast<std::string>();  // str or os.PathLike
  return make_scenario(scenario::parse_toml_file(file), file, settings);
}

template <class T>
py::array_t<T> to_array(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict histogram_dict(const assess::Histogram& h) {
  py::dict d;
  d["bin_width"] = h.bin_width;
  d["origin"] = h.origin;  // the first bin's lower edge
  d["counts"] = to_array(h.counts);
  d["total"] = h.total;
  d["mean"] = h.mean();
  return d;
}

// Every located mark as columns (one NumPy array per field, in (replicate, nail) order).
struct MarkColumns {
  std::vector<std::uint32_t> replicate, nail;
  std::vector<double> x, y, z, normal_energy, flight_time;
  std::vector<bool> in_zone, puncture, counted;
  std::vector<std::uint16_t> spindle, station;
  std::vector<std::int32_t> strikes;

  void add(const assess::MarkRow& r) {
    replicate.push_back(r.replicate), nail.push_back(r.nail);
    x.push_back(r.mark.point.x()), y.push_back(r.mark.point.y()), z.push_back(r.mark.point.z());
    normal_energy.push_back(r.mark.normal_energy), flight_time.push_back(r.flight_time);
    in_zone.push_back(r.mark.in_zone), puncture.push_back(r.mark.puncture), counted.push_back(r.mark.counted);
    spindle.push_back(r.spindle), station.push_back(r.station), strikes.push_back(r.strikes);
  }
  static py::array_t<bool> bools(const std::vector<bool>& v) {
    py::array_t<bool> a(static_cast<py::ssize_t>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) a.mutable_data()[i] = v[i];
    return a;
  }
  py::dict dict() const {
    py::dict d;
    d["replicate"] = to_array(replicate), d["nail"] = to_array(nail);
    d["x"] = to_array(x), d["y"] = to_array(y), d["z"] = to_array(z);
    d["normal_energy"] = to_array(normal_energy), d["flight_time"] = to_array(flight_time);
    d["in_zone"] = bools(in_zone), d["puncture"] = bools(puncture), d["counted"] = bools(counted);
    d["spindle"] = to_array(spindle), d["station"] = to_array(station), d["strikes"] = to_array(strikes);
    return d;
  }
};

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

py::dict assess_scenario(const PyScenario& p, std::optional<long long> replicates, std::optional<std::uint64_t> seed, int threads,
                         bool marks) {
  scenario::Scenario s = p.scenario;
  if (replicates) {
    if (*replicates < 1) throw py::value_error("replicates: expected at least 1, got " + std::to_string(*replicates));
    s.run.replicates = *replicates;
  }
  if (seed) s.run.seed = *seed;
  if (threads < 0) throw py::value_error("threads: expected 0 (all cores) or more, got " + std::to_string(threads));
  MarkColumns columns;
  assess::Assessment a;
  std::optional<assess::Simulator> simulator;
  {
    py::gil_scoped_release released;  // no Python object is touched below
    simulator.emplace(s);
    const assess::MarkSink sink = marks ? assess::MarkSink([&](const assess::MarkRow& r) { columns.add(r); }) : assess::MarkSink{};
    a = assess::run_assessment(*simulator, threads, nullptr, sink);
  }
  const assess::Summary sum = assess::summarise(a, s, assess::kExactDraws);  // as j232 run
  report::Provenance provenance{j232::version, j232::git_revision, utc_now(), "python", a.threads, a.wall_seconds, {}, 1};
  py::dict result = from_json(report::result_json(s, a, sum, provenance));
  py::dict histograms;
  histograms["exit_speed_m_s"] = histogram_dict(a.exit_speed);
  histograms["mark_energy_j"] = histogram_dict(a.mark_energy);
  histograms["board_energy_j"] = histogram_dict(a.board_energy);
  histograms["board_energy_per_width_j_m"] = histogram_dict(a.board_energy_per_width);
  histograms["contact_radius_m"] = histogram_dict(a.contact_radius);
  histograms["strikes"] = histogram_dict(a.strikes);
  histograms["launch_elevation_deg"] = histogram_dict(a.launch_elevation);
  histograms["contacts_per_pass"] = histogram_dict(a.contacts_per_pass);
  result["histograms"] = histograms;
  if (marks) result["marks_table"] = columns.dict();
  return result;
}

py::dict impact_checked(const py::object& source, const py::dict& settings) {
  toml::table doc;
  std::string file;
  if (py::isinstance<py::dict>(source)) {
    doc = to_toml_table(source.cast<py::dict>(), "");
    file = "<dict>";
  } else {
    file = py::str(source).cast<std::string>();
    doc = scenario::parse_toml_file(file);
  }
  const auto parsed = read_settings(settings, file);
  for (const auto& s : parsed) study::apply_to_document(s, doc, file);
  scenario::ImpactCase input = scenario::read_impact_case(doc, file);
  for (const auto& s : parsed) study::apply(s, input);
  const blade::BladeModel model(input.blade);
  const blade::ImpactSolution solution = blade::solve_impact(model, input.location, input.object, input.restitution);
  return from_json(report::impact_json(input, solution));
}

py::dict impact(const py::object& source, const py::dict& settings) {
  return from_python([&] { return impact_checked(source, settings); });
}

}  // namespace

PYBIND11_MODULE(_j232, m) {
  m.doc() = "j232: Monte Carlo assessment of the SAE J232 thrown-object test of rotary mowers";
  m.attr("__version__") = j232::version;
  m.attr("git_revision") = j232::git_revision;
  // Bad input is a ValueError that names file, key, value and what was expected.
  static py::exception<scenario::InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception<report::FileError>(m, "FileError", PyExc_OSError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const scenario::InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    } catch (const PythonInputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    }
  });

  py::class_<PyScenario>(m, "Scenario",
                         "A J232 scenario: read and checked from a TOML file or a dict, with keys or named parameters set "
                         "on top (as a sweep point is made).")
      .def(py::init(&load_scenario), py::arg("source"), py::arg("settings") = py::dict(), py::arg("base_dir") = ".",
           "Scenario(source, settings={}, base_dir='.'): source is a path or a dict of the TOML file's tables; settings "
           "maps dotted keys ('housing.skirt_bottom') or named parameters ('blade_speed', 'bevel_angle', ...) to values "
           "('2500 rpm', 0.5); base_dir anchors a dict's relative mesh paths. Raises j232.InputError naming the key, "
           "value and what was expected.")
      .def(
          "with_settings",
          [](const PyScenario& p, const py::dict& more) {
            py::dict all = p.settings.attr("copy")();
            for (const auto& [k, v] : more) all[k] = v;
            return make_scenario(p.document, p.file, all);
          },
          py::arg("settings"), "A copy with more settings on top of this one's.")
      .def_property_readonly("file", [](const PyScenario& p) { return p.file; })
      .def_property_readonly("settings", [](const PyScenario& p) { return p.settings; })
      .def(
          "to_dict", [](const PyScenario& p) { return from_json(report::scenario_json(p.scenario)); },
          "The scenario as every result echoes it: every value used, in SI.")
      .def("assess", &assess_scenario, py::arg("replicates") = py::none(), py::arg("seed") = py::none(), py::arg("threads") = 0,
           py::arg("marks") = true,
           "Runs the assessment (replicates and seed default to the scenario's; threads 0 = all cores) and returns what "
           "result.json holds, plus 'histograms' (bin_width and NumPy counts) and, with marks=True, 'marks_table': one "
           "NumPy array per column of every located mark. The same scenario and seed give the same numbers on any "
           "thread count.")
      .def("__repr__", [](const PyScenario& p) {
        return "<j232.Scenario " + p.file + (p.settings.empty() ? "" : " with " + py::repr(p.settings).cast<std::string>()) + ">";
      });

  m.def("impact", &impact, py::arg("source"), py::arg("settings") = py::dict(),
        "One nail-on-blade impact (report 445-1's model) from an impact file or dict, with settings on top (blade_speed, "
        "restitution, contact_radius, object_mass, object_speed, or dotted keys); returns what `j232 impact --json` "
        "prints.");
}
