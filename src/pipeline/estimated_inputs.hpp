#pragma once
// The estimated inputs both pipelines' studies draw by default (docs/model.md §8 and §9):
// the contact model's and the restitution law's forms, the ground's kind, and how open each
// chain curtain is; and the helpers that write an estimate or a model form, and name the
// commonest cut-off.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "flight/nail_flight.hpp"  // kCutOffReasons
#include "scenario/scenario.hpp"

namespace j232::pipeline {

// The contact model: both forms are defensible and neither is exact (docs/model.md §5.3).
scenario::UncertainInput contact_model_form();
// The restitution law of every impact (docs/model.md §5.1c).
scenario::UncertainInput restitution_law_form();
// What the test's mower stands on (every kind of the ground table).
scenario::UncertainInput ground_kind_form();
// How open the chain curtains are: one input for every guard when all are chains, else one
// per chain guard (a flap is a solid plate: it has no openness to draw).
std::vector<scenario::UncertainInput> guard_openness(const scenario::Scenario& s);

// An estimated input over [low, high] with its basis (a study's default inputs).
scenario::UncertainInput estimated(std::string parameter, std::string low, std::string high, std::string basis,
                                   std::string distribution = "uniform");
// A choice of the model's own form, drawn with the inputs: a verdict that rests on one form
// is not shown to rest on it until the other is drawn too.
scenario::UncertainInput model_form(std::string parameter, std::vector<std::string> values, std::string basis);
// The limit that cut off the most of `by` (0, none, when none was cut off).
int commonest_cut_off(const std::array<std::uint64_t, flight::kCutOffReasons>& by);

}  // namespace j232::pipeline
