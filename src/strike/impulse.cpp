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

// The direction a slip starting from rest takes when friction cannot hold the contact: u
// grows along a unit û with friction -mu û against it, so du/dp = k_n - mu K_tt û must point
// along +û (Stronge's consistent restart; a ray of the slip's flow): k_n - mu K_tt û = lambda û
// with lambda > 0, that is û = (lambda I + mu K_tt)^-1 k_n with |û| = 1. For K_tt positive
// definite (a principal block of a compliance) |û(lambda)| falls strictly as lambda grows, from
// |K_tt^-1 k_n| / mu > 1 at lambda = 0 (friction cannot hold) to below 1 at lambda = |k_n|: one
// outward ray, found by bisection on lambda.
Eigen::Vector2d restart_direction(const Eigen::Vector2d& kn, const Eigen::Matrix2d& ktt, double mu, const Eigen::Vector2d& stick_rate) {
  const auto along = [&](double lambda) -> Eigen::Vector2d {  // (lambda I + mu K_tt)^-1 k_n, explicit 2x2 inverse
    const double a = lambda + mu * ktt(0, 0), b = mu * ktt(0, 1), c = mu * ktt(1, 0), d = lambda + mu * ktt(1, 1);
    return Eigen::Vector2d(d * kn.x() - b * kn.y(), a * kn.y() - c * kn.x()) / (a * d - b * c);
  };
  double lo = 0, hi = kn.norm();
  if (!(hi > 0 && mu > 0)) {  // no drive along the tangent: any direction is a ray; opposite the sticking rate's
    const double need = stick_rate.norm();
    return need > 0 ? Eigen::Vector2d(-stick_rate / need) : Eigen::Vector2d(1, 0);
  }
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (along(mid).norm() > 1 ? lo : hi) = mid;
  }
  return along(0.5 * (lo + hi)).normalized();
}

ImpulseSolution solve_impulse(const Eigen::Matrix3d& K, const Vec3& v_rel, const Vec3& n, const blade::Restitution& law, double mu,
                              RestitutionLaw form) {
  return form == RestitutionLaw::Energetic ? solve_impulse_energetic(K, v_rel, n, law.at(-v_rel.dot(n)), mu)
                                           : solve_impulse_poisson(K, v_rel, n, law, mu);
}

// The same law where the normal and tangential motions do not couple (k_n = 0) and the
// tangential compliance is isotropic (K_tt = c I): a ball, or a rod struck end-on along its
// axis. The slip then keeps its direction and shrinks linearly, |u| - mu c p, while the
// normal velocity grows as knn p: the normal impulse is Poisson's and Stronge's alike,
// (1 + e) times the compression's, and the slip halts (and the contact sticks, friction
// needing nothing to hold it) at p = |u| / (mu c) if that comes first. Exact, in closed form.
ImpulseSolution decoupled_impulse(const Vec3& v_rel, const Vec3& n, double knn, double c, double e, double mu) {
  ImpulseSolution out;
  out.e = e;
  const double vn = v_rel.dot(n);
  if (!(vn < 0)) return out;  // (not approaching: no impulse)
  const Vec3 slip = v_rel - vn * n;
  const double p_total = (1 + e) * -vn / knn, speed = slip.norm();
  Vec3 tangential = Vec3::Zero();
  out.sticking = mu > 0 && speed == 0;  // (no slip: friction holds it, needing nothing)
  if (mu > 0 && speed > 0) {
    const double p_halt = speed / (mu * c);
    out.sticking = p_halt <= p_total;
    tangential = -(out.sticking ? speed / c : mu * p_total) / speed * slip;
  }
  out.impulse = p_total * n + tangential;
  return out;
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
// Uncoupled and isotropic (a ball's contacts), it is decoupled_impulse's closed form.
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
  // Uncoupled and isotropic to round-off (a ball's contacts): the closed form.
  {
    const double c = 0.5 * (ktt(0, 0) + ktt(1, 1)), tol = 1e-13 * (knn + c);
    if (std::abs(kn.x()) <= tol && std::abs(kn.y()) <= tol && std::abs(ktt(0, 0) - ktt(1, 1)) <= tol && std::abs(ktt(0, 1)) <= tol &&
        std::abs(ktt(1, 0)) <= tol && knn > 0 && c > 0) {
      out = decoupled_impulse(v_rel, n, knn, c, e, mu);
      out.energy_change = energy_change(K, v_rel, out.impulse);
      return out;
    }
  }
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
  // A slip that starts from rest (friction cannot hold it) starts along a direction it keeps:
  // found once, when first needed.
  bool restart_found = false;
  Eigen::Vector2d restart = Eigen::Vector2d::Zero();
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
    if (!restart_found) restart = restart_direction(kn, ktt, mu, stick_rate), restart_found = true;
    return Eigen::Vector2d(-mu * restart);
  };
  // A slip taken as stopped (within a stop's tolerance of zero) is brought to zero by the
  // tangential impulse that does it, K_tt^-1 times it, with the normal velocity that brings,
  // so the tracked velocities stay those of the impulse so far: a remainder merely dropped
  // would leave friction acting on a slip that is not there, which can create energy.
  const auto settle = [&]() {
    const Eigen::Vector2d stop = -(ktt_inv * u);
    pt += stop, vn += kn.dot(stop), u.setZero();
  };
  constexpr double kSlipTurn = 0.005;  // rad per step
  const double p_scale = -vn / knn;   // the frictionless compression
  // A slipping stretch far from every event (the slip halting or passing zero, compression's
  // end, the restitution's work reached): one classical Runge-Kutta step of the whole state
  // (slip, normal velocity, tangential impulse, work) along p, turning the slip by at most
  // kFastTurn; a step that would come near an event is left to the careful step below, which
  // finds events exactly. Returns false when it did not step.
  constexpr double kFastTurn = 0.05;    // rad per step
  constexpr double kFastShrink = 0.25;  // of the slip's size per step
  constexpr double kFarPass = 0.25;    // of the slip's size: a pass by zero no nearer than this is the fast steps' own
  constexpr double kFastStiff = 0.5;    // the direction's growth or decay exponent per step (RK4 is then within 4e-4 of the exponential)
  // A slip within 1e-5 of the approach speed of zero has stopped (as a halt found within
  // that is): friction then holds the contact or the slip restarts along its own direction.
  const double u_stopped = 1e-5 * approach;
  enum class Fast { No, Stepped, Compressed, Done };
  // How fast the rates can move the slip, per unit p: |k_n| + mu |K_tt| (the scale of the
  // ray test's round-off and of the stiff-and-small stop).
  const double rate_bound = kn.norm() + mu * ktt.norm();
  const auto fast_step = [&]() {
    const double speed = u.norm();
    struct Rate {
      Eigen::Vector2d f, du;
      double dvn;
    };
    const auto at = [&](const Eigen::Vector2d& slip) {
      Rate r;
      r.f = -mu * slip / slip.norm();
      r.du = kn + ktt * r.f;
      r.dvn = knn + kn.dot(r.f);
      return r;
    };
    // The step: turning the slip's direction by at most kFastTurn, nor changing its size by
    // more than kFastShrink of itself (its direction turns faster as it shrinks).
    const auto step_limit = [&](const Rate& k, bool on_ray) {
      const double across = on_ray ? 0.0 : std::abs(k.du.x() * u.y() - k.du.y() * u.x()) / speed;
      const double du_size = k.du.norm();
      return std::min({across > 0 ? kFastTurn * speed / across : HUGE_VAL, du_size > 0 && !on_ray ? kFastShrink * speed / du_size : HUGE_VAL,
                       4 * p_scale * (1 + e)});
    };
    Rate k1 = at(u);
    double limit = step_limit(k1, false);
    bool on_ray = false;
    // Near a ray of the slip's flow (a direction it keeps: du/dp along u) that attracts it, the
    // direction relaxes onto the ray over a span of p proportional to the slip's size: stiff
    // when that span is shorter than the step, where explicit steps would swing it from side
    // to side. There the direction is taken onto the ray (Newton's method on the turn rate),
    // which it then keeps exactly: the slip's size alone changes, linearly in p.
    {
      const auto turn_rate = [&](double a) {  // û x du/dp at direction a
        const Eigen::Vector2d d(std::cos(a), std::sin(a)), g = kn - mu * (ktt * d);
        return d.x() * g.y() - d.y() * g.x();
      };
      // At the present direction û (g = du/dp there): h = û x g, and its rate with the
      // direction's angle, dh/da = -û.g + û x (-mu K_tt û_perp), û_perp = û turned a right angle.
      const Eigen::Vector2d d = u / speed, d_perp(-d.y(), d.x()), g = k1.du, dg = -mu * (ktt * d_perp);
      const double h = d.x() * g.y() - d.y() * g.x();
      const double slope = -d.dot(g) + (d.x() * dg.y() - d.y() * dg.x());
      // (Only where what the transient's friction would have done differently, mu times the
      // angle times the span, is below 1e-6 of the impulse's scale.)
      const double angle = slope < 0 ? std::abs(h / slope) : HUGE_VAL, span = slope < 0 ? speed / -slope : HUGE_VAL;
      if (angle < kFastTurn && span < limit && mu * angle * span < 1e-6 * p_scale) {
        const double a = std::atan2(u.y(), u.x());
        double ray = a - h / slope;
        for (int k = 0; k < 3; ++k) ray -= turn_rate(ray) / slope;
        // (A ray found near, and truly one: else the direction is left as it is.)
        if (std::abs(ray - a) < kFastTurn && std::abs(turn_rate(ray)) <= 1e-9 * std::abs(h) + 1e-12 * rate_bound) {
          // The transient's friction, across the ray, is what turned the slip onto it: the
          // tangential impulse that makes that turn, K_tt^-1 times it, with the normal
          // velocity it brings (below 1e-6 of the impulse's scale, by the condition above).
          const Eigen::Vector2d onto = speed * Eigen::Vector2d(std::cos(ray), std::sin(ray));
          const Eigen::Vector2d turn_impulse = ktt_inv * (onto - u);
          pt += turn_impulse, vn += kn.dot(turn_impulse), u = onto;
          k1 = at(u);
          limit = step_limit(k1, true);
          on_ray = true;
        }
      }
      // Off a ray, a departure from the present direction grows or decays as exp(slope p / |u|):
      // the step keeps that exponent within kFastStiff (near a repelling ray the turn rate alone
      // would allow a step over which the direction runs away).
      if (!on_ray && slope != 0) limit = std::min(limit, kFastStiff * speed / std::abs(slope));
    }
    // The slip's closest approach to zero as the first rate foresees it: a halt (as the careful
    // step judges one) or a pass close by zero is the careful step's; so is one within reach
    // that comes within a quarter of the slip's size of zero (there its direction swings). A
    // pass farther out is a slip whose size has a broad minimum while its direction turns
    // slowly: the steps' own limits on the turn and the size hold its error (the careful steps
    // took it at 0.005 rad a step: 2 % of the flight's instructions on the shipped decks).
    const double d2 = k1.du.squaredNorm();
    if (d2 > 0 && -u.dot(k1.du) > 0) {
      const double close = -u.dot(k1.du) / d2, nearest = (u + close * k1.du).norm();
      if (nearest <= std::min(1e-3 * speed + 1e-5 * approach, 0.5 * speed)) return Fast::No;
      if (close < 2 * limit && nearest < kFarPass * speed) return Fast::No;
    }
    // The phase's end (compression's, or the restitution's work reached) as the first rate
    // foresees it: within reach, the step is aimed at it and brought onto it by Newton's method
    // on the step's length (the end's residual and its rate are the step's own).
    double end = HUGE_VAL;
    const double target = e * e * -work_compression - work_restitution;  // the restitution's work left
    if (compressing) {
      if (!(k1.dvn > 0)) return Fast::No;
      end = -vn / k1.dvn;
    } else {
      const double disc = vn * vn + 2 * k1.dvn * target;
      if (!(target > 0 && disc > 0)) return Fast::No;
      end = 2 * target / (vn + std::sqrt(disc));
    }
    const bool aimed = end <= limit;
    double dp = aimed ? end : limit;
    for (int newton = 0; newton < 6; ++newton) {
      // On a ray the rates are constant (the slip keeps its direction, f with it): the step is
      // exact with them. Evaluating stages there instead would be unstable: an attracting
      // ray's pull is stiff over such a step, and explicit stages would amplify round-off.
      const Rate k2 = on_ray ? k1 : at(u + 0.5 * dp * k1.du);
      const Rate k3 = on_ray ? k1 : at(u + 0.5 * dp * k2.du);
      const Rate k4 = on_ray ? k1 : at(u + dp * k3.du);
      const Eigen::Vector2d u_next = u + (dp / 6) * (k1.du + 2 * k2.du + 2 * k3.du + k4.du);
      const double vn_next = vn + (dp / 6) * (k1.dvn + 2 * k2.dvn + 2 * k3.dvn + k4.dvn);
      // The work, v_n integrated along p: Simpson's rule on v_n at the step's start, middle and
      // end, v_n at the middle from the quadratic through the stages' rates (k1 at the start,
      // k2 and k3 at the middle, k4 at the end) integrated over the first half.
      const double vn_mid = vn + (dp / 24) * (5 * k1.dvn + 4 * k2.dvn + 4 * k3.dvn - k4.dvn);
      const double w = (dp / 6) * (vn + 4 * vn_mid + vn_next);
      // The slip must stay clear of zero, and the normal approach must not jam.
      if (!(u_next.dot(u) > 0 && u_next.norm() > 0.25 * speed)) return Fast::No;
      if (compressing && !(k2.dvn > 0 && k3.dvn > 0 && k4.dvn > 0)) return Fast::No;
      const double residual = compressing ? vn_next : w - target;  // the phase ends at zero
      const double rate_end = compressing ? k4.dvn : vn_next;
      const double scale = compressing ? approach : std::max(target, 1e-300);
      if (!aimed) {
        if (!(residual < 0)) return Fast::No;  // the end came sooner than foreseen
      } else if (std::abs(residual) > 1e-12 * scale) {
        if (!(rate_end > 0)) return Fast::No;
        const double next = dp - residual / rate_end;
        if (!(next > 0 && next <= limit)) return Fast::No;
        dp = next;
        continue;
      }
      (compressing ? work_compression : work_restitution) += w;
      p += dp, pt += (dp / 6) * (k1.f + 2 * k2.f + 2 * k3.f + k4.f), u = u_next, vn = vn_next;
      sticking = false;
      if (!aimed) return Fast::Stepped;
      if (compressing) {
        vn = std::max(vn, 0.0), compressing = false;
        return e > 0 ? Fast::Compressed : Fast::Done;
      }
      return Fast::Done;
    }
    return Fast::No;
  };
  // A slip so small that its direction swings through a radian within 1e-3 of the impulse's
  // scale (the rates move u by at most |k_n| + mu |K_tt| per unit p), and whose stop costs
  // an impulse below 1e-4 of that scale, is at rest as far as Coulomb's law can tell: its
  // direction would relax onto the outward ray (or the contact stick) in a transient that
  // explicit steps resolve only in tens of thousands of steps. Settled, and then stuck or
  // restarted along the ray, it ends where that transient would, to that 1e-4.
  const auto stiff_and_small = [&]() {
    return u.norm() <= 1e-3 * p_scale * rate_bound && (ktt_inv * u).norm() <= 1e-4 * p_scale;
  };
  // (Each step ends at an event or turns the slip by a set angle: a few tens of steps a
  // contact, 6 on average over the shipped scenarios; beyond the cap, the legacy law.)
  constexpr int kStepCap = 100000;
  int steps = 0;
  for (; steps < kStepCap; ++steps) {
    if (mu > 0 && u.norm() > u_tiny && (u.norm() <= u_stopped || stiff_and_small())) {
      settle();
      if (compressing && vn >= 0) {  // the stop's normal velocity ended the compression
        vn = std::max(vn, 0.0), compressing = false;
        if (!(e > 0)) break;
      }
    }
    if (mu > 0 && u.norm() > u_tiny) {
      const Fast fast = fast_step();
      if (fast == Fast::Done) break;
      if (fast != Fast::No) continue;
    }
    bool holds;
    Eigen::Vector2d f = rate(u, holds);
    // Friction that would keep the normal velocity from ever growing (Painleve's jam, in either
    // phase: the approach would never end, or the restitution's work never be reached):
    // frictionless instead.
    const auto jams = [&](const Eigen::Vector2d& rate_f) { return !(knn + kn.dot(rate_f) > 0); };
    if (jams(f)) f.setZero(), holds = false;
    double dp = 4 * p_scale * (1 + e);
    bool halts = false;
    if (mu > 0 && !holds && u.norm() > u_tiny) {
      // The slip halting within the step: the step ends there, u nil.
      const auto halting = [&](const Eigen::Vector2d& rate_f) {
        const Eigen::Vector2d du = kn + ktt * rate_f;
        const double d2 = du.squaredNorm();
        if (!(d2 > 0)) return;
        const double s = -u.dot(du) / d2;
        if (!(s > 0 && s <= dp)) return;
        // (Passing within 1e-5 of the approach speed of a stop is stopping: the slip's last
        // turn there moves the impulse by less than that.)
        if ((u + s * du).norm() <= std::min(1e-3 * u.norm() + 1e-5 * approach, 0.5 * u.norm())) {
          dp = s, halts = true;
        } else if (s > 1e-6 * dp) {
          // Never past the slip's closest approach to zero: beyond it the slip would grow again
          // against a friction still held along its old direction, which would do positive work.
          // (From the closest approach itself the turn limit bounds the step.)
          dp = s;
        }
      };
      // A step that turns the slip's direction by at most kSlipTurn, with f at its midpoint.
      const Eigen::Vector2d du = kn + ktt * f;
      const double across = std::abs(du.x() * u.y() - du.y() * u.x()) / u.norm();
      if (across > 0) dp = std::min(dp, kSlipTurn * u.norm() / across);
      halting(f);
      bool mid_holds;
      const Eigen::Vector2d mid = rate(u + 0.5 * dp * du, mid_holds);
      if (!mid_holds && mid.dot(f) > 0 && !jams(mid)) {
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
    p += dp, pt += f * dp, u += du * dp, vn = vn_next;
    sticking = holds;
    if (holds || halts || (u.norm() <= u_tiny && !last)) settle();
    if (compressing && vn >= -1e-15 * approach) {
      vn = std::max(vn, 0.0), compressing = false;
      if (!(e > 0)) break;
    }
    if (!compressing && (last || e * e * -work_compression - work_restitution <= 0)) break;
  }
  if (steps >= kStepCap) {
    ImpulseSolution fallback = solve_impulse_poisson(K, v_rel, n, blade::Restitution::constant(e), mu);
    fallback.step_cap_fallback = true;
    return fallback;
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
  // The blade yielded during the impact (K_blade) but is driven, and the model turns it
  // rigidly again at once: where the body's point still approaches the rigid blade's (a
  // heavy stone against a pivoted blade), the recovering blade carries it on until it no
  // longer does, a plastic push against the unyielding blade (an assumption: the motor's
  // work, the link's recovery taken as instant). The contact search would otherwise find the
  // same touch again at the same instant (while it approaches faster than 1e-6 m/s, its
  // threshold), impact after impact (a 1.3 kg cobble: a dozen at every contact, until
  // [run] max_strikes cut it off); frictionless at a constant e, their sum is this push.
  const Vec3 v_left = out.velocity_after + out.spin_after.cross(r) - sp.velocity_at(k.point);
  if (v_left.dot(k.normal) < -kSameInstantApproach) {
    const ImpulseSolution push = solve_impulse(nail_compliance(nail, inv_i, r), v_left, k.normal, blade::Restitution::constant(0.0),
                                               sp.friction, sp.law);
    out.push = push.impulse;
    out.push_velocity = out.push / nail.mass;
    out.push_spin = inv_i * r.cross(out.push);
  }
  return out;
}

}  // namespace j232::strike
