#pragma once
// The two pictures of where nails marked the board: the board unrolled (azimuth x
// height) with the operator zone shaded, and a plan view of mower, guards and targets.
// Both draw the scene's own labelled triangles, so generated set-ups and user meshes
// look the same way.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "assess/runner.hpp"
#include "scenario/scenario.hpp"
#include "scene/soup.hpp"

namespace j232::report {

// The marks of the first replicates, up to about `max_marks` (replicates are
// independent, so this is a fair sample of the whole run; at least one replicate).
struct MarkSample {
  std::vector<const assess::MarkRow*> rows;
  std::uint64_t replicates_shown = 0, replicates = 0;
  std::size_t marks = 0;  // located marks in the whole run
};
MarkSample sample_marks(const assess::Assessment& a, std::size_t max_marks);

// Azimuth in degrees, -180 to 180, counter-clockwise from straight ahead (+x).
double azimuth_deg(double x, double y);

std::string hit_map_svg(const scenario::Scenario& s, const scene::Soup& soup, const MarkSample& marks);
std::string plan_view_svg(const scenario::Scenario& s, const scene::Soup& soup, const MarkSample& marks);
// The colour of a kept nail path by why it was kept ("sample", "operator zone",
// "puncture"): the report's pictures and the exported scene draw them alike.
std::array<std::uint8_t, 3> path_rgb(const std::string& why);

// Whole paths of chosen nails (run --trajectories) over the mower seen from above, and in
// side elevation (distance from the origin against height) with the board and blade plane.
std::string trajectories_plan_svg(const scenario::Scenario& s, const scene::Soup& soup, const std::vector<assess::Trajectory>& paths,
                                  std::uint64_t not_kept);
std::string trajectories_side_svg(const scenario::Scenario& s, const std::vector<assess::Trajectory>& paths, std::uint64_t not_kept);

}  // namespace j232::report
