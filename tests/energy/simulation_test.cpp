#include "swath/energy/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "lawnmower_plan.hpp"
#include "swath/base/input_error.hpp"
#include "swath/energy/flight.hpp"
#include "swath/energy/guidance.hpp"
#include "swath/energy/power_model.hpp"

namespace swath::energy {
namespace {

const std::string kSimulationPlans = std::string(SWATH_SOURCE_DIR) + "/plans/";

SimConfig quiet_config() {
  SimConfig c;
  c.source = "test.yaml";
  c.output_interval_s = 0.1;
  c.power.noise_w = 0.0;
  return c;
}

std::string error_of(const Plan& plan, const SimConfig& config) {
  try {
    simulate(plan, config);
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "flew";
}

// A circle of radius 200 m about the origin, counter-clockwise, ending at its south point.
Plan circle_plan() {
  return parse_plan("0.0003; 90; x^2+y^2-200^2\n0, -200\n[0, 0]\n", "circle.stages");
}

// The line x = 0 flown north, ending 600 m up.
Plan line_plan() {
  return parse_plan("0.05; 90; x\n0, 600\n[0, 0]\n", "line.stages");
}

class Guidance : public ::testing::TestWithParam<Wind> {};

TEST_P(Guidance, ConvergesOntoACircle) {
  SimConfig c = quiet_config();
  c.start = {300, 0};
  c.wind = GetParam();
  const SimulationResult r = simulate(circle_plan(), c);
  ASSERT_EQ(r.status, SimulationEnd::completed);
  double worst = 0.0, turned = 0.0;
  for (std::size_t i = 1; i < r.samples.size(); ++i) {
    const auto& s = r.samples[i];
    if (s.t_s > 25.0)
      worst = std::max(worst, std::abs(std::hypot(s.position.x, s.position.y) - 200));
    const auto& p = r.samples[i - 1].position;
    turned += p.x * s.position.y - p.y * s.position.x;  // > 0: counter-clockwise
  }
  EXPECT_LT(worst, 1.0);
  EXPECT_GT(turned, 0.0);
  const auto& end = r.samples.back().position;
  EXPECT_LT(std::hypot(end.x - 0, end.y + 200), c.trigger_radius_m + 0.2);
}

TEST_P(Guidance, ConvergesOntoALine) {
  SimConfig c = quiet_config();
  c.start = {-60, 0};
  c.wind = GetParam();
  const SimulationResult r = simulate(line_plan(), c);
  ASSERT_EQ(r.status, SimulationEnd::completed);
  double worst = 0.0;
  for (const auto& s : r.samples)
    if (s.position.y > 150.0) worst = std::max(worst, std::abs(s.position.x));
  EXPECT_LT(worst, 1.0);
  EXPECT_GT(r.samples.back().position.y, 590.0);
}

INSTANTIATE_TEST_SUITE_P(Winds, Guidance,
                         ::testing::Values(Wind{0, 0}, Wind{6, 270}, Wind{6, 0}, Wind{8, 135}));

TEST(Flight, WindTriangle) {
  // 10 m/s airspeed, course north, 6 m/s wind from the west (blowing east): the drone crabs
  // west and makes 8 m/s over the ground.
  const geometry::Point2 wind = Wind(6, 270).velocity_m_s();
  EXPECT_NEAR(wind.x, 6.0, 1e-12);
  EXPECT_NEAR(wind.y, 0.0, 1e-12);
  EXPECT_NEAR(*ground_speed_at_airspeed({0, 1}, wind, 10.0), 8.0, 1e-12);
  // Headwind 6 from the north: 4 m/s over the ground; 12 m/s against 10 m/s airspeed: none.
  EXPECT_NEAR(*ground_speed_at_airspeed({0, 1}, Wind(6, 0).velocity_m_s(), 10.0), 4.0, 1e-12);
  EXPECT_FALSE(ground_speed_at_airspeed({0, 1}, Wind(12, 0).velocity_m_s(), 10.0));
  // Commanded 12 m/s with a 6 m/s tailwind needs 6 m/s of air; into it, capped at 15: 9 m/s.
  EXPECT_NEAR(course_speed({0, 1}, Wind(6, 180).velocity_m_s(), 12.0, 15.0)->airspeed_m_s, 6.0,
              1e-12);
  EXPECT_NEAR(course_speed({0, 1}, Wind(6, 0).velocity_m_s(), 12.0, 15.0)->ground_speed_m_s, 9.0,
              1e-12);
}

TEST(Flight, ThePapersSurveyFliesItsStagesInOrder) {
  const Plan plan = read_plan(kSimulationPlans + "survey.stages");
  SimConfig c = quiet_config();
  c.start = {25, 146};
  c.replan = false;  // the stages' order at fixed parameters
  c.trajectory_parameters = {-1000};
  c.computation_parameters = {10, 448};
  c.power.computations = {{"fps", {{2, 4.75}, {10, 9.75}}}, {"key", {{32, 0.5}, {448, 2.0}}}};
  const SimulationResult r = simulate(plan, c);
  ASSERT_EQ(r.status, SimulationEnd::completed);
  ASSERT_EQ(r.stages.size(), 5u);
  const auto fields = stage_fields(plan, c.trajectory_parameters);
  for (std::size_t k = 0; k < r.stages.size(); ++k) {
    EXPECT_EQ(r.stages[k].stage, static_cast<int>(k));
    if (k == 0) continue;
    EXPECT_GT(r.stages[k].t_s, r.stages[k - 1].t_s);
    const geometry::Point2 tp = fields[k - 1].trigger;  // entered at the previous trigger
    EXPECT_LE(std::hypot(r.stages[k].position.x - tp.x, r.stages[k].position.y - tp.y),
              c.trigger_radius_m + 1e-9);
  }
  const auto end = r.samples.back().position;
  EXPECT_LE(std::hypot(end.x - fields[4].trigger.x, end.y - fields[4].trigger.y),
            c.trigger_radius_m + 1e-9);
  // The last stage switches the computations off: 9.75 + 2.0 W less in the measured power.
  double before = 0, after = 0;
  for (const auto& s : r.samples) {
    if (s.t_s > r.stages[3].t_s + 2 && s.t_s < r.stages[4].t_s - 0.5) before = s.measured_w;
    if (s.t_s > r.stages[4].t_s + 0.5 && after == 0) after = s.measured_w;
  }
  // On the last circle (radius sqrt(3900) m) the drone banks: v^2 / R of lateral acceleration.
  const double banking = mechanical_power_w(c.power.mechanical, 12.0, 144.0 / std::sqrt(3900.0)) -
                         level_flight_power_w(c.power.mechanical, 12.0);
  EXPECT_NEAR(before - after, 11.75 - banking, 0.3);
}

TEST(Simulation, EnergyIsThePowerIntegralAndTheBatteryFollowsIt) {
  SimConfig c = quiet_config();
  c.start = {0, 0};
  c.power.mechanical.parasitic_share = 0.0;  // constant mechanical power
  c.power.payload_w = 10.0;
  const SimulationResult r = simulate(line_plan(), c);
  ASSERT_EQ(r.status, SimulationEnd::completed);
  const double p = c.power.mechanical.cruise_w + 10.0;
  EXPECT_NEAR(r.energy_j, p * r.flight_time_s, 1e-6 * r.energy_j);
  EXPECT_NEAR(r.final_soc, soc_after(c.battery, 1.0, p, r.flight_time_s), 1e-9);
  EXPECT_NEAR(r.flight_time_s, 595.0 / 12.0, 0.02);  // 600 m less the trigger radius at 12 m/s
  EXPECT_NEAR(r.mean_relative_error, 0.0, 1e-9);     // constant power is predicted exactly
}

TEST(Simulation, SameInputSameResult) {
  SimConfig c = quiet_config();
  c.power.noise_w = 2.0;
  c.start = {300, 0};
  const SimulationResult a = simulate(circle_plan(), c), b = simulate(circle_plan(), c);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    EXPECT_EQ(a.samples[i].measured_w, b.samples[i].measured_w);
    EXPECT_EQ(a.samples[i].model_w, b.samples[i].model_w);
  }
}

// A long lawnmower: the period is re-estimated from the power (one lane and one turn: the up and
// down lanes cost the same), and the predicted total energy converges on the actual total.
TEST(Simulation, LawnmowerPeriodAndPrediction) {
  const Plan plan = parse_plan(test::lawnmower_plan(24, 50, 400), "lawnmower.stages");
  SimConfig c = quiet_config();
  c.power.noise_w = 3.0;
  c.start = {0, -20};
  c.initial_period_s = 60.0;
  c.output_interval_s = 1.0;
  c.kalman.process_w = 0.1;
  c.power.computations = {{"fps", {{2, 4.75}, {10, 9.75}}}};
  c.computation_parameters = {10};
  const SimulationResult r = simulate(plan, c);
  ASSERT_EQ(r.status, SimulationEnd::completed);
  const double lane_and_turn = (400.0 + 3.14159265 * 25.0) / 12.0;  // 39.88 s
  EXPECT_NEAR(r.final_period_s, lane_and_turn, 0.03 * lane_and_turn);
  EXPECT_LT(r.mean_relative_error, 0.01);
  // In the last third of the flight the prediction is within 1 % of the final total.
  for (const auto& s : r.samples) {
    if (s.t_s > 2.0 * r.flight_time_s / 3.0) {
      EXPECT_NEAR(s.predicted_total_j, r.energy_j, 0.01 * r.energy_j) << s.t_s;
    }
  }
}

TEST(Simulation, BatteryRunsOut) {
  SimConfig c = quiet_config();
  c.battery.capacity_ah = 0.1;  // ~ 0.1 * 3600 * 14.8^2 / 12 / 160 W ~ 41 s
  c.start = {0, 0};
  const SimulationResult r = simulate(line_plan(), c);
  EXPECT_EQ(r.status, SimulationEnd::battery_empty);
  EXPECT_LE(r.final_soc, 0.0);
  EXPECT_LT(r.flight_time_s, 49.0);
  ASSERT_TRUE(r.reserve_crossed_s);
  EXPECT_NEAR(*r.reserve_crossed_s, 0.8 * r.flight_time_s, 0.05);
  EXPECT_TRUE(std::isnan(r.mean_relative_error));
}

TEST(Simulation, ReplayedPowerIsUsed) {
  SimConfig c = quiet_config();
  c.start = {0, 0};
  c.replay = parse_power_trace("t_s,watts\n0,100\n30,100\n1000,100\n", "p.csv");
  const SimulationResult r = simulate(line_plan(), c);
  EXPECT_NEAR(r.energy_j, 100.0 * r.flight_time_s, 1e-6 * r.energy_j);
}

TEST(Simulation, StallsAreExplained) {
  SimConfig c = quiet_config();
  c.stall_time_s = 200.0;
  c.start = {300, 0};
  // The triggering point is off the circle: the drone circles for ever.
  const Plan off = parse_plan("0.0003; 90; x^2+y^2-200^2\n0, -260\n[0, 0]\n", "off.stages");
  const std::string stalled = error_of(off, c);
  EXPECT_NE(
      stalled.find("off.stages: line 1: the drone has not come closer to the triggering point "
                   "(0.0, -260.0) m for 200 s"),
      std::string::npos)
      << stalled;
  c.start = {0, 0};  // the circle's centre: grad phi = 0
  EXPECT_NE(error_of(circle_plan(), c)
                .find("circle.stages: line 1: the guidance field vanishes at "
                      "(0.0, 0.0) m"),
            std::string::npos);
  c.start = {-60, 0};
  c.wind = {30, 0};
  c.max_airspeed_m_s = 20;
  EXPECT_NE(error_of(line_plan(), c)
                .find("line.stages: line 1: the wind (30.0 m/s from 0 deg) is "
                      "stronger than the drone's maximum airspeed 20.0 m/s"),
            std::string::npos);
  // sqrt of a negative: no triggering point.
  const Plan undefined = parse_plan("0.05; 90; x\n0, sqrt(c1)\n[-10, -5]\n", "u.stages");
  EXPECT_NE(error_of(undefined, quiet_config())
                .find("u.stages: line 1: the triggering point is not "
                      "a finite number"),
            std::string::npos);
}

}  // namespace
}  // namespace swath::energy
