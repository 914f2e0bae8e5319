#pragma once
// Fitting the board to a lab's own drop tests (`j232 calibrate --board`, docs/model.md §6c):
// nails fired or dropped onto the board at a known speed and angle, each leaving no mark, a
// hit or a puncture. The board model's thresholds (E >= k_p w puncture, E >= f_h k_p w hit,
// w the width pressing within the crush depth delta; §5.5) with a scatter: the board's
// threshold at one spot is log-normal about the model's (flutes, liners, moisture), so
//   P(puncture) = Phi((ln(E/w) - ln k_p) / sigma),  P(hit or puncture) = Phi((ln(E/w) - ln(f_h k_p)) / sigma)
// (an ordered probit in ln(E/w)). k_p, f_h and sigma by maximum a posteriori (the likelihood
// and a weak prior on sigma, which keeps perfectly separated drops from collapsing it) at
// each delta of a grid, delta by the profile; 95 % intervals by bootstrap over the drops, and
// delta's from the profile (likelihood ratio, chi-square 1). E and w are the flight's own
// (flight::board_strike).
#include <string>
#include <vector>

#include "board/board.hpp"
#include "projectile/projectile.hpp"

namespace j232::study {

struct BoardDrop {
  double speed = 0;       // m/s, the nail's centre, square on to the board
  double axis_angle = 0;  // rad, between the nail's axis and the board's normal (0: point first)
  double spin = 0;        // rad/s, tumbling in the plane of the axis and the normal; positive turns the touching end toward the board
  board::Mark result = board::Mark::None;
  int line = 0;
};

// CSV with columns speed ("18 m/s"), axis_angle ("30 deg"), result (none, hit or puncture)
// and optionally spin ("40 rad/s"). Throws InputError naming the file, line and column.
std::vector<BoardDrop> read_board_drops(const std::string& csv_file);

struct Estimate {
  double value = 0, low = 0, high = 0;  // 95 %
  bool bounded = true;  // false: too many resamples left the threshold unbracketed; the interval is open
};

struct BoardFit {
  std::string drops_file;
  std::size_t drops = 0, hits = 0, punctures = 0;
  Estimate puncture_energy_per_width;  // J/m
  Estimate hit_fraction;
  Estimate crush_depth;      // m; the profile interval, clipped to the grid searched
  bool crush_depth_determined = false;  // false: the drops cannot tell the depths apart (the interval spans the grid)
  Estimate scatter;          // sigma, of ln(threshold)
  bool separated = false;    // a threshold separates the drops perfectly: sigma rests on its prior
  bool hit_fraction_determined = false;  // some drops left a hit, and some no mark
  double log_posterior = 0;  // at the fit (the likelihood and the prior on sigma)
  int bootstrap_draws = 0;
  // Per drop: E/w (J/m) at the fitted depth and the fitted probabilities of a hit or puncture.
  std::vector<double> energy_per_width, p_mark, p_puncture;
};

// Throws InputError when the drops cannot fit the board (fewer than 6; no puncture, or no
// drop without a puncture: the threshold is then not bracketed).
BoardFit fit_board(const std::vector<BoardDrop>& drops, const projectile::Projectile& nail, const std::string& drops_file,
                   unsigned long long seed = 20261126);

}  // namespace j232::study
