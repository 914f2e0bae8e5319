// The J232 test as a study's pipeline: replicates of the whole test at each draw, judged by
// P(pass), the four mean shares and the verdict (docs/model.md §6b).
#include <algorithm>
#include <string>

#include "assess/runner.hpp"
#include "assess/summary.hpp"
#include "pipeline/estimated_inputs.hpp"
#include "pipeline/pipeline.hpp"

namespace j232::pipeline {

namespace {

class J232Test final : public Pipeline {
 public:
  Kind kind() const override { return Kind::J232; }
  const char* assessment_words() const override { return "the simulated test"; }
  const char* cut_off_words() const override { return "struck nails"; }

  // P(pass) (the share of passing replicates, and from every nail: smooth, so its Sobol'
  // indices mean something), the four mean shares, and whether it passes.
  std::vector<Output> outputs(const scenario::Scenario&) const override {
    using Scale = Output::Scale;
    return {{"p_pass", "P(pass one test)", Scale::Probability, ""},
            {"p_pass_exact", "P(pass) from every nail (exact)", Scale::Probability, ""},
            {"hits_zone", "hits in the operator zone", Scale::Percent, ""},
            {"punctures_zone", "punctures in the operator zone", Scale::Percent, ""},
            {"hits_outside", "hits outside the zone", Scale::Percent, ""},
            {"punctures_outside", "punctures outside the zone", Scale::Percent, ""},
            {"passes", "passes (P(pass) at least the required)", Scale::Number, ""}};
  }
  std::size_t smooth_output(const scenario::Scenario&, const std::vector<Output>&) const override { return 1; }  // P(pass) from every nail

  std::vector<scenario::UncertainInput> estimated_inputs(const scenario::Scenario& s) const override {
    // The estimated inputs (docs/model.md §8), each over a range with its basis.
    std::vector<scenario::UncertainInput> in = {
        estimated("board.puncture_energy_per_width", "80 J/m", "140 J/m",
                  "estimate: no published value for 350# double-wall board; 110 J/m +/- ~27 %"),
        estimated("board.hit_fraction", "0.2", "0.4", "estimate: a hit takes about a third of a puncture's energy"),
        estimated("board.crush_depth", "3 mm", "12 mm", "estimate: about the board's caliper (7 mm); how deep a mark crushes it is not measured"),
        estimated(
            "restitution", "0.4", "0.95",
            "report 445-1: drop tests 0.9-0.96 at ~1 m/s, 0.45-0.6 at ~2.3 m/s; its Table 3.1 fits 0.53-0.65 at 11 m/s (j232 calibrate)"),
        estimated("bevel_angle", "20 deg", "45 deg", "estimate: mower blades are ground to about 30 deg; no figure for industrial cutters"),
        estimated("edge_friction", "0.2", "0.6", "handbook: steel on steel, kinetic 0.42-0.57; lower for an oily, worn edge"),
        estimated("housing.friction", "0.3", "0.6", "handbook: steel on steel, kinetic 0.42-0.57"),
        estimated("feed.tilt_max", "0 deg", "10 deg", "estimate: SAE J232's feed tube geometry is not available"),
    };
    for (auto& guard : guard_openness(s)) in.push_back(std::move(guard));
    in.push_back(ground_kind_form());
    in.push_back(contact_model_form());
    in.push_back(restitution_law_form());
    return in;
  }
  std::string cannot_vary(const std::string&) const override { return ""; }
  DrawSize draw_size(const scenario::Scenario& s) const override { return {s.uncertainty.replicates, 0}; }

  // Common random numbers: the same seed and replicates at every draw. Every rank of an MPI
  // job holds the merged assessment (assess::run_assessment), so all return the same.
  DrawOutputs assess(scenario::Scenario& sc, const scenario::Scenario& nominal, const DrawSize& size, int threads,
                     std::string& invalid) const override {
    const double required = nominal.criteria.required_pass_probability;
    sc.run.replicates = size.replicates;
    sc.run.target_half_width.reset();
    sc.run.until_settled = false;
    const assess::Simulator sim(sc);
    const auto a = assess::run_assessment(sim, threads);
    const auto sum = assess::summarise(a, sc);
    if (!sum.validity.valid) invalid = sum.validity.reasons.front();
    // (From every nail where it can be computed; else, for the `marks` denominator, the
    // replicates' share, as uq.json says.)
    const double exact = sum.exact.computed ? sum.exact.value : sum.pass.estimate;
    DrawOutputs out;
    out.outputs = {sum.pass.estimate,          exact,
                   sum.criteria[0].mean_share, sum.criteria[1].mean_share,
                   sum.criteria[2].mean_share, sum.criteria[3].mean_share,
                   exact >= required ? 1.0 : 0.0};
    const auto cut = sum.fates[static_cast<std::size_t>(flight::Fate::CutOff)];
    out.cut_off_share = sum.struck ? static_cast<double>(cut) / static_cast<double>(sum.struck) : 0.0;
    out.cut_off_limit = commonest_cut_off(sum.cut_off_by);
    return out;
  }
  void warn(const scenario::Scenario&, const std::vector<Output>&, const std::vector<double>&, const std::string&,
            std::vector<std::string>&) const override {}

  std::string refuse_parameter(const std::string& name, const scenario::Scenario&) const override {
    if (name == "object_speed") return "object_speed: a J232 scenario's nails fall onto the blade; sweep feed.ground_speed instead";
    // The J232 rig is checked against the blades' plane when the file is read (the operator
    // zone and the counted height against the board); moved after, those checks would not be
    // re-run, and a board whose top the file wrote would be left behind.
    if (name == "cut_height")
      return "cut_height: a J232 scenario's board is set from the blades' plane as the file is read; sweep the blades' height key ([blade] "
             "height) and the housing's keys instead";
    return "";
  }
  std::string refuse_drivers() const override { return ""; }

  std::vector<std::string> sweep_columns() const override {
    return {"replicates",
            "p_pass",
            "p_pass_low",
            "p_pass_high",
            "share_hits_zone",
            "share_punctures_zone",
            "share_hits_outside",
            "share_punctures_outside",
            "marks_per_nail",
            "q05_hits_zone",
            "q95_hits_zone",
            "limit_hits_zone",
            "q05_punctures_zone",
            "q95_punctures_zone",
            "limit_punctures_zone",
            "q05_hits_outside",
            "q95_hits_outside",
            "limit_hits_outside",
            "q05_punctures_outside",
            "q95_punctures_outside",
            "limit_punctures_outside"};
  }
  std::optional<Refusal> refuse_sweep_size(const DrawSize& size) const override {
    if (size.objects > 0)
      return Refusal{"run.objects", std::to_string(size.objects), "objects per point are for a field scenario's sweep; a J232 scenario takes run.replicates"};
    return std::nullopt;
  }
  std::vector<double> sweep_point(scenario::Scenario& sc, const DrawSize& size, bool, int threads, SweepColumns& t,
                                  std::string& invalid) const override {
    if (size.replicates > 0) sc.run.replicates = size.replicates;
    const assess::Simulator sim(sc);
    const assess::Assessment a = assess::run_assessment(sim, threads);
    const assess::Summary sum = assess::summarise(a, sc);
    // A point where the test did not really happen has no P(pass) to plot.
    if (!sum.validity.valid) {
      invalid = "the simulated test is invalid here: " + sum.validity.reasons.front();
      return {};
    }
    t.required_pass_probability = sum.required;
    std::vector<double> v{static_cast<double>(sum.replicates),
                          sum.pass.estimate,
                          sum.pass.low,
                          sum.pass.high,
                          sum.criteria[0].mean_share,
                          sum.criteria[1].mean_share,
                          sum.criteria[2].mean_share,
                          sum.criteria[3].mean_share,
                          sum.marks_per_nail};
    for (const auto& c : sum.criteria) v.insert(v.end(), {c.q05, c.q95, c.limit});
    return v;
  }

  // Binomial: a share of the nails fed p(1-p)/(R n), the replicates' P(pass) p(1-p)/R (not
  // P(pass) from every nail, the verdict, or shares of the marks).
  std::vector<double> noise_variance(const scenario::Scenario& nominal, const DrawSize& size, const std::vector<Output>& info,
                                     const std::vector<std::vector<double>>& runs, std::size_t base_runs, int) const override {
    std::vector<double> variance(info.size(), -1.0);
    const double replicates = static_cast<double>(size.replicates), nails = static_cast<double>(nominal.feed.nails);
    for (std::size_t o = 0; o < info.size() && base_runs > 0; ++o) {
      const auto& output = info[o];
      const bool share_of_nails = output.scale == Output::Scale::Percent && nominal.criteria.denominator == scenario::CriteriaSpec::Denominator::NailsFed;
      const double trials = output.name == "p_pass" ? replicates : share_of_nails ? replicates * nails : 0.0;
      if (!(trials > 0)) continue;
      double sum = 0;
      for (std::size_t run = 0; run < base_runs; ++run) sum += runs[run][o] * (1 - runs[run][o]) / trials;
      variance[o] = sum / static_cast<double>(base_runs);
    }
    return variance;
  }
};

}  // namespace

const Pipeline& j232_test() {
  static const J232Test pipeline;
  return pipeline;
}

}  // namespace j232::pipeline
