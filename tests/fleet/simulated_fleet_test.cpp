// The simulated fleet behind the runtime's Backend (docs/swath-fleet.md): its legs are leg.hpp's,
// its reports say what the legs say, and a run handed an explicit SimulatedFleet is the run that
// run_app makes with its own, byte for byte.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "swath/fleet/apps.hpp"
#include "swath/fleet/leg.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/fleet/simulated_fleet.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::fleet {
namespace {

DroneSpec drone_at(const std::string& name, Vec3 home) {
  DroneSpec d;
  d.drone.name = name;
  d.home_m = home;
  return d;
}

TEST(SimulatedFleet, ALegArrivesWhenTheClosedFormSaysAndReportsItsTarget) {
  const DroneSpec d = drone_at("a", {5, -3, 0});
  SimulatedFleet fleet({d}, 20, 3);
  const Kinematics& k = d.kinematics();
  EXPECT_TRUE(fleet.report(0).link_up);
  EXPECT_FALSE(fleet.reports_every_tick());
  EXPECT_TRUE(std::isinf(fleet.arrival_s(0)));
  fleet.go_to(0, 2.0, {105, 47, 20}, k.cruise_m_s, k.approach_m_s, k.approach_within_m);
  const double t = 2.0 + Leg({5, -3, 0}, {105, 47, 20}, k).duration_s();
  EXPECT_EQ(fleet.arrival_s(0), t);
  fleet.advance_to(t - 1);
  EXPECT_FALSE(fleet.report(0).arrived);
  fleet.advance_to(t);
  const VehicleReport r = fleet.report(0);
  EXPECT_TRUE(r.arrived);
  EXPECT_FALSE(r.landed_home);
  EXPECT_EQ(r.position_m.x, 105);
  EXPECT_EQ(r.position_m.y, 47);
  EXPECT_EQ(r.position_m.z, 20);
}

TEST(SimulatedFleet, ARetargetKeepsTheLegRuleAHoldStopsAndAReturnDescendsToHome) {
  const DroneSpec d = drone_at("a", {0, 0, 0});
  const Kinematics& k = d.kinematics();
  SimulatedFleet fleet({d}, 20, 3);
  fleet.go_to(0, 0.0, {200, 0, 20}, k.cruise_m_s, k.approach_m_s, k.approach_within_m);
  const Leg first({0, 0, 0}, {200, 0, 20}, k);
  // Mid-leg, at cruise: the new leg is next_leg's from where the first one is then.
  const double t1 = 15;
  const Vec3 at1 = first.position_at(t1);
  fleet.go_to(0, t1, {200, 100, 20}, k.cruise_m_s, k.approach_m_s, k.approach_within_m);
  const Leg second = next_leg(&first, t1, at1, {200, 100, 20}, k);
  EXPECT_GT(second.pieces().front().v0_m_s, 0);
  EXPECT_EQ(fleet.arrival_s(0), t1 + second.duration_s());
  // A hold: it stays where the second leg had it, and no arrival is due.
  const double t2 = t1 + 4;
  fleet.hold(0, t2);
  EXPECT_TRUE(std::isinf(fleet.arrival_s(0)));
  fleet.advance_to(t2 + 30);
  const Vec3 held = second.position_at(4);
  EXPECT_EQ(fleet.report(0).position_m.x, held.x);
  EXPECT_EQ(fleet.report(0).position_m.y, held.y);
  // Home from there at its altitude, then down at the descent speed: landed at home.
  fleet.return_home(0, t2 + 30);
  const double over_home_s = t2 + 30 + Leg(held, {0, 0, held.z}, k).duration_s();
  const double home_s = over_home_s + held.z / k.descent_m_s;
  EXPECT_EQ(fleet.arrival_s(0), home_s);
  fleet.advance_to(over_home_s + 2);
  const VehicleReport down = fleet.report(0);
  EXPECT_FALSE(down.landed_home);
  EXPECT_NEAR(down.position_m.z, held.z - 2 * k.descent_m_s, 1e-9);
  fleet.advance_to(home_s);
  const VehicleReport r = fleet.report(0);
  EXPECT_TRUE(r.landed_home);
  EXPECT_EQ(r.position_m.x, 0);
  EXPECT_EQ(r.position_m.z, 0);
}

TEST(SimulatedFleet, AnExplicitSimulatedFleetIsRunAppsOwnByteForByte) {
  for (const App& app : fleet::builtin_apps()) {
    const std::string kind = fleet::app_world_kind(app.name);
    if (kind == "static") continue;  // its world needs tasks
    const auto world = worlds::parse_world("kind: " + kind + "\nseed: 4\n", "w.yaml");
    const std::vector<DroneSpec> drones{drone_at("a", {}), drone_at("b", {10, 0, 0})};
    RuntimeSettings s;
    s.app_name = app.name;
    s.faults = {{30, 1, FaultKind::link_loss, 8, 0}, {50, 0, FaultKind::sensor_failure, 5, 0}};
    const RunRecord own = run_app(app, *world, drones, s);
    SimulatedFleet fleet(drones, s.layer_base_m, s.layer_step_m);
    s.backend = &fleet;
    const RunRecord given = run_app(app, *world, drones, s);
    EXPECT_EQ(own.events_jsonl, given.events_jsonl) << app.name;
    EXPECT_EQ(own.dtg_json, given.dtg_json) << app.name;
  }
}

}  // namespace
}  // namespace swath::fleet
