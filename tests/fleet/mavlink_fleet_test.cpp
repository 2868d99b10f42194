// swath-fleet's runtime flying two in-process fake ArduCopters over real loopback UDP through
// MavlinkFleet, on a stepped clock (docs/swath-fleet.md): a three-photo
// static app completes with every task done exactly once (the independent event checker), each
// photo taken within the arrival radius of its target at the drone's layer (targets from the world
// file, positions from the fakes' telemetry); lost commands (acknowledgements never sent, some
// commands timed out) still complete; a 10 s link cut of one vehicle in flight is detected, its
// request requeued and served, no task lost, completion later than without the cut; a vehicle
// refusing to arm or GUIDED (three rejections) leaves the fleet with its sentence; one refused in
// the air (a target outside the backend's fence) is still sent home and lands; at the end run_app
// itself has both vehicles return and land at home. Vehicles whose HEARTBEAT names PX4 get the
// PX4 driver (against the fake's PX4 flavour) and a warning that it is untested; a lost-link
// failsafe switched off is warned about and holds nothing back. The --vehicles parser refuses bad
// entries.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/fleet/event_check.hpp"
#include "swath/fleet/mavlink_fleet.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/mavlink/copter_driver.hpp"
#include "swath/mavlink/fake_copter.hpp"
#include "swath/mavlink/px4_driver.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::mavlink {
namespace {

// The adapter is fleet's (fleet -> mavlink); the fakes and drivers it flies are mavlink's.
using fleet::MavlinkFleet;
using fleet::MavlinkFleetSettings;

// Three photos 90–130 m out: legs long enough (≈ 20 s each) for a cut to catch a vehicle flying.
constexpr const char* kWorld = R"(kind: static
origin: {lat: 47.397742, lon: 8.545594}
fence: {width_m: 400, height_m: 400}
sensors: {camera: {time_s: 2.0}}
tasks:
  - {name: north, kind: photo, actions: [{fly_to: {x_m: 10, y_m: 120}}, {sense: camera}]}
  - {name: east, kind: photo, actions: [{fly_to: {x_m: 110, y_m: -20}}, {sense: camera}]}
  - {name: west, kind: photo, actions: [{fly_to: {x_m: -90, y_m: 40}}, {sense: camera}]}
)";
const std::map<std::string, fleet::Vec3> kTargets{
    {"north", {10, 120, 0}}, {"east", {110, -20, 0}}, {"west", {-90, 40, 0}}};

struct Mission {
  std::unique_ptr<worlds::BaseWorld> world = worlds::parse_world(kWorld, "test world");
  std::vector<fleet::DroneSpec> drones;
  std::vector<UdpLink> vehicle_links;
  std::vector<std::unique_ptr<FakeCopter>> fakes;
  std::unique_ptr<MavlinkFleet> backend;
  fleet::RunRecord record;

  // `adjust` changes the backend's settings before it is made.
  explicit Mission(const std::function<void(MavlinkFleetSettings&)>& adjust = {},
                   const std::function<void(FakeCopterSettings&)>& adjust_fakes = {}) {
    const geometry::LocalFrame frame(world->origin);
    std::vector<std::unique_ptr<Link>> gcs_links;
    for (int i = 0; i < 2; ++i) {
      fleet::DroneSpec d;
      d.drone.name = "copter-" + std::to_string(i + 1);
      d.home_m = {3.0 * i, 0, 0};
      d.recharge_s = 5;
      drones.push_back(d);
      vehicle_links.push_back(UdpLink::listen("127.0.0.1", 0));
    }
    for (int i = 0; i < 2; ++i) {
      FakeCopterSettings s;
      const geometry::GeoPoint home = frame.to_geo({drones[i].home_m.x, drones[i].home_m.y});
      s.home_lat_deg = home.lat_deg;
      s.home_lon_deg = home.lon_deg;
      s.sysid = static_cast<std::uint8_t>(i + 1);
      if (adjust_fakes) adjust_fakes(s);
      fakes.push_back(std::make_unique<FakeCopter>(vehicle_links[i], s));
      gcs_links.push_back(
          std::make_unique<UdpLink>(UdpLink::connect("127.0.0.1", vehicle_links[i].local_port())));
    }
    MavlinkFleetSettings settings;
    settings.origin = world->origin;
    settings.fence_m = world->fence();
    settings.before_poll = [this](double t_s) {
      for (auto& f : fakes) f->step(t_s);
    };
    if (adjust) adjust(settings);
    backend = std::make_unique<MavlinkFleet>(std::move(gcs_links), std::vector<std::uint8_t>{1, 2},
                                             settings);
  }

  void run() {
    fleet::RuntimeSettings s;
    s.app_name = "static";
    s.max_time_s = 900;
    s.backend = backend.get();
    fleet::App app;
    for (const fleet::App& a : fleet::builtin_apps())
      if (a.name == "static") app = a;
    record = fleet::run_app(app, *world, drones, s);
    // For a failing run: its events on stderr.
    if (std::getenv("SWATH_DUMP_EVENTS")) std::fputs(record.events_jsonl.c_str(), stderr);
  }

  std::vector<nlohmann::json> events(const std::string& ev) const {
    std::vector<nlohmann::json> out;
    std::istringstream in(record.events_jsonl);
    for (std::string line; std::getline(in, line);) {
      auto e = nlohmann::json::parse(line);
      if (e["ev"] == ev) out.push_back(e);
    }
    return out;
  }

  // Every photo task done exactly once, no result twice (the independent checker), each target
  // sensed once, within the driver's arrival radius (1.5 m) of it at the sensing drone's layer.
  void expect_every_photo_taken_once_at_its_target() const {
    ASSERT_TRUE(record.completed) << record.failure;
    const fleet::EventCheck c = fleet::check_events(record.events_jsonl);
    EXPECT_TRUE(c.ok()) << (c.violations.empty() ? "" : c.violations[0].message);
    EXPECT_EQ(c.terminal.count("task_done") ? c.terminal.at("task_done") : 0, 4);  // main + 3
    EXPECT_EQ(c.terminal.count("task_failed"), 0u);
    EXPECT_EQ(c.terminal.count("task_cancelled"), 0u);
    std::map<std::string, int> sensed;
    for (const auto& e : events("action_done")) {
      if (e["name"] != "camera") continue;
      const int drone = e["drone"];
      const double layer_m = 20 + 5 * drone;
      std::string nearest;
      double off_m = 1e9;
      for (const auto& [name, target] : kTargets) {
        const double d = std::hypot(double(e["x_m"]) - target.x, double(e["y_m"]) - target.y,
                                    double(e["alt_m"]) - layer_m);
        if (d < off_m) off_m = d, nearest = name;
      }
      ++sensed[nearest];
      EXPECT_LE(off_m, 1.5) << nearest << " sensed " << off_m << " m from its target";
    }
    EXPECT_EQ(sensed, (std::map<std::string, int>{{"east", 1}, {"north", 1}, {"west", 1}}));
  }

  // After the run the vehicles go home: run_app returns only once end_run has them landed,
  // disarmed, at their homes (nothing polls the backend after it).
  void expect_both_land_at_home() {
    for (const auto& f : fakes) {
      EXPECT_FALSE(f->armed());
      EXPECT_EQ(f->landed_state(), LandedState::on_ground);
      EXPECT_LT(std::hypot(f->north_m(), f->east_m()), 0.5);
    }
  }
};

int commands_received(const FakeCopter& f) {
  int n = 0;
  for (Cmd c : {Cmd::do_set_mode, Cmd::component_arm_disarm, Cmd::nav_takeoff, Cmd::do_change_speed,
                Cmd::nav_return_to_launch, Cmd::nav_land, Cmd::set_message_interval,
                Cmd::request_message, Cmd::image_start_capture})
    n += f.commands_received(c);
  return n;
}

TEST(MavlinkFleet, TwoFakeCoptersFlyAThreePhotoAppThroughTheRuntime) {
  Mission m;
  m.run();
  m.expect_every_photo_taken_once_at_its_target();
  // One photo command per sense, nothing lost on loopback.
  EXPECT_EQ(m.fakes[0]->images_taken() + m.fakes[1]->images_taken(), 3);
  // Both flew: take-off to their layers in GUIDED, the speed rule (cruise, then approach).
  for (const auto& f : m.fakes) {
    EXPECT_EQ(f->commands_received(Cmd::nav_takeoff), 1);
    EXPECT_GE(f->commands_received(Cmd::do_change_speed), 2);
  }
  EXPECT_TRUE(m.events("link_lost").empty());
  m.expect_both_land_at_home();
}

TEST(MavlinkFleet, LostAcknowledgementsAreResentOrReissuedAndTheAppCompletes) {
  Mission m;
  // copter-1 loses its first 16 commands (the link-up requests, their resends and GUIDED's: some
  // time out after 3 sends and the steering issues them again), copter-2 its first 2.
  m.fakes[0]->lose_commands(16);
  m.fakes[1]->lose_commands(2);
  m.run();
  m.expect_every_photo_taken_once_at_its_target();
  for (int i = 0; i < 2; ++i)  // the sends the fakes never saw are exactly the ones they lost
    EXPECT_EQ(static_cast<int>(m.backend->driver(i)->commands_sent()) -
                  commands_received(*m.fakes[static_cast<std::size_t>(i)]),
              i == 0 ? 16 : 2);
  m.expect_both_land_at_home();
}

TEST(MavlinkFleet, TenSecondLinkCutLosesNoTaskAndDelaysCompletion) {
  Mission plain;
  plain.run();
  ASSERT_TRUE(plain.record.completed);

  Mission m;
  // copter-2 is on its way to its first photo, at its layer (it took off at 12.6 s, once copter-1,
  // 3 m away, had climbed clear: the separation rule)
  const double cut_s = 25;
  m.fakes[1]->cut_link(cut_s, cut_s + 10);
  m.run();
  m.expect_every_photo_taken_once_at_its_target();
  const auto lost = m.events("link_lost");
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost[0]["drone"], 1);
  // Declared lost 2–3 s after the cut (its last heartbeat up to 1 s before), then back once the
  // cut ends.
  EXPECT_GT(double(lost[0]["t_s"]), cut_s + 2.0);
  EXPECT_LE(double(lost[0]["t_s"]), cut_s + 3.0 + 0.2);
  // Up when first heard (both), and copter-2 again once the cut ends.
  const auto up = m.events("link_up");
  ASSERT_EQ(up.size(), 3u);
  EXPECT_EQ(up[2]["drone"], 1);
  EXPECT_GE(double(up[2]["t_s"]), cut_s + 10);
  // Its request was requeued and then served (by whichever drone): done once, above.
  int requeued_task = -1;
  for (const auto& e : m.events("requeued"))
    if (e["drone"] == 1 && e["reason"] == "link_loss") requeued_task = e["task"];
  ASSERT_GE(requeued_task, 1);
  bool served_after = false;
  for (const auto& e : m.events("action_done"))
    if (e["task"] == requeued_task && e["name"] == "camera" &&
        double(e["t_s"]) > double(lost[0]["t_s"]))
      served_after = true;
  EXPECT_TRUE(served_after);
  // The vehicle's own failsafe (RTL after 5 s without the ground station) took it home: no RTL
  // command reached it, yet the runtime saw it land (charging) after the link came back.
  EXPECT_EQ(m.fakes[1]->commands_received(Cmd::nav_return_to_launch), 0);
  bool landed_after = false;
  for (const auto& e : m.events("drone_mode"))
    if (e["drone"] == 1 && e["state"] == "charging" && double(e["t_s"]) > double(up[2]["t_s"]))
      landed_after = true;
  EXPECT_TRUE(landed_after);
  EXPECT_GE(m.record.completion_time_s, plain.record.completion_time_s + 1.0);
  m.expect_both_land_at_home();
}

// ArduCopter's GUIDED flies a leg at the speed limit in force when its target arrived; a
// DO_CHANGE_SPEED mid-leg sets only the next leg's (ModeGuided::set_speed_xy_cms). Fakes doing
// the same fly the approach's last 20 m at cruise, so they complete no later than fakes that
// slow to 2 m/s there — unless a leg is planned at the previous leg's approach speed: with every
// DO_CHANGE_SPEED's first send lost, a cruise speed sent beside the target arrives after it (the
// second photo's 100+ m leg then flew at 2 m/s); answered before the target goes, it does not.
TEST(MavlinkFleet, EveryLegFliesAtCruiseOnAVehicleThatSetsItsSpeedPerLeg) {
  Mission plain;
  plain.run();
  plain.expect_every_photo_taken_once_at_its_target();
  Mission per_leg({}, [](FakeCopterSettings& s) { s.speed_per_leg = true; });
  for (auto& f : per_leg.fakes) f->lose_first_sends(Cmd::do_change_speed);
  per_leg.run();
  per_leg.expect_every_photo_taken_once_at_its_target();
  // One drone took two photos: it flew a leg after an approach.
  std::map<int, int> photos_by_drone;
  for (const auto& e : per_leg.events("action_done"))
    if (e["name"] == "camera") ++photos_by_drone[int(e["drone"])];
  EXPECT_EQ(std::max(photos_by_drone[0], photos_by_drone[1]), 2);
  EXPECT_LE(per_leg.record.completion_time_s, plain.record.completion_time_s + 0.5);
  per_leg.expect_both_land_at_home();
}

TEST(MavlinkFleet, AVehicleRefusingToArmLeavesTheFleetWithItsSentence) {
  Mission m;
  m.fakes[0]->refuse_arm("PreArm: Compass not calibrated");
  m.run();
  m.expect_every_photo_taken_once_at_its_target();
  const auto refused = m.events("vehicle_refused");
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused[0]["drone"], 0);
  EXPECT_EQ(refused[0]["reason"], "refused to arm: PreArm: Compass not calibrated");
  for (const auto& e : m.events("action_done")) EXPECT_EQ(e["drone"], 1);  // copter-2 did all
  EXPECT_EQ(m.fakes[0]->images_taken(), 0);
  EXPECT_EQ(m.fakes[1]->images_taken(), 3);
}

TEST(MavlinkFleet, APreArmCheckThatClearsOnItsOwnDelaysTheVehicleAndKeepsIt) {
  // ArduCopter SITL refused an arm 23 s after boot ("Need Position Estimate") and armed at 41 s:
  // a vehicle refusing to arm for 20 s is asked again every 2 s and flies once it accepts.
  Mission m;
  m.fakes[0]->refuse_arm("PreArm: Need Position Estimate", 20.0);
  m.run();
  m.expect_every_photo_taken_once_at_its_target();
  EXPECT_TRUE(m.events("vehicle_refused").empty());
  const int arms = m.fakes[0]->commands_received(Cmd::component_arm_disarm);
  EXPECT_GE(arms, 5);   // refused at ~0, 2, .. 18 s, then accepted (and disarm at the end)
  EXPECT_LE(arms, 14);  // not at every 0.1 s poll
  EXPECT_GE(m.fakes[0]->commands_received(Cmd::nav_takeoff), 1);  // it flew
  m.expect_both_land_at_home();
}

TEST(MavlinkFleet, AVehicleRefusingGuidedIsRefusedAfterThreeRejectionsWithItsSentence) {
  Mission m;
  m.fakes[0]->refuse_mode(CopterMode::guided, "Flight mode change failed");
  m.run();
  m.expect_every_photo_taken_once_at_its_target();
  const auto refused = m.events("vehicle_refused");
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused[0]["drone"], 0);
  EXPECT_EQ(refused[0]["reason"], "refused GUIDED: Flight mode change failed");
  EXPECT_EQ(m.fakes[0]->commands_received(Cmd::do_set_mode), 3);  // then no more retries
  EXPECT_EQ(m.fakes[0]->commands_received(Cmd::component_arm_disarm), 0);
  EXPECT_EQ(m.fakes[0]->images_taken(), 0);
  EXPECT_EQ(m.fakes[1]->images_taken(), 3);
  m.expect_both_land_at_home();
}

TEST(MavlinkFleet, AVehicleRefusedInTheAirIsStillSentHomeAndLands) {
  // The backend's fence leaves out the west photo (x = -90 m): a drone sent there is refused at
  // its layer, after take-off. end_run is given no time, so only the runtime's own return_home
  // at the refusal can bring it back before run_app returns.
  Mission m([](MavlinkFleetSettings& s) {
    s.fence_m = {{-50, -200}, {200, -200}, {200, 200}, {-50, 200}};
    s.end_timeout_s = 0;
  });
  m.run();
  const auto refused = m.events("vehicle_refused");
  ASSERT_GE(refused.size(), 1u);
  int refused_in_the_air = 0;
  for (const auto& e : refused) {
    EXPECT_EQ(e["reason"], "target outside the fence");
    const FakeCopter& f = *m.fakes[static_cast<std::size_t>(int(e["drone"]))];
    // Refused on the ground, it never took off (nothing was sent for that target); refused in
    // the air (after a photo inside the fence), it was told to return.
    if (f.commands_received(Cmd::nav_takeoff) >= 1) {
      ++refused_in_the_air;
      EXPECT_GE(f.commands_received(Cmd::nav_return_to_launch), 1);
    }
    EXPECT_FALSE(f.armed());
    EXPECT_EQ(f.landed_state(), LandedState::on_ground);
    EXPECT_LT(std::hypot(f.north_m(), f.east_m()), 0.5);
  }
  (void)refused_in_the_air;  // which case comes is the scheduler's (both seen in the tests)
  // The west photo was never taken outside the fence.
  for (const auto& e : m.events("action_done"))
    if (e["name"] == "camera") {
      EXPECT_GT(double(e["x_m"]), -50.0);
    }
}

// The world's fence (a 400 m square about the origin) goes to both vehicles before they arm:
// stored by each fake as four inclusion vertices at the square's corners (computed here from the
// world's text), read back equal, and enabled (FENCE_ENABLE 1, FENCE_TYPE keeping its polygon bit).
TEST(MavlinkFleet, TheWorldsFenceIsUploadedReadBackAndEnabledOnEveryVehicle) {
  Mission m;
  m.run();
  m.expect_every_photo_taken_once_at_its_target();
  const geometry::LocalFrame frame(m.world->origin);
  const double corners[4][2] = {{-200, -200}, {200, -200}, {200, 200}, {-200, 200}};
  for (const auto& f : m.fakes) {
    const std::vector<MissionItemInt>& items = f->fence_items();
    ASSERT_EQ(items.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
      const geometry::GeoPoint g = frame.to_geo({corners[i][0], corners[i][1]});
      EXPECT_EQ(items[i].command,
                static_cast<std::uint16_t>(Cmd::nav_fence_polygon_vertex_inclusion));
      EXPECT_EQ(items[i].param1, 4.0f);
      EXPECT_NEAR(items[i].x / 1e7, g.lat_deg, 1e-7);
      EXPECT_NEAR(items[i].y / 1e7, g.lon_deg, 1e-7);
    }
    EXPECT_EQ(f->param("FENCE_ENABLE"), 1);
    EXPECT_EQ(int(f->param("FENCE_TYPE")) & 4, 4);
  }
  for (int i = 0; i < 2; ++i) EXPECT_EQ(m.backend->driver(i)->fence_state(), FenceState::verified);
}

// A vehicle that stores one vertex elsewhere (the read-back shows it) is refused with the
// difference in its sentence and never armed; the other flies every task.
TEST(MavlinkFleet, AVehicleWhoseFenceReadsBackDifferentIsRefusedAndNeverArms) {
  Mission m;
  m.fakes[0]->corrupt_fence_vertex(2);
  m.run();
  const auto refused = m.events("vehicle_refused");
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused[0]["drone"], 0);
  const std::string why = refused[0]["reason"];
  EXPECT_EQ(why.rfind("its fence was not verified (the fence read back differs from the one sent: "
                      "item 2 (MAV_CMD 5001) reads back at ",
                      0),
            0u)
      << why;
  EXPECT_EQ(m.fakes[0]->commands_received(Cmd::component_arm_disarm), 0);
  EXPECT_EQ(m.fakes[0]->commands_received(Cmd::nav_takeoff), 0);
  EXPECT_FALSE(m.fakes[0]->armed());
  EXPECT_EQ(m.backend->report(0).refusal, why);
  ASSERT_TRUE(m.record.completed) << m.record.failure;  // copter-2 took all three photos
  for (const auto& e : m.events("action_done"))
    if (e["name"] == "camera") EXPECT_EQ(e["drone"], 1);
}

// A target outside the fence is refused when it is given: no mode, arm, take-off or position
// target is ever sent to the vehicle for it.
TEST(MavlinkFleet, ATargetOutsideTheFenceIsRefusedBeforeAnyCommandGoesOut) {
  Mission m;
  m.backend->go_to(0, 0, {300, 0, 20}, 10, 2, 20);  // the fence's east side is at x = 200 m
  m.backend->advance_to(15);
  EXPECT_EQ(m.backend->report(0).refusal, "target outside the fence");
  const FakeCopter& f = *m.fakes[0];
  for (Cmd c :
       {Cmd::do_set_mode, Cmd::component_arm_disarm, Cmd::nav_takeoff, Cmd::do_change_speed})
    EXPECT_EQ(f.commands_received(c), 0) << static_cast<int>(c);
  EXPECT_EQ(f.position_targets_received(), 0);
  EXPECT_FALSE(f.armed());
  EXPECT_EQ(f.fence_items().size(), 4u);  // the fence itself went up meanwhile
  // The same call inside the fence flies (the refusal was the place's, not the vehicle's).
  m.backend->go_to(1, 15, {100, 0, 25}, 10, 2, 20);
  m.backend->advance_to(60);
  EXPECT_TRUE(m.backend->report(1).refusal.empty());
  ASSERT_TRUE(m.backend->report(1).arrived);
  // In the air, an outside target is refused as well: no new target goes out; sent home (what
  // the runtime does on a refusal) it returns and lands.
  const int targets = m.fakes[1]->position_targets_received();
  m.backend->go_to(1, 60, {100, 250, 25}, 10, 2, 20);
  m.backend->advance_to(65);
  EXPECT_EQ(m.backend->report(1).refusal, "target outside the fence");
  EXPECT_EQ(m.fakes[1]->position_targets_received(), targets);
  m.backend->return_home(1, 65);
  m.backend->advance_to(140);
  EXPECT_GE(m.fakes[1]->commands_received(Cmd::nav_return_to_launch), 1);
  EXPECT_FALSE(m.fakes[1]->armed());
  EXPECT_LT(std::hypot(m.fakes[1]->north_m(), m.fakes[1]->east_m()), 0.5);
}

// The driver is chosen by the autopilot the vehicle's HEARTBEAT names: two fakes in their PX4
// flavour (autopilot 12) are flown by the PX4 driver (Hold, NAV_TAKEOFF, DO_REPOSITION), the app
// completes as with ArduCopters, and each vehicle is announced once as flown by an untested
// driver. (Our reading of PX4's documents against itself, not PX4.)
TEST(MavlinkFleet, VehiclesNamingPx4AreFlownByThePx4DriverAndSaidUntested) {
  std::vector<std::pair<int, std::string>> warnings;
  Mission m(
      [&](MavlinkFleetSettings& s) {
        s.warn = [&](int drone, const std::string& text) { warnings.emplace_back(drone, text); };
      },
      [](FakeCopterSettings& s) { s.autopilot = FakeAutopilot::px4; });
  m.run();
  m.expect_every_photo_taken_once_at_its_target();
  for (int i = 0; i < 2; ++i) {
    ASSERT_NE(dynamic_cast<const Px4Driver*>(m.backend->driver(i)), nullptr);
    const FakeCopter& f = *m.fakes[static_cast<std::size_t>(i)];
    EXPECT_EQ(f.commands_received(Cmd::nav_takeoff), 1);
    EXPECT_GE(f.commands_received(Cmd::do_reposition), 1);
    EXPECT_EQ(f.position_targets_received(), f.commands_received(Cmd::do_reposition));
  }
  ASSERT_EQ(warnings.size(), 2u);  // NAV_DLL_ACT 2 (Return): no safety warning
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(warnings[static_cast<std::size_t>(i)].first, i);
    EXPECT_NE(warnings[static_cast<std::size_t>(i)].second.find("untested on PX4"),
              std::string::npos);
  }
  m.expect_both_land_at_home();
}

// With --allow-no-gcs-failsafe the safety check does not hold the mission back: ArduCopters with
// FS_GCS_ENABLE 0 fly the app as the others do, each reported once (without it they are refused:
// abort_test.cpp).
TEST(MavlinkFleet, AFailsafeOffIsReportedOnceAndTheAppStillCompletes) {
  std::vector<std::pair<int, std::string>> warnings;
  Mission m(
      [&](MavlinkFleetSettings& s) {
        s.warn = [&](int drone, const std::string& text) { warnings.emplace_back(drone, text); };
        s.allow_no_gcs_failsafe = true;
      },
      [](FakeCopterSettings& s) { s.params["FS_GCS_ENABLE"] = 0; });
  m.run();
  m.expect_every_photo_taken_once_at_its_target();
  ASSERT_NE(dynamic_cast<const CopterDriver*>(m.backend->driver(0)), nullptr);
  std::map<int, int> per_drone;
  for (const auto& [drone, text] : warnings) {
    ++per_drone[drone];
    EXPECT_EQ(text,
              "FS_GCS_ENABLE is 0: ArduCopter will not return to launch when the link is lost");
  }
  EXPECT_EQ(per_drone, (std::map<int, int>{{0, 1}, {1, 1}}));
  m.expect_both_land_at_home();
}

TEST(MavlinkFleet, VehicleUrlsAreParsedAndBadOnesRefusedInOneSentence) {
  const auto v = fleet::parse_vehicle_addresses("udp:0.0.0.0:14550,tcp:127.0.0.1:5770/7");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_FALSE(v[0].tcp);
  EXPECT_EQ(v[0].host, "0.0.0.0");
  EXPECT_EQ(v[0].port, 14550);
  EXPECT_EQ(v[0].sysid, 1);
  EXPECT_TRUE(v[1].tcp);
  EXPECT_EQ(v[1].port, 5770);
  EXPECT_EQ(v[1].sysid, 7);
  for (const char* bad : {"", "serial:/dev/ttyUSB0", "udp:14550", "udp:h:0", "udp:h:70000",
                          "tcp:h:5760/0", "tcp:h:5760/x", "udp:h:1x"})
    EXPECT_THROW(fleet::parse_vehicle_addresses(bad), base::InputError) << bad;
}

}  // namespace
}  // namespace swath::mavlink
