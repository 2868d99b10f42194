// The drones' energy and flight-time model: what they spend (paper 004 eq. 12, per leg piece),
// and when they must head home.

#include "runtime/runtime_impl.hpp"

namespace swath::fleet::rt {

namespace {

// ∫ f over [a, b] by 5-point Gauss–Legendre: exact for the polynomials of degree ≤ 9 that power
// is within a piece of constant acceleration (level power is cubic in speed, speed linear in t).
template <class F>
double gauss(F f, double a, double b) {
  static constexpr std::array<double, 5> x{0.0, -0.5384693101056831, 0.5384693101056831,
                                           -0.9061798459386640, 0.9061798459386640};
  static constexpr std::array<double, 5> w{0.5688888888888889, 0.4786286704993665,
                                           0.4786286704993665, 0.2369268850561891,
                                           0.2369268850561891};
  const double h = 0.5 * (b - a), m = 0.5 * (a + b);
  double s = 0;
  for (std::size_t i = 0; i < 5; ++i) s += w[i] * f(m + h * x[i]);
  return s * h;
}

}  // namespace

void Runtime::integrate(Drone& d, double t) {
  if (t <= d.t_mark) return;
  const double a = d.t_mark, b = t;
  const DroneSpec& s = d.spec;
  double energy = 0, charge_as = 0;  // J, A·s
  auto constant = [&](double watts, double secs) {
    energy += watts * secs;
    charge_as += energy::battery_current_a(s.battery, watts) * secs;
  };
  switch (d.mode) {
    case Mode::landed:
    case Mode::lost:
      break;
    case Mode::charging:
      break;  // full when charge_end comes
    case Mode::hovering:
    case Mode::acting:
    case Mode::held:
      constant(hover_power_w(s, settings_.wind.velocity3_m_s()), b - a);
      d.idle_s += d.mode == Mode::acting ? 0.0 : b - a;
      break;
    case Mode::flying:
    case Mode::positioning:
    case Mode::returning: {
      const Leg& leg = *d.leg;
      const double la = a - d.leg_start, lb = b - d.leg_start;
      // Vertical part at the climb or descent power.
      const double v0 = std::clamp(la, 0.0, leg.vertical_s()),
                   v1 = std::clamp(lb, 0.0, leg.vertical_s());
      if (v1 > v0) constant(leg.climbing() ? climb_power_w(s) : descent_power_w(s), v1 - v0);
      // Level part, piece by piece (constant acceleration within each), at the airspeed.
      const auto& pieces = leg.pieces();
      const Vec3 wind = settings_.wind.velocity3_m_s();
      const double run = std::hypot(leg.to().x - leg.from().x, leg.to().y - leg.from().y);
      const double ux = run > 0 ? (leg.to().x - leg.from().x) / run : 0.0;
      const double uy = run > 0 ? (leg.to().y - leg.from().y) / run : 0.0;
      for (std::size_t i = 0; i < pieces.size(); ++i) {
        const double p0 = leg.vertical_s() + pieces[i].t0_s;
        const double p1 =
            i + 1 < pieces.size() ? leg.vertical_s() + pieces[i + 1].t0_s : leg.duration_s();
        const double x0 = std::max(la, p0), x1 = std::min(lb, p1);
        if (x1 <= x0) continue;
        auto watts = [&](double tl) {
          const double v = leg.speed_at(tl);
          return energy::level_flight_power_w(s.power.mechanical,
                                              std::hypot(ux * v - wind.x, uy * v - wind.y)) +
                 s.power.payload_w;
        };
        energy += gauss(watts, x0, x1);
        charge_as += gauss(
            [&](double tl) { return energy::battery_current_a(s.battery, watts(tl)); }, x0, x1);
      }
      // Hovering at the end if the interval runs past the leg (it stops there).
      if (lb > leg.duration_s())
        constant(hover_power_w(s, settings_.wind.velocity3_m_s()),
                 lb - std::max(la, leg.duration_s()));
      const Vec3 p0 = leg.position_at(la), p1 = leg.position_at(lb);
      d.distance_m += std::hypot(p1.x - p0.x, p1.y - p0.y);
      break;
    }
  }
  if (d.mode != Mode::landed && d.mode != Mode::lost && d.mode != Mode::charging)
    d.flight_s += b - a;
  d.energy_j += energy;
  d.soc = vehicle::soc_after_charge(s.battery, d.soc, charge_as);
  d.pos = position_at(d, t);
  d.t_mark = t;
}

double Runtime::leave_time(const Drone& d) const {
  if (d.mode != Mode::hovering && d.mode != Mode::held) return kInf;
  return must_leave_at(d);
}

// When the drone must head home from where it is now: its flight time, or its battery drained at
// hover power down to what the way home takes (a hovering drone's exact limit; for one on a leg
// or acting, an estimate from its place at t_mark).
double Runtime::must_leave_at(const Drone& d) const {
  return std::max(leave_from(d, d.pos, d.airborne_since, d.t_mark, 0.0), d.t_mark);
}

// When drone `d`, waiting at `place`, must leave for home: airborne since `airborne_s`, its
// flight time less the way home; or, its charge d.soc draining at hover power from `soc_s`, when
// what is left just takes it home plus `extra_flight_s` of cruise (a flight still to make there).
double Runtime::leave_from(const Drone& d, const Vec3& place, double airborne_s, double soc_s,
                           double extra_flight_s) const {
  const Vec3 home{d.spec.home_m.x, d.spec.home_m.y, d.layer_m};
  const double back_s =
      way_s(d, place, home) + d.layer_m / d.spec.kinematics().descent_m_s + 2 * settings_.tick_s;
  const double cruise_w = cruise_power_w(d.spec, settings_.wind.velocity3_m_s());
  const double need =
      d.spec.battery.reserve_soc +
      vehicle::soc_of_charge(d.spec.battery, energy::battery_current_a(d.spec.battery, cruise_w) *
                                                 (back_s + extra_flight_s));
  return std::min(
      airborne_s + d.spec.max_flight_time_s - back_s,
      soc_s + energy::seconds_to_soc(d.spec.battery, d.soc, need,
                                     hover_power_w(d.spec, settings_.wind.velocity3_m_s())));
}

// The most a drone draws: level flight from still air to cruise into the wind (the power curve's
// ends bound it), climbing, descending.
namespace {
double most_power_w(const DroneSpec& s, const Vec3& wind) {
  return std::max({energy::level_flight_power_w(s.power.mechanical, 0.0) + s.power.payload_w,
                   cruise_power_w(s, wind), hover_power_w(s, wind), climb_power_w(s),
                   descent_power_w(s)});
}
}  // namespace

double Runtime::exhausted_at(const Drone& d) const {
  if (!airborne(d)) return kInf;
  const double most_w = most_power_w(d.spec, settings_.wind.velocity3_m_s());
  return d.t_mark + energy::seconds_to_soc(d.spec.battery, d.soc, 0.0, most_w) - settings_.tick_s;
}

bool Runtime::must_go_home(const Drone& d, double t) const {
  if (d.mode == Mode::landed || d.mode == Mode::charging || d.mode == Mode::lost ||
      d.mode == Mode::returning)
    return false;
  const Vec3 home{d.spec.home_m.x, d.spec.home_m.y, d.layer_m};
  const double back_s = way_s(d, d.pos, home) + d.layer_m / d.spec.kinematics().descent_m_s;
  if (t - d.airborne_since + back_s + 2 * settings_.tick_s >= d.spec.max_flight_time_s) return true;
  const double cruise_w = cruise_power_w(d.spec, settings_.wind.velocity3_m_s());
  const double landing =
      energy::soc_after(d.spec.battery, d.soc, cruise_w, back_s + 2 * settings_.tick_s);
  return !(landing >= d.spec.battery.reserve_soc);
}

}  // namespace swath::fleet::rt
