#pragma once
// Corrugated board: does a nail striking it with this energy, pressing on this width of
// it, leave a mark? (docs/model.md §5.5 and §8)
//   puncture energy  E_p = k_p * w,   w = min(L, delta / |cos theta|) |sin theta| + D |cos theta|
//   hit energy       E_h = f_h * E_p
// theta: angle between the nail's axis and the board normal; D: the shank diameter;
// delta: the crush depth (the part of the nail within delta of its first touch presses on
// the board). A point-first nail (theta = 0) presses only D; a broadside one its length L;
// one struck end first at an angle the part of its shank the crush reaches.
// The energy is what a plastic impact at the point that strikes takes out of the nail,
// m_eff v_n^2 / 2 (flight/plane_touch.hpp).
#include "scenario/scenario.hpp"

namespace j232::board {

enum class Mark { None, Hit, Puncture };

double presented_width(double length, double diameter, double cos_theta, double crush_depth);

Mark classify(double normal_energy, double presented_width, const scenario::BoardSpec& board);

}  // namespace j232::board
