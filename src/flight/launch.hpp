#pragma once
// A struck body leaving the blade, the same for both pipelines (the J232 test's nail falling
// onto the blade, a field's object met by it as the mower travels): the blade's impulse at
// its first contact, whether that threw the body at all, and the body the flight starts from.
#include "flight/trajectory.hpp"
#include "projectile/projectile.hpp"
#include "strike/contact_search.hpp"
#include "strike/impulse.hpp"

namespace j232::flight {

struct Launch {
  enum class Result {
    Thrown,     // the blade gave it energy: `body` leaves from the contact
    NotThrown,  // the blade's point was not approaching it, or gave it no energy (a blade too slow to throw it)
    NonFinite,  // the impulse is not a finite number: cut off, never counted as not struck
  };
  Result result = Result::NotThrown;
  strike::StrikeOutcome hit;
  Body body;  // (Thrown only) at the contact, on the blades' clock
};

// `coming`: the body's velocity at the contact, in the mower's frame (falling; carried by
// the turf), without spin.
Launch launch(const strike::Spindle& spindle, const strike::Contact& contact, const projectile::Projectile& body, const Vec3& coming);

// Where a strike leaves a body, first or later, in either pipeline. Held by nothing, it
// leaves with the driven blade's push. Struck into soil that takes strikes (`soil`: the
// ground's friction and velocity, the body's reach below its centre and what it rests on),
// it is judged on the impact alone: the soil takes the downward part, and `ride_over` says
// whether the blade is then still in its way (the knife rides over it). Spin as the impulse
// left it (the caller drops a rod's axial part).
struct StruckSoil {
  double reach = 0, friction = 0, support = 0;
  Vec3 turf = Vec3::Zero();
};
struct AfterStrike {
  Vec3 velocity = Vec3::Zero(), spin = Vec3::Zero();
  bool ride_over = false;
};
AfterStrike after_strike(const strike::StrikeOutcome& hit, const strike::Spindle& spindle, const strike::Contact& contact,
                         const Vec3& centre, const StruckSoil* soil);

}  // namespace j232::flight
