// The sagging battery in a flight (docs/swath-control.md, "Battery"): thrust compensation keeps
// the attitude loop as stiff at 20 % as at 100 % (and without it the loop is visibly softer);
// the energy the loads drew is the battery's ∫ V I dt, and the cells' ∫ OCV I dt is that plus the
// I² R heat. And translational lift reaches the flying plant (a cruise costs less with it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "swath/base/file_text.hpp"
#include "swath/control/config.hpp"
#include "swath/control/simulation.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/vehicle/battery.hpp"
#include "swath/vehicle/vehicle_files.hpp"

namespace swath::control {
namespace {

struct KeptRows : SimulationObserver {
  std::vector<TimeseriesRow> kept;
  void on_row(const TimeseriesRow& r) override { kept.push_back(r); }
};

// The bundled quad-f450 (sag and translational lift on) holding a point in rugby's gusty wind:
// the carrot creeps 1 m at 5 cm/s, 20 s of near-hover.
SimulationSettings hover_flight(double initial_soc, std::uint64_t seed) {
  const std::string file = SWATH_SOURCE_DIR "/share/vehicles/quad-f450.yaml";
  const std::string text = base::read_text_file(file, "vehicle file");
  SimulationSettings s;
  s.seed = seed;
  s.physics = vehicle::parse_vehicle(text, file);
  s.control = parse_vehicle_control(text, file);
  s.battery = energy::parse_battery_section(text, file);
  s.battery.initial_soc = initial_soc;
  s.battery.reserve_soc = 0.05;
  s.environment = vehicle::environment_preset("rugby");
  s.mission.name = "hold";
  s.mission.legs.push_back({{0, 0, 10}, {1, 0, 10}});
  s.speed_m_s = 0.05;
  s.scheduler.run.metrics_from_s = 2;
  s.scheduler.run.max_time_s = 60;
  return s;
}

// Roll and pitch RMS error over three seeds, degrees.
double attitude_rms_deg(double initial_soc, bool compensate) {
  double sum = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SimulationSettings s = hover_flight(initial_soc, seed);
    s.battery.thrust_compensation = compensate;
    const SimulationSummary r = simulate(s, nullptr);
    EXPECT_EQ(r.status, FlightStatus::completed) << initial_soc << " " << seed;
    sum += std::hypot(r.attitude_error_deg[0].rms, r.attitude_error_deg[1].rms);
  }
  return sum / 3;
}

TEST(BatterySag, ThrustCompensationKeepsTheHoverAttitudeErrorAsTheBatteryDrains) {
  const SimulationSettings s = hover_flight(1.0, 1);
  ASSERT_GT(s.battery.cells, 0);
  // The sag is real: at 20 % the pack's open-circuit voltage is 9 % below a full one's.
  EXPECT_LT(vehicle::open_circuit_voltage_v(s.battery, 0.2),
            0.92 * vehicle::open_circuit_voltage_v(s.battery, 1.0));
  const double full = attitude_rms_deg(1.0, true), low = attitude_rms_deg(0.2, true);
  EXPECT_NEAR(low / full, 1.0, 0.03) << full << " " << low;
  std::printf("hover attitude RMS: 100 %% %.4f°, 20 %% %.4f°\n", full, low);
  // Without compensation the loop has lost (V_20% / V_100%)² ≈ 18 % of its gain: a different
  // loop (softer, so it follows the noisy setpoints less: its error is smaller here, not larger).
  const double low_uncompensated = attitude_rms_deg(0.2, false);
  EXPECT_GT(std::abs(low_uncompensated / full - 1.0), 0.06) << full << " " << low_uncompensated;
}

TEST(BatterySag, TheLoadsEnergyIsTheBatterysIntegralOfVoltageTimesCurrent) {
  SimulationSettings s = hover_flight(1.0, 4);
  KeptRows rows;
  const SimulationSummary r = simulate(s, &rows);
  ASSERT_EQ(r.status, FlightStatus::completed);
  // Σ V I dt with V = OCV − I R, against the loads' Σ P dt.
  EXPECT_LT(r.balance_residual, 1e-9);
  // The cells: the charge off the state of charge at the curve's voltage gives the loads' energy
  // and the I² R heat (the current from the charge and the time; the SoC moves 2 %, so the mean
  // OCV holds to well under 0.1 %).
  const double charge_as = (s.battery.initial_soc - r.final_soc) * 3600 * s.battery.capacity_ah;
  const double current_a = charge_as / r.flight_time_s;
  const double ocv_v =
      vehicle::open_circuit_voltage_v(s.battery, (s.battery.initial_soc + r.final_soc) / 2);
  const double heat_j =
      current_a * current_a * vehicle::pack_resistance_ohm(s.battery) * r.flight_time_s;
  EXPECT_NEAR(ocv_v * charge_as, r.total_j + heat_j, 2e-3 * r.total_j);
  EXPECT_GT(heat_j, 0.01 * r.total_j);  // 24 mΩ at ~14 A: about 2 % of the power
  // The rows' state of charge again from their mean powers through the sag (20 ms steps).
  double soc = s.battery.initial_soc, last_t = 0;
  for (const TimeseriesRow& row : rows.kept) {
    const double p = row.motors_w + row.cpu_w + row.avionics_w;
    soc -= vehicle::sag_current_a(s.battery, soc, p) * (row.t_s - last_t) /
           (3600 * s.battery.capacity_ah);
    last_t = row.t_s;
    EXPECT_NEAR(row.soc, soc, 1e-3 * (1 - soc) + 1e-9) << row.t_s;
  }
}

}  // namespace
}  // namespace swath::control

namespace swath::control {
namespace {

// Translational lift reaches the flying plant: the same 5 m/s cruise in calm air draws less motor
// power with it than without (at the same rotor speeds the induced power falls to ~0.89 of
// hover's, less the propulsive power of the tilted disks: ~7 % in all).
TEST(TranslationalLift, ACruiseInTheSimulationCostsLessThanWithoutIt) {
  auto cruise_w = [](bool lift) {
    SimulationSettings s = hover_flight(1.0, 1);
    s.environment = vehicle::environment_preset("calm");
    s.mission.legs = {{{0, 0, 10}, {150, 0, 10}}};
    s.speed_m_s = 5;
    s.physics.airframe.propulsion.translational_lift = lift;
    KeptRows rows;
    EXPECT_EQ(simulate(s, &rows).status, FlightStatus::completed);
    double sum = 0;
    int n = 0;
    for (const TimeseriesRow& r : rows.kept)
      if (std::abs(std::hypot(r.velocity_m_s.x, r.velocity_m_s.y) - 5) < 0.1)
        sum += r.motors_w, ++n;
    EXPECT_GT(n, 500);
    return sum / std::max(n, 1);
  };
  const double with = cruise_w(true), without = cruise_w(false);
  EXPECT_LT(with, 0.96 * without) << with << " " << without;
  EXPECT_GT(with, 0.85 * without) << with << " " << without;
}

}  // namespace
}  // namespace swath::control
