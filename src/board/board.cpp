#include "board/board.hpp"

#include <algorithm>
#include <cmath>

namespace j232::board {

double presented_width(double length, double diameter, double cos_theta, double crush_depth) {
  const double c = std::min(1.0, std::abs(cos_theta));
  const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
  const double pressing = c * length > crush_depth ? crush_depth / c : length;
  return pressing * s + diameter * c;
}

Mark classify(double normal_energy, double width, const scenario::BoardSpec& board) {
  const double puncture = board.puncture_energy_per_width * width;
  if (normal_energy >= puncture) return Mark::Puncture;
  if (normal_energy >= board.hit_fraction * puncture) return Mark::Hit;
  return Mark::None;
}

}  // namespace j232::board
