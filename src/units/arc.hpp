#pragma once
// Azimuth ranges (rad, counter-clockwise from `from` to `to`, about the deck's centre), as
// openings, guards and the board's pieces are given: one set of rules for every stage.
#include <cmath>

#include "units/quantity.hpp"

namespace j232::units {

// The arc's extent in (0, 2 pi]: from == to is the whole turn, and so is an end a whole turn
// from the start to rounding (the reader takes "360 deg past azimuth_from" as the whole turn,
// and 420 deg - 60 deg comes out 2 pi + 9e-16 in radians, which the remainder alone would
// make an arc of nothing).
inline double arc_span(double from, double to) {
  if (std::abs(to - from) >= two_pi * (1 - 1e-12)) return two_pi;
  double span = std::fmod(to - from, two_pi);
  if (span <= 0) span += two_pi;
  return span;
}

// How far azimuth a lies past the arc's start, in [0, 2 pi].
inline double arc_offset(double a, double from) { return std::fmod(std::fmod(a - from, two_pi) + two_pi, two_pi); }

// Whether azimuth a lies in the arc, its start included and its end not (so that arcs that
// meet share no azimuth).
inline bool in_arc(double a, double from, double to) { return arc_offset(a, from) < arc_span(from, to); }

// Whether two arcs share more than an end: one's start lies in the other.
inline bool arcs_overlap(double from_a, double to_a, double from_b, double to_b) {
  return in_arc(from_a, from_b, to_b) || in_arc(from_b, from_a, to_a);
}

// An azimuth range as the scenario gives it (openings, guards, deflectors, a sector
// operator zone): the one type every stage reads, with the rules above.
struct Arc {
  double from = 0.0, to = 0.0;  // rad, counter-clockwise from -> to; from == to: the whole turn

  double span() const { return arc_span(from, to); }
  double offset(double a) const { return arc_offset(a, from); }
  bool contains(double a) const { return in_arc(a, from, to); }
  bool overlaps(const Arc& other) const { return arcs_overlap(from, to, other.from, other.to); }
  double middle() const { return from + 0.5 * span(); }
};

}  // namespace j232::units
