#pragma once
// The blade as a linear mechanical system for impulsive contact (docs/model.md §2–3).
//
// Generalised coordinates are the absolute angles of the free bodies: the hub (unless
// it is driven at constant speed) and every link whose inner pin is not seized. A
// seized link shares the coordinate of the body inboard of it. In the radially aligned
// pre-impact configuration every point at radius r on a body moves tangentially, and
// its tangential speed is linear in the coordinate rates q':  v = J q'.
//
// Kinetic energy T = 1/2 q'^T M q' defines the constant mass matrix M. An impulse P
// along the tangent at a contact with Jacobian row J changes the rates by
//     M dq' = J^T P,
// so the blade's effective mass at that contact is m_b = 1 / (J M^-1 J^T).
// For a contact at distance s along a link, J(s) = a + s b (a: the link's inner pin,
// b: the link's own rotation), so J M^-1 J^T is a quadratic in s whose three
// coefficients are precomputed per link: the per-nail cost is a handful of flops.
#include <Eigen/Dense>
#include <limits>
#include <vector>

#include "blade/blade.hpp"

namespace j232::blade {

class BladeModel {
 public:
  // Throws std::invalid_argument if the blade is unsound (see problems()) or its
  // mass matrix is singular (a free body with no inertia about its pin).
  explicit BladeModel(Blade blade);

  const Blade& blade() const { return blade_; }
  int dof() const { return static_cast<int>(mass_matrix_.rows()); }
  const Eigen::MatrixXd& mass_matrix() const { return mass_matrix_; }

  // Effective blade mass at a contact, kg. Infinite when the struck body cannot
  // give way (constant-speed hub with every pin outboard of it seized, or dof() == 0).
  double effective_mass(const ContactLocation& where) const;

  // The blade's compliance at a contact `forward_offset` metres off the arm's line along the
  // blade's motion (negative: behind it), for an impulse in the blade plane: the 2x2 matrix C in the basis
  // (tangential, radial) such that the contact point's velocity changes by C P for an
  // impulse P on the blade there. The tangential-tangential entry is 1 / effective_mass at
  // forward_offset = 0; a radial impulse acts through the offset on the body's rotation. Zero for
  // a body that cannot give way.
  Eigen::Matrix2d planar_compliance(const ContactLocation& where, double forward_offset) const;
  // Rates after an impulse (tangential, radial) at `where`, `forward_offset` off the arm's line.
  Eigen::VectorXd rates_after(const ContactLocation& where, double forward_offset, double tangential, double radial) const;

  // Tangential speed of the contact point before impact: omega * radius.
  double contact_speed(const ContactLocation& where) const;

  // Rates of every coordinate after a tangential impulse P on the blade at `where`
  // (P > 0 pushes the blade forward; an object struck by the blade pushes it back).
  Eigen::VectorXd rates_after(const ContactLocation& where, double impulse) const;

  // Absolute angular velocity of the hub and of every link after the rates q'.
  double hub_rate(const Eigen::VectorXd& rates) const;
  double link_rate(const Eigen::VectorXd& rates, std::size_t arm, std::size_t link) const;

  // Kinetic energy of the blade at rates q' (hub, drive line and links).
  double kinetic_energy(const Eigen::VectorXd& rates) const;
  // Rates of the rigid, radially aligned blade turning at omega.
  Eigen::VectorXd rigid_rates() const;

 private:
  static constexpr int kPrescribed = -1;
  struct LinkCoefficients {
    int coordinate = kPrescribed;  // coordinate of the link's own rotation
    Eigen::VectorXd pin;           // a: tangential speed of the inner pin per q'
    Eigen::VectorXd spin;          // b: angular velocity of the link per q'
    // J M^-1 J^T = c0 + 2 s c1 + s^2 c2
    double c0 = 0.0, c1 = 0.0, c2 = 0.0;
    Eigen::VectorXd minv_pin, minv_spin;  // M^-1 a, M^-1 b
  };

  const LinkCoefficients& coefficients(const ContactLocation& where) const;
  // The constructor's steps: number the free bodies (returns each link's coordinate and
  // the count), assemble kinematics and the mass matrix, factor it and derive each body's
  // contact coefficients.
  std::vector<std::vector<int>> number_coordinates(int& n);
  void assemble(const std::vector<std::vector<int>>& coordinate, int n);
  void factor_and_prepare(int n);

  Blade blade_;
  int hub_coordinate_ = kPrescribed;
  Eigen::MatrixXd mass_matrix_;
  Eigen::LDLT<Eigen::MatrixXd> factor_;
  LinkCoefficients hub_;  // the hub treated as a "link" from the spindle: pin = 0, spin = hub
  std::vector<std::vector<LinkCoefficients>> links_;
};

inline constexpr double kInfiniteMass = std::numeric_limits<double>::infinity();

}  // namespace j232::blade
