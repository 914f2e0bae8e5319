#include "blade/restitution.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace j232::blade {

double Restitution::at(double approach_speed) const {
  if (model == Model::Constant) return e;
  const double v = std::max(approach_speed, 1e-12);
  const double cap = std::min(maximum, 1.0);
  // Slow contacts (grazing bounces, most of them) sit on the cap. For Johnson's exponent
  // -1/4 the speed below which the law exceeds the cap is (coefficient / cap)^4 times the
  // reference: no pow needed there (with a margin, so the answer is the same).
  if (exponent == -0.25 && cap > 0) {
    const double r = coefficient / cap, r2 = r * r;
    if (v < reference_speed * r2 * r2 * (1 - 1e-9)) return cap;
  }
  return std::clamp(coefficient * std::pow(v / reference_speed, exponent), 0.0, cap);
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
