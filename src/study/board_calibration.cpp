#include "study/board_calibration.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "assess/statistics.hpp"
#include "flight/board_strike.hpp"
#include "random/stream.hpp"
#include "scenario/csv_reader.hpp"
#include "scenario/input_error.hpp"

namespace j232::study {

namespace {
using scenario::InputError;
using Vec3 = Eigen::Vector3d;
using Params = std::array<double, 3>;  // ln k_p, ln(-ln f_h), ln sigma
constexpr double kScatterPriorMedian = 0.1, kScatterPriorWidth = 1.0;

// ln Phi(x), accurate in the far tail (erfc keeps its relative precision there).
double log_phi(double x) { return std::log(std::max(0.5 * std::erfc(-x / std::sqrt(2.0)), 1e-300)); }
double phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

double hit_fraction_of(const Params& p) { return std::exp(-std::exp(p[1])); }

// The ordered probit's log-likelihood of the drops' marks at y = ln(E/w).
double log_likelihood(const std::vector<double>& y, const std::vector<board::Mark>& marks, const std::vector<std::size_t>& use, const Params& p) {
  const double sigma = std::exp(p[2]), puncture = p[0], hit = p[0] - std::exp(p[1]);  // ln f_h = -exp(c)
  if (!(sigma >= 0.005 && sigma <= 5)) return -std::numeric_limits<double>::infinity();
  double sum = 0;
  for (std::size_t i : use) {
    const double zh = (y[i] - hit) / sigma, zp = (y[i] - puncture) / sigma;
    switch (marks[i]) {
      case board::Mark::None: sum += log_phi(-zh); break;
      case board::Mark::Puncture: sum += log_phi(zp); break;
      case board::Mark::Hit:  // in the upper tail from the other side, where the difference keeps its digits
        sum += std::log(std::max(zp > 0 ? phi(-zp) - phi(-zh) : phi(zh) - phi(zp), 1e-300));
        break;
    }
  }
  return sum;
}

// A weak prior on the scatter, ln sigma ~ N(ln 0.1, 1) [est]: drops that a threshold
// separates perfectly (few drops, or none near the thresholds) have no finite maximum of the
// likelihood (sigma -> 0, the thresholds anywhere in the gaps), and the profile over the
// crush depth then picks any depth that separates them. The prior keeps sigma finite; with
// many drops it changes nothing (docs/model.md §6c).
double log_prior(const Params& p) {
  const double z = (p[2] - std::log(kScatterPriorMedian)) / kScatterPriorWidth;
  return -0.5 * z * z;
}

// Nelder-Mead on -(log-likelihood + log prior) (3 parameters).
Params maximise(const std::vector<double>& y, const std::vector<board::Mark>& marks, const std::vector<std::size_t>& use, Params start) {
  const auto f = [&](const Params& p) { return -(log_likelihood(y, marks, use, p) + log_prior(p)); };
  std::array<Params, 4> v{start, start, start, start};
  v[1][0] += 0.3, v[2][1] += 0.5, v[3][2] += 0.5;
  std::array<double, 4> fv{};
  for (int i = 0; i < 4; ++i) fv[static_cast<std::size_t>(i)] = f(v[static_cast<std::size_t>(i)]);
  for (int iteration = 0; iteration < 2000; ++iteration) {
    std::array<std::size_t, 4> order{0, 1, 2, 3};
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return fv[a] < fv[b]; });
    std::array<Params, 4> sv;
    std::array<double, 4> sf{};
    for (std::size_t i = 0; i < 4; ++i) sv[i] = v[order[i]], sf[i] = fv[order[i]];
    v = sv, fv = sf;
    if (std::abs(fv[3] - fv[0]) < 1e-12 * (1 + std::abs(fv[0])) && iteration > 20) break;
    Params centroid{};
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t k = 0; k < 3; ++k) centroid[k] += v[i][k] / 3;
    const auto along = [&](double t) {
      Params p;
      for (std::size_t k = 0; k < 3; ++k) p[k] = centroid[k] + t * (v[3][k] - centroid[k]);
      return p;
    };
    const Params reflected = along(-1);
    const double fr = f(reflected);
    if (fr < fv[0]) {
      const Params expanded = along(-2);
      const double fe = f(expanded);
      if (fe < fr) v[3] = expanded, fv[3] = fe;
      else v[3] = reflected, fv[3] = fr;
    } else if (fr < fv[2]) {
      v[3] = reflected, fv[3] = fr;
    } else {
      const Params contracted = fr < fv[3] ? along(-0.5) : along(0.5);
      const double fc = f(contracted);
      if (fc < std::min(fr, fv[3])) {
        v[3] = contracted, fv[3] = fc;
      } else {
        for (std::size_t i = 1; i < 4; ++i) {
          for (std::size_t k = 0; k < 3; ++k) v[i][k] = v[0][k] + 0.5 * (v[i][k] - v[0][k]);
          fv[i] = f(v[i]);
        }
      }
    }
  }
  return v[static_cast<std::size_t>(std::min_element(fv.begin(), fv.end()) - fv.begin())];
}

// ln(E/w) of each drop at crush depth `depth`: the nail square on to a board facing +z,
// its lower end first (point first at angle 0, flat at 90 deg), tumbling in the plane of its
// axis and the normal (a positive spin turns the touching end toward the board).
std::vector<double> log_energy_per_width(const std::vector<BoardDrop>& drops, const projectile::Projectile& nail, double depth) {
  const Vec3 n = Vec3::UnitZ();
  std::vector<double> y;
  for (const auto& d : drops) {
    const Vec3 axis(std::sin(d.axis_angle), 0.0, std::cos(d.axis_angle));
    const Vec3 arm = -nail.half_segment() * axis - nail.radius() * n;  // the lower end's lowest point
    const Vec3 spin = -d.spin * Vec3::UnitY();  // positive: the touching end turns toward the board
    const auto strike = flight::board_strike(nail, axis, arm, n, Vec3(0, 0, -d.speed), spin, depth);
    y.push_back(std::log(std::max(strike.energy, 1e-300) / strike.width));
  }
  return y;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return assess::quantile_sorted(v, q);
}
}  // namespace

std::vector<BoardDrop> read_board_drops(const std::string& csv_file) {
  const scenario::CsvTable t = scenario::read_csv(csv_file);
  const int speed = scenario::require_column(t, "speed", "the nail's speed square on to the board, e.g. \"18 m/s\"");
  const int angle = scenario::require_column(t, "axis_angle", "the angle between the nail's axis and the board's normal, e.g. \"30 deg\" (0: point first)");
  const int result = scenario::require_column(t, "result", "what the nail left: none, hit or puncture");
  const int spin = t.column("spin");
  std::vector<BoardDrop> out;
  for (const auto& row : t.rows) {
    BoardDrop d;
    d.line = row.line;
    d.speed = scenario::quantity_cell(t, row, speed, units::Kind::Speed);
    if (!(d.speed > 0 && d.speed < 1000)) throw InputError(csv_file, row.line, "speed", row.fields[static_cast<std::size_t>(speed)], "a speed above zero (and below 1000 m/s)");
    d.axis_angle = scenario::quantity_cell(t, row, angle, units::Kind::Angle);
    if (!(d.axis_angle >= 0 && d.axis_angle <= 0.5 * M_PI + 1e-12))
      throw InputError(csv_file, row.line, "axis_angle", row.fields[static_cast<std::size_t>(angle)], "an angle from 0 deg (point first) to 90 deg (flat)");
    if (spin >= 0) {
      d.spin = scenario::quantity_cell(t, row, spin, units::Kind::AngularSpeed);
      if (!std::isfinite(d.spin)) throw InputError(csv_file, row.line, "spin", row.fields[static_cast<std::size_t>(spin)], "a finite angular speed");
    }
    const std::string& r = row.fields[static_cast<std::size_t>(result)];
    if (r == "none") d.result = board::Mark::None;
    else if (r == "hit") d.result = board::Mark::Hit;
    else if (r == "puncture") d.result = board::Mark::Puncture;
    else throw InputError(csv_file, row.line, "result", r, "none, hit or puncture");
    out.push_back(d);
  }
  return out;
}

BoardFit fit_board(const std::vector<BoardDrop>& drops, const projectile::Projectile& nail, const std::string& drops_file, unsigned long long seed) {
  BoardFit fit;
  fit.drops_file = drops_file;
  fit.drops = drops.size();
  std::vector<board::Mark> marks;
  for (const auto& d : drops) {
    marks.push_back(d.result);
    fit.hits += d.result == board::Mark::Hit, fit.punctures += d.result == board::Mark::Puncture;
  }
  if (drops.size() < 6) throw InputError::file_problem(drops_file, std::nullopt, fmt::format("{} drops; expected at least 6 to fit the board", drops.size()));
  if (fit.punctures == 0 || fit.punctures == drops.size())
    throw InputError::file_problem(drops_file, std::nullopt,
                                   fit.punctures == 0 ? "no drop punctured the board: its puncture threshold is not bracketed (drop faster)"
                                                      : "every drop punctured the board: its puncture threshold is not bracketed (drop slower)");
  std::vector<std::size_t> all(drops.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;

  // Each crush depth of the grid, its best k_p, f_h and sigma; delta by the profile.
  const auto start_at = [&](const std::vector<double>& y) {
    double mean = 0;
    for (double v : y) mean += v / static_cast<double>(y.size());
    return Params{mean, std::log(-std::log(0.3)), std::log(0.3)};
  };
  std::vector<double> depths, profile;
  std::vector<Params> best;
  for (int k = 0; k <= 28; ++k) {
    const double depth = 0.001 + 0.0005 * k;
    const auto y = log_energy_per_width(drops, nail, depth);
    const Params p = maximise(y, marks, all, start_at(y));
    depths.push_back(depth), best.push_back(p), profile.push_back(log_likelihood(y, marks, all, p) + log_prior(p));
  }
  const auto top = static_cast<std::size_t>(std::max_element(profile.begin(), profile.end()) - profile.begin());
  const double cut = profile[top] - 0.5 * 3.841458820694124;  // chi-square, 1 degree of freedom, 95 %
  std::size_t lo = top, hi = top;
  while (lo > 0 && profile[lo - 1] >= cut) --lo;
  while (hi + 1 < depths.size() && profile[hi + 1] >= cut) ++hi;
  // Where the profile crosses the cut, between grid depths (linear in between).
  const auto crossing = [&](std::size_t in, std::size_t out) {
    return depths[out] + (cut - profile[out]) / (profile[in] - profile[out]) * (depths[in] - depths[out]);
  };
  fit.crush_depth = {depths[top], lo > 0 ? crossing(lo, lo - 1) : depths[lo], hi + 1 < depths.size() ? crossing(hi, hi + 1) : depths[hi]};
  fit.crush_depth_determined = !(lo == 0 && hi + 1 == depths.size());
  fit.log_posterior = profile[top];
  const Params p = best[top];
  const auto y = log_energy_per_width(drops, nail, depths[top]);
  const double sigma = std::exp(p[2]), hit_threshold = p[0] - std::exp(p[1]);
  // Perfectly separated: every mark above every drop without one, every puncture above every
  // other drop (the scatter then rests on its prior).
  double none_top = -1e300, mark_bottom = 1e300, other_top = -1e300, puncture_bottom = 1e300;
  for (std::size_t i = 0; i < y.size(); ++i) {
    if (marks[i] == board::Mark::None) none_top = std::max(none_top, y[i]);
    else mark_bottom = std::min(mark_bottom, y[i]);
    if (marks[i] == board::Mark::Puncture) puncture_bottom = std::min(puncture_bottom, y[i]);
    else other_top = std::max(other_top, y[i]);
  }
  fit.separated = none_top < mark_bottom && other_top < puncture_bottom;
  for (double v : y) {
    fit.energy_per_width.push_back(std::exp(v));
    fit.p_mark.push_back(phi((v - hit_threshold) / sigma));
    fit.p_puncture.push_back(phi((v - p[0]) / sigma));
  }

  // Intervals: the drops resampled, each resample fitted afresh at every depth of the
  // profile's interval (and a grid step beyond each end), keeping the best: k_p and the
  // depth are linked (a deeper crush presses a wider nail), so the depth is refitted too.
  const std::size_t first = lo > 0 ? lo - 1 : lo, last = hi + 1 < depths.size() ? hi + 1 : hi;
  std::vector<std::vector<double>> y_at;
  for (std::size_t k = first; k <= last; ++k) y_at.push_back(log_energy_per_width(drops, nail, depths[k]));
  fit.bootstrap_draws = 400;
  random::Stream stream(seed, 0, 0, random::Purpose::BoardFit);
  std::vector<double> kp, fh, sg;
  int puncture_open = 0, hit_open = 0;  // resamples that do not bracket the threshold
  for (int b = 0; b < fit.bootstrap_draws; ++b) {
    std::vector<std::size_t> use(drops.size());
    std::size_t unmarked = 0, punctured = 0;
    for (auto& i : use) {
      i = std::min(drops.size() - 1, static_cast<std::size_t>(stream.uniform() * static_cast<double>(drops.size())));
      unmarked += marks[i] == board::Mark::None, punctured += marks[i] == board::Mark::Puncture;
    }
    puncture_open += punctured == 0 || punctured == use.size();
    hit_open += unmarked == 0 || unmarked == use.size();
    Params q = p;
    double q_best = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < y_at.size(); ++k) {
      const Params r = maximise(y_at[k], marks, use, best[first + k]);
      const double value = log_likelihood(y_at[k], marks, use, r) + log_prior(r);
      if (value > q_best) q_best = value, q = r;
    }
    kp.push_back(std::exp(q[0])), fh.push_back(hit_fraction_of(q)), sg.push_back(std::exp(q[2]));
  }
  // More than 2.5 % of resamples leave a threshold unbracketed: its interval is open there.
  const double open_limit = 0.025 * fit.bootstrap_draws;
  fit.puncture_energy_per_width = {std::exp(p[0]), quantile(kp, 0.025), quantile(kp, 0.975), puncture_open <= open_limit};
  fit.hit_fraction = {hit_fraction_of(p), quantile(fh, 0.025), quantile(fh, 0.975), hit_open <= open_limit};
  fit.hit_fraction_determined = fit.hits > 0 && fit.hits + fit.punctures < fit.drops;
  fit.scatter = {sigma, quantile(sg, 0.025), quantile(sg, 0.975)};
  return fit;
}

}  // namespace j232::study
