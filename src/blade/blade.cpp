#include "blade/blade.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace j232::blade {

double Arm::pin_radius(std::size_t k) const {
  double r = pivot_radius;
  for (std::size_t i = 0; i < k && i < links.size(); ++i) r += links[i].length;
  return r;
}

double Arm::tip_radius() const { return pin_radius(links.size()); }

double Hub::inertia() const {
  const double bar = bar_mount == BarMount::End ? bar_mass * bar_length * bar_length / 3.0 : bar_mass * bar_length * bar_length / 12.0;
  return bar + extra_inertia + drive_inertia;
}

double Blade::tip_radius() const {
  double r = hub.reach();
  for (const auto& arm : arms) r = std::max(r, arm.tip_radius());
  return r;
}

double Blade::mass() const {
  double m = hub.bar_mass;
  for (const auto& arm : arms)
    for (const auto& link : arm.links) m += link.mass;
  return m;
}

std::optional<ContactLocation> locate(const Blade& blade, std::size_t arm, double radius) {
  if (radius < 0.0) return std::nullopt;
  if (blade.arms.empty() || arm >= blade.arms.size()) {
    if (radius <= blade.hub.reach()) return ContactLocation::hub(radius);
    return std::nullopt;
  }
  const Arm& a = blade.arms[arm];
  if (radius < a.pivot_radius) {
    if (radius <= blade.hub.reach()) return ContactLocation::hub(radius);
    return std::nullopt;
  }
  // A radius exactly at a pin belongs to the outer link; both give the same pin velocity.
  for (std::size_t k = 0; k < a.links.size(); ++k) {
    const double inner = a.pin_radius(k);
    if (radius < inner + a.links[k].length || k + 1 == a.links.size()) {
      if (radius > inner + a.links[k].length) return std::nullopt;
      return ContactLocation::on_link(arm, k, radius - inner);
    }
  }
  return std::nullopt;
}

double contact_radius(const Blade& blade, const ContactLocation& where) {
  if (where.on_hub) return where.distance;
  return blade.arms.at(where.arm).pin_radius(where.link) + where.distance;
}

std::vector<std::string> problems(const Blade& blade) {
  std::vector<std::string> out;
  auto positive = [&](double v, const std::string& what, const char* unit) {
    if (!std::isfinite(v) || v <= 0.0) out.push_back(fmt::format("{} must be positive, got {} {}", what, v, unit));
  };
  auto non_negative = [&](double v, const std::string& what, const char* unit) {
    if (!std::isfinite(v) || v < 0.0) out.push_back(fmt::format("{} must not be negative, got {} {}", what, v, unit));
  };
  if (!std::isfinite(blade.omega)) out.push_back("blade speed must be a finite number");
  non_negative(blade.hub.bar_mass, "hub bar mass", "kg");
  non_negative(blade.hub.bar_length, "hub bar length", "m");
  non_negative(blade.hub.extra_inertia, "hub inertia", "kg m^2");
  non_negative(blade.hub.drive_inertia, "drive inertia", "kg m^2");
  if (!blade.hub.constant_speed && blade.hub.inertia() <= 0.0 && blade.arms.empty())
    out.push_back("the blade has no inertia: give the hub bar a mass and length, an inertia, or arms");
  for (std::size_t a = 0; a < blade.arms.size(); ++a) {
    const Arm& arm = blade.arms[a];
    const std::string name = fmt::format("arm {}", a + 1);
    non_negative(arm.pivot_radius, name + " pivot radius", "m");
    if (arm.links.empty()) out.push_back(name + " has no links");
    for (std::size_t k = 0; k < arm.links.size(); ++k) {
      const Link& link = arm.links[k];
      const std::string lname = fmt::format("{} link {}", name, k + 1);
      positive(link.length, lname + " length", "m");
      positive(link.mass, lname + " mass", "kg");
      if (link.centre_of_mass && (*link.centre_of_mass < 0.0 || *link.centre_of_mass > link.length))
        out.push_back(
            fmt::format("{} centre of mass must lie on the link (0 to {} m), got {} m", lname, link.length, *link.centre_of_mass));
      if (link.inertia_about_centre) non_negative(*link.inertia_about_centre, lname + " inertia", "kg m^2");
    }
  }
  return out;
}

}  // namespace j232::blade
