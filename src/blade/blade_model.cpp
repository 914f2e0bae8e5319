#include "blade/blade_model.hpp"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

namespace j232::blade {

BladeModel::BladeModel(Blade blade) : blade_(std::move(blade)) {
  if (auto issues = problems(blade_); !issues.empty()) {
    std::string text = "unsound blade:";
    for (const auto& issue : issues) text += "\n  " + issue;
    throw std::invalid_argument(text);
  }
  int n = 0;
  const std::vector<std::vector<int>> coordinate = number_coordinates(n);
  assemble(coordinate, n);
  factor_and_prepare(n);
}

std::vector<std::vector<int>> BladeModel::number_coordinates(int& n) {
  // 1. Number the free bodies. A seized link takes its parent's coordinate.
  n = 0;
  if (!blade_.hub.constant_speed) hub_coordinate_ = n++;
  std::vector<std::vector<int>> coordinate(blade_.arms.size());
  for (std::size_t a = 0; a < blade_.arms.size(); ++a) {
    int parent = hub_coordinate_;
    for (const Link& link : blade_.arms[a].links) {
      const int c = link.seized ? parent : n++;
      coordinate[a].push_back(c);
      parent = c;
    }
  }
  return coordinate;
}

void BladeModel::assemble(const std::vector<std::vector<int>>& coordinate, int n) {
  auto unit = [n](int c) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    if (c != kPrescribed) v[c] = 1.0;
    return v;
  };

  // 2. Kinematics and kinetic energy, body by body:
  //    a link's point at s from its inner pin moves at (a + s b) q'; its kinetic energy is
  //    1/2 m ((a + c b) q')^2 + 1/2 I_c (b q')^2 with c its centre of mass.
  mass_matrix_ = Eigen::MatrixXd::Zero(n, n);
  hub_.coordinate = hub_coordinate_;
  hub_.pin = Eigen::VectorXd::Zero(n);
  hub_.spin = unit(hub_coordinate_);
  if (hub_coordinate_ != kPrescribed) mass_matrix_(hub_coordinate_, hub_coordinate_) += blade_.hub.inertia();

  links_.resize(blade_.arms.size());
  for (std::size_t a = 0; a < blade_.arms.size(); ++a) {
    const Arm& arm = blade_.arms[a];
    Eigen::VectorXd pin = blade_.arms[a].pivot_radius * hub_.spin;
    for (std::size_t k = 0; k < arm.links.size(); ++k) {
      const Link& link = arm.links[k];
      LinkCoefficients lc;
      lc.coordinate = coordinate[a][k];
      lc.pin = pin;
      lc.spin = unit(lc.coordinate);
      const Eigen::VectorXd centre = lc.pin + link.centre() * lc.spin;
      mass_matrix_ += link.mass * centre * centre.transpose() + link.inertia() * lc.spin * lc.spin.transpose();
      pin = lc.pin + link.length * lc.spin;
      links_[a].push_back(std::move(lc));
    }
  }
}

void BladeModel::factor_and_prepare(int n) {
  // 3. Factor once; every contact's coefficients follow from M^-1 a and M^-1 b.
  if (n > 0) {
    factor_.compute(mass_matrix_);
    const Eigen::VectorXd d = factor_.vectorD();
    const double scale = mass_matrix_.diagonal().cwiseAbs().maxCoeff();
    if (factor_.info() != Eigen::Success || !(d.minCoeff() > 1e-12 * scale))
      throw std::invalid_argument(
          "the blade's mass matrix is singular: some free body has no inertia about its pin "
          "(give the hub an inertia or a pivot radius > 0, and links a mass)");
  }
  auto prepare = [&](LinkCoefficients& lc) {
    if (n == 0) {
      lc.minv_pin = lc.minv_spin = Eigen::VectorXd::Zero(0);
      return;
    }
    lc.minv_pin = factor_.solve(lc.pin);
    lc.minv_spin = factor_.solve(lc.spin);
    lc.c0 = lc.pin.dot(lc.minv_pin);
    lc.c1 = lc.pin.dot(lc.minv_spin);
    lc.c2 = lc.spin.dot(lc.minv_spin);
  };
  prepare(hub_);
  for (auto& arm : links_)
    for (auto& lc : arm) prepare(lc);
}

const BladeModel::LinkCoefficients& BladeModel::coefficients(const ContactLocation& where) const {
  if (where.on_hub) return hub_;
  return links_.at(where.arm).at(where.link);
}

double BladeModel::effective_mass(const ContactLocation& where) const {
  const auto& lc = coefficients(where);
  const double s = where.distance;
  const double compliance = lc.c0 + 2.0 * s * lc.c1 + s * s * lc.c2;  // J M^-1 J^T, 1/kg
  // Round-off can leave a tiny value where the exact one is zero (an immovable point).
  const double scale = lc.c0 + 2.0 * std::abs(s * lc.c1) + s * s * lc.c2;
  if (!(compliance > 1e-14 * scale) || compliance <= 0.0) return kInfiniteMass;
  return 1.0 / compliance;
}

Eigen::Matrix2d BladeModel::planar_compliance(const ContactLocation& where, double forward_offset) const {
  // A point s along the body and `forward_offset` off its line (along the motion) moves at (a + s b) q' along the motion
  // and -forward_offset (b q') radially, so the
  // impulse's generalised force is J_t^T P_t + J_r^T P_r with J_r = -forward_offset b.
  const auto& lc = coefficients(where);
  const double s = where.distance;
  Eigen::Matrix2d c = Eigen::Matrix2d::Zero();
  if (dof() == 0) return c;
  c(0, 0) = lc.c0 + 2.0 * s * lc.c1 + s * s * lc.c2;
  c(0, 1) = c(1, 0) = -forward_offset * (lc.c1 + s * lc.c2);
  c(1, 1) = forward_offset * forward_offset * lc.c2;
  const double scale = lc.c0 + 2.0 * std::abs(s * lc.c1) + s * s * lc.c2;
  if (!(c(0, 0) > 1e-14 * scale)) c(0, 0) = 0.0, c(0, 1) = c(1, 0) = 0.0;
  return c;
}

Eigen::VectorXd BladeModel::rates_after(const ContactLocation& where, double forward_offset, double tangential, double radial) const {
  const auto& lc = coefficients(where);
  Eigen::VectorXd rates = rigid_rates();
  if (dof() > 0) rates += tangential * (lc.minv_pin + where.distance * lc.minv_spin) - forward_offset * radial * lc.minv_spin;
  return rates;
}

double BladeModel::contact_speed(const ContactLocation& where) const { return blade_.omega * contact_radius(blade_, where); }

Eigen::VectorXd BladeModel::rigid_rates() const { return Eigen::VectorXd::Constant(dof(), blade_.omega); }

Eigen::VectorXd BladeModel::rates_after(const ContactLocation& where, double impulse) const {
  const auto& lc = coefficients(where);
  Eigen::VectorXd rates = rigid_rates();
  if (dof() > 0) rates += impulse * (lc.minv_pin + where.distance * lc.minv_spin);
  return rates;
}

double BladeModel::hub_rate(const Eigen::VectorXd& rates) const {
  return hub_coordinate_ == kPrescribed ? blade_.omega : rates[hub_coordinate_];
}

double BladeModel::link_rate(const Eigen::VectorXd& rates, std::size_t arm, std::size_t link) const {
  const int c = links_.at(arm).at(link).coordinate;
  return c == kPrescribed ? blade_.omega : rates[c];
}

double BladeModel::kinetic_energy(const Eigen::VectorXd& rates) const {
  // Prescribed (constant-speed) bodies are left out: their energy is the drive's to keep.
  return dof() == 0 ? 0.0 : 0.5 * rates.dot(mass_matrix_ * rates);
}

}  // namespace j232::blade
