#pragma once
// The pictures of report.html: where nails marked the board (the board unrolled, azimuth x
// height, with the operator zone shaded, and a plan view of mower, guards and targets) and
// the paths of chosen nails. They are drawn in two steps, so that the page can be drawn
// again from a saved result.json (`j232 redraw`): what the pictures need of the run and its
// scene is first put into result.json's "pictures" object (the board's cells and the plan's
// layers from the scene's own labelled triangles, so generated set-ups and user meshes look
// the same way; a sample of the marks; the tip circles, feed stations and deck outline), and
// each picture is then drawn from that JSON alone.
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "assess/runner.hpp"
#include "scenario/scenario.hpp"
#include "scene/soup.hpp"

namespace j232::report {

// Azimuth in degrees, -180 to 180, counter-clockwise from straight ahead (+x).
double azimuth_deg(double x, double y);

// result.json's "pictures": what the report's pictures draw that the rest of result.json
// does not hold. The marks are those of the first replicates, as many whole replicates as
// fit in assess::kMarkSample marks (a fair sample, as replicates are independent).
nlohmann::ordered_json pictures_json(const scenario::Scenario& s, const assess::Assessment& a, const scene::Soup& soup);

// Each picture from a result.json as saved (its "pictures" and, for the paths, its
// "trajectories").
std::string hit_map_svg(const nlohmann::ordered_json& result);
std::string plan_view_svg(const nlohmann::ordered_json& result);
std::string trajectories_plan_svg(const nlohmann::ordered_json& result);
std::string trajectories_side_svg(const nlohmann::ordered_json& result);

// The colour of a kept nail path by why it was kept ("sample", "operator zone",
// "puncture"): the report's pictures and the exported scene draw them alike.
std::array<std::uint8_t, 3> path_rgb(const std::string& why);

}  // namespace j232::report
