#include "strike/impulse.hpp"

#include <cmath>

namespace j232::strike {

namespace {
Eigen::Matrix3d skew(const Vec3& r) {
  Eigen::Matrix3d m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

double energy_change(const Eigen::Matrix3d& K, const Vec3& v_rel, const Vec3& P) { return P.dot(v_rel + 0.5 * (K * P)); }

// The impulse for restitution e (Poisson's: the restitution phase's normal impulse is e
// times the compression's): sticking if friction can hold it, else sliding.
ImpulseSolution impulse_for(const Eigen::Matrix3d& K, const Eigen::LDLT<Eigen::Matrix3d>& Kf, const Vec3& v_rel, const Vec3& n, double e,
                            double mu) {
  ImpulseSolution out;
  out.e = e;
  const double vn = v_rel.dot(n);
  // Sticking: compression brings the relative velocity to zero (P_c = -K^-1 v_rel); the
  // restitution impulse then acts only along the normal's relative velocity, K P_r || n,
  // with n . P_r = e n . P_c.
  const Vec3 compression = Kf.solve(Vec3(-v_rel));
  const Vec3 along_normal = Kf.solve(n);
  const Vec3 stick = compression + (e * compression.dot(n) / n.dot(along_normal)) * along_normal;
  const double pn = stick.dot(n);
  const Vec3 pt = stick - pn * n;
  if (pn >= 0 && pt.norm() <= mu * pn) {
    out.impulse = stick;
    out.sticking = true;
  } else {
    // Sliding against the initial slip: P = P_n (n - mu t), compression to zero normal
    // relative velocity and restitution e times it (Poisson's and Newton's rules agree here).
    Vec3 slip = v_rel - vn * n;
    if (slip.norm() > 1e-12)
      slip.normalize();
    else
      slip = pt.norm() > 0 ? Vec3(-pt.normalized()) : Vec3::Zero();
    Vec3 direction = n - mu * slip;
    double along = n.dot(K * direction);
    if (!(along > 0)) direction = n, along = n.dot(K * n);  // friction jams the contact: frictionless instead
    out.impulse = (-(1 + e) * vn / along) * direction;
  }
  out.energy_change = energy_change(K, v_rel, out.impulse);
  return out;
}
}  // namespace

ImpulseSolution solve_impulse(const Eigen::Matrix3d& K, const Vec3& v_rel, const Vec3& n, const blade::Restitution& law, double mu) {
  const Eigen::LDLT<Eigen::Matrix3d> Kf(K);
  const double e0 = law.at(-v_rel.dot(n));
  ImpulseSolution s = impulse_for(K, Kf, v_rel, n, e0, mu);
  const double scale = 1e-12 * std::abs(v_rel.dot(s.impulse)) + 1e-300;
  if (s.energy_change <= scale) return s;
  // Energy created (the slip would have reversed): the largest e that creates none.
  double lo = 0, hi = e0;
  ImpulseSolution best = impulse_for(K, Kf, v_rel, n, 0.0, mu);
  if (best.energy_change > scale) {
    // Perfectly inelastic sticking (the relative velocity brought to zero) never creates
    // energy; if it would pull rather than push, a frictionless plastic impulse.
    best = ImpulseSolution{};
    best.sticking = true;
    const Vec3 plastic = Kf.solve(Vec3(-v_rel));
    best.impulse = plastic.dot(n) > 0 ? plastic : Vec3((-v_rel.dot(n) / n.dot(K * n)) * n);
    best.energy_change = energy_change(K, v_rel, best.impulse);
    return best;
  }
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    const ImpulseSolution m = impulse_for(K, Kf, v_rel, n, mid, mu);
    if (m.energy_change <= scale)
      lo = mid, best = m;
    else
      hi = mid;
  }
  return best;
}

Eigen::Matrix3d inverse_inertia(const projectile::Projectile& nail, const Vec3& axis) {
  const Eigen::Matrix3d along = axis * axis.transpose();
  return (Eigen::Matrix3d::Identity() - along) / nail.transverse_inertia() + along / nail.axial_inertia();
}

Eigen::Matrix3d nail_compliance(const projectile::Projectile& nail, const Eigen::Matrix3d& inv_i, const Vec3& r) {
  const Eigen::Matrix3d R = skew(r);
  return Eigen::Matrix3d::Identity() / nail.mass - R * inv_i * R;
}

StrikeOutcome strike(const Spindle& sp, const Contact& k, const projectile::Projectile& nail, const Vec3& velocity, const Vec3& spin) {
  StrikeOutcome out;
  const Vec3 r = k.point - k.centre;
  const Vec3 v_rel = velocity + spin.cross(r) - sp.velocity_at(k.point);
  out.approach_speed = -v_rel.dot(k.normal);
  out.velocity_after = velocity;
  out.spin_after = spin;
  if (!(out.approach_speed > 0)) return out;
  const Edge& edge = sp.edges[k.edge];
  const auto where = edge.arm ? blade::locate(sp.blade, *edge.arm, k.radius) : std::optional<blade::ContactLocation>(blade::ContactLocation::hub(k.radius));
  if (!where) return out;
  out.approaching = true;
  out.where = *where;

  const Eigen::Matrix3d inv_i = inverse_inertia(nail, k.axis);
  Eigen::Matrix3d K = nail_compliance(nail, inv_i, r);
  // The blade yields in its plane, along its motion and radially (through the offset).
  const Eigen::Matrix2d C = sp.model.planar_compliance(*where, k.forward_offset);
  Eigen::Matrix<double, 3, 2> B;
  B.col(0) = k.forward;
  B.col(1) = k.radial;
  K += B * C * B.transpose();
  out.blade_effective_mass = C(0, 0) > 0 ? 1.0 / C(0, 0) : blade::kInfiniteMass;

  out.solution = solve_impulse(K, v_rel, k.normal, sp.restitution, sp.friction);
  const Vec3& P = out.solution.impulse;
  out.velocity_after = velocity + P / nail.mass;
  out.spin_after = spin + inv_i * r.cross(P);
  out.energy_lost = -out.solution.energy_change;
  return out;
}

}  // namespace j232::strike
