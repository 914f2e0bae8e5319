// j232 calibrate --board: the board's thresholds fitted to drop tests.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <string>

#include "flight/board_strike.hpp"
#include "random/stream.hpp"
#include "scenario/input_error.hpp"
#include "study/board_calibration.hpp"

using namespace j232;

namespace {
const auto kNail = projectile::Projectile::capsule(0.0508, 0.00251, 0.0020);

std::string write(const std::string& name, const std::string& text) {
  const std::string path = std::string(J232_BINARY_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}
}  // namespace

TEST_CASE("board fit: point-first drops recover k_p from the hand threshold v = sqrt(2 k_p D / m)", "[calibration][board]") {
  // A point-first nail presses its diameter D and gives up m v^2 / 2 (its mass felt whole on
  // its axis): it punctures above v_p = sqrt(2 k_p D / m) = 16.62 m/s at k_p = 110 J/m, and
  // marks above v_p sqrt(f_h) = 9.10 m/s at f_h = 0.3. Drops every 0.25 m/s from 5 to 25.
  const double kp = 110, fh = 0.3;
  const double vp = std::sqrt(2 * kp * kNail.diameter / kNail.mass), vh = vp * std::sqrt(fh);
  REQUIRE(vp == Approx(16.617).epsilon(1e-3));
  std::string csv = "speed,axis_angle,result\n";
  for (double v = 5; v <= 25.0001; v += 0.25) csv += fmt::format("{} m/s,0 deg,{}\n", v, v >= vp ? "puncture" : v >= vh ? "hit" : "none");
  const std::string file = write("board-point-first.csv", csv);
  const auto drops = study::read_board_drops(file);
  REQUIRE(drops.size() == 81);
  const auto fit = study::fit_board(drops, kNail, file);
  // The threshold lies between the last speed without a puncture and the first with one.
  const double kp_low = 16.5 * 16.5 * kNail.mass / (2 * kNail.diameter), kp_high = 16.75 * 16.75 * kNail.mass / (2 * kNail.diameter);
  CHECK(fit.puncture_energy_per_width.value >= kp_low * 0.99);
  CHECK(fit.puncture_energy_per_width.value <= kp_high * 1.01);
  CHECK(fit.hit_fraction.value == Approx(fh).epsilon(0.06));
  CHECK(fit.scatter.value < 0.05);  // the data have none (the prior keeps it above 0)
  CHECK(fit.separated);
  // Point first, the width and energy do not depend on the crush depth: it cannot be fitted.
  CHECK_FALSE(fit.crush_depth_determined);
}

TEST_CASE("board fit: drops drawn from the model with scatter give intervals that cover the truth", "[calibration][board]") {
  // 600 drops at angles from point first to flat, speeds 5-45 m/s; each spot's threshold
  // log-normal about the model's (sigma 0.15); k_p 110 J/m, f_h 0.3, crush depth 7 mm.
  const double kp = 110, fh = 0.3, depth = 0.007, sigma = 0.15;
  random::Stream s(7, 0, 0, random::Purpose::Test);
  std::string csv = "speed,axis_angle,spin,result\n";
  for (int i = 0; i < 600; ++i) {
    const double v = 5 + 40 * s.uniform(), angle = 90 * s.uniform() * M_PI / 180, spin = 0.0;
    const Eigen::Vector3d n = Eigen::Vector3d::UnitZ(), axis(std::sin(angle), 0, std::cos(angle));
    const auto strike = flight::board_strike(kNail, axis, -kNail.half_segment() * axis - kNail.radius() * n, n, Eigen::Vector3d(0, 0, -v),
                                             Eigen::Vector3d::Zero(), depth);
    const double z = std::sqrt(-2 * std::log(1 - s.uniform())) * std::cos(2 * M_PI * s.uniform());
    const double threshold = kp * std::exp(sigma * z);  // this spot's k_p
    const double e = strike.energy / strike.width;
    csv += fmt::format("{} m/s,{} deg,{} rad/s,{}\n", v, angle * 180 / M_PI, spin, e >= threshold ? "puncture" : e >= fh * threshold ? "hit" : "none");
  }
  const std::string file = write("board-scatter.csv", csv);
  const auto fit = study::fit_board(study::read_board_drops(file), kNail, file);
  INFO("k_p " << fit.puncture_energy_per_width.value << " (" << fit.puncture_energy_per_width.low << "-" << fit.puncture_energy_per_width.high
              << "), f_h " << fit.hit_fraction.value << " (" << fit.hit_fraction.low << "-" << fit.hit_fraction.high << "), depth "
              << fit.crush_depth.value << " (" << fit.crush_depth.low << "-" << fit.crush_depth.high << "), sigma " << fit.scatter.value);
  CHECK((fit.puncture_energy_per_width.low <= kp && kp <= fit.puncture_energy_per_width.high));
  CHECK((fit.hit_fraction.low <= fh && fh <= fit.hit_fraction.high));
  CHECK((fit.scatter.low <= sigma && sigma <= fit.scatter.high));
  CHECK(fit.crush_depth_determined);
  CHECK((fit.crush_depth.low <= depth + 1e-9 && depth - 1e-9 <= fit.crush_depth.high));
  CHECK(fit.puncture_energy_per_width.high / fit.puncture_energy_per_width.low < 1.3);  // 600 drops pin it down
}

TEST_CASE("board fit: drops that cannot fit the board are refused with the file, line and what was expected", "[calibration][board][input]") {
  using Catch::Contains;
  const auto refused = [](const std::string& text, const std::string& says) {
    const std::string file = write("board-bad.csv", text);
    INFO(text);
    CHECK_THROWS_WITH(study::fit_board(study::read_board_drops(file), kNail, file), Contains(says));
  };
  std::string all_punctured = "speed,axis_angle,result\n";
  for (int i = 0; i < 8; ++i) all_punctured += fmt::format("{} m/s,0 deg,puncture\n", 20 + i);
  refused(all_punctured, "every drop punctured the board");
  refused("speed,axis_angle,result\n20 m/s,0 deg,puncture\n5 m/s,0 deg,none\n", "2 drops; expected at least 6");
  refused("speed,axis_angle,result\n20 m/s,0 deg,dent\n", ":2: result = dent: none, hit or puncture");
  refused("speed,axis_angle,result\n20 m/s,120 deg,hit\n", "axis_angle = 120 deg");
  refused("speed,axis_angle,result\n20 kg,0 deg,hit\n", "speed = 20 kg");
  refused("speed,result\n20 m/s,hit\n", "no column \"axis_angle\"");
}
