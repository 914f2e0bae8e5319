#pragma once
// Things a viewer of the exported scene wants to see that are not surfaces a nail meets
// (docs/model.md §5.4, "Export"): the blades' tip circles, the feed stations, the operator's
// seat and reach envelope, and nail paths from a run. Each is a polyline in a named group.
#include <vector>

#include "scenario/scenario.hpp"
#include "scene/soup.hpp"

namespace j232::scene {

// Each spindle's tip circle in its blade plane; each feed station as the vertical line its
// nails fall down (from the funnel outlet to the blade plane); the seat index point as a
// small cross; the derived operator zone's reach spheres as three great circles each.
std::vector<Polyline> mower_markers(const scenario::Scenario& s);

}  // namespace j232::scene
