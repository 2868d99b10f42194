// The ArduCopter driver against the fake ArduCopter over real loopback UDP sockets, on a simulated
// clock (docs/swath-fleet.md): connect and telemetry, arm, take-off, go-to and arrival
// checked against the fake's own position; lost commands resent and counted; a refusal to arm
// with its sentence; a 10 s link cut (lost after 3 s, the vehicle's failsafe, the flight resumed);
// the fence; return, landing and photos; the safety check at connect (FS_GCS_ENABLE). The PX4
// driver against the fake's PX4 flavour (our reading of PX4's documents, not PX4): Hold, arm,
// take-off above sea level, DO_REPOSITION, lost acknowledgements, modes, NAV_DLL_ACT.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <functional>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "swath/geometry/local_frame.hpp"
#include "swath/mavlink/copter_driver.hpp"
#include "swath/mavlink/endpoint.hpp"
#include "swath/mavlink/fake_copter.hpp"
#include "swath/mavlink/link.hpp"
#include "swath/mavlink/px4_driver.hpp"

namespace swath::mavlink {
namespace {

constexpr double kStepS = 0.02;

// The driver D against the fake of its flavour (FakeCopterSettings::autopilot).
template <class D>
struct BasicRig {
  explicit BasicRig(DriverSettings settings = {}, FakeCopterSettings copter_settings = {})
      : vehicle_link(UdpLink::listen("127.0.0.1", 0)),
        gcs_link(UdpLink::connect("127.0.0.1", vehicle_link.local_port())),
        copter(vehicle_link, copter_settings),
        driver(gcs_link, std::move(settings)) {}

  // Advances the clock until `done` holds or `limit_s` passed; returns whether `done` held.
  bool run_until(const std::function<bool()>& done, double limit_s) {
    const double end = now_s + limit_s;
    while (now_s < end) {
      driver.poll(now_s);
      copter.step(now_s);
      now_s += kStepS;
      if (done && done()) return true;
    }
    return false;
  }
  void run(double seconds) { run_until({}, seconds); }
  bool command_done(int id, double limit_s = 5) {
    return run_until([&] { return driver.command_state(id) != CommandState::pending; }, limit_s);
  }
  // Connected, GUIDED, armed and at `altitude_m`.
  void take_off(double altitude_m) {
    ASSERT_TRUE(run_until([&] { return driver.state().link_alive; }, 3));
    const int mode = driver.enter_guided();  // ArduCopter: GUIDED; PX4: Hold
    ASSERT_TRUE(command_done(mode));
    ASSERT_EQ(driver.command_state(mode), CommandState::accepted);
    const int arm = driver.arm();
    ASSERT_TRUE(command_done(arm));
    ASSERT_EQ(driver.command_state(arm), CommandState::accepted);
    const int takeoff = driver.takeoff(altitude_m);
    ASSERT_TRUE(command_done(takeoff));
    ASSERT_EQ(driver.command_state(takeoff), CommandState::accepted);
    ASSERT_TRUE(run_until([&] { return copter.landed_state() == LandedState::in_air; }, 30));
  }

  UdpLink vehicle_link;
  UdpLink gcs_link;
  FakeCopter copter;
  D driver;
  double now_s = 0;
};
using Rig = BasicRig<CopterDriver>;

TEST(CopterDriver, ConnectsAsksForTelemetryArmsTakesOffAndFliesToATarget) {
  Rig rig;
  rig.take_off(20);
  EXPECT_EQ(rig.copter.commands_received(Cmd::set_message_interval), 4);
  EXPECT_EQ(rig.copter.commands_received(Cmd::request_message), 1);
  ASSERT_TRUE(rig.driver.state().home.has_value());
  EXPECT_EQ(rig.driver.state().home->latitude_degE7, 473977420);
  EXPECT_TRUE(rig.driver.state().armed);
  EXPECT_EQ(rig.driver.state().custom_mode, static_cast<std::uint32_t>(CopterMode::guided));
  EXPECT_GE(rig.copter.altitude_m(), 0.95 * 20);  // "in air" from 95 % of the take-off altitude
  rig.run(1);
  EXPECT_NEAR(rig.copter.altitude_m(), 20, 1e-9);

  // 80 m north, 60 m east: 100 m at 10 m/s.
  double lat = 0, lon = 0;
  rig.copter.to_geodetic(80, 60, lat, lon);
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 20));
  const double start_s = rig.now_s;
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.arrived(); }, 30));
  EXPECT_NEAR(rig.now_s - start_s, 100.0 / 10.0, 0.5);  // + one telemetry period, a poll
  EXPECT_NEAR(rig.copter.north_m(), 80, 1.5);
  EXPECT_NEAR(rig.copter.east_m(), 60, 1.5);
  // What the driver reads equals the vehicle's truth (to the 1e-7 degree of the wire format).
  const auto& p = *rig.driver.state().position;
  const geometry::LocalFrame home({47.397742, 8.545594});
  const geometry::Point2 seen = home.to_local({p.lat_degE7 / 1e7, p.lon_degE7 / 1e7});
  EXPECT_NEAR(seen.y, rig.copter.north_m(), 0.06);  // up to one 0.1 s report old, < 0.5 m/s
  EXPECT_NEAR(seen.x, rig.copter.east_m(), 0.06);
  EXPECT_NEAR(p.relative_alt_mm / 1000.0, rig.copter.altitude_m(), 0.01);
}

// ArduCopter re-plans a GUIDED leg from rest on every target it receives before reaching the last
// (AC_WPNav::set_wp_destination_NEU_cm): a target sent each second would hold a 10 m/s leg near
// 2.5 m/s. The fake does the same with an acceleration: the
// target goes once, the vehicle's report (POSITION_TARGET_GLOBAL_INT) confirms it, and the leg
// takes the closed-form time; a lost target is sent again because the report does not match.
TEST(CopterDriver, ATargetIsSentUntilTheVehicleReportsItNotEachSecond) {
  FakeCopterSettings fake;
  fake.accel_m_s2 = 2.5;  // WPNAV_ACCEL's default, 250 cm/s²
  Rig rig({}, fake);
  rig.take_off(20);
  rig.run(1);
  double lat = 0, lon = 0;
  rig.copter.to_geodetic(150, 0, lat, lon);
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 20));
  double start_s = rig.now_s;
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.arrived(); }, 60));
  // 0 -> 10 m/s at 2.5 m/s²: 4 s and 20 m, then 130 m at 10 m/s: 17 s (+ a poll, a report).
  EXPECT_NEAR(rig.now_s - start_s, 4.0 + 130.0 / 10.0, 0.3);
  EXPECT_TRUE(rig.driver.target_confirmed());
  EXPECT_EQ(rig.driver.targets_sent(), 1u);
  EXPECT_EQ(rig.copter.position_targets_received(), 1);
  ASSERT_TRUE(rig.driver.state().target.has_value());
  EXPECT_EQ(rig.driver.state().target->lat_degE7,
            static_cast<std::int32_t>(std::lround(lat * 1e7)));

  // The next target is lost on the way: the vehicle still reports the last one, so it is sent
  // again one resend period later, and only then is the leg flown.
  rig.copter.lose_targets(1);
  rig.copter.to_geodetic(150, 40, lat, lon);
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 20));
  start_s = rig.now_s;
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.arrived(); }, 30));
  EXPECT_EQ(rig.driver.targets_sent(), 3u);
  EXPECT_EQ(rig.copter.position_targets_received(), 2);
  // 1 s until the resend, then 40 m: 4 s and 20 m accelerating, 2 s at 10 m/s.
  EXPECT_NEAR(rig.now_s - start_s, 1.0 + 4.0 + 2.0, 0.3);
  EXPECT_NEAR(rig.copter.east_m(), 40, 1.5);
}

TEST(CopterDriver, LostCommandsAreResentAndTimeOutAfterThreeSends) {
  Rig rig;
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.state().link_alive; }, 3));
  rig.run(1);  // the telemetry requests answered
  rig.copter.lose_commands(2);
  const std::uint64_t before = rig.driver.commands_sent();
  const int mode = rig.driver.set_mode(CopterMode::guided);
  const double sent_s = rig.now_s;
  ASSERT_TRUE(rig.command_done(mode));
  EXPECT_EQ(rig.driver.command_state(mode), CommandState::accepted);
  EXPECT_EQ(rig.driver.commands_sent() - before, 3u);  // two lost, the third acknowledged
  EXPECT_EQ(rig.copter.commands_received(Cmd::do_set_mode), 1);
  EXPECT_NEAR(rig.now_s - sent_s, 2.0, 0.1);  // resent after 1 s, twice

  rig.copter.lose_commands(3);
  const int speed = rig.driver.set_speed(4);
  ASSERT_TRUE(rig.command_done(speed));
  EXPECT_EQ(rig.driver.command_state(speed), CommandState::timed_out);
  EXPECT_EQ(rig.copter.speed_setting_m_s(), 10);  // never arrived
  EXPECT_EQ(rig.copter.commands_received(Cmd::do_change_speed), 0);
}

TEST(CopterDriver, ARefusalToArmComesWithTheVehiclesSentence) {
  Rig rig;
  rig.copter.refuse_arm("PreArm: Need Position Estimate");
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.state().link_alive; }, 3));
  ASSERT_TRUE(rig.command_done(rig.driver.set_mode(CopterMode::guided)));
  const int arm = rig.driver.arm();
  ASSERT_TRUE(rig.command_done(arm));
  EXPECT_EQ(rig.driver.command_state(arm), CommandState::rejected);
  EXPECT_EQ(rig.driver.command_result(arm), CmdResult::failed);
  ASSERT_EQ(rig.driver.state().status_texts.size(), 1u);
  EXPECT_EQ(rig.driver.state().status_texts[0], "PreArm: Need Position Estimate");
  EXPECT_FALSE(rig.copter.armed());
}

TEST(CopterDriver, TenSecondLinkCutIsDetectedTheVehicleReturnsAndTheFlightResumes) {
  Rig rig;
  rig.take_off(15);
  double lat = 0, lon = 0;
  rig.copter.to_geodetic(300, 0, lat, lon);
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 15));
  rig.run(5);  // 50 m out
  const double cut_s = rig.now_s;
  rig.copter.cut_link(cut_s, cut_s + 10);
  ASSERT_TRUE(rig.run_until([&] { return !rig.driver.state().link_alive; }, 10));
  const double lost_after = rig.now_s - cut_s;
  EXPECT_GT(lost_after, 2.0);  // last heartbeat up to 1 s before the cut, then 3 s of silence
  EXPECT_LE(lost_after, 3.0 + 2 * kStepS);
  rig.run(cut_s + 10 - rig.now_s);
  EXPECT_EQ(rig.copter.mode(), CopterMode::rtl);  // GCS failsafe after 5 s without heartbeat
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.state().link_alive; }, 2));
  EXPECT_EQ(rig.driver.state().links_lost, 1);
  rig.run(0.5);
  EXPECT_EQ(rig.driver.state().custom_mode, static_cast<std::uint32_t>(CopterMode::rtl));
  EXPECT_EQ(rig.copter.commands_received(Cmd::set_message_interval), 8);  // asked again

  // The flight resumes: GUIDED again, the same target, reached.
  ASSERT_TRUE(rig.command_done(rig.driver.set_mode(CopterMode::guided)));
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 15));
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.arrived(); }, 60));
  EXPECT_NEAR(rig.copter.north_m(), 300, 1.5);
  EXPECT_TRUE(rig.copter.armed());
}

// A vehicle that heartbeats but never answers a command, its link flapping: the telemetry
// requests stay one pending set (4 intervals and home), not one more set per link-up.
TEST(CopterDriver, AFlappingSilentVehicleKeepsOneSetOfTelemetryRequests) {
  UdpLink vehicle_link = UdpLink::listen("127.0.0.1", 0);
  UdpLink gcs_link = UdpLink::connect("127.0.0.1", vehicle_link.local_port());
  Endpoint vehicle(vehicle_link, 1, 1);
  CopterDriver driver(gcs_link);
  double now_s = 0;
  for (int flap = 0; flap < 6; ++flap) {
    // Heard for 4 s (some requests sent 3 times and timed out, then asked again) ...
    for (int i = 0; i < 200; ++i, now_s += kStepS) {
      if (i % 50 == 0) vehicle.send(Heartbeat{.custom_mode = 0, .type = 2, .autopilot = 3});
      driver.poll(now_s);
      vehicle.receive();  // never acknowledged
    }
    EXPECT_EQ(driver.commands_pending(), 5) << "flap " << flap;
    // ... then silent until declared lost.
    for (int i = 0; i < 200; ++i, now_s += kStepS) driver.poll(now_s);
    ASSERT_FALSE(driver.state().link_alive);
  }
  EXPECT_EQ(driver.state().links_lost, 6);
  EXPECT_EQ(driver.commands_pending(), 5);
}

TEST(CopterDriver, NeverSendsATargetOutsideTheFence) {
  DriverSettings settings;
  settings.inside_fence = [](double lat_deg, double) { return lat_deg < 47.3985; };
  Rig rig(settings);
  rig.take_off(10);
  double lat = 0, lon = 0;
  rig.copter.to_geodetic(200, 0, lat, lon);  // ~84 m north of the fence line
  ASSERT_GT(lat, 47.3985);
  EXPECT_FALSE(rig.driver.go_to(lat, lon, 10));
  rig.run(3);
  EXPECT_EQ(rig.copter.position_targets_received(), 0);
  rig.copter.to_geodetic(50, 0, lat, lon);
  EXPECT_TRUE(rig.driver.go_to(lat, lon, 10));
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.arrived(); }, 20));
  EXPECT_GT(rig.copter.position_targets_received(), 0);
}

// ---- The fence over the mission protocol (MAV_MISSION_TYPE_FENCE). The truth is the fake's own
// store and parameters, and fence items the test builds itself from positions north/east of home.
struct FenceRig {
  explicit FenceRig(FakeCopterSettings copter_settings = {}) : rig({}, copter_settings) {}

  // A 200 m square about home (inclusion, 4 vertices) and a triangle inside it (exclusion).
  std::vector<MissionItemInt> items() const {
    const double square[4][2] = {{-100, -100}, {-100, 100}, {100, 100}, {100, -100}};
    const double triangle[3][2] = {{30, 30}, {30, 60}, {60, 30}};
    std::vector<MissionItemInt> out;
    const auto add = [&](const double(*ring)[2], int n, Cmd cmd) {
      for (int i = 0; i < n; ++i) {
        double lat = 0, lon = 0;
        rig.copter.to_geodetic(ring[i][0], ring[i][1], lat, lon);
        MissionItemInt m;
        m.command = static_cast<std::uint16_t>(cmd);
        m.param1 = static_cast<float>(n);
        m.x = static_cast<std::int32_t>(std::lround(lat * 1e7));
        m.y = static_cast<std::int32_t>(std::lround(lon * 1e7));
        out.push_back(m);
      }
    };
    add(square, 4, Cmd::nav_fence_polygon_vertex_inclusion);
    add(triangle, 3, Cmd::nav_fence_polygon_vertex_exclusion);
    return out;
  }

  // Uploads; true once the driver's fence state is verified or failed within `limit_s`.
  bool upload(double limit_s = 20) {
    rig.driver.upload_fence(items());
    return rig.run_until(
        [&] {
          const FenceState f = rig.driver.fence_state();
          return f == FenceState::verified || f == FenceState::failed;
        },
        limit_s);
  }

  Rig rig;
};

void expect_same_items(const std::vector<MissionItemInt>& got,
                       const std::vector<MissionItemInt>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got[i].command, want[i].command) << i;
    EXPECT_EQ(got[i].x, want[i].x) << i;
    EXPECT_EQ(got[i].y, want[i].y) << i;
    EXPECT_EQ(got[i].param1, want[i].param1) << i;
    EXPECT_EQ(got[i].seq, i);
    EXPECT_EQ(got[i].mission_type, static_cast<std::uint8_t>(MissionType::fence)) << i;
  }
}

TEST(FenceUpload, UploadedReadBackAndEnabledWithThePolygonBitAdded) {
  FakeCopterSettings s;
  s.params["FENCE_TYPE"] = 1;  // the owner's altitude limit alone: kept, polygons added (1 | 4)
  FenceRig f(s);
  ASSERT_TRUE(f.upload());
  ASSERT_EQ(f.rig.driver.fence_state(), FenceState::verified) << f.rig.driver.fence_error();
  expect_same_items(f.rig.copter.fence_items(), f.items());  // the vehicle's store
  expect_same_items(f.rig.driver.fence_read_back(), f.items());
  EXPECT_EQ(f.rig.copter.param("FENCE_ENABLE"), 1);
  EXPECT_EQ(f.rig.copter.param("FENCE_TYPE"), 5);
  EXPECT_EQ(f.rig.driver.fence_resends(), 0);
}

// Two inclusion areas: swath's envelope flies in their union, ArduPilot by default in their
// intersection; the driver sets FENCE_OPTIONS' union bit. With one (above) it is left alone.
TEST(FenceUpload, TwoInclusionAreasSetTheUnionOption) {
  FenceRig f;
  std::vector<MissionItemInt> items = f.items();
  for (MissionItemInt& m : items)  // the triangle becomes a second inclusion
    m.command = static_cast<std::uint16_t>(Cmd::nav_fence_polygon_vertex_inclusion);
  f.rig.driver.upload_fence(items);
  ASSERT_TRUE(
      f.rig.run_until([&] { return f.rig.driver.fence_state() == FenceState::verified; }, 20))
      << f.rig.driver.fence_error();
  EXPECT_EQ(f.rig.copter.param("FENCE_OPTIONS"), 2);
  EXPECT_EQ(f.rig.copter.param("FENCE_ENABLE"), 1);
  FenceRig one;
  ASSERT_TRUE(one.upload());
  EXPECT_EQ(one.rig.copter.param("FENCE_OPTIONS"), 0);
}

TEST(FenceUpload, AVertexStoredElsewhereFailsTheReadBackAndTheFenceIsNotEnabled) {
  FenceRig f;
  f.rig.copter.corrupt_fence_vertex(5);
  ASSERT_TRUE(f.upload());
  ASSERT_EQ(f.rig.driver.fence_state(), FenceState::failed);
  const std::string& why = f.rig.driver.fence_error();
  EXPECT_NE(why.find("read back differs"), std::string::npos) << why;
  EXPECT_NE(why.find("item 5 (MAV_CMD 5002) reads back at"), std::string::npos) << why;
  EXPECT_EQ(f.rig.copter.param("FENCE_ENABLE"), 0);
}

TEST(FenceUpload, ARefusalAtTheCountFailsTheUploadWithTheVehiclesResult) {
  FenceRig f;
  f.rig.copter.refuse_fence(MissionResult::no_space);
  ASSERT_TRUE(f.upload());
  ASSERT_EQ(f.rig.driver.fence_state(), FenceState::failed);
  EXPECT_EQ(f.rig.driver.fence_error(), "upload: the vehicle answered MISSION_ACK 4 (no space)");
  EXPECT_TRUE(f.rig.copter.fence_items().empty());
  EXPECT_EQ(f.rig.copter.param("FENCE_ENABLE"), 0);
}

// Two lost messages (the count and one of the first items or requests): each is sent again after
// the timeout and the fence still arrives whole. Three lost counts: the upload gives up.
TEST(FenceUpload, LostMessagesAreSentAgainAndThreeLostCountsFailTheUpload) {
  FenceRig f;
  f.rig.run_until([&] { return f.rig.driver.state().link_alive; }, 3);
  f.rig.copter.lose_mission_messages(2);
  ASSERT_TRUE(f.upload());
  ASSERT_EQ(f.rig.driver.fence_state(), FenceState::verified) << f.rig.driver.fence_error();
  EXPECT_EQ(f.rig.driver.fence_resends(), 2);
  expect_same_items(f.rig.copter.fence_items(), f.items());

  FenceRig g;
  g.rig.run_until([&] { return g.rig.driver.state().link_alive; }, 3);
  g.rig.copter.lose_mission_messages(3);
  ASSERT_TRUE(g.upload());
  ASSERT_EQ(g.rig.driver.fence_state(), FenceState::failed);
  EXPECT_EQ(g.rig.driver.fence_error(), "upload: no answer to MISSION_COUNT after 3 sends");
  EXPECT_TRUE(g.rig.copter.fence_items().empty());
}

TEST(CopterDriver, PhotosReturnAndLandingEndDisarmedAtHome) {
  Rig rig;
  rig.take_off(12);
  double lat = 0, lon = 0;
  rig.copter.to_geodetic(-40, 30, lat, lon);
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 12));
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.arrived(); }, 20));
  ASSERT_TRUE(rig.command_done(rig.driver.capture_image()));
  ASSERT_EQ(rig.driver.state().images.size(), 1u);
  const auto& image = rig.driver.state().images[0];
  EXPECT_NEAR(image.lat_degE7 / 1e7, lat, 2e-7);  // the photo is where the vehicle is
  EXPECT_NEAR(image.relative_alt_mm / 1000.0, 12, 0.05);

  ASSERT_TRUE(rig.command_done(rig.driver.return_to_launch()));
  ASSERT_TRUE(rig.run_until(
      [&] {
        return !rig.driver.state().armed && rig.driver.state().landed == LandedState::on_ground;
      },
      60));
  EXPECT_NEAR(rig.copter.north_m(), 0, 0.5);
  EXPECT_NEAR(rig.copter.east_m(), 0, 0.5);
  EXPECT_EQ(rig.copter.altitude_m(), 0);
  // On the ground, landing is refused with a reason code.
  const int land = rig.driver.land();
  ASSERT_TRUE(rig.command_done(land));
  EXPECT_EQ(rig.driver.command_result(land), CmdResult::failed);
}

// The safety check at connect (docs/swath-fleet.md): FS_GCS_ENABLE read with PARAM_REQUEST_READ; a
// warning when it is 0 (no return on a lost link), none when it is 1, "could not read" once three
// requests a second apart went unanswered; the flight is never held back by it.
TEST(CopterDriver, SafetyCheckWarnsWhenTheLostLinkFailsafeIsOff) {
  FakeCopterSettings off;
  off.params["FS_GCS_ENABLE"] = 0;
  Rig rig({}, off);
  ASSERT_TRUE(rig.run_until([&] { return !rig.driver.state().warnings.empty(); }, 5));
  ASSERT_EQ(rig.driver.state().warnings.size(), 1u);
  EXPECT_EQ(rig.driver.state().warnings[0],
            "FS_GCS_ENABLE is 0: ArduCopter will not return to launch when the link is lost");
  EXPECT_EQ(rig.driver.state().params.at("FS_GCS_ENABLE"), 0);
  EXPECT_EQ(rig.copter.param_requests_received(), 1);
}

TEST(CopterDriver, SafetyCheckIsSilentWhenTheFailsafeReturns) {
  Rig rig;  // FS_GCS_ENABLE 1
  rig.take_off(10);
  rig.run(5);
  EXPECT_EQ(rig.driver.state().params.at("FS_GCS_ENABLE"), 1);
  EXPECT_TRUE(rig.driver.state().warnings.empty());
  EXPECT_EQ(rig.copter.param_requests_received(), 1);
}

TEST(CopterDriver, SafetyCheckSaysItCouldNotReadAfterThreeRequestsAndTheFlightGoesOn) {
  Rig rig;
  rig.copter.drop_param_requests();
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.state().link_alive; }, 3));
  const double up_s = rig.now_s;
  ASSERT_TRUE(rig.run_until([&] { return !rig.driver.state().warnings.empty(); }, 10));
  // Sent at 0, 1 and 2 s after the link came up, timed out 1 s after the third.
  EXPECT_NEAR(rig.now_s - up_s, 3.0, 2 * kStepS);
  ASSERT_EQ(rig.driver.state().warnings.size(), 1u);
  EXPECT_EQ(rig.driver.state().warnings[0].rfind("could not read FS_GCS_ENABLE (no answer to 3 "
                                                 "requests)",
                                                 0),
            0u)
      << rig.driver.state().warnings[0];
  EXPECT_TRUE(rig.driver.state().params.empty());
  rig.take_off(10);  // the check held nothing back
  EXPECT_EQ(rig.driver.state().warnings.size(), 1u);
}

// PX4's custom_mode (px4_custom_mode.h: uint16 reserved, uint8 main_mode, uint8 sub_mode over a
// little-endian uint32), written out by hand.
TEST(Px4Modes, MainModeInBits16To23SubModeIn24To31) {
  EXPECT_EQ(px4::kHold, 0x03040000u);     // AUTO 4, LOITER 3
  EXPECT_EQ(px4::kTakeoff, 0x02040000u);  // AUTO 4, TAKEOFF 2
  EXPECT_EQ(px4::kRtl, 0x05040000u);      // AUTO 4, RTL 5
  EXPECT_EQ(px4::kLand, 0x06040000u);     // AUTO 4, LAND 6
  EXPECT_EQ(px4::kPosctl, 0x00030000u);   // POSCTL 3
  EXPECT_EQ(px4::custom_mode(px4::kMainOffboard), 0x00060000u);
  EXPECT_EQ(px4::main_mode(0x05040000u), 4);
  EXPECT_EQ(px4::sub_mode(0x05040000u), 5);
}

// The PX4 driver against the fake in its PX4 flavour: this checks the driver against our reading
// of PX4's documents (the fake encodes the same reading), not against PX4.
FakeCopterSettings fake_px4() {
  FakeCopterSettings s;
  s.autopilot = FakeAutopilot::px4;
  return s;
}
using Px4Rig = BasicRig<Px4Driver>;

TEST(Px4Driver, HoldArmTakeOffAboveSeaLevelAndRepositionToATarget) {
  Px4Rig rig({}, fake_px4());
  rig.take_off(20);
  EXPECT_EQ(rig.driver.state().autopilot, kAutopilotPx4);
  EXPECT_EQ(rig.copter.commands_received(Cmd::set_message_interval), 4);
  ASSERT_TRUE(rig.driver.state().home.has_value());
  // NAV_TAKEOFF went above sea level (home 488 m + 20 m): the fake climbs to 20 m above home.
  rig.run(2);
  EXPECT_NEAR(rig.copter.altitude_m(), 20, 1e-3);
  EXPECT_EQ(rig.driver.state().custom_mode, px4::kHold);  // AUTO.TAKEOFF ends in Hold
  EXPECT_TRUE(rig.driver.in_guided());

  double lat = 0, lon = 0;
  rig.copter.to_geodetic(80, 60, lat, lon);
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 25));
  const double start_s = rig.now_s;
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.arrived(); }, 30));
  EXPECT_NEAR(rig.now_s - start_s, 100.0 / 10.0, 0.5);
  EXPECT_NEAR(rig.copter.north_m(), 80, 1.5);
  EXPECT_NEAR(rig.copter.east_m(), 60, 1.5);
  EXPECT_NEAR(rig.copter.altitude_m(), 25, 1.5);
  EXPECT_TRUE(rig.driver.target_confirmed());
  EXPECT_EQ(rig.copter.commands_received(Cmd::do_reposition), 1);  // a command, not repeated
  EXPECT_EQ(rig.copter.position_targets_received(), 1);
  EXPECT_TRUE(rig.driver.state().warnings.empty());  // NAV_DLL_ACT 2: Return
}

TEST(Px4Driver, ALostRepositionIsResentAndThreeLostTimeOut) {
  Px4Rig rig({}, fake_px4());
  rig.take_off(15);
  rig.run(2);
  double lat = 0, lon = 0;
  rig.copter.to_geodetic(50, 0, lat, lon);
  rig.copter.lose_commands(2);
  const std::uint64_t before = rig.driver.commands_sent();
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 15));
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.arrived(); }, 30));
  EXPECT_EQ(rig.driver.commands_sent() - before, 3u);  // two lost, the third acknowledged
  EXPECT_EQ(rig.copter.commands_received(Cmd::do_reposition), 1);
  EXPECT_TRUE(rig.driver.target_confirmed());

  rig.copter.lose_commands(3);
  rig.copter.to_geodetic(0, 0, lat, lon);
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 15));
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.commands_pending() == 0; }, 10));
  EXPECT_FALSE(rig.driver.target_confirmed());
  EXPECT_EQ(rig.copter.commands_received(Cmd::do_reposition), 1);
  EXPECT_NEAR(rig.copter.north_m(), 50, 1.5);  // never asked to move
}

TEST(Px4Driver, RefusedArmAndModesComeBackAsPx4ModesReturnAndLand) {
  Px4Rig rig({}, fake_px4());
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.state().link_alive; }, 3));
  rig.run(1);
  EXPECT_EQ(rig.driver.state().custom_mode, px4::kPosctl);  // the fake starts in Position
  // Arming is refused outside Hold (the fake's rule, as it refuses outside GUIDED).
  const int arm = rig.driver.arm();
  ASSERT_TRUE(rig.command_done(arm));
  EXPECT_EQ(rig.driver.command_state(arm), CommandState::rejected);
  rig.take_off(10);
  double lat = 0, lon = 0;
  rig.copter.to_geodetic(0, 40, lat, lon);  // away from home, so that RTL flies before landing
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 10));
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.arrived(); }, 20));
  ASSERT_TRUE(rig.command_done(rig.driver.return_to_launch()));
  rig.run(1.5);
  EXPECT_EQ(rig.driver.state().custom_mode, px4::kRtl);
  EXPECT_TRUE(rig.driver.returning());
  ASSERT_TRUE(rig.run_until(
      [&] {
        return !rig.driver.state().armed && rig.driver.state().landed == LandedState::on_ground;
      },
      60));
}

// PX4 sends integer parameters byte for byte: NAV_DLL_ACT 2 arrives as the float whose bits are
// 2, which read as a number is 2.8e-45 (and COM_DL_LOSS_T 10 is 1.4e-44, "0 s" in a warning).
TEST(Px4Driver, SafetyCheckReadsBytewiseParametersAndWarnsOnlyWhenTheLossActionIsOff) {
  {
    Px4Rig rig({}, fake_px4());  // NAV_DLL_ACT 2, COM_DL_LOSS_T 10
    rig.run(6);
    EXPECT_EQ(rig.driver.state().params.at("NAV_DLL_ACT"), 2);
    EXPECT_EQ(rig.driver.state().params.at("COM_DL_LOSS_T"), 10);
    EXPECT_TRUE(rig.driver.state().warnings.empty());
  }
  {
    FakeCopterSettings off = fake_px4();
    off.params["NAV_DLL_ACT"] = 0;  // PX4's default
    off.params["COM_DL_LOSS_T"] = 7;
    Px4Rig rig({}, off);
    rig.run(6);
    ASSERT_EQ(rig.driver.state().warnings.size(), 1u);
    EXPECT_EQ(rig.driver.state().warnings[0],
              "NAV_DLL_ACT is 0 (disabled): PX4 takes no action when the link is lost (lost "
              "after COM_DL_LOSS_T = 7 s of silence)");
  }
  {
    Px4Rig rig({}, fake_px4());
    rig.copter.drop_param_requests();
    rig.run(6);
    ASSERT_EQ(rig.driver.state().warnings.size(), 2u);
    EXPECT_EQ(rig.driver.state().warnings[0].rfind("could not read COM_DL_LOSS_T", 0), 0u);
    EXPECT_EQ(rig.driver.state().warnings[1].rfind("could not read NAV_DLL_ACT", 0), 0u);
  }
}

// PX4's data-link-loss failsafe in the fake follows NAV_DLL_ACT after COM_DL_LOSS_T: with Return
// (2) a 15 s cut sends the vehicle home; the driver sees the link lost and AUTO.RTL after it.
TEST(Px4Driver, ALinkCutPastComDlLossTSendsTheVehicleHome) {
  Px4Rig rig({}, fake_px4());
  rig.take_off(15);
  double lat = 0, lon = 0;
  rig.copter.to_geodetic(300, 0, lat, lon);
  ASSERT_TRUE(rig.driver.go_to(lat, lon, 15));
  rig.run(5);
  const double cut_s = rig.now_s;
  rig.copter.cut_link(cut_s, cut_s + 15);
  ASSERT_TRUE(rig.run_until([&] { return !rig.driver.state().link_alive; }, 10));
  rig.run(cut_s + 15 - rig.now_s);
  EXPECT_EQ(rig.copter.mode(), CopterMode::rtl);
  ASSERT_TRUE(rig.run_until([&] { return rig.driver.state().link_alive; }, 2));
  rig.run(1.5);
  EXPECT_EQ(rig.driver.state().custom_mode, px4::kRtl);
  EXPECT_TRUE(rig.driver.returning());
}

// A TCP listener on the loopback address at a port of the kernel's choice (written to `port`);
// -1 when the socket cannot be made.
int tcp_listener(std::uint16_t& port) {
  const int server = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof a;
  if (server < 0 || bind(server, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      listen(server, 1) != 0 || getsockname(server, reinterpret_cast<sockaddr*>(&a), &length) != 0)
    return -1;
  port = ntohs(a.sin_port);
  return server;
}

// TCP (SITL's port 5760): frames written a few bytes at a time arrive whole and in order, the
// link carries our frames back, and a closed peer ends the link without a signal or a throw.
TEST(TcpLink, FramesSplitAcrossWritesArriveWholeAndAClosedPeerEndsTheLink) {
  std::uint16_t port = 0;
  const int server = tcp_listener(port);
  ASSERT_GE(server, 0);

  TcpLink client = TcpLink::connect("127.0.0.1", port);
  const int peer = accept(server, nullptr, nullptr);
  ASSERT_GE(peer, 0);
  std::vector<std::uint8_t> stream;
  for (int i = 0; i < 20; ++i) {
    const auto b = serialize(
        pack(GlobalPositionInt{.time_boot_ms = std::uint32_t(i), .lat_degE7 = 473977420 + i},
             FrameHeader{std::uint8_t(i), 1, 1}));
    stream.insert(stream.end(), b.begin(), b.end());
  }
  for (std::size_t at = 0; at < stream.size(); at += 3)  // three bytes per write
    ASSERT_GT(write(peer, stream.data() + at, std::min<std::size_t>(3, stream.size() - at)), 0);
  Endpoint gcs(client, kGcsSysid, kGcsCompid);
  std::vector<Frame> got;
  for (int tries = 0; tries < 1000 && got.size() < 20; ++tries) {
    for (const Frame& f : gcs.receive()) got.push_back(f);
    if (got.size() < 20) usleep(1000);
  }
  ASSERT_EQ(got.size(), 20u);
  for (std::size_t i = 0; i < got.size(); ++i)
    EXPECT_EQ(unpack<GlobalPositionInt>(got[i])->lat_degE7, 473977420 + int(i));

  gcs.send(Heartbeat{.type = kMavTypeGcs});
  std::vector<std::uint8_t> back(64);
  const ssize_t n = read(peer, back.data(), back.size());
  ASSERT_GT(n, 0);
  FrameParser parser;
  parser.feed({back.data(), std::size_t(n)});
  Frame f;
  ASSERT_TRUE(parser.next(f));
  EXPECT_EQ(unpack<Heartbeat>(f)->type, kMavTypeGcs);
  EXPECT_EQ(f.header.sysid, kGcsSysid);

  close(peer);
  for (int tries = 0; tries < 1000 && !client.closed(); ++tries) {
    gcs.receive();
    if (!client.closed()) usleep(1000);
  }
  EXPECT_TRUE(client.closed());
  gcs.send(Heartbeat{});  // dropped, no SIGPIPE
  close(server);
  EXPECT_THROW(TcpLink::connect("127.0.0.1", port), std::system_error);  // nobody listens now
}

// A local peer streaming junk as fast as it can: every receive() appends at most
// kMaxReceiveBytes and leaves the rest in the socket, so a reader's memory stays bounded; every
// byte still arrives, in order, over later calls.
TEST(TcpLink, AJunkStreamIsReadInBoundedSlices) {
  std::uint16_t port = 0;
  const int server = tcp_listener(port);
  ASSERT_GE(server, 0);
  TcpLink client = TcpLink::connect("127.0.0.1", port);
  const int peer = accept(server, nullptr, nullptr);
  ASSERT_GE(peer, 0);
  constexpr std::size_t kTotal = 16u << 20;
  std::thread writer([peer] {
    std::vector<std::uint8_t> junk(1 << 16);
    for (std::size_t i = 0; i < junk.size(); ++i) junk[i] = std::uint8_t(i * 131 + 7);
    for (std::size_t sent = 0; sent < kTotal;) {
      const ssize_t n = write(peer, junk.data(), std::min(junk.size(), kTotal - sent));
      if (n <= 0) break;
      sent += std::size_t(n);
    }
    close(peer);
  });
  usleep(100'000);  // the socket buffers fill first
  std::size_t received = 0, largest = 0;
  std::vector<std::uint8_t> out;
  for (int tries = 0; tries < 200'000 && !client.closed(); ++tries) {
    out.clear();
    const std::size_t n = client.receive(out);
    ASSERT_EQ(n, out.size());
    for (std::size_t i = 0; i < n; ++i)
      ASSERT_EQ(out[i], std::uint8_t(((received + i) % (1 << 16)) * 131 + 7));
    received += n;
    largest = std::max(largest, n);
    if (n == 0) usleep(200);
  }
  writer.join();
  close(server);
  EXPECT_EQ(received, kTotal);
  EXPECT_LE(largest, kMaxReceiveBytes);
  EXPECT_GT(largest, 0u);
}

TEST(UdpLink, ABusyPortIsRefusedNamingTheAddress) {
  UdpLink first = UdpLink::listen("127.0.0.1", 0);
  try {
    UdpLink second = UdpLink::listen("127.0.0.1", first.local_port());
    FAIL() << "a second listener on the same port";
  } catch (const std::system_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:" + std::to_string(first.local_port())),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(UdpLink::connect("not-an-address", 14550), std::system_error);
}

// A listening link answers only a sender of good MAVLink frames from the expected system: a
// 1-byte sender, a stream of junk and a good frame from another system are dropped and never
// become the peer; the vehicle's heartbeat does, and a later stranger's junk does not take over.
TEST(UdpLink, OnlyASenderOfGoodFramesFromTheSystemBecomesThePeer) {
  UdpLink ground = UdpLink::listen("127.0.0.1", 0, 1);
  UdpLink junk = UdpLink::connect("127.0.0.1", ground.local_port());
  UdpLink stranger = UdpLink::connect("127.0.0.1", ground.local_port());
  UdpLink vehicle = UdpLink::connect("127.0.0.1", ground.local_port());
  auto drain = [](UdpLink& link) {
    std::vector<std::uint8_t> got;
    for (int tries = 0; tries < 50 && got.empty(); ++tries) {
      link.receive(got);
      if (got.empty()) usleep(1000);
    }
    return got;
  };
  auto heartbeat = [](std::uint8_t sysid) {
    return serialize(pack(Heartbeat{.type = 2}, FrameHeader{0, sysid, 1}));
  };
  const std::uint8_t one_byte = 0xfe;
  junk.send({&one_byte, 1});
  const auto other_system = heartbeat(7);
  stranger.send(other_system);
  usleep(20'000);
  std::vector<std::uint8_t> got;
  ground.receive(got);
  EXPECT_TRUE(got.empty());  // neither reached the reader
  const std::uint8_t hello = 0x42;
  ground.send({&hello, 1});  // no peer yet: dropped, as a radio would
  EXPECT_TRUE(drain(junk).empty());
  EXPECT_TRUE(drain(stranger).empty());

  const auto beat = heartbeat(1);
  vehicle.send(beat);
  EXPECT_EQ(drain(ground), std::vector<std::uint8_t>(beat.begin(), beat.end()));
  junk.send({&one_byte, 1});
  stranger.send(other_system);
  usleep(20'000);
  got.clear();
  ground.receive(got);
  EXPECT_TRUE(got.empty());
  ground.send({&hello, 1});
  EXPECT_EQ(drain(vehicle), std::vector<std::uint8_t>{hello});
  EXPECT_TRUE(drain(junk).empty());
  EXPECT_TRUE(drain(stranger).empty());
}

}  // namespace
}  // namespace swath::mavlink
