#pragma once
// What the mower stands on (`[ground] kind`): each kind's bounce and roll, and for soils how
// readily a nail arriving point-first sinks in (Young's penetrability number S). The values
// and where they come from are in docs/model.md §5.3a; a key given in [ground] overrides its
// kind's value.
#include <array>
#include <string_view>

namespace j232::scenario {

struct GroundKind {
  std::string_view name;
  double restitution;         // e_n at a perpendicular impact
  double angle_exponent;      // of the angle law (rockfall data on soil); 0: one e_n at every angle
  double friction;            // Coulomb, during the bounce and the slide
  double roughness_deg;       // std. dev. of the local normal's tilt
  double rolling_resistance;  // g, a ball rolling on it
  double penetrability;       // Young's S (0: a nail is taken not to sink in)
  std::string_view basis;     // where the figures come from, in a line (the report's assumption)
};

inline constexpr std::array<GroundKind, 6> kGroundKinds = {{
    {"turf", 0.15, 1.03, 0.5, 10, 0.3, 0,
     "estimates: mown grass, nails taken not to sink in (the earlier releases' ground); angle law of rockfall field data (Wyllie 2014)"},
    {"turf_on_topsoil", 0.15, 1.03, 0.5, 10, 0.3, 15,
     "the turf's estimates, on moist topsoil that a point-first nail sinks into: Young's penetrability S 10-20 for moist topsoil "
     "(Young 1997, SAND97-2426; recalled, not checked here)"},
    {"bare_soil", 0.30, 1.03, 0.5, 5, 0.2, 6,
     "normal restitution of soil about 0.3 (rockfall tables, Pfeiffer and Bowen 1989; recalled); firm soil S 4-10 (Young 1997; "
     "recalled); friction, roughness and rolling estimates"},
    {"artificial_turf", 0.30, 1.03, 0.6, 3, 0.1, 0,
     "estimates (ball bounce and roll on artificial turf: Biber et al. 2023 fit such figures, not retrieved here); nothing sinks in"},
    {"plywood", 0.45, 0.0, 0.4, 1, 0.05, 0,
     "estimates, one restitution at every angle (the rockfall angle law is of soil); steel on wood sliding friction 0.2-0.6 "
     "(handbook tables; recalled)"},
    {"concrete", 0.55, 0.0, 0.45, 1, 0.03, 0,
     "normal restitution of paving about 0.4 for rock (rockfall tables; recalled), higher for steel (estimate), one at every angle; "
     "steel on concrete friction 0.4-0.6 (handbooks; recalled)"},
}};

inline const GroundKind* ground_kind(std::string_view name) {
  for (const auto& k : kGroundKinds)
    if (k.name == name) return &k;
  return nullptr;
}

}  // namespace j232::scenario
