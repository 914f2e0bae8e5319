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

ImpulseSolution solve_impulse(const Eigen::Matrix3d& K, const Vec3& v_rel, const Vec3& n, const blade::Restitution& law, double mu,
                              RestitutionLaw form) {
  return form == RestitutionLaw::Energetic ? solve_impulse_energetic(K, v_rel, n, law.at(-v_rel.dot(n)), mu)
                                           : solve_impulse_poisson(K, v_rel, n, law, mu);
}

// Stronge's energetic restitution with Coulomb friction, integrated along the normal impulse
// p (docs/model.md §5.1c). With P = p n + T f-integrated, the relative velocity moves as
// dv/dp = K (n + T f), f the tangential impulse per unit normal impulse: -mu u/|u| while the
// contact slips (u the tangential relative velocity), the sticking value -K_tt^-1 K_tn while
// friction can hold it (|f| <= mu), else mu along that (the slip starting opposite). Steps
// end exactly where compression ends (v_n = 0), where the slip halts (u = 0), and where the
// restitution phase's normal work reaches e^2 times the compression's (Stronge's e*); within a
// step f is held at its midpoint value, and a step turns the slip's direction by at most
// kSlipTurn. Frictionless, or sticking throughout, this is Poisson's and Newton's impulse.
ImpulseSolution solve_impulse_energetic(const Eigen::Matrix3d& K, const Vec3& v_rel, const Vec3& n, double e, double mu) {
  ImpulseSolution out;
  out.e = e;
  double vn = v_rel.dot(n);
  if (!(vn < 0)) return out;
  const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  const Vec3 Kn = K * n, Kt1 = K * t1, Kt2 = K * t2;
  const double knn = n.dot(Kn);
  const Eigen::Vector2d kn(t1.dot(Kn), t2.dot(Kn));
  Eigen::Matrix2d ktt;
  ktt << t1.dot(Kt1), t1.dot(Kt2), t2.dot(Kt1), t2.dot(Kt2);
  const double det = ktt(0, 0) * ktt(1, 1) - ktt(0, 1) * ktt(1, 0);
  Eigen::Matrix2d ktt_inv;
  ktt_inv << ktt(1, 1), -ktt(0, 1), -ktt(1, 0), ktt(0, 0);
  ktt_inv /= det;
  const Eigen::Vector2d stick_rate = -(ktt_inv * kn);  // the tangential impulse rate that keeps u = 0
  Eigen::Vector2d u(t1.dot(v_rel), t2.dot(v_rel)), pt = Eigen::Vector2d::Zero();
  const double u_tiny = 1e-12 * (v_rel.norm() + 1e-300), approach = -vn;
  double p = 0, work_compression = 0, work_restitution = 0;
  bool compressing = true, sticking = false;
  // The tangential rate at slip u (sticking when u is nil and friction can hold it).
  const auto rate = [&](const Eigen::Vector2d& slip, bool& holds) {
    holds = false;
    if (mu <= 0) return Eigen::Vector2d(Eigen::Vector2d::Zero());
    const double speed = slip.norm();
    if (speed > u_tiny) return Eigen::Vector2d(-mu * slip / speed);
    const double need = stick_rate.norm();
    if (det > 0 && need <= mu * (1 + 1e-12)) {
      holds = true;
      return stick_rate;
    }
    return Eigen::Vector2d(need > 0 ? Eigen::Vector2d(mu * stick_rate / need) : Eigen::Vector2d::Zero());
  };
  constexpr double kSlipTurn = 0.005;  // rad per step
  const double p_scale = -vn / knn;   // the frictionless compression
  for (int it = 0; it < 100000; ++it) {
    bool holds;
    Eigen::Vector2d f = rate(u, holds);
    // Friction that would stop the normal approach from ever ending (a jam): frictionless.
    if (compressing && !(knn + kn.dot(f) > 0)) f.setZero(), holds = false;
    double dp = 4 * p_scale * (1 + e);
    bool halts = false;
    if (!holds && u.norm() > u_tiny) {
      // The slip halting within the step: the step ends there, u nil.
      const auto halting = [&](const Eigen::Vector2d& rate_f) {
        const Eigen::Vector2d du = kn + ktt * rate_f;
        const double d2 = du.squaredNorm();
        if (!(d2 > 0)) return;
        const double s = -u.dot(du) / d2;
        // (Passing within 1e-5 of the approach speed of a stop is stopping: the slip's last
        // turn there moves the impulse by less than that.)
        if (s > 0 && s <= dp && (u + s * du).norm() <= std::min(1e-3 * u.norm() + 1e-5 * approach, 0.5 * u.norm())) dp = s, halts = true;
      };
      // A step that turns the slip's direction by at most kSlipTurn, with f at its midpoint.
      const Eigen::Vector2d du = kn + ktt * f;
      const double across = std::abs(du.x() * u.y() - du.y() * u.x()) / u.norm();
      if (across > 0) dp = std::min(dp, kSlipTurn * u.norm() / across);
      halting(f);
      bool mid_holds;
      const Eigen::Vector2d mid = rate(u + 0.5 * dp * du, mid_holds);
      if (!mid_holds && mid.dot(f) > 0) {
        f = mid;
        halts = false;
        halting(f);
      }
    }
    const double dvn = knn + kn.dot(f);
    bool last = false;
    if (compressing) {
      if (vn + dvn * dp >= 0) dp = -vn / dvn, halts = false;  // the end of compression (before the slip halts)
    } else {
      // The restitution phase's work: v_n dp + dvn dp^2 / 2 reaching what is left.
      const double left = e * e * -work_compression - work_restitution;
      const double step_work = vn * dp + 0.5 * dvn * dp * dp;
      if (step_work >= left) {
        const double disc = vn * vn + 2 * dvn * left;
        dp = disc > 0 ? 2 * left / (vn + std::sqrt(disc)) : dp;
        last = true, halts = false;
      }
    }
    const double w = vn * dp + 0.5 * dvn * dp * dp;
    (compressing ? work_compression : work_restitution) += w;
    const Eigen::Vector2d du = kn + ktt * f;
    const double vn_next = vn + dvn * dp;
    p += dp, pt += f * dp, u += du * dp;
    sticking = holds;
    if (holds || halts) u.setZero();
    if (compressing && vn_next >= -1e-15 * std::abs(v_rel.dot(n))) {
      vn = 0, compressing = false;
      if (!(e > 0)) break;
    } else {
      vn = vn_next;
    }
    if (!compressing && (last || e * e * -work_compression - work_restitution <= 0)) break;
    if (u.norm() <= u_tiny) u.setZero();
  }
  out.impulse = p * n + pt.x() * t1 + pt.y() * t2;
  out.sticking = sticking;
  out.energy_change = energy_change(K, v_rel, out.impulse);
  return out;
}

ImpulseSolution solve_impulse_poisson(const Eigen::Matrix3d& K, const Vec3& v_rel, const Vec3& n, const blade::Restitution& law, double mu) {
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

const char* restitution_law_name(RestitutionLaw l) { return l == RestitutionLaw::Energetic ? "energetic" : "poisson"; }

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

  out.solution = solve_impulse(K, v_rel, k.normal, sp.restitution, sp.friction, sp.law);
  const Vec3& P = out.solution.impulse;
  out.velocity_after = velocity + P / nail.mass;
  out.spin_after = spin + inv_i * r.cross(P);
  out.energy_lost = -out.solution.energy_change;
  return out;
}

}  // namespace j232::strike
