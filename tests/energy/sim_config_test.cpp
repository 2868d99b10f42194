#include "swath/energy/sim_config.hpp"

#include <gtest/gtest.h>

#include "swath/base/input_error.hpp"

namespace swath::energy {
namespace {

const std::string kConfigPlans = std::string(SWATH_SOURCE_DIR) + "/plans/";
const std::string kShare = std::string(SWATH_SOURCE_DIR) + "/share/";

std::string config_error_of(const std::string& text) {
  try {
    parse_sim_config(text, "c.yaml");
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SimConfig, TheBundledConfig) {
  const SimConfig c = read_sim_config(kConfigPlans + "survey-sim.yaml");
  EXPECT_DOUBLE_EQ(c.time_step_s, 0.01);
  EXPECT_DOUBLE_EQ(c.start.x, 25.0);
  EXPECT_EQ(c.fourier_order, 3);
  EXPECT_DOUBLE_EQ(c.battery.voltage_v, 14.8);
  EXPECT_DOUBLE_EQ(c.battery.resistance_ohm, 0.0012);
  ASSERT_EQ(c.power.computations.size(), 2u);
  EXPECT_DOUBLE_EQ(c.power.computations[0].points[1].second, 9.75);
  EXPECT_EQ(c.computation_parameters, (std::vector<double>{10, 448}));
  const DroneProfile d = read_drone_profile(kShare + "drones/quad-5ah.yaml");
  EXPECT_DOUBLE_EQ(d.battery.capacity_ah, 5.0);
  EXPECT_DOUBLE_EQ(d.power.payload_w, 8.0);
  // The drone itself: the same vehicle::Drone a fleet file gives.
  EXPECT_FALSE(d.drone.speed_m_s.has_value());  // 0 in the file: each leg at its own speed
  EXPECT_DOUBLE_EQ(d.drone.climb_speed_m_s, 3.0);
  EXPECT_DOUBLE_EQ(d.drone.descent_speed_m_s, 2.0);
  EXPECT_DOUBLE_EQ(d.drone.max_airspeed_m_s, 16.0);
}

TEST(SimConfig, ErrorsNameTheLineAndKey) {
  EXPECT_EQ(config_error_of("time_step_s: [1"),
            "c.yaml: line 1: invalid YAML (end of sequence flow not found)");
  EXPECT_EQ(config_error_of("- 1"), "c.yaml: a simulation config is a mapping of keys");
  EXPECT_EQ(config_error_of("speed: 3"),
            "c.yaml: line 1: unknown key 'speed' (known: time_step_s speed_m_s max_airspeed_m_s "
            "wind trigger_radius_m start_m max_time_s stall_time_s output_interval_s parameters "
            "gains model mpc battery power replay_csv)");
  EXPECT_EQ(config_error_of("time_step_s: fast"), "c.yaml: line 1: time_step_s must be a number");
  EXPECT_EQ(config_error_of("\nbattery: {capacity_ah: -1}"),
            "c.yaml: line 2: battery.capacity_ah must be in (0.0000, 1000.0000], found -1");
  EXPECT_EQ(config_error_of("battery: {reserve_soc: 0.5, initial_soc: 0.4}"),
            "c.yaml: line 1: battery.reserve_soc must be below battery.initial_soc");
  EXPECT_EQ(config_error_of("start_m: [1, 2, 3]"),
            "c.yaml: line 1: start_m must be [x, y] in local metres");
  EXPECT_EQ(config_error_of("power: {computations: [{name: a, points: [[2, 1], [1, 2]]}]}"),
            "c.yaml: line 1: power.computations[0]: points must have increasing parameters");
  EXPECT_EQ(
      config_error_of("model: {kalman: {measurement_w: 0}}"),
      "c.yaml: line 1: model.kalman.measurement_w must be in (0.0000, 1000000.0000], found 0");
  EXPECT_EQ(config_error_of("model: {fourier_order: 2.5}"),
            "c.yaml: line 1: model.fourier_order must be a whole number");
  EXPECT_EQ(config_error_of("wind: 3"), "c.yaml: line 1: 'wind' must be a mapping of keys");
}

// One spelling of speeds (docs/architecture.md): the old `_mps` keys still read, with a warning
// naming the line, in the root and in nested mappings; both spellings at once are refused.
TEST(SimConfig, OldSpeedSpellingIsReadWithAWarning) {
  const SimConfig old_keys = parse_sim_config(
      "speed_mps: 9\nmax_airspeed_m_s: 20\nwind: {speed_mps: 3, from_deg: 90}\n", "c.yaml");
  EXPECT_DOUBLE_EQ(old_keys.speed_m_s, 9);
  EXPECT_DOUBLE_EQ(old_keys.wind.speed_m_s(), 3);
  ASSERT_EQ(old_keys.warnings.size(), 2u);
  EXPECT_EQ(old_keys.warnings[0],
            "c.yaml: line 1: 'speed_mps' is the old spelling, read as 'speed_m_s'; write "
            "'speed_m_s' (speeds are in m_s everywhere)");
  EXPECT_NE(old_keys.warnings[1].find("line 3: 'wind.speed_mps'"), std::string::npos)
      << old_keys.warnings[1];
  const SimConfig new_keys = parse_sim_config("speed_m_s: 9\n", "c.yaml");
  EXPECT_TRUE(new_keys.warnings.empty());
  EXPECT_EQ(config_error_of("speed_m_s: 9\nspeed_mps: 8\n"),
            "c.yaml: line 2: 'speed_mps' and 'speed_m_s' both given: keep 'speed_m_s'");
  // Only speeds: another key ending in _mps is still unknown.
  EXPECT_NE(config_error_of("climb_mps: 3\n").find("unknown key 'climb_mps'"), std::string::npos);
}

TEST(SimConfig, PowerTrace) {
  const PowerTrace t = parse_power_trace("t_s,watts\n0, 100\n10, 200\n", "p.csv");
  EXPECT_DOUBLE_EQ(t.at(5), 150.0);
  EXPECT_TRUE(std::isnan(t.at(11)));
  try {
    parse_power_trace("0,1\n2,x\n", "p.csv");
    FAIL();
  } catch (const base::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "p.csv: line 2: expected 't_s, watts' (two numbers separated by a comma)");
  }
}

}  // namespace
}  // namespace swath::energy
