// The uncertainty study of a scenario (study/uncertainty.hpp): deterministic, checked inputs,
// and an input the simulation ignores gets no share of the variance.
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <map>
#include <string>

#include "scenario/input_error.hpp"
#include "scenario/scenario.hpp"
#include "scenario/scenario_reader.hpp"
#include "scenario/toml_override.hpp"
#include "scenario/toml_reader.hpp"
#include "field/field_simulator.hpp"
#include "field/hazard_run.hpp"
#include "flight/nail_flight.hpp"
#include "report/uncertainty_report.hpp"
#include "study/sensitivity.hpp"
#include "study/uncertainty.hpp"
#include "study/drivers.hpp"
#include "study/parameters.hpp"
#include "assess/runner.hpp"
#include "assess/simulator.hpp"
#include "assess/summary.hpp"
#include "field_scenario.hpp"

using namespace j232;

namespace {
std::string scenario_path(const char* name) { return std::string(J232_SOURCE_DIR) + "/scenarios/" + name; }

// The raised-skirt scenario with an [uncertainty] table replaced by `table`.
std::string with_uncertainty(const std::string& name, const std::string& table) {
  std::ifstream in(scenario_path("highway-pivoted-raised-skirt.toml"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = text.substr(0, text.find("[uncertainty]"));
  // Meshes and relative paths: none in this scenario, so the copy may live anywhere.
  const std::string path = std::string(J232_BINARY_DIR) + "/" + name;
  std::ofstream(path) << text << table;
  return path;
}
// A study of one input (the edge's bevel) over two base draws, its outputs left to fill.
study::UncertaintyResult one_input_study() {
  study::UncertaintyResult r;
  r.title = "test", r.scenario_file = "test.toml";
  r.output_info = study::uq_outputs(scenario::Scenario{});
  scenario::UncertainInput input;
  input.parameter = "bevel_angle", input.low = "20 deg", input.high = "45 deg", input.basis = "test";
  r.plan.inputs.push_back(input);
  r.plan.base_draws = 2;
  r.design = study::saltelli_design(1, 2);
  return r;
}
}  // namespace

TEST_CASE("uncertainty: the study is deterministic, and an ignored input gets no share", "[uncertainty][long]") {
  // air.cd_axial is a real input, but with drag off it changes nothing.
  const auto file = with_uncertainty("uq-ignored.toml", R"(
[air]
drag = false
[uncertainty]
base_draws = 6
replicates = 12
[[uncertainty.inputs]]
parameter = "bevel_angle"
low = "20 deg"
high = "45 deg"
basis = "test"
[[uncertainty.inputs]]
parameter = "air.cd_axial"
low = 0.5
high = 1.0
basis = "test: drag is off, so this must not matter"
)");
  const auto a = study::run_uncertainty(file, 2), b = study::run_uncertainty(file, 1);
  REQUIRE(a.outputs.size() == 6 * 4);
  for (std::size_t i = 0; i < a.outputs.size(); ++i) CHECK(a.outputs[i] == b.outputs[i]);  // any thread count
  const auto& pass = a.indices[0];
  CHECK(pass.total[1].estimate == 0.0);  // f(AB_2) == f(A) at every row
  CHECK(pass.first[1].estimate == 0.0);
  CHECK(a.indices[1].total[1].estimate == 0.0);  // and for P(pass) from every nail
  // P(pass) from every nail, at every draw: a probability, near the replicates' share.
  for (const auto& out : a.outputs) {
    CHECK(out[1] >= 0.0);
    CHECK(out[1] <= 1.0);
    CHECK(std::abs(out[1] - out[0]) < 4 * std::sqrt(0.25 / 12) + 0.02);
  }
  // What chance alone would give each output's variance: binomial over the base draws (A
  // and B), of the replicates for P(pass), of the nails fed for a share; none for P(pass)
  // from every nail or the verdict.
  REQUIRE(a.noise_variance.size() == a.output_info.size());
  double pass_noise = 0, share_noise = 0;
  for (std::size_t run = 0; run < 2 * a.design.base; ++run)
    pass_noise += a.outputs[run][0] * (1 - a.outputs[run][0]) / 12, share_noise += a.outputs[run][5] * (1 - a.outputs[run][5]) / (12 * 150);
  CHECK(a.noise_variance[0] == Approx(pass_noise / static_cast<double>(2 * a.design.base)));
  CHECK(a.noise_variance[5] == Approx(share_noise / static_cast<double>(2 * a.design.base)));
  CHECK(a.noise_variance[1] == -1.0);
  CHECK(a.noise_variance[6] == -1.0);
  // The edge's bevel decides how this mower's nails leave: it carries the variance.
  REQUIRE(a.output_info[5].name == "punctures_outside");
  const auto& punct = a.indices[5];
  REQUIRE(punct.variance > 0);
  CHECK(punct.total[0].estimate > 0.5);
}

TEST_CASE("uncertainty: bad inputs are refused with the key and what was expected", "[uncertainty][input]") {
  using Catch::Contains;
  auto one = [](const std::string& low, const std::string& high) {
    return "[uncertainty]\n[[uncertainty.inputs]]\nparameter = \"bevel_angle\"\nlow = " + low + "\nhigh = " + high + "\nbasis = \"x\"\n";
  };
  CHECK_THROWS_WITH(study::run_uncertainty(with_uncertainty("uq-bad1.toml", one("\"20 deg\"", "\"10 rad\"")), 1),
                    Contains("uncertainty.inputs[1].high") && Contains("same unit"));
  CHECK_THROWS_WITH(study::run_uncertainty(with_uncertainty("uq-bad2.toml", one("\"30 deg\"", "\"25 deg\"")), 1),
                    Contains("uncertainty.inputs[1].high") && Contains("above low"));
  CHECK_THROWS_WITH(study::run_uncertainty(with_uncertainty("uq-bad3.toml", one("\"20 deg\"", "\"95 deg\"")), 1), Contains("90 deg"));
  CHECK_THROWS_AS(scenario::read_scenario(
                      with_uncertainty("uq-bad4.toml", "[uncertainty]\n[[uncertainty.inputs]]\nparameter = \"x\"\nlow = 1\nhigh = 2\n")),
                  scenario::InputError);  // no basis
  // A drawn value the scenario's reader refuses is blamed on the input that draws it (file,
  // line and input), not on the command line.
  const std::string drawn = with_uncertainty(
      "uq-bad5.toml", "[uncertainty]\n[[uncertainty.inputs]]\nparameter = \"restitution.e\"\nlow = 0.5\nhigh = 1.5\nbasis = \"x\"\n");
  try {
    study::run_uncertainty(drawn, 1);
    FAIL("a drawn restitution of 1.5 was accepted");
  } catch (const scenario::InputError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK_THAT(what, Contains("uq-bad5.toml:") && Contains("(uncertainty.inputs[1])") && Contains("restitution.e = 1.5") &&
                         !Contains("command line"));
  }
}

TEST_CASE("uncertainty: a discrete input takes each of its values, equally often, and is ranked like any other", "[uncertainty][discrete][long]") {
  using Catch::Contains;
  const auto file = with_uncertainty("uq-discrete.toml", R"(
[uncertainty]
base_draws = 8
replicates = 12
[[uncertainty.inputs]]
parameter = "bevel_angle"
values = ["20 deg", "45 deg"]
basis = "test: two edges on offer"
[[uncertainty.inputs]]
parameter = "air.cd_axial"
low = 0.7
high = 0.9
basis = "test"
)");
  const auto r = study::run_uncertainty(file, 2);
  REQUIRE(r.values.size() == 8 * 4);
  int first = 0, second = 0;
  for (const auto& v : r.values) {
    CHECK((v[0] == 0.0 || v[0] == 1.0));  // the index of the value drawn
    (v[0] == 0.0 ? first : second) += 1;
  }
  CHECK(first >= 8);  // a Sobol' sequence splits [0, 1) evenly
  CHECK(second >= 8);
  // The bevel decides how this mower's nails leave, as a range does (the test above).
  REQUIRE(r.indices[5].variance > 0);
  CHECK(r.indices[5].total[0].estimate > 0.5);
  const auto j = report::uncertainty_json(r);
  CHECK(j["inputs"][0]["values"].size() == 2);
  CHECK(j["inputs"][0]["distribution"].get<std::string>().find("discrete") == 0);
  // A discrete input with a range, or one value, or a value the key cannot take, is refused.
  CHECK_THROWS_WITH(scenario::read_scenario(with_uncertainty(
                        "uq-discrete-bad1.toml",
                        "[uncertainty]\n[[uncertainty.inputs]]\nparameter = \"bevel_angle\"\nvalues = [\"20 deg\", \"30 deg\"]\nlow = \"20 deg\"\nbasis = \"x\"\n")),
                    Contains("low") && Contains("not both"));
  CHECK_THROWS_WITH(scenario::read_scenario(with_uncertainty(
                        "uq-discrete-bad2.toml", "[uncertainty]\n[[uncertainty.inputs]]\nparameter = \"bevel_angle\"\nvalues = [\"20 deg\"]\nbasis = \"x\"\n")),
                    Contains("values") && Contains("at least two"));
  CHECK_THROWS_WITH(study::run_uncertainty(with_uncertainty("uq-discrete-bad3.toml",
                                                            "[uncertainty]\n[[uncertainty.inputs]]\nparameter = \"bevel_angle\"\nvalues = "
                                                            "[\"20 deg\", \"95 deg\"]\nbasis = \"x\"\n"),
                                           1),
                    Contains("uncertainty.inputs[1].values") && Contains("95 deg"));
}

TEST_CASE("uncertainty: inputs drawn uniform, triangular or normal (truncated) over their range", "[uncertainty][distribution]") {
  using K = study::InputDistribution::Kind;
  const study::InputDistribution uniform{K::Uniform, 2, 6, 4, 1}, triangle{K::Triangular, 0, 10, 2, 0},
      normal{K::Normal, 0.5, 0.7, 0.6, 0.03};
  CHECK(uniform.quantile(0.25) == Approx(3));
  // Triangular: F(mode) = (mode - low) / (high - low); the quantile inverts it on both sides.
  CHECK(triangle.quantile(0.2) == Approx(2));
  CHECK(triangle.quantile(0.2 * 0.25) == Approx(1));     // F(x) = x^2 / (10 * 2) below the mode
  CHECK(triangle.quantile(1 - 16.0 / 80) == Approx(6));  // 1 - F(x) = (10 - x)^2 / (10 * 8) above it
  CHECK(normal.quantile(0.5) == Approx(0.6));
  CHECK(normal.quantile(1e-9) >= 0.5);
  CHECK(normal.quantile(1 - 1e-9) <= 0.7);
  // Over many points, the mean and spread are the distributions' (the normal's, truncated
  // at 3.33 sd, barely narrowed).
  double mean_t = 0, mean_n = 0, var_n = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n;
    mean_t += triangle.quantile(u) / n;
    const double x = normal.quantile(u);
    CHECK((x >= 0.5 && x <= 0.7));
    mean_n += x / n, var_n += (x - 0.6) * (x - 0.6) / n;
  }
  CHECK(mean_t == Approx((0 + 10 + 2) / 3.0).epsilon(1e-4));
  CHECK(mean_n == Approx(0.6).epsilon(1e-6));
  CHECK(std::sqrt(var_n) == Approx(0.03).epsilon(0.02));
  // Keys refused where they mean nothing, or out of range.
  using Catch::Contains;
  auto input = [](const std::string& extra) {
    return "[uncertainty]\n[[uncertainty.inputs]]\nparameter = \"bevel_angle\"\nlow = \"20 deg\"\nhigh = \"45 deg\"\nbasis = \"x\"\n" + extra;
  };
  CHECK_THROWS_WITH(scenario::read_scenario(with_uncertainty("uq-dist1.toml", input("mode = \"30 deg\"\n"))),
                    Contains("only a triangular distribution has a mode"));
  CHECK_THROWS_WITH(scenario::read_scenario(with_uncertainty("uq-dist2.toml", input("distribution = \"lognormal\"\n"))),
                    Contains("lognormal"));
  CHECK_THROWS_WITH(
      study::run_uncertainty(with_uncertainty("uq-dist3.toml", input("distribution = \"triangular\"\nmode = \"50 deg\"\n")), 1),
      Contains("uncertainty.inputs[1].mode") && Contains("from low to high"));
  CHECK_THROWS_WITH(study::run_uncertainty(with_uncertainty("uq-dist4.toml", input("distribution = \"normal\"\nsd = \"0 deg\"\n")), 1),
                    Contains("uncertainty.inputs[1].sd"));
}

TEST_CASE("uncertainty: an interrupted study resumes from its journal to the same result, bit for bit", "[uncertainty][resume]") {
  const auto file = with_uncertainty("uq-resume.toml", R"(
[uncertainty]
base_draws = 4
replicates = 10
[[uncertainty.inputs]]
parameter = "bevel_angle"
low = "20 deg"
high = "45 deg"
basis = "test"
[[uncertainty.inputs]]
parameter = "restitution"
low = 0.4
high = 0.95
distribution = "normal"
basis = "test"
)");
  const auto whole = study::run_uncertainty(file, 2);
  REQUIRE(whole.outputs.size() == 4 * 4);
  // The first attempt records 6 assessments, then is interrupted.
  struct Interrupted {};
  std::map<std::size_t, study::UqRun> kept;
  study::UncertaintyJournal first{{}, [&](std::size_t run, const study::UqRun& v) {
                                    kept[run] = v;
                                    if (kept.size() == 6) throw Interrupted{};
                                  }};
  CHECK_THROWS_AS(study::run_uncertainty(file, 2, {}, &first), Interrupted);
  // The second takes them and computes only the rest.
  std::size_t computed = 0;
  study::UncertaintyJournal second{[&](std::size_t run) -> std::optional<study::UqRun> {
                                     const auto it = kept.find(run);
                                     if (it == kept.end()) return std::nullopt;
                                     return it->second;
                                   },
                                   [&](std::size_t, const study::UqRun&) { ++computed; }};
  const auto resumed = study::run_uncertainty(file, 1, {}, &second);
  CHECK(computed == whole.outputs.size() - 6);
  CHECK(resumed.outputs == whole.outputs);
  CHECK(resumed.warnings == whole.warnings);
  CHECK(resumed.values == whole.values);
  for (std::size_t o = 0; o < whole.output_info.size(); ++o)
    for (std::size_t i = 0; i < 2; ++i) {
      CHECK(resumed.indices[o].total[i].estimate == whole.indices[o].total[i].estimate);
      CHECK(resumed.indices[o].first[i].high == whole.indices[o].first[i].high);
    }
}

namespace {
// Sobol' indices of every output of a hand-made study (20 bootstrap draws).
void index_outputs(study::UncertaintyResult& r) {
  for (std::size_t o = 0; o < r.output_info.size(); ++o) {
    std::vector<double> f;
    for (const auto& out : r.outputs) f.push_back(out[o]);
    r.indices.push_back(study::sobol_indices(r.design, f, 20, 1));
  }
}
}  // namespace

TEST_CASE("uncertainty: the page never calls an output the same at every draw when its table shows a spread", "[uncertainty][report]") {
  // One input, two base draws: A and B give every output the same value, one mixed draw
  // (AB_1) another. The base draws carry no variance, yet the output moves.
  study::UncertaintyResult r = one_input_study();
  const auto runs = r.design.runs();
  REQUIRE(runs.size() == 6);
  for (std::size_t run = 0; run < runs.size(); ++run) {
    const double v = run == 5 ? 0.9 : 0.5;
    r.values.push_back({runs[run][0]});
    std::vector<double> out(r.output_info.size(), 0.01);
    out[0] = v, out[1] = 0.25;
    r.outputs.push_back(out);
  }
  index_outputs(r);
  REQUIRE(r.indices[0].variance == 0.0);
  const std::string html = report::uncertainty_html(report::uncertainty_json(r));
  CHECK_THAT(html, Catch::Contains("P(pass one test): the same at every base draw (A and B)"));
  CHECK_THAT(html, Catch::Contains("from 0.5 to 0.9"));
  CHECK_THAT(html, Catch::Contains("P(pass) from every nail (exact): the same at every draw (no variance"));
}

TEST_CASE("uncertainty: warnings come after the verdict, counted, the first few shown and the rest folded; draws named with units", "[uncertainty][report]") {
  study::UncertaintyResult r;
  r.title = "test", r.scenario_file = "test.toml";
  r.output_info = study::uq_outputs(scenario::Scenario{});
  scenario::UncertainInput input;
  input.parameter = "blade.thickness", input.low = "5 mm", input.high = "12 mm", input.basis = "test";
  r.plan.inputs.push_back(input);
  scenario::UncertainInput kind;
  kind.parameter = "housing.guards[1].kind", kind.values = {"chains", "flap"}, kind.basis = "test";
  r.plan.inputs.push_back(kind);
  CHECK(study::draw_inputs(r.plan, {9.125, 1.0}) == "blade.thickness = 9.125 mm, housing.guards[1].kind = flap");
  r.plan.base_draws = 2;
  r.design = study::saltelli_design(2, 2);
  for (const auto& run : r.design.runs()) {
    r.values.push_back({run[0], 0.0});
    std::vector<double> out(r.output_info.size(), 0.5);
    out[0] = run[0];
    r.outputs.push_back(out);
  }
  index_outputs(r);
  for (int k = 1; k <= 28; ++k) r.warnings.push_back(fmt::format("draw {}: warning number {}", k, k));
  const std::string html = report::uncertainty_html(report::uncertainty_json(r));
  CHECK_THAT(html, Catch::Contains("note (28 warnings):"));
  CHECK_THAT(html, Catch::Contains("<summary>the other 25</summary>"));
  const auto at = [&](const std::string& text) { return html.find(text); };
  REQUIRE(at("warning number 1<") != std::string::npos);
  REQUIRE(at("warning number 28<") != std::string::npos);
  CHECK(at("warning number 3<") < at("<summary>"));
  CHECK(at("<summary>") < at("warning number 4<"));
  // After the verdict, before the inputs' table (never inside it).
  CHECK(at("Robust verdict") < at("note (28 warnings)"));
  CHECK(at("note (28 warnings)") < at("<th>input</th>"));
  CHECK(at("</details>") < at("<th>input</th>"));
}

namespace {
// A small field: one kind of stones before a 21-in mower, a lane on its right and a path
// on its left.
std::string field_file(const std::string& name, const std::string& uncertainty) {
  const std::string path = std::string(J232_BINARY_DIR) + "/" + name;
  std::ofstream(path) << test::kMower << test::kStones << R"(
[[field.planes]]
name = "path"
side = "left"
distance = "4 m"
receptor = "person"
)" << uncertainty;
  return path;
}
}  // namespace

TEST_CASE("uncertainty: a field's study draws its inputs over the same objects", "[uncertainty][field][long]") {
  const auto file = field_file("uq-field.toml", R"(
[uncertainty]
base_draws = 4
objects = 1200
[[uncertainty.inputs]]
parameter = "field.objects[1].per_area"
low = "0.25 m^-2"
high = "1 m^-2"
distribution = "loguniform"
basis = "test"
[[uncertainty.inputs]]
parameter = "field.objects[1].drag_coefficient"
low = 0.47
high = 0.8
basis = "test"
)");
  const auto a = study::run_uncertainty(file, 2), b = study::run_uncertainty(file, 1);
  REQUIRE(a.field);
  REQUIRE(a.plan.objects == 1200);
  REQUIRE(a.outputs.size() == 4 * 4);
  CHECK(a.outputs == b.outputs);  // any thread count
  std::vector<std::string> names;
  for (const auto& o : a.output_info) names.push_back(o.name);
  CHECK(names == std::vector<std::string>{"thrown_per_km", "hazard_distance_left", "hazard_distance_right", "hazard_distance_front",
                                          "hazard_distance_rear", "plane1_hazardous_per_km", "plane2_hazardous_per_km", "plane2_p_struck",
                                          "acceptable_beyond_deck"});
  for (const auto& out : a.outputs) REQUIRE(out.size() == names.size());
  // The inputs are ranked by the flux at the first plane a person stands at (the lane is a vehicle's).
  CHECK(a.output_info[a.smooth_output].name == "plane2_hazardous_per_km");
  // A loguniform draw stays within its range.
  for (const auto& v : a.values) CHECK((v[0] >= 0.25 && v[0] <= 1.0));
  // Common random numbers: AB_1 differs from A only in the density of stones, so it meets
  // the same objects, throws the same ones, and its rate per km scales with the density.
  const std::size_t n = a.design.base;
  for (std::size_t j = 0; j < n; ++j) {
    const auto &base = a.outputs[j], &mixed = a.outputs[2 * n + j];
    REQUIRE(a.values[2 * n + j][1] == a.values[j][1]);
    CHECK(mixed[0] / base[0] == Approx(a.values[2 * n + j][0] / a.values[j][0]).epsilon(1e-12));
  }
  // What chance alone gives each figure: from a run of the nominal field at the draws' size,
  // worked out here from that run's per-object counts (each kind's weight squared times its
  // counts' squares; the thrown share binomial; P(struck) to first order); none for a
  // distance or the acceptable flag.
  {
    scenario::Scenario nominal = scenario::read_scenario(scenario::parse_toml_file(file), file);
    nominal.field.objects_simulated = 1200;
    const field::FieldSimulator sim(nominal);
    const field::HazardRun run = field::run_hazard(sim, 2);
    const std::vector<double> w = field::weights_per_object(sim, run);
    double thrown = 0;
    std::vector<double> plane(2, 0.0);
    for (std::size_t k = 0; k < run.strata.size(); ++k) {
      const auto& t = run.strata[k];
      const double count = static_cast<double>(t.objects);
      const double share = static_cast<double>(t.fates[static_cast<std::size_t>(field::ObjectFate::Thrown)] +
                                               t.fates[static_cast<std::size_t>(field::ObjectFate::CutOff)]) / count;
      thrown += 1e6 * w[k] * w[k] * count * share * (1 - share);
      for (std::size_t q = 0; q < 2; ++q) plane[q] += 1e6 * w[k] * w[k] * static_cast<double>(t.planes[q].hazardous.squares);
    }
    REQUIRE(a.noise_variance.size() == names.size());
    CHECK(a.noise_variance[0] == Approx(thrown).epsilon(1e-9));
    for (std::size_t o = 1; o <= 4; ++o) CHECK(a.noise_variance[o] == -1.0);
    CHECK(a.noise_variance[5] == Approx(plane[0]).epsilon(1e-9));
    CHECK(a.noise_variance[6] == Approx(plane[1]).epsilon(1e-9));
    REQUIRE(plane[1] > 0);  // the path saw hazardous crossings: the check means something
    const auto& f = nominal.field;
    const double q = field::summarise(sim, run).planes[1].hazardous_per_km.value / 1000 / f.person_height;
    const double slope = f.presented_area * std::exp(-q * f.presented_area) / 1000 / f.person_height;
    CHECK(a.noise_variance[7] == Approx(slope * slope * plane[1]).epsilon(1e-9));
    CHECK(a.noise_variance[8] == -1.0);
    CHECK(a.noise_variance[6] == b.noise_variance[6]);
  }
  // The page and the table name the field's outputs.
  const auto j = report::uncertainty_json(a);
  CHECK(j["kind"] == "field");
  CHECK(j["objects_per_assessment"] == 1200);
  const std::string html = report::uncertainty_html(j);
  CHECK_THAT(html, Catch::Contains("path at 4 m: hazardous crossings of a person&#39;s height per km") ||
                       Catch::Contains("path at 4 m: hazardous crossings of a person's height per km"));
  CHECK_THAT(html, Catch::Contains("data-key=\"objects_per_assessment\" data-value=\"1200\""));
  CHECK_THAT(report::uncertainty_csv(a), Catch::StartsWith("assessment,block,field.objects[1].per_area,field.objects[1].drag_coefficient,thrown_per_km"));
}

TEST_CASE("uncertainty: a field's study refuses what has no meaning in it", "[uncertainty][field][input]") {
  using Catch::Contains;
  auto input = [](const std::string& parameter, const std::string& low, const std::string& high) {
    return "[[uncertainty.inputs]]\nparameter = \"" + parameter + "\"\nlow = " + low + "\nhigh = " + high + "\nbasis = \"x\"\n";
  };
  CHECK_THROWS_WITH(scenario::read_scenario(field_file("uq-field-bad1.toml", "[uncertainty]\nreplicates = 20\n" + input("bevel_angle", "\"20 deg\"", "\"40 deg\""))),
                    Contains("uncertainty.replicates") && Contains("objects = N"));
  CHECK_THROWS_WITH(scenario::read_scenario(with_uncertainty("uq-field-bad2.toml", "[uncertainty]\nobjects = 2000\n")),
                    Contains("uncertainty.objects") && Contains("replicates = N"));
  // Every object has its own restitution: the scenario's is unused.
  CHECK_THROWS_WITH(study::run_uncertainty(field_file("uq-field-bad3.toml", "[uncertainty]\n" + input("restitution", "0.4", "0.9")), 1),
                    Contains("restitution") && Contains("own restitution"));
  CHECK_THROWS_WITH(study::run_uncertainty(field_file("uq-field-bad4.toml", "[uncertainty]\n" + input("edge_friction", "0.2", "0.5")), 1),
                    Contains("field.objects[N].friction"));
  // An element of an array of tables the file does not have.
  CHECK_THROWS_WITH(study::run_uncertainty(field_file("uq-field-bad5.toml", "[uncertainty]\n" + input("field.objects[2].per_area", "\"1 m^-2\"", "\"2 m^-2\"")), 1),
                    Contains("field.objects[2].per_area") && Contains("one of the 1 [[field.objects]] tables"));
  CHECK_THROWS_WITH(study::run_uncertainty(field_file("uq-field-bad6.toml", "[uncertainty]\n" + input("field.objects[1].per_area", "\"0 m^-2\"", "\"2 m^-2\"") +
                                                                              "distribution = \"loguniform\"\n"),
                                           1),
                    Contains("above zero"));
}

TEST_CASE("uncertainty: a field's default inputs keep every draw one the reader accepts", "[uncertainty][field][input]") {
  // The shoulder's gravel reaches a blade only when the updraft lifts it: at the updraft's
  // low end with the drag's low end it must still lift the smallest, and the cobbles sunk to
  // the embedment's deep end must still stand up to the blade. Every corner of the inputs
  // that decide it is read.
  const std::string file = scenario_path("field/batwing-highway-shoulder.toml");
  const toml::table base = scenario::parse_toml_file(file);
  const auto plan = study::uncertainty_plan(scenario::read_scenario(base, file));
  REQUIRE(plan.defaults);
  REQUIRE(plan.objects == 240);  // 30 of each of the two kinds' four size strata
  std::vector<const scenario::UncertainInput*> coupled;
  for (const auto& in : plan.inputs)
    if (in.parameter == "field.updraft_speed" || in.parameter.find("drag_coefficient") != std::string::npos ||
        in.parameter.find("embedment") != std::string::npos || in.parameter.find("median_size") != std::string::npos)
      coupled.push_back(&in);
  REQUIRE(coupled.size() >= 5);
  for (unsigned corner = 0; corner < (1u << coupled.size()); ++corner) {
    toml::table doc = base;
    for (std::size_t i = 0; i < coupled.size(); ++i)
      scenario::set_key(doc, coupled[i]->parameter, (corner >> i) & 1 ? coupled[i]->high : coupled[i]->low, "test");
    INFO("corner " << corner);
    CHECK_NOTHROW(scenario::read_scenario(doc, file));
  }
  // A kind's own key, element by element: the second table only.
  toml::table doc = base;
  scenario::set_key(doc, "field.objects[2].per_area", "\"1 m^-2\"", "test");
  const auto s = scenario::read_scenario(doc, file);
  CHECK(s.field.objects[0].per_area == Approx(20));
  CHECK(s.field.objects[1].per_area == Approx(1));
  CHECK_THROWS_WITH(scenario::set_key(doc, "field.objects[3].per_area", "1", "test"), Catch::Contains("one of the 2 [[field.objects]] tables"));
  CHECK_THROWS_WITH(scenario::set_key(doc, "field.objects[0].per_area", "1", "test"), Catch::Contains("N counted from 1"));
  // A loguniform range's median is the geometric mean of its ends.
  study::InputDistribution d{study::InputDistribution::Kind::LogUniform, 0.25, 4.0};
  CHECK(d.quantile(0.5) == Approx(1.0));
  CHECK(d.quantile(0.0) == Approx(0.25));
  CHECK(d.quantile(1.0) == Approx(4.0));
}

TEST_CASE("uncertainty: keys a study cannot draw are refused with what to do instead", "[uncertainty][input]") {
  using Catch::Contains;
  auto input = [](const std::string& parameter, const std::string& low, const std::string& high) {
    return "[[uncertainty.inputs]]\nparameter = \"" + parameter + "\"\nlow = " + low + "\nhigh = " + high + "\nbasis = \"x\"\n";
  };
  CHECK_THROWS_WITH(study::run_uncertainty(with_uncertainty("uq-seed.toml", "[uncertainty]\n" + input("run.seed", "1", "9")), 1),
                    Contains("uncertainty.inputs[1].parameter") && Contains("common random numbers"));
  CHECK_THROWS_WITH(study::run_uncertainty(field_file("uq-side.toml", "[uncertainty]\n[[uncertainty.inputs]]\nparameter = \"field.planes[2].side\"\n"
                                                                      "values = [\"left\", \"front\"]\nbasis = \"x\"\n"),
                                           1),
                    Contains("only its distance"));
  CHECK_THROWS_WITH(study::run_uncertainty(field_file("uq-cd.toml", "[uncertainty]\n" + input("air.cd_axial", "0.5", "1.0")), 1),
                    Contains("field.objects[N].drag_coefficient"));
  CHECK_THROWS_WITH(study::run_uncertainty(field_file("uq-n.toml", "[uncertainty]\n" + input("field.objects_simulated", "1000", "2000")), 1),
                    Contains("[uncertainty] objects"));
}

TEST_CASE("uncertainty: the default set draws the model's form (contact model, restitution law, a field's knife push), each form one the reader accepts", "[uncertainty][input]") {
  for (const char* name : {"highway-pivoted.toml", "field/batwing-highway-shoulder.toml"}) {
    const std::string file = scenario_path(name);
    const toml::table base = scenario::parse_toml_file(file);
    const auto plan = study::uncertainty_plan(scenario::read_scenario(base, file));
    REQUIRE(plan.defaults);
    std::vector<std::string> forms;
    for (const auto& in : plan.inputs) {
      if (in.values.empty()) continue;
      forms.push_back(in.parameter);
      CHECK_FALSE(in.basis.empty());
      for (const auto& v : in.values) {
        toml::table doc = base;
        scenario::set_key(doc, in.parameter, v, "test");
        INFO(in.parameter << " = " << v);
        const auto s = scenario::read_scenario(doc, file);
        if (in.parameter == "contacts.model")
          CHECK((s.run.contact_model == scenario::ContactModel::Simultaneous) == (v == "simultaneous"));
        if (in.parameter == "ground.kind") CHECK(s.ground.kind == v);
        if (in.parameter == "contacts.blade_push") CHECK((s.run.blade_push == scenario::BladePush::Impacts) == (v == "impacts"));
      }
    }
    INFO(name);
    CHECK(std::count(forms.begin(), forms.end(), "contacts.model") == 1);
    CHECK(std::count(forms.begin(), forms.end(), "run.restitution_law") == 1);
    // A J232 test's ground is drawn over every kind; its restitution and cap are the kind's,
    // never drawn beside it (they would override it).
    const bool field = std::string(name).rfind("field/", 0) == 0;
    CHECK(std::count(forms.begin(), forms.end(), "ground.kind") == (field ? 0 : 1));
    // A knife's push is held only on a field's stones: drawn for a field alone.
    CHECK(std::count(forms.begin(), forms.end(), "contacts.blade_push") == (field ? 1 : 0));
    if (!field)
      for (const auto& in : plan.inputs) CHECK((in.parameter != "ground.restitution" && in.parameter != "ground.max_restitution"));
  }
}

TEST_CASE("uncertainty: uq.csv holds every assessment exactly, and reads back; a broken table is refused by line and column", "[uncertainty][report]") {
  study::UncertaintyResult r = one_input_study();
  const auto runs = r.design.runs();
  for (std::size_t run = 0; run < runs.size(); ++run) {
    r.values.push_back({0.1 + 1.0 / 3 * static_cast<double>(run)});  // no short decimal
    std::vector<double> out(r.output_info.size());
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = std::nextafter(1.0 / 7 * static_cast<double>(k + run), 2.0);
    r.outputs.push_back(out);
    r.runs.push_back({out, run == 3 ? 0.0125 : 0.0, run == 3 ? static_cast<int>(flight::CutOff::MaxBounces) : 0});
  }
  const std::string path = "uq-roundtrip-test.csv";
  std::ofstream(path) << report::uncertainty_csv(r);
  const auto t = report::read_uncertainty_csv(path);
  REQUIRE(t.cells.size() == runs.size());
  REQUIRE(t.columns.size() == 1 + r.output_info.size());
  CHECK(t.columns[0] == "bevel_angle");
  for (std::size_t run = 0; run < runs.size(); ++run) {
    CHECK(t.cells[run][0] == r.values[run][0]);  // bit for bit
    for (std::size_t k = 0; k < r.output_info.size(); ++k) CHECK(t.cells[run][1 + k] == r.outputs[run][k]);
    CHECK(t.runs[run].cut_off_share == r.runs[run].cut_off_share);
    CHECK(t.runs[run].cut_off_limit == r.runs[run].cut_off_limit);
    CHECK(t.lines[run] == static_cast<int>(run) + 2);
  }
  // Broken: a cell that is not a number, a row out of order, a missing cut-off column.
  const auto refused = [&](const std::string& text, const std::string& says) {
    std::ofstream(path) << text;
    INFO(text);
    CHECK_THROWS_WITH(report::read_uncertainty_csv(path), Catch::Contains(says));
  };
  const std::string head = "assessment,block,bevel_angle,p_pass,cut_off_share,cut_off_mostly_by\n";
  refused(head + "1,A,25,x,0,none\n", ":2: p_pass = x");
  refused(head + "2,A,25,0.5,0,none\n", "the rows in order");
  refused(head + "1,A,25,0.5,0,tired\n", "cut_off_mostly_by = tired");
  refused(head + "1,A,25,0.5,0\n", "cells, as the header has");
  refused("assessment,block,bevel_angle,p_pass\n", "expected a uq.csv of this version");
  std::remove(path.c_str());
  CHECK_THROWS_WITH(report::read_uncertainty_csv(path), Catch::Contains("cannot be read"));
}

TEST_CASE("drivers: each input at its ends, paired with the scenario as written; an ignored input moves nothing", "[uncertainty][drivers]") {
  const auto file = with_uncertainty("drivers-ignored.toml", R"(
[air]
drag = false
[uncertainty]
replicates = 10
[[uncertainty.inputs]]
parameter = "air.cd_axial"
low = 0.5
high = 1.0
basis = "test: drag is off, so this must not matter"
[[uncertainty.inputs]]
parameter = "board.crush_depth"
low = "3 mm"
high = "12 mm"
basis = "test"
)");
  const int punctures_outside = 3;
  const auto a = study::deciding_drivers(file, punctures_outside, 2), b = study::deciding_drivers(file, punctures_outside, 1);
  REQUIRE(a.ranked.size() == 2);
  CHECK(a.replicates == 10);
  CHECK_FALSE(a.default_inputs);
  // The crush depth moves the board's marks; drag's coefficient, with drag off, nothing.
  CHECK(a.ranked[0].input == "board.crush_depth");
  CHECK(a.ranked[0].largest_change > 0);
  CHECK(a.ranked[1].input == "air.cd_axial");
  CHECK(a.ranked[1].largest_change == 0.0);
  for (const auto& e : a.ranked[1].ends) CHECK((e.change.mean == 0.0 && e.change.low == 0.0 && e.change.high == 0.0));
  // Any thread count, the same numbers.
  for (std::size_t i = 0; i < a.ranked.size(); ++i)
    for (std::size_t e = 0; e < a.ranked[i].ends.size(); ++e) CHECK(a.ranked[i].ends[e].share == b.ranked[i].ends[e].share);
  // Independently: each end's share and change from runs of its own (the scenario with the
  // key written in, run by the assessment alone).
  const auto share_of = [&](const std::string& extra) {
    std::ifstream in(file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string path = std::string(J232_BINARY_DIR) + "/drivers-end.toml";
    std::ofstream(path) << text.substr(0, text.find("[uncertainty]")) << extra << "\n[uncertainty]\nreplicates = 10\n";
    auto s = scenario::read_scenario(path);
    s.run.replicates = 10, s.run.until_settled = false, s.run.target_half_width.reset();
    const assess::Simulator sim(s);
    return assess::summarise(assess::run_assessment(sim, 2), s).criteria[punctures_outside].mean_share;
  };
  const double as_written = share_of("");
  CHECK(a.share == Approx(as_written).margin(1e-15));
  const auto& crush = a.ranked[0].ends;
  REQUIRE(crush.size() == 2);
  CHECK(crush[0].value == "3 mm");
  const double shallow = share_of("[board]\ncrush_depth = \"3 mm\"\n");
  CHECK(crush[0].share == Approx(shallow).margin(1e-15));
  CHECK(crush[0].change.mean == Approx(shallow - as_written).margin(1e-12));
  CHECK((crush[0].change.low <= crush[0].change.mean && crush[0].change.mean <= crush[0].change.high));
}

TEST_CASE("uncertainty: every shipped J232 scenario's default set has ends the reader accepts (a flap deck draws no openness)", "[uncertainty][input]") {
  for (const auto& entry : std::filesystem::directory_iterator(std::string(J232_SOURCE_DIR) + "/scenarios")) {
    if (entry.path().extension() != ".toml") continue;
    const std::string file = entry.path().string();
    const toml::table base = scenario::parse_toml_file(file);
    const auto nominal = scenario::read_scenario(base, file);
    const auto plan = study::uncertainty_plan(nominal);
    for (const auto& in : plan.inputs) {
      const auto values = in.values.empty() ? std::vector<std::string>{in.low, in.high} : in.values;
      for (const auto& v : values) {
        INFO(file << ": " << in.parameter << " = " << v);
        CHECK_NOTHROW(study::scenario_with(base, file, in, v, in.parameter));
      }
    }
  }
}
