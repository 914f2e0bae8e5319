#pragma once
// Corrugated board: does a nail arriving with this kinetic energy normal to the board,
// presenting this width, leave a mark? (docs/model.md §5.5 and §8)
//   puncture energy  E_p = k_p * w,   w = L |sin theta| + D |cos theta|
//   hit energy       E_h = f_h * E_p
// theta: angle between the nail's axis and the board normal; D: the shank diameter.
// A point-first nail (theta = 0) presents only D; a broadside one presents L.
#include "scenario/scenario.hpp"

namespace j232::board {

enum class Mark { None, Hit, Puncture };

double presented_width(double length, double diameter, double cos_theta);

Mark classify(double normal_energy, double presented_width, const scenario::BoardSpec& board);

}  // namespace j232::board
