// The plant's battery sag and translational lift (docs/swath-control.md) against closed forms
// written out again here: a constant-current discharge of a LiPo pack through Chen and
// Rincón-Mora's open-circuit voltage minus I R; the current that delivers a power from the
// quadratic; the induced velocity in edgewise flight (the level-flight quartic) and in axial
// climb (momentum theory's climb branch); the hover-to-cruise shaft power ratio.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "swath/vehicle/battery.hpp"
#include "swath/vehicle/multirotor.hpp"

namespace swath::vehicle {
namespace {

// Chen & Rincón-Mora (IEEE Trans. Energy Conversion 21(2), 2006), one cell, typed in again.
double chen_ocv(double soc) {
  return -1.031 * std::exp(-35 * soc) + 3.685 + 0.2156 * soc - 0.1178 * soc * soc +
         0.3201 * soc * soc * soc;
}

Battery lipo_4s() {
  Battery b;
  b.cells = 4;
  b.internal_resistance_ohm = 0.006;
  b.capacity_ah = 5;
  return b;
}

TEST(BatterySag, AConstantCurrentDischargeFollowsTheOpenCircuitCurveMinusIR) {
  const Battery b = lipo_4s();
  const double current_a = 20.0, dt_s = 1.0;
  double soc = 1.0;
  // 0.8 of the capacity at 20 A: 720 s, one step a second through soc_after_charge.
  for (int k = 1; k <= 720; ++k) {
    soc = soc_after_charge(b, soc, current_a * dt_s);
    const double t_s = k * dt_s;
    const double soc_closed = 1.0 - current_a * t_s / (3600.0 * 5.0);
    ASSERT_NEAR(soc, soc_closed, 1e-12) << t_s;
    const double v_closed = 4 * chen_ocv(soc_closed) - current_a * 4 * 0.006;
    ASSERT_NEAR(terminal_voltage_v(b, soc, current_a), v_closed, 1e-9) << t_s;
  }
  // The curve's anchors: 4.10 V a cell full, 3.73 V at 20 %, and the sag 0.48 V at 20 A.
  EXPECT_NEAR(lipo_cell_ocv_v(1.0), 4.1029, 1e-4);
  EXPECT_NEAR(lipo_cell_ocv_v(0.2), 3.7250, 1e-4);
  EXPECT_NEAR(open_circuit_voltage_v(b, 0.5) - terminal_voltage_v(b, 0.5, 20), 0.48, 1e-12);
  // Outside [0, 1] the curve holds its ends.
  EXPECT_EQ(lipo_cell_ocv_v(1.5), lipo_cell_ocv_v(1.0));
  EXPECT_EQ(lipo_cell_ocv_v(-0.1), lipo_cell_ocv_v(0.0));
}

TEST(BatterySag, TheCurrentForAPowerDeliversItAtTheSaggedVoltage) {
  const Battery b = lipo_4s();
  for (const double soc : {1.0, 0.6, 0.2, 0.05}) {
    const double e = 4 * chen_ocv(soc), r = 4 * 0.006;
    for (const double p : {50.0, 200.0, 800.0}) {
      const double i = sag_current_a(b, soc, p);
      // The smaller root of R I² − E I + P = 0.
      EXPECT_NEAR(i, (e - std::sqrt(e * e - 4 * r * p)) / (2 * r), 1e-9) << soc << " " << p;
      EXPECT_NEAR(terminal_voltage_v(b, soc, i) * i, p, 1e-9 * p);
    }
    // Beyond E² / 4R the pack cannot deliver.
    EXPECT_TRUE(std::isnan(sag_current_a(b, soc, 1.01 * e * e / (4 * r))));
  }
}

Propulsion lifting() {
  Propulsion p;
  p.translational_lift = true;
  return p;
}

constexpr double kRho = 1.225;

// Hover induced velocity of one rotor at Ω, from momentum theory: √(T / 2ρA).
double v_hover(const Propulsion& p, double omega) {
  const double area = std::numbers::pi * p.diameter_m * p.diameter_m / 4;
  return std::sqrt(p.thrust_coeff_n_s2 * omega * omega / (2 * kRho * area));
}

TEST(TranslationalLift, EdgewiseInducedVelocitySolvesTheLevelFlightQuartic) {
  const double v_h = 5.44;
  for (const double v : {0.0, 2.0, 5.0, 10.0, 20.0}) {
    // v_i⁴ + V² v_i² − v_h⁴ = 0.
    const double closed = std::sqrt((-v * v + std::sqrt(v * v * v * v + 4 * std::pow(v_h, 4))) / 2);
    EXPECT_NEAR(induced_velocity_m_s(v_h, v, 0.0), closed, 1e-9 * v_h) << v;
  }
  // Axial climb at V_c: v_i = −V_c / 2 + √((V_c / 2)² + v_h²).
  for (const double vc : {-2.0, 1.0, 3.0}) {
    const double closed = -vc / 2 + std::sqrt(vc * vc / 4 + v_h * v_h);
    EXPECT_NEAR(induced_velocity_m_s(v_h, 0.0, vc), closed, 1e-9 * v_h) << vc;
  }
  // Oblique flow: the momentum balance T = 2ρA v_i √(u_xy² + (v_i + u_z)²) holds.
  const double vi = induced_velocity_m_s(v_h, 8.0, 0.7);
  EXPECT_NEAR(vi * std::hypot(8.0, vi + 0.7), v_h * v_h, 1e-9);
}

TEST(TranslationalLift, CruiseShaftPowerAgainstHoverFollowsMomentumTheory) {
  const Propulsion p = lifting();
  const double omega = 678.0;
  const double q0 = rotor_drag_torque_nm(p, 1.0, kRho, omega, {0, 0, 0});
  // In hover the torque is the measured k_Q Ω²: the hover figures do not change.
  EXPECT_NEAR(q0, p.torque_coeff_nm_s2 * omega * omega, 1e-15);
  // The induced share of hover power, κ T v_h / (k_Q Ω³), from its definition.
  const double thrust = p.thrust_coeff_n_s2 * omega * omega;
  const double v_h = v_hover(p, omega);
  const double share = p.induced_power_factor * thrust * v_h / (q0 * omega);
  EXPECT_NEAR(induced_power_share(p, 1.0, kRho), share, 1e-12);
  EXPECT_GT(share, 0.5);  // 10-inch propeller, figure of merit 0.50, κ 1.15
  EXPECT_LT(share, 0.7);
  for (const double v : {3.0, 5.0, 10.0}) {
    const double vi = std::sqrt((-v * v + std::sqrt(v * v * v * v + 4 * std::pow(v_h, 4))) / 2);
    const double ratio_closed = 1 - share * (1 - vi / v_h);
    const double ratio = rotor_drag_torque_nm(p, 1.0, kRho, omega, {v, 0, 0}) / q0;
    EXPECT_NEAR(ratio, ratio_closed, 1e-9) << v;
    EXPECT_LT(ratio, 1.0) << v;
    // The wind is airflow like any other: flying into 5 m/s of it is 5 m/s of cruise.
    EXPECT_EQ(rotor_drag_torque_nm(p, 1.0, kRho, omega, {0, -v, 0}),
              rotor_drag_torque_nm(p, 1.0, kRho, omega, {v, 0, 0}));
  }
  // A disk tilted into the flow takes the propulsive power T u_z on top.
  const double tilted = rotor_drag_torque_nm(p, 1.0, kRho, omega, {5, 0, 0.5});
  const double vi = induced_velocity_m_s(v_h, 5, 0.5);
  EXPECT_NEAR(tilted * omega, q0 * omega + p.induced_power_factor * thrust * (vi + 0.5 - v_h),
              1e-9);
  // Off: k_Q Ω² whatever the airflow.
  Propulsion off = p;
  off.translational_lift = false;
  EXPECT_EQ(rotor_drag_torque_nm(off, 1.0, kRho, omega, {10, 0, 0}), q0);
}

}  // namespace
}  // namespace swath::vehicle
