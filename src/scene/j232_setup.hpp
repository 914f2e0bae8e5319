#pragma once
// The scene of a scenario: the standard J232 set-up generated from its dimensions
// (ground, deck with skirt, chain guards, deflectors, ring of target board carrying
// the operator zone), with any part replaced by the scenario's own meshes (a label per
// file: see MeshRoles).
#include "scenario/scenario.hpp"
#include "scene/soup.hpp"

namespace j232::scene {

// Throws scenario::InputError (bad mesh file) naming the scenario key.
Soup build_scene_soup(const scenario::Scenario& s);

// The guards as the scene numbers them (the soup's guard_index): the mesh guards in file
// order, then housing.guards; a default one when there are none, so that the index 0 the
// other faces carry names something.
std::vector<scenario::GuardSpec> scene_guards(const scenario::Scenario& s);

// The radius of the generated target ring.
// The generated board's farthest horizontal distance from the deck's centre (a ring's radius).
double target_radius(const scenario::Scenario& s);
// A board of shape "outline" seen from above, counter-clockwise: the convex hull of every
// tip circle widened by the target's distance.
std::vector<Eigen::Vector2d> board_outline(const scenario::Scenario& s);

// What the scenario's meshes replace of the standard set-up: a ground mesh the generated
// turf, a housing mesh the generated deck, skirt, guards and deflectors, a target (or
// operator_zone) mesh the generated board ring. Guard and deflector meshes add to it.
struct MeshRoles {
  bool ground = false, housing = false, target = false;
};
MeshRoles mesh_roles(const scenario::Scenario& s);

// The deck in plan: its outline (convex, counter-clockwise) - the generated deck's, or
// the hull of the housing meshes' points - and the heights that name how a nail crossed
// it (a mesh deck's skirt height is not known: 0).
struct DeckFootprint {
  std::vector<Eigen::Vector2d> outline;
  double top = 0, skirt_bottom = 0;
  bool generated = true;
};
DeckFootprint deck_footprint(const scenario::Scenario& s, const Soup& soup);

// Beyond this horizontal distance a nail has left the test: 1 m past the farthest of
// the board ring and every mesh surface but the ground (a field: field_ground_half).
double escape_radius(const scenario::Scenario& s, const Soup& soup);
// How far a field's objects are followed from the mower (in its frame): past the corners
// of the tallied square, and as far again as the mower travels in a flight's time limit.
inline double field_ground_half(const scenario::Scenario& s) {
  return 1.5 * s.field.range + s.field.ground_speed * s.time_limit();
}
// A generated polygon deck's skirt, piece by piece along its outline: pieces of at most
// 0.1 m, split where an opening or a guard given by azimuths begins or ends, so that each
// is cut exactly at its azimuths. `azimuth`: of the piece's middle, about the origin.
struct SkirtPiece {
  Eigen::Vector2d a, b;
  double azimuth = 0;
  std::size_t edge = 0;  // of the outline
};
std::vector<SkirtPiece> skirt_pieces(const scenario::Scenario& s);
// A flap's hinge (its top edge's height above ground), lower edge, and width along where it
// hangs: along a polyline, its top and the polyline's length; given by azimuths, across the
// openings it spans, up to their tops, the skirt pieces it hangs on. `swinging`: the width
// that swings as one plate (its panel_width, or the whole flap).
struct FlapGeometry {
  double hinge = 0, bottom = 0, width = 0, swinging = 0;
};
FlapGeometry flap_geometry(const scenario::Scenario& s, const scenario::GuardSpec& g);
// Each opening's width as cut, along the deck's outline, m (0 on a mesh deck).
std::vector<double> opening_widths(const scenario::Scenario& s);
// The horizontal distance of the board's nearest point from the deck's centre (HUGE_VAL
// without a board): a nail at rest nearer than it has not gone past the board.
double board_near_radius(const Soup& soup);

}  // namespace j232::scene
