#include "swath/vehicle/multirotor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swath::vehicle {
namespace {

constexpr Vec3 kUp{0, 0, 1};
constexpr std::size_t kStateSize = 13 + kMaxRotors;
using StateVector = std::array<double, kStateSize>;

StateVector pack(const MultirotorState& s) {
  StateVector x{};
  x[0] = s.position_m.x, x[1] = s.position_m.y, x[2] = s.position_m.z;
  x[3] = s.velocity_m_s.x, x[4] = s.velocity_m_s.y, x[5] = s.velocity_m_s.z;
  x[6] = s.attitude.w, x[7] = s.attitude.x, x[8] = s.attitude.y, x[9] = s.attitude.z;
  x[10] = s.rate_rad_s.x, x[11] = s.rate_rad_s.y, x[12] = s.rate_rad_s.z;
  for (std::size_t i = 0; i < kMaxRotors; ++i) x[13 + i] = s.rotor_rad_s[i];
  return x;
}

MultirotorState unpack(const StateVector& x) {
  MultirotorState s;
  s.position_m = {x[0], x[1], x[2]};
  s.velocity_m_s = {x[3], x[4], x[5]};
  // Unnormalised within RK4's stages: rotate() below assumes unit length, so normalise here.
  s.attitude = normalized({x[6], x[7], x[8], x[9]});
  s.rate_rad_s = {x[10], x[11], x[12]};
  for (std::size_t i = 0; i < kMaxRotors; ++i) s.rotor_rad_s[i] = x[13 + i];
  return s;
}

// One step of classic RK4 with the arithmetic of odeint's runge_kutta4 (its generic explicit RK
// with the classic tableau, stepping in place), term by term and in its order, so that flights
// keep their bits; but over the first `used` entries only (13 + the rotors: the others have no
// derivative) and without odeint's generic algebra, which cost as much as the model itself.
template <typename System>
void rk4_step(System& system, StateVector& x, double dt, std::size_t used) {
  // odeint's coefficients times dt: a = (1/2), (0, 1/2), (0, 0, 1); b = (1/6, 1/3, 1/3, 1/6).
  const double half = 0.5 * dt, zero = 0.0 * dt, one = 1.0 * dt;
  const double sixth = (1.0 / 6.0) * dt, third = (1.0 / 3.0) * dt;
  StateVector k1{}, k2{}, k3{}, k4{}, tmp = x;
  system(x, k1, 0.0);
  for (std::size_t i = 0; i < used; ++i) tmp[i] = 1.0 * x[i] + half * k1[i];
  system(tmp, k2, 0.0);
  for (std::size_t i = 0; i < used; ++i) tmp[i] = 1.0 * x[i] + zero * k1[i] + half * k2[i];
  system(tmp, k3, 0.0);
  for (std::size_t i = 0; i < used; ++i)
    tmp[i] = 1.0 * x[i] + zero * k1[i] + zero * k2[i] + one * k3[i];
  system(tmp, k4, 0.0);
  for (std::size_t i = 0; i < used; ++i)
    x[i] = 1.0 * x[i] + sixth * k1[i] + third * k2[i] + third * k3[i] + sixth * k4[i];
}

double clamp_command(const Propulsion& p, double command_rad_s) {
  return std::clamp(command_rad_s, 0.0, p.max_speed_rad_s);
}

}  // namespace

std::vector<Rotor> rotor_layout(RotorLayout layout, double arm_m, int first_spin,
                                double coaxial_lower_efficiency) {
  std::vector<Rotor> rotors;
  const double deg = std::numbers::pi / 180;
  auto at = [&](double angle_deg, double z_m) {
    return Vec3{arm_m * std::cos(angle_deg * deg), arm_m * std::sin(angle_deg * deg), z_m};
  };
  switch (layout) {
    case RotorLayout::quad_x:
    case RotorLayout::hexa_x: {
      const int n = layout == RotorLayout::quad_x ? 4 : 6;
      const double step = 360.0 / n;
      for (int k = 0; k < n; ++k)
        rotors.push_back({at(step / 2 + k * step, 0.0), k % 2 == 0 ? first_spin : -first_spin});
      break;
    }
    case RotorLayout::y6:
      for (const double angle : {60.0, 180.0, 300.0}) {
        rotors.push_back({at(angle, 0.05), first_spin, 1.0});
        rotors.push_back({at(angle, -0.05), -first_spin, coaxial_lower_efficiency});
      }
      break;
  }
  return rotors;
}

double Propulsion::motor_constant() const {
  return 60.0 / (2 * std::numbers::pi * kv_rpm_per_v);
}

double motor_current_at_torque_a(const Propulsion& p, double drag_torque_nm, double accel_rad_s2) {
  return (drag_torque_nm + p.rotor_inertia_kg_m2 * accel_rad_s2) / p.motor_constant() +
         p.no_load_current_a;
}

double motor_power_at_torque_w(const Propulsion& p, double speed_rad_s, double drag_torque_nm,
                               double accel_rad_s2) {
  const double i = motor_current_at_torque_a(p, drag_torque_nm, accel_rad_s2);
  return std::max((p.resistance_ohm * i + p.motor_constant() * speed_rad_s) * i, 0.0) /
         p.esc_efficiency;
}

double motor_current_a(const Propulsion& p, double speed_rad_s, double accel_rad_s2) {
  return motor_current_at_torque_a(p, p.torque_coeff_nm_s2 * speed_rad_s * speed_rad_s,
                                   accel_rad_s2);
}

double motor_power_w(const Propulsion& p, double speed_rad_s, double accel_rad_s2) {
  return motor_power_at_torque_w(p, speed_rad_s, p.torque_coeff_nm_s2 * speed_rad_s * speed_rad_s,
                                 accel_rad_s2);
}

double induced_velocity_m_s(double v_h, double edgewise_m_s, double axial_m_s) {
  if (!(v_h > 0)) return 0.0;
  const double uz = std::max(axial_m_s, -v_h);
  const double uxy2 = edgewise_m_s * edgewise_m_s;
  // g(v) = v √(u_xy² + (v + u_z)²) − v_h²: g(0) < 0 ≤ g(v_h + |u_z|), so a root lies between;
  // Newton from v_h, kept inside the bracket (bisection when a step leaves it).
  double lo = 0.0, hi = v_h + std::abs(uz), v = v_h;
  for (int k = 0; k < 60; ++k) {
    const double root = std::sqrt(uxy2 + (v + uz) * (v + uz));
    const double gv = v * root - v_h * v_h;
    if (std::abs(gv) <= 1e-13 * v_h * v_h) break;
    (gv < 0 ? lo : hi) = v;
    const double slope = root > 0 ? root + v * (v + uz) / root : 0.0;
    double next = slope > 0 ? v - gv / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    v = next;
  }
  return v;
}

double induced_power_share(const Propulsion& p, double efficiency, double rho) {
  const double area = std::numbers::pi * p.diameter_m * p.diameter_m / 4;
  const double kt = efficiency * p.thrust_coeff_n_s2;
  return p.induced_power_factor * kt * std::sqrt(kt) /
         (p.torque_coeff_nm_s2 * std::sqrt(2 * rho * area));
}

double drag_torque_factor(const Propulsion& p, double efficiency, double rho, double omega,
                          const Vec3& air) {
  if (!p.translational_lift || !(omega > 0)) return 1.0;
  const double area = std::numbers::pi * p.diameter_m * p.diameter_m / 4;
  const double thrust = efficiency * p.thrust_coeff_n_s2 * omega * omega;
  const double v_h = std::sqrt(thrust / (2 * rho * area));
  const double axial = std::max(air.z, -v_h);
  const double v_i = induced_velocity_m_s(v_h, std::sqrt(air.x * air.x + air.y * air.y), axial);
  // k_Q Ω² + κ T (v_i + u_z − v_h) / Ω = k_Q Ω² (1 + share (v_i + u_z − v_h) / v_h).
  return std::max(1.0 + induced_power_share(p, efficiency, rho) * (v_i + axial - v_h) / v_h, 0.0);
}

double rotor_drag_torque_nm(const Propulsion& p, double efficiency, double rho, double omega,
                            const Vec3& air) {
  return p.torque_coeff_nm_s2 * omega * omega * drag_torque_factor(p, efficiency, rho, omega, air);
}

std::array<double, kMaxRotors> drag_torque_factors(const Airframe& a, const MultirotorState& s,
                                                   const Vec3& wind_m_s) {
  std::array<double, kMaxRotors> factors;
  factors.fill(1.0);
  if (!a.propulsion.translational_lift) return factors;
  const Vec3 air = rotate_inverse(s.attitude, s.velocity_m_s - wind_m_s);
  for (std::size_t i = 0; i < a.rotors.size(); ++i)
    factors[i] = drag_torque_factor(a.propulsion, a.rotors[i].efficiency, a.frame.air_density_kg_m3,
                                    s.rotor_rad_s[i], air);
  return factors;
}

namespace {

// The pieces of applied_wrench shared with applied_force_world_n and motors_power_w: one
// expression each, so the three agree to the bit.
Vec3 air_in_body(const MultirotorState& s, const MultirotorInputs& in) {
  return rotate_inverse(s.attitude, s.velocity_m_s - in.wind_m_s);
}

Vec3 body_drag_n(const Frame& f, const Vec3& air) {
  const Vec3 abs_air{std::abs(air.x), std::abs(air.y), std::abs(air.z)};
  return -1.0 * hadamard(f.drag_linear_n_per_m_s, air) -
         0.5 * f.air_density_kg_m3 * hadamard(f.drag_cda_m2, hadamard(abs_air, air));
}

// A rotor's thrust, N, along body z.
double rotor_thrust_n(const Propulsion& p, const Rotor& r, double omega) {
  return r.efficiency * p.thrust_coeff_n_s2 * omega * omega;
}

// The rotors' thrust (0, 0, Σ T) and the body's drag, body axes.
Vec3 body_force_n(const Frame& f, const Vec3& air, double thrust_z) {
  const Vec3 drag = body_drag_n(f, air);
  return {0.0 + drag.x, 0.0 + drag.y, thrust_z + drag.z};
}

double rotor_accel_rad_s2(const Propulsion& p, double command_rad_s, double omega) {
  return (clamp_command(p, command_rad_s) - omega) / p.time_constant_s;
}

double held_drag_torque_nm(const Propulsion& p, double omega, double factor) {
  return p.torque_coeff_nm_s2 * omega * omega * factor;
}

}  // namespace

Wrench applied_wrench(const Airframe& a, const MultirotorState& s, const MultirotorInputs& in) {
  const Propulsion& p = a.propulsion;
  const Frame& f = a.frame;
  Wrench w;
  // Air relative to the body, in body axes: drag and flapping depend on it.
  const Vec3 air = air_in_body(s, in);
  // Every thrust and spin axis is body z (e3), so the products with e3 are written out: only
  // their non-zero components are computed (the zeros would only add signed zeros).
  double thrust_z = 0, momentum_z = 0;  // Σ T_i; Σ s_i J_r Ω_i
  Vec3 torque = in.torque_noise_nm;
  for (std::size_t i = 0; i < a.rotors.size(); ++i) {
    const Rotor& r = a.rotors[i];
    const double omega = s.rotor_rad_s[i];
    const double accel = rotor_accel_rad_s2(p, in.command_rad_s[i], omega);
    w.rotor_accel_rad_s2[i] = accel;
    const double t = rotor_thrust_n(p, r, omega);
    thrust_z += t;
    torque.x += r.position_m.y * t;  // r × (0, 0, T)
    torque.y -= r.position_m.x * t;
    // The rotor's drag torque and the reaction to spinning it up, opposite to its spin.
    const double drag_torque = held_drag_torque_nm(p, omega, in.drag_torque_factor[i]);
    w.rotor_drag_torque_nm[i] = drag_torque;
    torque.z -= r.spin * (drag_torque + p.rotor_inertia_kg_m2 * accel);
    momentum_z += r.spin * p.rotor_inertia_kg_m2 * omega;
  }
  // The gyroscopic moment of the spinning rotors, −ω × (0, 0, H).
  torque.x -= s.rate_rad_s.y * momentum_z;
  torque.y += s.rate_rad_s.x * momentum_z;
  // Flapping, −k_f (e3 × v_r).
  torque.x += air.y * f.flapping_nm_per_m_s;
  torque.y -= air.x * f.flapping_nm_per_m_s;
  w.force_world_n = rotate(s.attitude, body_force_n(f, air, thrust_z));
  w.torque_body_nm = torque;
  return w;
}

Vec3 applied_force_world_n(const Airframe& a, const MultirotorState& s,
                           const MultirotorInputs& in) {
  double thrust_z = 0;
  for (std::size_t i = 0; i < a.rotors.size(); ++i)
    thrust_z += rotor_thrust_n(a.propulsion, a.rotors[i], s.rotor_rad_s[i]);
  return rotate(s.attitude, body_force_n(a.frame, air_in_body(s, in), thrust_z));
}

double motors_power_w(const Airframe& a, const MultirotorState& s, const MultirotorInputs& in) {
  const Propulsion& p = a.propulsion;
  double power = 0;
  for (std::size_t i = 0; i < a.rotors.size(); ++i) {
    const double omega = s.rotor_rad_s[i];
    power +=
        motor_power_at_torque_w(p, omega, held_drag_torque_nm(p, omega, in.drag_torque_factor[i]),
                                rotor_accel_rad_s2(p, in.command_rad_s[i], omega));
  }
  return power;
}

MultirotorState integrate(const Airframe& a, MultirotorState state, const MultirotorInputs& in,
                          double duration_s, double max_step_s) {
  if (!(duration_s > 0)) return state;
  const auto steps = static_cast<long>(std::ceil(duration_s / max_step_s - 1e-9));
  const double h = duration_s / static_cast<double>(std::max(1L, steps));
  const Frame& f = a.frame;
  auto system = [&](const StateVector& x, StateVector& dx, double /*t*/) {
    const MultirotorState s = unpack(x);
    const Wrench w = applied_wrench(a, s, in);
    const Vec3 accel = w.force_world_n / f.mass_kg - kUp * kStandardGravity_m_s2;
    const Vec3& om = s.rate_rad_s;
    // J ω̇ = τ − ω × (J ω) (the rotors' part of the momentum is in τ already).
    const Vec3 jw = hadamard(f.inertia_kg_m2, om);
    const Vec3 rhs = w.torque_body_nm - cross(om, jw);
    const Vec3 alpha{rhs.x / f.inertia_kg_m2.x, rhs.y / f.inertia_kg_m2.y,
                     rhs.z / f.inertia_kg_m2.z};
    // q̇ = ½ q ⊗ (0, ω), on the unnormalised stage quaternion as RK4 carries it.
    const Quat q{x[6], x[7], x[8], x[9]};
    const Quat qd = q * Quat{0, om.x, om.y, om.z};
    dx[0] = x[3], dx[1] = x[4], dx[2] = x[5];
    dx[3] = accel.x, dx[4] = accel.y, dx[5] = accel.z;
    dx[6] = 0.5 * qd.w, dx[7] = 0.5 * qd.x, dx[8] = 0.5 * qd.y, dx[9] = 0.5 * qd.z;
    dx[10] = alpha.x, dx[11] = alpha.y, dx[12] = alpha.z;
    for (std::size_t i = 0; i < kMaxRotors; ++i) dx[13 + i] = w.rotor_accel_rad_s2[i];
  };
  const std::size_t used = 13 + std::min(a.rotors.size(), kMaxRotors);
  StateVector x = pack(state);
  for (long k = 0; k < std::max(1L, steps); ++k) {
    rk4_step(system, x, h, used);
    const Quat q = normalized({x[6], x[7], x[8], x[9]});
    x[6] = q.w, x[7] = q.x, x[8] = q.y, x[9] = q.z;
  }
  return unpack(x);
}

Hover hover(const Airframe& a) {
  const Propulsion& p = a.propulsion;
  double efficiency_sum = 0;
  for (const Rotor& r : a.rotors) efficiency_sum += r.efficiency;
  // Σ η_i k_T Ω² = m g with one Ω for all (a symmetric frame needs no moment).
  const double omega =
      std::sqrt(a.frame.mass_kg * kStandardGravity_m_s2 / (efficiency_sum * p.thrust_coeff_n_s2));
  Hover h;
  for (std::size_t i = 0; i < a.rotors.size(); ++i) {
    h.rotor_rad_s[i] = omega;
    h.motor_power_w += motor_power_w(p, omega, 0.0);
  }
  return h;
}

Esc::Esc(const EscSettings& settings, double max_speed_rad_s)
    : settings_(settings),
      max_speed_rad_s_(max_speed_rad_s),
      period_ns_(settings.frame_rate_hz > 0 ? period_of_rate(settings.frame_rate_hz) : 0),
      applied_us_(settings.pwm_min_us),
      pending_us_(settings.pwm_min_us) {
  // A rate that does not divide a second into whole nanoseconds: the nearest whole period.
  if (settings.frame_rate_hz > 0 && period_ns_ == 0)
    period_ns_ = std::max<SimTime>(1, std::llround(1e9 / settings.frame_rate_hz));
}

double Esc::quantised_us(double pwm_us) const {
  const double clamped = std::clamp(pwm_us, settings_.pwm_min_us, settings_.pwm_max_us);
  if (!(settings_.resolution_us > 0)) return clamped;
  const double levels = std::round((clamped - settings_.pwm_min_us) / settings_.resolution_us);
  return std::min(settings_.pwm_max_us, settings_.pwm_min_us + levels * settings_.resolution_us);
}

SimTime Esc::next_frame(SimTime t) const {
  if (period_ns_ <= 0) return t;
  return (t + period_ns_ - 1) / period_ns_ * period_ns_;
}

void Esc::command(double pwm_us, SimTime now) {
  pending_us_ = quantised_us(pwm_us);
  pending_at_ = next_frame(now);
  has_pending_ = true;
}

double Esc::speed_command_rad_s(SimTime now) {
  if (has_pending_ && now >= pending_at_) {
    applied_us_ = pending_us_;
    has_pending_ = false;
  }
  const double u =
      (applied_us_ - settings_.pwm_min_us) / (settings_.pwm_max_us - settings_.pwm_min_us);
  return max_speed_rad_s_ * (settings_.thrust_linear ? std::sqrt(u) : u);
}

double body_energy_j(const Airframe& a, const MultirotorState& s) {
  const Frame& f = a.frame;
  const Vec3 jw = hadamard(f.inertia_kg_m2, s.rate_rad_s);
  return 0.5 * f.mass_kg * dot(s.velocity_m_s, s.velocity_m_s) +
         f.mass_kg * kStandardGravity_m_s2 * s.position_m.z + 0.5 * dot(s.rate_rad_s, jw);
}

Vec3 body_angular_momentum_world(const Airframe& a, const MultirotorState& s) {
  return rotate(s.attitude, hadamard(a.frame.inertia_kg_m2, s.rate_rad_s));
}

}  // namespace swath::vehicle
