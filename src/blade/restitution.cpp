#include "blade/restitution.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace j232::blade {

double Restitution::at(double approach_speed) const {
  if (model == Model::Constant) return e;
  const double v = std::max(approach_speed, 1e-12);
  return std::clamp(coefficient * std::pow(v / reference_speed, exponent), 0.0, std::min(maximum, 1.0));
}

std::string Restitution::problem() const {
  if (model == Model::Constant) {
    if (!(e >= 0.0 && e <= 1.0)) return fmt::format("e must lie in [0, 1], got {}", e);
    return {};
  }
  if (!(coefficient > 0.0) || !std::isfinite(coefficient))
    return fmt::format("power-law coefficient must be positive, got {}", coefficient);
  if (!(exponent <= 0.0) || !std::isfinite(exponent))
    return fmt::format("power-law exponent must be zero or negative (e falls with speed), got {}", exponent);
  if (!(maximum >= 0.0 && maximum <= 1.0)) return fmt::format("maximum e must lie in [0, 1], got {}", maximum);
  if (!(reference_speed > 0.0) || !std::isfinite(reference_speed))
    return fmt::format("reference speed must be positive, got {} m/s", reference_speed);
  return {};
}

std::string Restitution::describe() const {
  if (model == Model::Constant) return fmt::format("e = {:g} (constant)", e);
  return fmt::format("e(v) = min({:g}, {:g} (v / {:g} m/s)^{:g})", maximum, coefficient, reference_speed, exponent);
}

}  // namespace j232::blade
