#pragma once
// The estimated inputs both pipelines' studies draw by default (docs/model.md §8 and §9):
// the contact model's and the restitution law's forms, the ground's kind, and how open each
// chain curtain is.
#include <vector>

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

}  // namespace j232::pipeline
