#pragma once
// The 3D view of a scenario's scene (`j232 scene --html`): one self-contained HTML page
// that draws the labelled surfaces a nail meets (ground, deck and skirt, deflectors, each
// guard by name and kind, board, operator zone) and the markers (tip circles, feed
// stations, seat and reach envelope, nail paths of a run) with three.js, which a user turns,
// zooms and pans with the mouse, each part shown or hidden from the legend.
#include <string>
#include <vector>

#include "scenario/scenario.hpp"
#include "scene/soup.hpp"

namespace j232::report {

// A nail's path as the 3D view draws it: coloured by its fate, with what
// a click on it shows (its replicate and number, fate, strikes, surfaces touched, way out)
// and its marks on the board.
struct ScenePath {
  std::vector<scene::Vec3> points;
  std::string why;                // why it was kept: "sample", "operator zone", "puncture"
  std::string fate;               // flight::fate_name: "marked_board", "over_board", ...
  std::vector<std::string> info;  // lines of its trail
  std::vector<std::pair<scene::Vec3, int>> marks;  // where it marked the board: 1 hit, 2 puncture
};

// Whether this build found three.js (Debian's libjs-three) at configure time.
bool scene_view_available();

// The page. `guards` as the scene numbers them (scene::scene_guards). Throws
// std::runtime_error when this build has no three.js, saying how to get it.
std::string scene_view_html(const scenario::Scenario& s, const scene::Soup& soup, const std::vector<scenario::GuardSpec>& guards,
                            const std::vector<scene::Polyline>& lines, const std::vector<ScenePath>& paths = {});

}  // namespace j232::report
