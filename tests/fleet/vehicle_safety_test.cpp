// The vehicles' safety over MAVLink (docs/swath-fleet.md, "Abort and control"). An abort
// (docs/swath-fleet.md, "Abort and control"): two in-process fake ArduCopters on loopback UDP flown
// by MavlinkFleet on a stepped clock; mid-mission an order from the control source (what SIGINT
// becomes), or an exception escaping the run, aborts it. Truth is the vehicles' side: every vehicle
// in the air received MAV_CMD_NAV_RETURN_TO_LAUNCH (or NAV_LAND) and flies in RTL (LAND) when
// run_app returns; the log has the aborted event, an abort_command per airborne drone and ends with
// run_end, every rule of the event checker holding. No take-off with the GCS failsafe read as off.
// The ground station's heartbeat goes on while the app's compute() holds the runtime's thread for 4
// s (a fake on the wall clock in its own thread counts the gaps).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "swath/fleet/apps.hpp"
#include "swath/fleet/event_check.hpp"
#include "swath/fleet/mavlink_fleet.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/mavlink/fake_copter.hpp"
#include "swath/mavlink/signing_link.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::mavlink::vehicle_safety {
namespace {

// Photos 90–130 m out: at 15 s both vehicles are climbing or on their way.
constexpr const char* kWorld = R"(kind: static
origin: {lat: 47.397742, lon: 8.545594}
fence: {width_m: 400, height_m: 400}
sensors: {camera: {time_s: 2.0}}
tasks:
  - {name: north, kind: photo, actions: [{fly_to: {x_m: 10, y_m: 120}}, {sense: camera}]}
  - {name: east, kind: photo, actions: [{fly_to: {x_m: 110, y_m: -20}}, {sense: camera}]}
)";

struct AbortedMission {
  std::unique_ptr<worlds::BaseWorld> world = worlds::parse_world(kWorld, "test world");
  std::vector<fleet::DroneSpec> drones;
  std::vector<UdpLink> vehicle_links;
  std::vector<std::unique_ptr<Link>> signing_links;  // the fakes' own, when they sign
  std::function<bool()> stop_waiting;                // the backend's, at the end of the run
  std::vector<std::unique_ptr<FakeCopter>> fakes;
  std::unique_ptr<fleet::MavlinkFleet> backend;
  fleet::RunRecord record;

  // The fakes' failsafe parameter and battery drain; the keys the fleet and the fakes sign with
  // (none: unsigned).
  explicit AbortedMission(double fs_gcs_enable = 1, double drain_percent_s = 0.05,
                          std::optional<SigningKey> fleet_key = {},
                          std::optional<SigningKey> vehicle_key = {}) {
    const geometry::LocalFrame frame(world->origin);
    std::vector<std::unique_ptr<Link>> gcs_links;
    for (int i = 0; i < 2; ++i) {
      fleet::DroneSpec d;
      d.drone.name = "copter-" + std::to_string(i + 1);
      d.home_m = {3.0 * i, 0, 0};
      drones.push_back(d);
      vehicle_links.push_back(UdpLink::listen("127.0.0.1", 0));
    }
    for (int i = 0; i < 2; ++i) {
      FakeCopterSettings s;
      const geometry::GeoPoint home = frame.to_geo({drones[i].home_m.x, drones[i].home_m.y});
      s.home_lat_deg = home.lat_deg;
      s.home_lon_deg = home.lon_deg;
      s.sysid = static_cast<std::uint8_t>(i + 1);
      s.params["FS_GCS_ENABLE"] = fs_gcs_enable;
      s.battery_drain_percent_s = drain_percent_s;
      gcs_links.push_back(
          std::make_unique<UdpLink>(UdpLink::connect("127.0.0.1", vehicle_links[i].local_port())));
      Link* fake_link = &vehicle_links[i];
      if (vehicle_key) {
        signing_links.push_back(
            std::make_unique<SigningLink>(std::make_unique<UdpLink>(std::move(vehicle_links[i])),
                                          *vehicle_key, static_cast<std::uint8_t>(10 + i)));
        fake_link = signing_links.back().get();
      }
      fakes.push_back(std::make_unique<FakeCopter>(*fake_link, s));
    }
    fleet::MavlinkFleetSettings settings;
    settings.origin = world->origin;
    settings.fence_m = world->fence();
    settings.before_poll = [this](double t_s) {
      for (auto& f : fakes) f->step(t_s);
    };
    settings.warn = [](int, const std::string&) {};
    settings.signing_key = fleet_key;
    settings.stop_waiting = [this] { return stop_waiting && stop_waiting(); };
    backend = std::make_unique<fleet::MavlinkFleet>(std::move(gcs_links),
                                                    std::vector<std::uint8_t>{1, 2}, settings);
  }

  // Runs the static app; `control` is polled by the runtime.
  void run(fleet::ControlSource control, fleet::AbortAction on_abort = fleet::AbortAction::rtl) {
    fleet::RuntimeSettings s;
    s.app_name = "static";
    s.max_time_s = 900;
    s.backend = backend.get();
    s.control = std::move(control);
    s.on_abort = on_abort;
    fleet::App app;
    for (const fleet::App& a : fleet::builtin_apps())
      if (a.name == "static") app = a;
    record = fleet::run_app(app, *world, drones, s);
  }

  std::vector<nlohmann::json> events() const {
    std::vector<nlohmann::json> out;
    std::istringstream in(record.events_jsonl);
    for (std::string line; std::getline(in, line);) out.push_back(nlohmann::json::parse(line));
    return out;
  }

  // The vehicles' truth and the log agree: every vehicle in the air got the command and is in
  // the mode; the log is complete.
  void expect_aborted(const std::string& reason, Cmd command, CopterMode mode) {
    EXPECT_FALSE(record.completed);
    EXPECT_EQ(record.aborted, reason);
    int airborne = 0;
    for (const auto& f : fakes) {
      if (f->altitude_m() < 0.5 && !f->armed()) continue;
      ++airborne;
      EXPECT_GE(f->commands_received(command), 1);
      // A vehicle near home ends its RTL descending in LAND (the FakeCopter as ArduCopter).
      if (!(mode == CopterMode::rtl && f->mode() == CopterMode::land)) EXPECT_EQ(f->mode(), mode);
    }
    EXPECT_EQ(airborne, 2) << "both vehicles should be flying when the abort comes";
    const std::vector<nlohmann::json> e = events();
    int aborted = 0, commanded = 0;
    for (const auto& x : e) {
      aborted += x["ev"] == "aborted";
      commanded += x["ev"] == "abort_command";
    }
    EXPECT_EQ(aborted, 1);
    EXPECT_EQ(commanded, 2);
    ASSERT_FALSE(e.empty());
    EXPECT_EQ(e.back()["ev"], "run_end");
    const fleet::EventCheck c = fleet::check_events(record.events_jsonl);
    EXPECT_TRUE(c.ok()) << (c.violations.empty() ? "" : c.violations[0].message);
  }
};

// When the aborts below come: both vehicles in the air (copter-2, 3 m from copter-1's home, takes
// off at ~12.7 s, once copter-1's climb is clear of it by the separation; at 15 s it was still
// arming on the ground, where no RTL is sent).
constexpr double kAbortAt_s = 25;

// What SIGINT becomes in `swath-fleet run` (RunControl): one rtl_all from the control source.
fleet::ControlSource order_at(const fleet::MavlinkFleet& backend, double t_s,
                              fleet::ControlOrder order, const std::string& reason) {
  return [&backend, t_s, order, reason, given = false]() mutable {
    if (given || backend.now_s() < t_s) return fleet::ControlRequest{};
    given = true;
    return fleet::ControlRequest{order, reason};
  };
}

TEST(FleetAbort, AnAbortMidMissionPutsEveryFlyingFakeCopterInRtl) {
  AbortedMission m;
  m.run(order_at(*m.backend, kAbortAt_s, fleet::ControlOrder::rtl_all, "SIGINT"));
  m.expect_aborted("SIGINT", Cmd::nav_return_to_launch, CopterMode::rtl);
  EXPECT_FALSE(m.record.aborted_by_error);
}

TEST(FleetAbort, LandAllPutsEveryFlyingFakeCopterInLand) {
  AbortedMission m;
  m.run(order_at(*m.backend, kAbortAt_s, fleet::ControlOrder::land_all, "ctl land-all"));
  m.expect_aborted("ctl land-all", Cmd::nav_land, CopterMode::land);
}

// An abort that finds a vehicle armed but still on the ground (copter-2 between its arm and its
// take-off; the order comes the first time the fake itself is armed on the ground) disarms it:
// no RTL, which would first climb to its return altitude, and it never leaves the ground. The
// vehicle in the air (copter-1) is told to return as before; the log is complete.
TEST(FleetAbort, AVehicleArmedOnTheGroundAtTheAbortIsDisarmedNotSentToRtl) {
  AbortedMission m;
  bool given = false;
  m.run([&]() -> fleet::ControlRequest {
    const FakeCopter& waiting = *m.fakes[1];
    if (given || !waiting.armed() || waiting.landed_state() != LandedState::on_ground) return {};
    given = true;
    return {fleet::ControlOrder::rtl_all, "SIGINT"};
  });
  ASSERT_TRUE(given) << "copter-2 was never armed on the ground";
  const FakeCopter& ground = *m.fakes[1];
  EXPECT_FALSE(ground.armed());
  EXPECT_EQ(ground.commands_received(Cmd::nav_return_to_launch), 0);
  EXPECT_EQ(ground.commands_received(Cmd::nav_takeoff), 0);
  EXPECT_EQ(ground.commands_received(Cmd::component_arm_disarm), 2);  // arm, then disarm
  EXPECT_EQ(ground.altitude_m(), 0);
  const FakeCopter& air = *m.fakes[0];
  EXPECT_GE(air.commands_received(Cmd::nav_return_to_launch), 1);
  EXPECT_TRUE(air.mode() == CopterMode::rtl || air.mode() == CopterMode::land);
  int commanded = 0;
  for (const auto& e : m.events()) commanded += e["ev"] == "abort_command";
  EXPECT_EQ(commanded, 2);
  EXPECT_EQ(m.events().back()["ev"], "run_end");
  const fleet::EventCheck c = fleet::check_events(m.record.events_jsonl);
  EXPECT_TRUE(c.ok()) << (c.violations.empty() ? "" : c.violations[0].message);
}

// An exception escaping the run's loop (here thrown by the control source itself) aborts the run
// with settings.on_abort: the vehicles are told, the record is complete and says why.
TEST(FleetAbort, AnExceptionEscapingTheRunStillSendsEveryVehicleHome) {
  AbortedMission m;
  const fleet::MavlinkFleet& b = *m.backend;
  m.run([&b]() -> fleet::ControlRequest {
    if (b.now_s() >= kAbortAt_s) throw std::runtime_error("planted failure");
    return {};
  });
  m.expect_aborted("exception: planted failure", Cmd::nav_return_to_launch, CopterMode::rtl);
  EXPECT_TRUE(m.record.aborted_by_error);
}

// No take-off with the GCS failsafe off: FS_GCS_ENABLE read as 0 from each fake (PARAM_VALUE)
// refuses both vehicles before they arm; read as 1 they fly (the tests above).
TEST(FleetGcsFailsafe, VehiclesWithFsGcsEnableZeroAreRefusedAndNeverTakeOff) {
  AbortedMission m(0);
  m.run({});
  int refused = 0;
  for (const auto& e : m.events())
    if (e["ev"] == "vehicle_refused") {
      ++refused;
      EXPECT_NE(e["reason"].get<std::string>().find("FS_GCS_ENABLE is 0"), std::string::npos)
          << e.dump();
    }
  EXPECT_EQ(refused, 2);
  EXPECT_EQ(m.record.tasks_by_outcome.count("done") ? m.record.tasks_by_outcome.at("done") : 0,
            m.record.completed ? 1 : 0)
      << "no photo task can be done without a vehicle";
  for (const auto& f : m.fakes) {
    EXPECT_GE(f->param_requests_received(), 1);  // read from the vehicle
    EXPECT_EQ(f->commands_received(Cmd::component_arm_disarm), 0);
    EXPECT_EQ(f->commands_received(Cmd::nav_takeoff), 0);
    EXPECT_FALSE(f->armed());
  }
}

TEST(FleetGcsFailsafe, VehiclesWithFsGcsEnableOneTakeOffAndComplete) {
  AbortedMission m(1);
  m.run({});
  EXPECT_TRUE(m.record.completed) << m.record.failure;
  for (const auto& f : m.fakes) EXPECT_GE(f->param_requests_received(), 1);
}

// A signal while the run waits for the vehicles to land at its end (stop_waiting: what `swath-fleet
// run` sets from its signal handler's note) ends the wait at once: the vehicles were told to return
// and go on in RTL on their own. Without it the same run waits until both have landed (the
// MavlinkFleet tests).
TEST(FleetAbort, ASignalDuringTheFinalWaitEndsItWithTheVehiclesInRtl) {
  AbortedMission m;
  m.stop_waiting = [] { return true; };
  m.run({});
  EXPECT_TRUE(m.record.completed) << m.record.failure;
  int in_rtl = 0;
  for (const auto& f : m.fakes) in_rtl += f->armed() && f->mode() == CopterMode::rtl;
  EXPECT_EQ(in_rtl, 2) << "both told to return and still on their way when the wait ended";
}

// The vehicles' battery is theirs, not the model's: fakes draining 3 % a second while armed report
// it in BATTERY_STATUS; the runtime's charge follows the report (whole percents, falling below
// half) and sends drones home for their battery (the only reason to return in this run: no fault,
// no link lost). With the model alone the two short photo legs never come near the reserve.
TEST(FleetBattery, AFallingBatteryStatusSendsTheDroneHome) {
  AbortedMission m(1, 3.0);
  m.run({});
  int returns = 0, reports_below_half = 0, links_lost = 0;
  for (const auto& e : m.events()) {
    if (e["ev"] == "drone_mode" && e["state"] == "returning") ++returns;
    if (e["ev"] == "link_lost") ++links_lost;
    if (e["ev"] == "drone_state" && e["state"] != "landed" && e["state"] != "charging") {
      const double soc = e["soc"];
      EXPECT_NEAR(soc * 100, std::round(soc * 100), 1e-6) << "a reported percent: " << e.dump();
      reports_below_half += soc < 0.5;
    }
  }
  EXPECT_EQ(links_lost, 0);
  EXPECT_GE(returns, 1);
  EXPECT_GE(reports_below_half, 1);
}

// MAVLink 2 signing through the backend: fakes that sign with the fleet's key fly the mission;
// unsigned fakes, or fakes with another key, are never heard (their frames refused), so nothing
// flies. (Frame-level refusals of wrong signatures and replays: tests/mavlink/signing_test.cpp.)
SigningKey key_of(std::uint8_t first) {
  SigningKey k;
  for (std::size_t i = 0; i < k.secret.size(); ++i)
    k.secret[i] = static_cast<std::uint8_t>(first + 7 * i);
  return k;
}

TEST(FleetSigning, FakesSigningWithTheFleetsKeyFlyTheMission) {
  AbortedMission m(1, 0.05, key_of(1), key_of(1));
  m.run({});
  EXPECT_TRUE(m.record.completed) << m.record.failure;
  for (const auto& f : m.fakes) EXPECT_GE(f->commands_received(Cmd::nav_takeoff), 1);
  for (const auto& l : m.signing_links) {
    const auto& c = dynamic_cast<const SigningLink&>(*l).counts();
    EXPECT_GT(c.accepted, 10u);
    EXPECT_EQ(c.refused_unsigned + c.refused_signature + c.refused_replay, 0u);
  }
}

TEST(FleetSigning, UnsignedFakesOrAnotherKeyAreNeverHeard) {
  for (const bool other_key : {false, true}) {
    AbortedMission m(1, 0.05, key_of(1),
                     other_key ? std::optional<SigningKey>(key_of(2)) : std::nullopt);
    m.run({});
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(m.backend->driver(i), nullptr) << "vehicle " << i << " was heard";
      EXPECT_EQ(m.fakes[static_cast<std::size_t>(i)]->commands_received(Cmd::nav_takeoff), 0);
    }
  }
}

// The app's main computes for 4 s of wall time on the runtime's thread; the fake, stepped on the
// wall clock by a thread of its own, must hear the ground station at least every 1.5 s.
fleet::Co<void> compute_four_seconds(fleet::Ctx& c) {
  co_await c.compute(
      [] {
        std::this_thread::sleep_for(std::chrono::seconds(4));
        return 0;
      },
      0.1);
}

TEST(FleetHeartbeat, AComputeHoldingTheRuntimeFourSecondsDoesNotSilenceTheGcsHeartbeat) {
  const geometry::GeoPoint origin{47.397742, 8.545594};
  UdpLink vehicle_link = UdpLink::listen("127.0.0.1", 0);
  FakeCopterSettings fs;
  fs.home_lat_deg = origin.lat_deg;
  fs.home_lon_deg = origin.lon_deg;
  FakeCopter fake(vehicle_link, fs);
  std::atomic<bool> stop{false};
  const auto start = std::chrono::steady_clock::now();
  std::thread vehicle([&] {
    while (!stop) {
      fake.step(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  {
    std::vector<std::unique_ptr<Link>> links;
    links.push_back(
        std::make_unique<UdpLink>(UdpLink::connect("127.0.0.1", vehicle_link.local_port())));
    fleet::MavlinkFleetSettings settings;
    settings.origin = origin;
    settings.wall_clock = true;
    settings.end_timeout_s = 2;
    settings.warn = [](int, const std::string&) {};
    fleet::MavlinkFleet backend(std::move(links), {1}, settings);
    fleet::DroneSpec d;
    d.drone.name = "copter-1";
    fleet::RuntimeSettings s;
    s.app_name = "compute";
    s.max_time_s = 60;
    s.backend = &backend;
    const auto world = worlds::parse_world(kWorld, "test world");
    const fleet::App app{"compute", "4 s of compute()", compute_four_seconds};
    const fleet::RunRecord r = fleet::run_app(app, *world, {d}, s);
    EXPECT_TRUE(r.completed) << r.failure;
  }
  stop = true;
  vehicle.join();
  EXPECT_GE(fake.gcs_heartbeats_received(), 4);
  EXPECT_LE(fake.longest_gcs_silence_s(), 1.5);
  RecordProperty("longest_gcs_silence_ms",
                 static_cast<int>(std::lround(fake.longest_gcs_silence_s() * 1000)));
}

}  // namespace
}  // namespace swath::mavlink::vehicle_safety
