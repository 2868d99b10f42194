// The plant on its event clock: hover holds and draws the closed-form power, events split the
// integration without changing it (free fall stays the parabola), sensors deliver on their exact
// schedules, ESCs act at their frames, and a seed gives the same flight to the bit.
#include "swath/vehicle/flight_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <utility>
#include <vector>

namespace swath::vehicle {
namespace {

FlightModelSettings quiet_hover() {
  FlightModelSettings s;
  s.physics.esc.resolution_us = 0;  // the exact hover PWM
  s.physics.airframe.frame.torque_noise_sigma_nm = 0;
  s.initial.position_m = {0, 0, 10};
  s.initial.rotor_rad_s = hover(s.physics.airframe).rotor_rad_s;
  return s;
}

TEST(FlightModel, HoverHoldsAndDrawsTheClosedFormPower) {
  FlightModel m(quiet_hover());
  m.advance_to(10 * kNanosecondsPerSecond);
  EXPECT_EQ(m.now(), 10 * kNanosecondsPerSecond);
  EXPECT_NEAR(m.state().position_m.z, 10, 1e-6);
  EXPECT_NEAR(norm(m.state().velocity_m_s), 0, 1e-6);
  const double p = hover(m.physics().airframe).motor_power_w;
  EXPECT_NEAR(m.motor_energy_j(), p * 10, 1e-6 * p * 10);
}

TEST(FlightModel, EventsDoNotChangeTheFreeFall) {
  FlightModelSettings s;
  s.physics.airframe.frame.drag_linear_n_per_m_s = s.physics.airframe.frame.drag_cda_m2 = {};
  s.physics.airframe.frame.flapping_nm_per_m_s = 0;
  s.physics.airframe.frame.torque_noise_sigma_nm = 0;
  s.initial.position_m = {0, 0, 100};
  FlightModel m(s);
  m.advance_to(2'000'000'000);
  EXPECT_NEAR(m.state().position_m.z, 100 - 0.5 * kStandardGravity_m_s2 * 4, 1e-9);
  // Stopped rotors: only the no-load current through the windings, R I_0² / η each.
  const Propulsion& p = s.physics.airframe.propulsion;
  EXPECT_NEAR(
      m.motor_energy_j(),
      4 * p.resistance_ohm * p.no_load_current_a * p.no_load_current_a / p.esc_efficiency * 2.0,
      1e-12);
}

TEST(FlightModel, SensorsDeliverOnTheirSchedules) {
  FlightModel m(quiet_hover());
  m.advance_to(kNanosecondsPerSecond);
  std::vector<int> count(m.physics().sensors.size(), 0);
  SimTime last = -1;
  for (const DeliveredSample& d : m.take_samples()) {
    ++count[d.sensor];
    EXPECT_GE(d.sample.delivered_at, last);  // in delivery order
    last = d.sample.delivered_at;
  }
  EXPECT_EQ(count[0], 1001);  // gyro at 1 kHz over [0, 1 s]
  EXPECT_EQ(count[1], 1001);  // accel
  EXPECT_EQ(count[2], 101);   // mag at 100 Hz
  EXPECT_EQ(count[3], 51);    // baro at 50 Hz
  EXPECT_EQ(count[4], 10);    // GPS at 10 Hz, 0.1 s late: the one of 1.0 s not yet
  EXPECT_TRUE(m.take_samples().empty());
}

TEST(FlightModel, AnEscActsAtItsNextFrame) {
  FlightModelSettings s = quiet_hover();
  FlightModel m(s);
  m.advance_to(1'000'000);  // 1 ms, between frames (490 Hz: 2.04 ms)
  const double before = m.state().rotor_rad_s[0];
  m.command_pwm(0, 2000);
  m.advance_to(2'000'000);
  EXPECT_NEAR(m.state().rotor_rad_s[0], before, 1e-9);  // not yet
  m.advance_to(3'000'000);
  EXPECT_GT(m.state().rotor_rad_s[0], before + 1);  // spinning up after 2.04 ms
}

// The instants in (from, to] at which some sensor measures or the wind updates: the events a
// plant without ESC frames must run, counted by brute force over every nanosecond multiple.
long long scheduled_instants(const FlightModelSettings& s, SimTime from, SimTime to) {
  std::vector<std::pair<SimTime, SimTime>> schedules;  // period, phase
  schedules.push_back({std::max<SimTime>(1, from_seconds(1.0 / s.environment.update_hz)), 0});
  for (const SensorSettings& sensor : s.physics.sensors)
    schedules.push_back({sensor.period_ns, sensor.phase_ns});
  std::vector<SimTime> instants;
  for (const auto& [period, phase] : schedules)
    for (SimTime t = phase; t <= to; t += period)
      if (t > from) instants.push_back(t);
  std::sort(instants.begin(), instants.end());
  return std::unique(instants.begin(), instants.end()) - instants.begin();
}

TEST(FlightModel, AnEscWithoutFramesActsAtOnceAndAddsNoEvents) {
  FlightModelSettings s = quiet_hover();
  s.physics.esc.frame_rate_hz = 0;
  FlightModel m(s);
  m.advance_to(1'000'000);
  const double before = m.state().rotor_rad_s[0];
  m.command_pwm(0, 2000);
  m.advance_to(1'100'000);  // 0.1 ms later the rotor is already spinning up
  EXPECT_GT(m.state().rotor_rad_s[0], before + 0.1);
  // The work is the sensors' and the wind's events, in proportion to flight time: checked in
  // 1 ms steps so that a schedule of one frame per nanosecond fails after the first.
  SimTime t = m.now();
  long long events = m.events_run();
  for (int step = 0; step < 1000; ++step) {
    const SimTime next = t + 1'000'000;
    m.command_pwm(step % 4, 1500 + step % 7);
    m.advance_to(next);
    ASSERT_EQ(m.events_run() - events, scheduled_instants(s, t, next)) << "at " << seconds(next);
    events = m.events_run(), t = next;
  }
}

bool same_bits(const MultirotorState& a, const MultirotorState& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(FlightModel, ASeedIsAFlight) {
  FlightModelSettings s = quiet_hover();
  s.environment = environment_preset("arch");
  s.physics.airframe.frame.torque_noise_sigma_nm = 0.002;
  FlightModel a(s), b(s);
  a.advance_to(3 * kNanosecondsPerSecond);
  b.advance_to(3 * kNanosecondsPerSecond);
  EXPECT_TRUE(same_bits(a.state(), b.state()));
  EXPECT_EQ(a.take_samples().size(), b.take_samples().size());
  s.seed = 2;
  FlightModel c(s);
  c.advance_to(3 * kNanosecondsPerSecond);
  EXPECT_FALSE(same_bits(a.state(), c.state()));
  // The arch's wind is there: the hovering body drifts downwind (from 240°: towards the
  // north-east, x > 0, y > 0).
  EXPECT_GT(a.state().position_m.x, 0.1);
  EXPECT_GT(a.state().position_m.y, 0.05);
}

}  // namespace
}  // namespace swath::vehicle
