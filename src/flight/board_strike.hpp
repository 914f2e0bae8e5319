#pragma once
// What a nail striking the board leaves in it (docs/model.md §5.5): one function for the
// flight (NailFlight::reach_board) and for fitting the board to a lab's drop tests
// (`j232 calibrate --board`), so the two cannot drift apart.
#include <algorithm>
#include <cmath>

#include "board/board.hpp"
#include "flight/plane_touch.hpp"
#include "projectile/projectile.hpp"

namespace j232::flight {

struct BoardStrike {
  double energy = 0;  // J: what a plastic impact takes out of the nail there
  double width = 0;   // m: the width of nail pressing on the board (board::presented_width)
};

// The nail's state at the touch: its axis, the arm from its centre to the touching point,
// the board's outward normal n, the centre's velocity and the spin. The energy is the larger
// of m_eff v_n^2 / 2 at the touching point and the share of a plastic contact along the whole
// shank that falls on the part within the crush depth.
inline BoardStrike board_strike(const projectile::Projectile& nail, const Vec3& axis, const Vec3& arm, const Vec3& n, const Vec3& velocity,
                                const Vec3& spin, double crush_depth) {
  const double length = nail.length, mass = nail.mass;
  const double approach = std::max(0.0, -n.dot(velocity + spin.cross(arm)));
  const double at_point = 0.5 * effective_mass(nail, axis, arm, n) * approach * approach;
  // A nail nearly flat has more of its shank within the crush depth than its end: the part
  // pressing on the board shares what a plastic contact along the whole shank takes out (its
  // normal translation and the turn that moves its ends along n), in proportion to its length.
  const double cos_theta = std::abs(axis.dot(n));
  const double pressing = cos_theta * length > crush_depth ? crush_depth / cos_theta : length;
  const double centre_in = std::max(0.0, -n.dot(velocity)), turn = n.dot(spin.cross(axis));
  const double along_shank = centre_in > 0 ? 0.5 * mass * centre_in * centre_in + 0.5 * nail.transverse_inertia() * turn * turn : 0.0;
  return {std::max(at_point, pressing / length * along_shank), board::presented_width(length, nail.diameter, axis.dot(n), crush_depth)};
}

}  // namespace j232::flight
