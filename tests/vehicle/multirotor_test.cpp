// The multirotor against closed forms and physical invariants (docs/swath-control.md): hover speed
// and power, free fall, torque-free rotation (energy and angular momentum, the intermediate-axis
// flip), RK4's fourth order against a tight adaptive reference, the work-energy balance, the ESC.
#include "swath/vehicle/multirotor.hpp"

#include <gtest/gtest.h>

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstring>

#include "swath/vehicle/random.hpp"

namespace swath::vehicle {
namespace {

constexpr double g = kStandardGravity_m_s2;

// The closed form of docs/swath-control.md, 'The simulated multirotor' written out again here,
// independently of hover(): Ω = sqrt(m g / (n k_T)); I = k_Q Ω² / K_t + I_0; P = n (R I + K_e Ω) I
// / η.
struct ClosedHover {
  double omega, power;
};
ClosedHover closed_hover(double mass, int n, const Propulsion& p) {
  const double omega = std::sqrt(mass * g / (n * p.thrust_coeff_n_s2));
  const double k = 60.0 / (2 * M_PI * p.kv_rpm_per_v);
  const double i = p.torque_coeff_nm_s2 * omega * omega / k + p.no_load_current_a;
  return {omega, n * (p.resistance_ohm * i + k * omega) * i / p.esc_efficiency};
}

TEST(Multirotor, HoverSpeedAndPowerAgainstTheClosedForm) {
  const Airframe quad;
  const Hover h = hover(quad);
  const ClosedHover c = closed_hover(1.5, 4, quad.propulsion);
  EXPECT_NEAR(h.rotor_rad_s[0], c.omega, 1e-9);
  EXPECT_NEAR(h.motor_power_w, c.power, 1e-9);
  // docs/swath-control.md figures for the defaults: 678.0 rad/s and 195.3 W.
  EXPECT_NEAR(h.rotor_rad_s[0], 678.0, 0.05);
  EXPECT_NEAR(h.motor_power_w, 195.3, 0.05);
  Airframe hexa;
  hexa.frame.mass_kg = 2.4;
  hexa.rotors = rotor_layout(RotorLayout::hexa_x, 0.275);
  EXPECT_NEAR(hover(hexa).rotor_rad_s[0], 700.2, 0.05);
  EXPECT_NEAR(hover(hexa).rotor_rad_s[0], closed_hover(2.4, 6, hexa.propulsion).omega, 1e-9);

  // Flown: held at the hover speeds in still air the quad stays where it is, level.
  MultirotorState s;
  s.position_m = {0, 0, 10};
  MultirotorInputs in;
  s.rotor_rad_s = in.command_rad_s = h.rotor_rad_s;
  const MultirotorState after = integrate(quad, s, in, 5.0, 0.001);
  EXPECT_NEAR(after.position_m.z, 10, 1e-9);
  EXPECT_NEAR(norm(after.velocity_m_s), 0, 1e-9);
  EXPECT_NEAR(norm(after.rate_rad_s), 0, 1e-12);
}

TEST(Multirotor, RotorLayoutsBalanceTheirMomentsAndSpins) {
  for (RotorLayout layout : {RotorLayout::quad_x, RotorLayout::hexa_x, RotorLayout::y6}) {
    const std::vector<Rotor> rotors = rotor_layout(layout, 0.3, +1, 0.8);
    Vec3 centre{};
    int spin = 0;
    for (const Rotor& r : rotors) {
      centre += r.position_m;
      spin += r.spin;
      EXPECT_NEAR(std::hypot(r.position_m.x, r.position_m.y), 0.3, 1e-12);
    }
    EXPECT_NEAR(norm(centre), 0, 1e-12);  // equal speeds: no moment from thrust
    EXPECT_EQ(spin, 0);                   // and none from drag torque
  }
  EXPECT_EQ(rotor_layout(RotorLayout::y6, 0.3, +1, 0.8)[1].efficiency, 0.8);
}

TEST(Multirotor, FreeFallIsTheParabola) {
  Airframe a;
  a.frame.drag_linear_n_per_m_s = a.frame.drag_cda_m2 = {};
  a.frame.flapping_nm_per_m_s = 0;
  MultirotorState s;
  s.position_m = {1, 2, 100};
  s.velocity_m_s = {3, -1, 2};
  const MultirotorState after = integrate(a, s, {}, 2.0, 0.01);
  // RK4 is exact on a quadratic in time.
  EXPECT_NEAR(after.position_m.x, 1 + 3 * 2.0, 1e-9);
  EXPECT_NEAR(after.position_m.y, 2 - 1 * 2.0, 1e-9);
  EXPECT_NEAR(after.position_m.z, 100 + 2 * 2.0 - 0.5 * g * 4.0, 1e-9);
  EXPECT_NEAR(after.velocity_m_s.z, 2 - g * 2.0, 1e-9);
}

Airframe rigid_body(Vec3 inertia) {
  Airframe a;
  a.frame.inertia_kg_m2 = inertia;
  a.frame.drag_linear_n_per_m_s = a.frame.drag_cda_m2 = {};
  a.frame.flapping_nm_per_m_s = 0;
  return a;
}

TEST(Multirotor, TorqueFreeRotationKeepsEnergyAndMomentumAndFlipsAboutTheMiddleAxis) {
  const Airframe a = rigid_body({0.01, 0.02, 0.03});
  MultirotorState s;
  s.rate_rad_s = {0.3, 0.2, -0.5};
  // Rotational energy ½ ωᵀ J ω, written out here (body_energy_j adds the falling body's).
  auto rotational = [&](const MultirotorState& x) {
    return 0.5 * dot(x.rate_rad_s, hadamard(a.frame.inertia_kg_m2, x.rate_rad_s));
  };
  const double e0 = rotational(s), total0 = body_energy_j(a, s);
  const Vec3 l0 = body_angular_momentum_world(a, s);
  MultirotorState x = s;
  for (int k = 0; k < 100; ++k) {
    x = integrate(a, x, {}, 0.1, 0.001);
    EXPECT_NEAR(rotational(x), e0, 1e-9 * e0);
    EXPECT_NEAR(norm(body_angular_momentum_world(a, x) - l0), 0, 1e-9 * norm(l0));
    // Falling too: kinetic + potential + rotational stays (to rounding of the large terms).
    EXPECT_NEAR(body_energy_j(a, x), total0, 1e-9 * a.frame.mass_kg * g * std::abs(x.position_m.z));
  }
  // Spun about the intermediate axis with a small disturbance, the body tumbles: the rate about
  // that axis reverses (Dzhanibekov); about the largest axis it stays.
  MultirotorState mid;
  mid.rate_rad_s = {1e-3, 5.0, 1e-3};
  double lowest = 5.0;
  for (int k = 0; k < 200; ++k) {
    mid = integrate(a, mid, {}, 0.05, 0.0005);
    lowest = std::min(lowest, mid.rate_rad_s.y);
  }
  EXPECT_LT(lowest, -4.5);
  MultirotorState major;
  major.rate_rad_s = {1e-3, 1e-3, 5.0};
  for (int k = 0; k < 200; ++k) {
    major = integrate(a, major, {}, 0.05, 0.0005);
    EXPECT_GT(major.rate_rad_s.z, 4.99);
  }
}

// A manoeuvre with everything on: rotors spinning up unevenly, drag in wind, flapping, a tilt.
struct Manoeuvre {
  Airframe airframe;
  MultirotorState start;
  MultirotorInputs inputs;
};
Manoeuvre manoeuvre() {
  Manoeuvre m;
  m.start.position_m = {0, 0, 20};
  m.start.velocity_m_s = {2, -1, 0.5};
  m.start.attitude = axis_angle({0.6, 0.8, 0}, 0.3);
  m.start.rate_rad_s = {0.4, -0.2, 0.1};
  const Hover h = hover(m.airframe);
  for (std::size_t i = 0; i < 4; ++i) {
    m.start.rotor_rad_s[i] = h.rotor_rad_s[i];
    m.inputs.command_rad_s[i] = h.rotor_rad_s[i] * (1.0 + 0.05 * static_cast<double>(i));
  }
  m.inputs.wind_m_s = {3, 1, 0};
  m.inputs.torque_noise_nm = {0.001, -0.002, 0.0005};
  return m;
}

std::array<double, 21> as_vector(const MultirotorState& s) {
  std::array<double, 21> v{s.position_m.x,   s.position_m.y,   s.position_m.z, s.velocity_m_s.x,
                           s.velocity_m_s.y, s.velocity_m_s.z, s.attitude.w,   s.attitude.x,
                           s.attitude.y,     s.attitude.z,     s.rate_rad_s.x, s.rate_rad_s.y,
                           s.rate_rad_s.z};
  for (std::size_t i = 0; i < 8; ++i) v[13 + i] = s.rotor_rad_s[i];
  return v;
}

// The model's right-hand side written out again (docs/swath-control.md, 'The simulated
// multirotor'), through applied_wrench(), for odeint's steppers.
using V = std::array<double, 21>;
struct ModelRhs {
  const Airframe& airframe;
  const MultirotorInputs& inputs;
  void operator()(const V& x, V& dx, double) const {
    MultirotorState s;
    s.position_m = {x[0], x[1], x[2]};
    s.velocity_m_s = {x[3], x[4], x[5]};
    s.attitude = normalized({x[6], x[7], x[8], x[9]});
    s.rate_rad_s = {x[10], x[11], x[12]};
    for (std::size_t i = 0; i < 8; ++i) s.rotor_rad_s[i] = x[13 + i];
    const Wrench w = applied_wrench(airframe, s, inputs);
    const Frame& f = airframe.frame;
    const Vec3 acc = w.force_world_n / f.mass_kg - Vec3{0, 0, g};
    const Vec3 jw = hadamard(f.inertia_kg_m2, s.rate_rad_s);
    const Vec3 r = w.torque_body_nm - cross(s.rate_rad_s, jw);
    const Quat qd =
        Quat{x[6], x[7], x[8], x[9]} * Quat{0, s.rate_rad_s.x, s.rate_rad_s.y, s.rate_rad_s.z};
    dx = {x[3],
          x[4],
          x[5],
          acc.x,
          acc.y,
          acc.z,
          qd.w / 2,
          qd.x / 2,
          qd.y / 2,
          qd.z / 2,
          r.x / f.inertia_kg_m2.x,
          r.y / f.inertia_kg_m2.y,
          r.z / f.inertia_kg_m2.z};
    for (std::size_t i = 0; i < 8; ++i) dx[13 + i] = w.rotor_accel_rad_s2[i];
  }
};

TEST(Multirotor, Rk4ErrorFallsSixteenfoldPerHalvedStepAgainstDopri5) {
  const Manoeuvre m = manoeuvre();
  // Reference: Dormand-Prince 5(4) at 1e-13, the same right-hand side through applied_wrench().
  const ModelRhs rhs{m.airframe, m.inputs};
  V reference = as_vector(m.start);
  namespace ode = boost::numeric::odeint;
  ode::integrate_adaptive(ode::make_controlled(1e-13, 1e-13, ode::runge_kutta_dopri5<V>()), rhs,
                          reference, 0.0, 0.5, 1e-4);
  auto error_at = [&](double h) {
    const V x = as_vector(integrate(m.airframe, m.start, m.inputs, 0.5, h));
    double e = 0;
    for (std::size_t k = 0; k < 13; ++k) e = std::max(e, std::abs(x[k] - reference[k]));
    return e;
  };
  const double e1 = error_at(0.02), e2 = error_at(0.01), e3 = error_at(0.005);
  EXPECT_GT(e1 / e2, 12.0) << e1 << " " << e2;
  EXPECT_LT(e1 / e2, 20.0) << e1 << " " << e2;
  EXPECT_GT(e2 / e3, 12.0) << e2 << " " << e3;
  EXPECT_LT(e2 / e3, 20.0) << e2 << " " << e3;
}

// Random states and inputs of the three layouts, translational lift factors included (fixed seed).
struct RandomCase {
  Airframe airframe;
  MultirotorState state;
  MultirotorInputs inputs;
};
RandomCase random_case(SplitMix64& r, int k) {
  RandomCase c;
  const RotorLayout layouts[] = {RotorLayout::quad_x, RotorLayout::hexa_x, RotorLayout::y6};
  c.airframe.rotors = rotor_layout(layouts[k % 3], 0.25, 1, 0.8);
  c.state.position_m = {r.uniform(-50, 50), r.uniform(-50, 50), r.uniform(1, 80)};
  c.state.velocity_m_s = {r.uniform(-8, 8), r.uniform(-8, 8), r.uniform(-3, 3)};
  const Vec3 axis{r.normal(), r.normal(), r.normal()};
  const double angle_rad = r.uniform(-0.8, 0.8);
  c.state.attitude = axis_angle(axis / norm(axis), angle_rad);
  c.state.rate_rad_s = {r.uniform(-2, 2), r.uniform(-2, 2), r.uniform(-1, 1)};
  const double max = c.airframe.propulsion.max_speed_rad_s;
  for (std::size_t i = 0; i < c.airframe.rotors.size(); ++i) {
    c.state.rotor_rad_s[i] = r.uniform(0.3, 0.9) * max;
    c.inputs.command_rad_s[i] = r.uniform(-0.1, 1.1) * max;  // clamped at both ends
    c.inputs.drag_torque_factor[i] = r.uniform(0.8, 1.0);
  }
  c.inputs.wind_m_s = {r.uniform(-6, 6), r.uniform(-6, 6), r.uniform(-1, 1)};
  c.inputs.torque_noise_nm = {r.uniform(-0.01, 0.01), r.uniform(-0.01, 0.01), 0.0};
  return c;
}

// integrate() steps like odeint's runge_kutta4 on the model's right-hand side (then renormalises
// the attitude), to the bit: flights keep their outputs whichever stepper carries them.
TEST(Multirotor, IntegrateIsOdeintsRk4ToTheBit) {
  SplitMix64 random(7);
  for (int k = 0; k < 30; ++k) {
    const RandomCase c = random_case(random, k);
    const MultirotorState ours = integrate(c.airframe, c.state, c.inputs, 0.01, 0.001);
    V x = as_vector(c.state);
    boost::numeric::odeint::runge_kutta4<V> stepper;
    const ModelRhs rhs{c.airframe, c.inputs};
    for (int step = 0; step < 10; ++step) {
      stepper.do_step(rhs, x, 0.0, 0.01 / 10);
      const Quat q = normalized({x[6], x[7], x[8], x[9]});
      x[6] = q.w, x[7] = q.x, x[8] = q.y, x[9] = q.z;
    }
    // The state comes back through MultirotorState, its attitude normalised once more.
    const Quat q = normalized({x[6], x[7], x[8], x[9]});
    x[6] = q.w, x[7] = q.x, x[8] = q.y, x[9] = q.z;
    const V ours_v = as_vector(ours);
    EXPECT_EQ(std::memcmp(ours_v.data(), x.data(), sizeof(V)), 0) << "case " << k;
    EXPECT_GT(norm(ours.velocity_m_s - c.state.velocity_m_s), 1e-3) << "case " << k;
  }
}

// The force and the motors' power have their own short paths (the accelerometer's truth, the
// energy per step); they are applied_wrench's figures to the bit.
TEST(Multirotor, ForceAndPowerPathsAreTheWrenchsToTheBit) {
  SplitMix64 random(11);
  for (int k = 0; k < 300; ++k) {
    const RandomCase c = random_case(random, k);
    const Wrench w = applied_wrench(c.airframe, c.state, c.inputs);
    const Vec3 f = applied_force_world_n(c.airframe, c.state, c.inputs);
    EXPECT_EQ(std::memcmp(&f, &w.force_world_n, sizeof f), 0) << "case " << k;
    double power = 0;
    for (std::size_t i = 0; i < c.airframe.rotors.size(); ++i)
      power += motor_power_at_torque_w(c.airframe.propulsion, c.state.rotor_rad_s[i],
                                       w.rotor_drag_torque_nm[i], w.rotor_accel_rad_s2[i]);
    const double ours = motors_power_w(c.airframe, c.state, c.inputs);
    EXPECT_EQ(std::memcmp(&ours, &power, sizeof ours), 0) << "case " << k << ": " << ours;
  }
}

// The body's mechanical energy changes by the work of the applied forces and moments:
// dE/dt = F · v + τ · ω (gravity is in E as potential energy).
TEST(Multirotor, WorkOfForcesAndMomentsIsTheChangeOfEnergy) {
  const Manoeuvre m = manoeuvre();
  MultirotorState s = m.start;
  const double dt = 0.0005;
  double work = 0, gross = 0;
  auto power = [&](const MultirotorState& x) {
    const Wrench w = applied_wrench(m.airframe, x, m.inputs);
    return dot(w.force_world_n, x.velocity_m_s) + dot(w.torque_body_nm, x.rate_rad_s);
  };
  double p_prev = power(s);
  const double e0 = body_energy_j(m.airframe, s);
  for (int k = 0; k < 2000; ++k) {
    s = integrate(m.airframe, s, m.inputs, dt, dt);
    const double p = power(s);
    work += 0.5 * (p_prev + p) * dt;  // trapezoid
    gross += 0.5 * (std::abs(p_prev) + std::abs(p)) * dt;
    p_prev = p;
  }
  const double change = body_energy_j(m.airframe, s) - e0;
  EXPECT_GT(std::abs(change), 1.0);  // the manoeuvre does change the energy
  // The trapezoid's error is O(dt²) of the power's curvature: 1e-5 of the gross work.
  EXPECT_NEAR(change, work, 1e-5 * gross) << gross;
}

TEST(Multirotor, MotorPowerIsTheElectricalBalanceAndNeverNegative) {
  const Propulsion p;
  const double k = p.motor_constant();
  EXPECT_NEAR(k, 60 / (2 * M_PI * 920), 1e-15);
  // Spinning up: more current (J_r Ω̇ / K_t); braking hard: no regeneration.
  const double steady = motor_power_w(p, 600, 0);
  EXPECT_NEAR(motor_current_a(p, 600, 1000) - motor_current_a(p, 600, 0),
              p.rotor_inertia_kg_m2 * 1000 / k, 1e-12);
  EXPECT_GT(motor_power_w(p, 600, 1000), steady);
  // Cutting the command to zero: Ω̇ = −Ω / τ_m; the current reverses and the motor would give
  // power back, which the ESC does not take.
  EXPECT_LT(motor_current_a(p, 600, -600 / p.time_constant_s), 0.0);
  EXPECT_EQ(motor_power_w(p, 600, -600 / p.time_constant_s), 0.0);
  // The electrical power covers the shaft's k_Q Ω³, the copper loss and I_0 K_e Ω.
  const double i = motor_current_a(p, 600, 0);
  EXPECT_NEAR(steady * p.esc_efficiency,
              p.torque_coeff_nm_s2 * 600 * 600 * 600 + p.resistance_ohm * i * i +
                  p.no_load_current_a * k * 600,
              1e-9);
}

TEST(Esc, QuantisesAndLatchesAtItsFrames) {
  EscSettings settings;
  settings.resolution_us = 4;
  Esc esc(settings, 1000);
  EXPECT_EQ(esc.quantised_us(1501.9), 1500);
  EXPECT_EQ(esc.quantised_us(1502.1), 1504);
  EXPECT_EQ(esc.quantised_us(900), 1000);
  EXPECT_EQ(esc.quantised_us(2500), 2000);
  // 490 Hz does not divide a second into whole ns: the nearest period, 2,040,816 ns.
  EXPECT_EQ(esc.next_frame(1), 2'040'816);
  EXPECT_EQ(esc.next_frame(2'040'816), 2'040'816);
  EXPECT_EQ(esc.speed_command_rad_s(0), 0.0);
  esc.command(1500, 1'000'000);
  EXPECT_EQ(esc.speed_command_rad_s(2'000'000), 0.0);  // not before the frame
  EXPECT_NEAR(esc.speed_command_rad_s(2'040'816), 1000 * std::sqrt(0.5), 1e-12);
  settings.frame_rate_hz = 0;
  settings.thrust_linear = false;
  Esc at_once(settings, 1000);
  at_once.command(1750, 123);  // 187.5 levels of 4 µs round to 188: 1752 µs
  EXPECT_NEAR(at_once.speed_command_rad_s(123), 752, 1e-12);
}

}  // namespace
}  // namespace swath::vehicle
