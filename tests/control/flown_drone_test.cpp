// The drone swath-control flies is one vehicle::Drone (SimulationSettings::drone()): what the
// vehicle file and the cruise speed give reaches it, field by field, and the carrot flies it —
// checked against vehicle::rest_to_rest_s, the closed form swath plan and swath-fleet time legs
// with, not control's own trapezoid.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "swath/control/config.hpp"
#include "swath/control/simulation.hpp"
#include "swath/vehicle/kinematics.hpp"
#include "swath/vehicle/vehicle_files.hpp"

namespace swath::control {
namespace {

// Every figure differs from every default (drone.hpp, control_task.hpp), so a field left out of
// drone() shows as a default.
constexpr double kAccel_m_s2 = 0.75;  // the file's max_accel_m_s2 below
const std::string kVehicle = R"(name: hexa-under-test
controller:
  limits:
    max_speed_m_s: 6
    max_climb_m_s: 1.25
    max_accel_m_s2: 0.75
)";

SimulationSettings settings_from_files(double speed_m_s) {
  SimulationSettings s;
  s.physics = vehicle::parse_vehicle(kVehicle, "hexa.yaml");
  s.control = parse_vehicle_control(kVehicle, "hexa.yaml");
  s.speed_m_s = speed_m_s;
  return s;
}

TEST(FlownDrone, TheVehicleFileAndTheCruiseSpeedReachTheDrone) {
  const vehicle::Drone d = settings_from_files(4.5).drone();
  EXPECT_EQ(d.name, "hexa-under-test");
  ASSERT_TRUE(d.speed_m_s.has_value());
  EXPECT_EQ(*d.speed_m_s, 4.5);
  EXPECT_EQ(d.climb_speed_m_s, 1.25);
  EXPECT_EQ(d.descent_speed_m_s, 1.25);  // the controller's vertical limit holds both ways
  EXPECT_EQ(d.accel_m_s2, kAccel_m_s2);
  // What a flight does not know stays unknown, as in a fleet file that leaves it out.
  EXPECT_FALSE(d.endurance_s.has_value());
  EXPECT_FALSE(d.home.has_value());
}

// The flight along a straight level leg ends when a drone of that speed and acceleration, flown
// from rest to rest, would.
TEST(FlownDrone, TheCarrotFliesTheDronesSpeedAndAcceleration) {
  for (const double speed_m_s : {2.0, 4.5}) {
    SimulationSettings s = settings_from_files(speed_m_s);
    const double length_m = 24;
    s.mission.name = "line";
    s.mission.legs.push_back({{0, 0, 5}, {length_m, 0, 5}});
    s.scheduler.run.metrics_from_s = 0;
    s.scheduler.run.max_time_s = 120;
    const SimulationSummary summary = simulate(s, nullptr);
    ASSERT_EQ(summary.status, FlightStatus::completed) << speed_m_s;
    const double expected_s = vehicle::rest_to_rest_s(length_m, speed_m_s, kAccel_m_s2);
    // The flight ends once the carrot has stopped at the end and the vehicle is there: no sooner
    // than the drone's rest-to-rest time, and (in calm air) within 0.2 s of it.
    EXPECT_GE(summary.flight_time_s, expected_s - 1e-3) << speed_m_s;
    EXPECT_LE(summary.flight_time_s, expected_s + 0.2) << speed_m_s;
  }
}

}  // namespace
}  // namespace swath::control
