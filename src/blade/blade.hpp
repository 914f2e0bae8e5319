#pragma once
// What a rotary mower blade is, as the impact core sees it (docs/model.md §2–3):
// a hub turning about the spindle, carrying arms; each arm is a chain of slender
// links pinned end to end, the first pinned to the hub at the arm's pivot radius.
//
//   report 445-1 Case I   (straight blade):   hub bar only, no arms
//   report 445-1 Case II  (pivoted blade):    hub bar + one arm of one link
//   report 445-1 Case III (N rods):           hub bar + one arm of N-1 links
//   a real two-arm pivoted blade:             centred hub bar + two arms at 0 and 180 deg
//
// All lengths and masses are SI. Before impact the blade turns rigidly at omega
// with every link lying radially (centrifugal alignment).
#include <optional>
#include <string>
#include <vector>

namespace j232::blade {

struct Link {
  double length = 0.0;  // pin to pin (or pin to tip for the last link), m
  double mass = 0.0;    // kg
  // Distance of the centre of mass from the inner pin; default length / 2 (uniform rod).
  std::optional<double> centre_of_mass;
  // Moment of inertia about the centre of mass, in the blade plane; default m l^2 / 12.
  std::optional<double> inertia_about_centre;
  // A seized (rusted) inner pin: the link moves rigidly with the body inboard of it.
  bool seized = false;

  double centre() const { return centre_of_mass.value_or(0.5 * length); }
  double inertia() const { return inertia_about_centre.value_or(mass * length * length / 12.0); }
};

struct Arm {
  double azimuth = 0.0;       // rad, angle of the arm in the blade frame (leading arm at 0)
  double pivot_radius = 0.0;  // m, where the first link is pinned to the hub
  std::vector<Link> links;

  double tip_radius() const;
  // Radius of the inner pin of link k (k = 0 .. links.size() - 1).
  double pin_radius(std::size_t k) const;
};

// How the hub's own bar is mounted: a bar centred on the spindle (I = m L^2 / 12,
// reach L / 2), or a bar from the spindle outwards (I = m L^2 / 3, reach L), the
// report's one-rod model of a blade.
enum class BarMount { Centre, End };

struct Hub {
  double bar_mass = 0.0;
  double bar_length = 0.0;
  BarMount bar_mount = BarMount::Centre;
  double extra_inertia = 0.0;   // explicit hub inertia (plates, bolts) about the spindle, kg m^2
  double drive_inertia = 0.0;   // drive line (gearbox, shaft, flywheel) seen at the spindle, kg m^2
  bool constant_speed = false;  // driven at constant speed: infinite inertia

  double reach() const { return bar_mount == BarMount::End ? bar_length : 0.5 * bar_length; }
  double inertia() const;  // bar + extra + drive, about the spindle
};

struct Blade {
  Hub hub;
  std::vector<Arm> arms;
  double omega = 0.0;  // rad/s, positive: the blade's direction of motion defines +tangent

  double tip_radius() const;  // largest radius any part reaches
  double mass() const;        // hub bar + links
};

// Where the object meets the blade: on the hub bar, or on link `link` of arm `arm`
// at `distance` from that link's inner pin. Indices are 0-based.
struct ContactLocation {
  bool on_hub = true;
  std::size_t arm = 0;
  std::size_t link = 0;
  double distance = 0.0;  // m, from the link's inner pin; for the hub: radius from the spindle

  static ContactLocation hub(double radius) { return {true, 0, 0, radius}; }
  static ContactLocation on_link(std::size_t arm, std::size_t link, double distance) { return {false, arm, link, distance}; }
};

// Finds the body at `radius` from the spindle along arm `arm` (hub if inside the pivot
// radius or the blade has no arms). Returns nullopt when the radius lies beyond the blade.
std::optional<ContactLocation> locate(const Blade& blade, std::size_t arm, double radius);

// Radius of a contact location from the spindle.
double contact_radius(const Blade& blade, const ContactLocation& where);

// Checks a blade for physical sense. Returns a list of problems, each naming the
// part ("arm 2 link 1: mass must be positive, got -0.1 kg"); empty when it is sound.
std::vector<std::string> problems(const Blade& blade);

}  // namespace j232::blade
