#pragma once
// The scene of a scenario: the standard J232 set-up generated from its dimensions
// (ground, deck with skirt, chain guards, deflectors, ring of target board carrying
// the operator zone), or the scenario's own meshes with a label per file.
#include "scenario/scenario.hpp"
#include "scene/soup.hpp"

namespace j232::scene {

// Throws scenario::InputError (bad mesh file) naming the scenario key.
Soup build_scene_soup(const scenario::Scenario& s);

// The radius of the generated target ring.
double target_radius(const scenario::Scenario& s);

}  // namespace j232::scene
