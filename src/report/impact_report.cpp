#include "report/impact_report.hpp"
#include "j232/version.hpp"

#include <cmath>
#include <fmt/format.h>

namespace j232::report {

using units::ft_per_min;
using units::rpm;

namespace {

std::string body_name(const blade::ContactLocation& where) {
  if (where.on_hub) return "hub bar";
  return fmt::format("arm {} link {}", where.arm + 1, where.link + 1);
}

nlohmann::ordered_json vec(const blade::Vec3& v) {
  // The calculator's frame is the struck arm's: x radial, y tangential, z vertical.
  return {{"radial", v.x()}, {"tangential", v.y()}, {"vertical", v.z()}};
}

// JSON has no infinity: an immovable contact reports null and says why.
nlohmann::ordered_json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; }

}  // namespace

nlohmann::ordered_json impact_json(const scenario::ImpactCase& in, const blade::ImpactSolution& s) {
  const auto& c = s.contact;
  nlohmann::ordered_json links = nlohmann::ordered_json::array();
  for (std::size_t a = 0; a < s.link_rates.size(); ++a)
    for (std::size_t k = 0; k < s.link_rates[a].size(); ++k)
      links.push_back(
          {{"arm", a + 1}, {"link", k + 1}, {"rate_after_rad_s", s.link_rates[a][k]}, {"rate_after_rpm", s.link_rates[a][k] / rpm}});
  return {
      {"program", "j232 impact"},
      {"version", j232::version},
      {"source", in.source},
      {"title", in.title},
      {"units", "SI (m, kg, s, rad) unless a key names another unit"},
      {"input",
       {{"blade_speed_rad_s", in.blade.omega},
        {"blade_speed_rpm", in.blade.omega / rpm},
        {"blade_mass_kg", in.blade.mass()},
        {"tip_radius_m", in.blade.tip_radius()},
        {"tip_speed_m_s", in.blade.omega * in.blade.tip_radius()},
        {"hub_drive", in.blade.hub.constant_speed ? "constant_speed" : "free"},
        {"object", in.object_name},
        {"object_mass_kg", in.object.mass},
        {"object_velocity_before_m_s", vec(in.object.velocity)},
        {"eccentric", in.object.rod.has_value()},
        {"restitution", in.restitution.describe()}}},
      {"contact", {{"body", body_name(s.location)}, {"radius_m", s.contact_radius}, {"distance_from_inner_pin_m", s.location.distance}}},
      {"blade_effective_mass_kg", finite_or_null(s.blade_effective_mass)},
      {"blade_immovable_at_contact", !std::isfinite(s.blade_effective_mass)},
      {"object_effective_mass_kg", c.object_effective_mass},
      {"blade_contact_speed_before_m_s", c.blade_speed_before},
      {"blade_contact_speed_after_m_s", c.blade_speed_after},
      {"approach_speed_m_s", c.approach_speed},
      {"e", c.e},
      {"impulse_N_s", c.impulse},
      {"object_velocity_after_m_s", vec(c.velocity_after)},
      {"object_speed_after_m_s", c.velocity_after.norm()},
      {"object_speed_after_ft_min", c.velocity_after.norm() / ft_per_min},
      {"object_speed_after_over_tip_speed", c.velocity_after.norm() / (in.blade.omega * in.blade.tip_radius())},
      {"object_discharge_speed_ft_min", c.velocity_after.y() / ft_per_min},
      {"object_spin_after_rad_s", vec(c.spin_after)},
      {"hub_rate_after_rad_s", s.hub_rate_after},
      {"hub_rate_after_rpm", s.hub_rate_after / rpm},
      {"links_after", links},
      {"energy_lost_J", c.energy_lost},
  };
}

std::string impact_table(const scenario::ImpactCase& in, const blade::ImpactSolution& s) {
  const auto& c = s.contact;
  std::string out;
  auto row = [&](std::string_view label, std::string value) { out += fmt::format("  {:<34} {}\n", label, value); };
  out += fmt::format("j232 impact — {}\n", in.title.empty() ? in.source : in.title);
  out += "\nInput\n";
  row("blade speed", fmt::format("{:.1f} rpm ({:.2f} rad/s); tip speed {:.2f} m/s ({:.0f} ft/min)", in.blade.omega / rpm, in.blade.omega,
                                 in.blade.omega * in.blade.tip_radius(), in.blade.omega * in.blade.tip_radius() / ft_per_min));
  row("blade mass, tip radius", fmt::format("{:.4g} kg ({:.4g} lb), {:.4g} m ({:.4g} in)", in.blade.mass(), in.blade.mass() / units::pound,
                                            in.blade.tip_radius(), in.blade.tip_radius() / units::inch));
  row("object", fmt::format("{}, {:.4g} kg ({:.4g} g){}", in.object_name, in.object.mass, in.object.mass / units::gram,
                            in.object.rod ? ", slender rod struck off centre" : ""));
  row("object speed toward blade",
      fmt::format("{:.4g} m/s ({:.1f} ft/min)", -in.object.velocity.y(), -in.object.velocity.y() / ft_per_min));
  row("restitution", in.restitution.describe());
  row("contact",
      fmt::format("{} at {:.4g} m ({:.4g} in) from the spindle", body_name(s.location), s.contact_radius, s.contact_radius / units::inch));
  out += "\nResult\n";
  row("blade effective mass at contact", std::isfinite(s.blade_effective_mass)
                                             ? fmt::format("{:.5g} kg", s.blade_effective_mass)
                                             : std::string("infinite (the struck point cannot give way)"));
  row("approach speed", fmt::format("{:.4f} m/s, e = {:.4g}", c.approach_speed, c.e));
  row("impulse on object", fmt::format("{:.5g} N s", c.impulse));
  row("OBJECT SPEED AFTER IMPACT",
      fmt::format("{:.4f} m/s ({:.1f} ft/min)", c.velocity_after.norm(), c.velocity_after.norm() / ft_per_min));
  row("  as a multiple of tip speed", fmt::format("{:.3f}", c.velocity_after.norm() / (in.blade.omega * in.blade.tip_radius())));
  row("  along the blade's motion", fmt::format("{:.4f} m/s ({:.1f} ft/min)", c.velocity_after.y(), c.velocity_after.y() / ft_per_min));
  if (in.object.rod) row("object spin after", fmt::format("{:.1f} rad/s ({:.0f} rpm)", c.spin_after.norm(), c.spin_after.norm() / rpm));
  row("hub after", fmt::format("{:.4f} rad/s ({:.2f} rpm)", s.hub_rate_after, s.hub_rate_after / rpm));
  for (std::size_t a = 0; a < s.link_rates.size(); ++a)
    for (std::size_t k = 0; k < s.link_rates[a].size(); ++k)
      row(fmt::format("arm {} link {} after", a + 1, k + 1),
          fmt::format("{:.4f} rad/s ({:.2f} rpm)", s.link_rates[a][k], s.link_rates[a][k] / rpm));
  row("kinetic energy lost", fmt::format("{:.5g} J", c.energy_lost));
  return out;
}

}  // namespace j232::report
