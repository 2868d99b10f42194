// swath's plant behind ArduPilot's JSON SITL interface (control/ardupilot_json). CI cannot build
// SITL, so ArduPilot's side is written down here from its source (ArduPilot 90700977c5):
// the servo packet as libraries/SITL/SIM_JSON.h lines 43-55 lay it out, and the reply read back
// the way SIM_JSON.cpp parse_sensors() (lines 155-250) reads it: strstr for the key, step over
// `"key":`, sscanf("[%f, %f, %f]"). Physics checked against closed forms: free fall at g, hover
// at the thrust that carries m g, and the signs of FRD rates for torques of known direction.
#include <arpa/inet.h>
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <vector>

#include "swath/base/input_error.hpp"
#include "swath/control/ardupilot_json.hpp"
#include "swath/vehicle/vehicle_files.hpp"

namespace swath::control {
namespace {

using vehicle::kStandardGravity_m_s2;
using vehicle::Vec3;

// SIM_JSON.h servo_packet_16 / servo_packet_32: uint16 magic, uint16 frame_rate,
// uint32 frame_count, uint16 pwm[N]; x86 and ARM SITL are little-endian.
std::vector<std::uint8_t> packet_bytes(std::uint16_t magic, std::uint16_t rate_hz,
                                       std::uint32_t frame, const std::vector<std::uint16_t>& pwm,
                                       std::size_t channels = 16) {
  std::vector<std::uint8_t> b;
  const auto u16 = [&](std::uint16_t v) {
    b.push_back(static_cast<std::uint8_t>(v & 0xff));
    b.push_back(static_cast<std::uint8_t>(v >> 8));
  };
  u16(magic);
  u16(rate_hz);
  for (int k = 0; k < 4; ++k) b.push_back(static_cast<std::uint8_t>(frame >> (8 * k)));
  for (std::size_t c = 0; c < channels; ++c) u16(c < pwm.size() ? pwm[c] : 0);
  return b;
}

// What SIM_JSON.cpp's parser makes of one line: the value after `"key":` in the section (its
// strstr/sscanf steps, which need no space after the colon).
struct ParsedLine {
  bool ok = true;
  double timestamp = 0;
  float gyro[3]{}, accel[3]{}, attitude[3]{}, velocity[3]{};
  double position[3]{};
};
ParsedLine parse_like_ardupilot(const std::string& line) {
  ParsedLine out;
  const char* json = line.c_str();
  const auto find = [&](const char* section, const char* key) -> const char* {
    const char* p = std::strstr(json, section);
    if (!p) return nullptr;
    p += std::strlen(section) + 1;
    p = std::strstr(p, key);
    return p ? p + std::strlen(key) + 2 : nullptr;
  };
  const auto vec3f = [&](const char* section, const char* key, float* v) {
    const char* p = find(section, key);
    out.ok = out.ok && p && std::sscanf(p, "[%f, %f, %f]", &v[0], &v[1], &v[2]) == 3;
  };
  const char* t = find("", "timestamp");
  out.ok = t != nullptr;
  if (t) out.timestamp = std::atof(t);
  vec3f("imu", "gyro", out.gyro);
  vec3f("imu", "accel_body", out.accel);
  vec3f("", "attitude", out.attitude);
  vec3f("", "velocity", out.velocity);
  const char* p = find("", "position");
  out.ok =
      out.ok && p &&
      std::sscanf(p, "[%lf, %lf, %lf]", &out.position[0], &out.position[1], &out.position[2]) == 3;
  return out;
}

// The bundled quad-f450 without the random torque (no controller holds it here) and, for the
// closed forms, without drag.
ArduPilotJsonSettings quiet_quad(bool drag = true) {
  ArduPilotJsonSettings s;
  s.physics.airframe.frame.torque_noise_sigma_nm = 0;
  if (!drag) {
    s.physics.airframe.frame.drag_linear_n_per_m_s = {};
    s.physics.airframe.frame.drag_cda_m2 = {};
    s.physics.airframe.frame.flapping_nm_per_m_s = 0;
  }
  return s;
}

std::string send(ArduPilotJsonServer& server, std::uint32_t frame,
                 const std::vector<std::uint16_t>& pwm, std::uint16_t rate_hz = 1200) {
  const auto b = packet_bytes(kServoMagic16, rate_hz, frame, pwm);
  const auto reply = server.handle(b.data(), b.size());
  EXPECT_TRUE(reply.has_value());
  return reply.value_or("");
}

// A packet as ArduCopter 4.7 sends it (SIM_JSON.cpp output_servos(), 16 channels): 1200 Hz,
// frame 4711, outputs 1-4 at 1100, 1200, 1300, 1400 µs, the other 12 unassigned (0).
const std::vector<std::uint8_t> kRecordedPacket = {
    0x1a, 0x48,                                      // magic 18458
    0xb0, 0x04,                                      // frame_rate 1200
    0x67, 0x12, 0x00, 0x00,                          // frame_count 4711
    0x4c, 0x04, 0xb0, 0x04, 0x14, 0x05, 0x78, 0x05,  // pwm[0..3]
    0,    0,    0,    0,    0,    0,    0,    0,    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};

TEST(ArduPilotJson, RecordedPacketRoundTrip) {
  ASSERT_EQ(kRecordedPacket.size(), 40u);  // sizeof(servo_packet_16)
  const auto p = parse_servo_packet(kRecordedPacket.data(), kRecordedPacket.size());
  ASSERT_TRUE(p);
  EXPECT_EQ(p->frame_rate_hz, 1200);
  EXPECT_EQ(p->frame_count, 4711u);
  ASSERT_EQ(p->pwm_us.size(), 16u);
  EXPECT_EQ(p->pwm_us[0], 1100);
  EXPECT_EQ(p->pwm_us[3], 1400);
  EXPECT_EQ(p->pwm_us[4], 0);

  ArduPilotJsonServer server(quiet_quad());
  const auto reply = server.handle(kRecordedPacket.data(), kRecordedPacket.size());
  ASSERT_TRUE(reply);
  // One line, newline-framed as ArduPilot's recv_fdm() splits it.
  ASSERT_GE(reply->size(), 2u);
  EXPECT_EQ(reply->front(), '\n');
  EXPECT_EQ(reply->back(), '\n');
  EXPECT_EQ(reply->find('\n', 1), reply->size() - 1);
  const ParsedLine j = parse_like_ardupilot(reply->substr(1, reply->size() - 2));
  ASSERT_TRUE(j.ok) << *reply;
  EXPECT_NEAR(j.timestamp, 1.0 / 1200, 1e-9);
  // Below hover thrust (u <= 0.4 < 0.46): at rest on the ground, level, facing north, the
  // accelerometer reading 1 g up (FRD z is down).
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(j.position[k], 0.0);
    EXPECT_EQ(j.velocity[k], 0.0f);
    EXPECT_NEAR(j.gyro[k], 0.0, 1e-12);
    EXPECT_NEAR(j.attitude[k], 0.0, 1e-6);
  }
  EXPECT_NEAR(j.accel[0], 0.0, 1e-6);
  EXPECT_NEAR(j.accel[1], 0.0, 1e-6);
  EXPECT_NEAR(j.accel[2], -kStandardGravity_m_s2, 1e-5);
}

TEST(ArduPilotJson, ThirtyTwoChannelPacket) {
  std::vector<std::uint16_t> pwm(32, 1000);
  pwm[31] = 1999;
  const auto b = packet_bytes(kServoMagic32, 400, 9, pwm, 32);
  ASSERT_EQ(b.size(), 72u);  // sizeof(servo_packet_32)
  const auto p = parse_servo_packet(b.data(), b.size());
  ASSERT_TRUE(p);
  EXPECT_EQ(p->pwm_us.size(), 32u);
  EXPECT_EQ(p->pwm_us[31], 1999);
  EXPECT_EQ(p->frame_rate_hz, 400);
}

TEST(ArduPilotJson, BadPacketsAreCountedAndIgnored) {
  ArduPilotJsonServer server(quiet_quad());
  const std::vector<std::uint16_t> pwm(4, 1000);
  auto wrong_magic = packet_bytes(12345, 1200, 1, pwm);
  auto magic16_size32 = packet_bytes(kServoMagic16, 1200, 1, pwm, 32);
  auto truncated = packet_bytes(kServoMagic16, 1200, 1, pwm);
  truncated.pop_back();
  auto no_rate = packet_bytes(kServoMagic16, 0, 1, pwm);
  for (const auto* b : {&wrong_magic, &magic16_size32, &truncated, &no_rate})
    EXPECT_FALSE(server.handle(b->data(), b->size()));
  EXPECT_FALSE(server.handle(nullptr, 0));
  EXPECT_EQ(server.bad_packets(), 5);
  EXPECT_EQ(server.frames_served(), 0);
  EXPECT_EQ(server.sim_time_s(), 0.0);
  send(server, 1, pwm);
  EXPECT_EQ(server.frames_served(), 1);
  EXPECT_EQ(server.bad_packets(), 5);
}

// Packets with any frame rate (1 Hz: a second a step), any frame counts (resends, jumps back)
// and any PWM (0 to 65535 µs, clamped to the ESC's range) keep the plant finite: every answer is
// a line ArduPilot's parser reads, all its numbers finite, the clock never going back. Fixed seed.
TEST(ArduPilotJson, RandomPacketsGetFiniteAnswers) {
  std::mt19937_64 rng(50);
  for (int flight = 0; flight < 20; ++flight) {
    ArduPilotJsonServer server(quiet_quad());
    double last_t = 0;
    for (int k = 0; k < 60; ++k) {
      std::vector<std::uint16_t> pwm(16);
      for (auto& v : pwm)
        v = static_cast<std::uint16_t>(rng() % 3 == 0 ? rng() : 1000 + rng() % 1001);
      const auto rate = static_cast<std::uint16_t>(rng() % 4 == 0 ? 1 + rng() % 65535 : 400);
      const auto frame = static_cast<std::uint32_t>(rng() % 5 == 0 ? rng() : k);
      const std::string line = send(server, frame, pwm, rate);
      const ParsedLine p = parse_like_ardupilot(line);
      ASSERT_TRUE(p.ok) << "flight " << flight << ", packet " << k << ": " << line;
      for (int a = 0; a < 3; ++a)
        ASSERT_TRUE(std::isfinite(p.position[a]) && std::isfinite(p.velocity[a]) &&
                    std::isfinite(p.attitude[a]) && std::isfinite(p.gyro[a]) &&
                    std::isfinite(p.accel[a]))
            << "flight " << flight << ", packet " << k << ": " << line;
      ASSERT_GE(p.timestamp, last_t) << line;
      ASSERT_GE(p.position[2], -1e5) << line;  // NED: not beyond 100 km up
      last_t = p.timestamp;
    }
  }
}

TEST(ArduPilotJson, ResendIsAnsweredWithoutStepping) {
  ArduPilotJsonServer server(quiet_quad());
  const std::vector<std::uint16_t> pwm(4, 1800);  // climbing: every step changes the state
  send(server, 1, pwm);
  const std::string second = send(server, 2, pwm);
  const double t = server.sim_time_s();
  EXPECT_EQ(send(server, 2, pwm), second);
  EXPECT_EQ(server.sim_time_s(), t);
  EXPECT_EQ(server.resends(), 1);
  EXPECT_EQ(server.frames_served(), 2);
  EXPECT_NE(send(server, 3, pwm), second);
  EXPECT_NEAR(server.sim_time_s(), 3.0 / 1200, 1e-9);
}

TEST(ArduPilotJson, FreeFallAtGUntilTheGround) {
  ArduPilotJsonSettings s = quiet_quad(/*drag=*/false);
  const double h = 20;
  s.start_height_m = h;
  ArduPilotJsonServer server(s);
  const std::vector<std::uint16_t> idle(4, 1000);
  const double t_ground = std::sqrt(2 * h / kStandardGravity_m_s2);
  std::uint32_t frame = 0;
  while (server.sim_time_s() < t_ground + 1) {
    const ParsedLine j = parse_like_ardupilot(send(server, ++frame, idle));
    ASSERT_TRUE(j.ok);
    const double t = j.timestamp;
    if (t < t_ground - 1.0 / 1200) {
      ASSERT_FALSE(server.on_ground()) << t;
      // NED: down is positive; in free fall the accelerometers read nothing.
      ASSERT_NEAR(j.position[2], -(h - 0.5 * kStandardGravity_m_s2 * t * t), 1e-6) << t;
      ASSERT_NEAR(j.velocity[2], kStandardGravity_m_s2 * t, 1e-4) << t;
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(j.accel[k], 0.0, 1e-6) << t;
    } else if (t > t_ground + 1.0 / 1200) {
      ASSERT_TRUE(server.on_ground()) << t;
      EXPECT_EQ(j.position[2], 0.0);
      EXPECT_EQ(j.velocity[2], 0.0f);
      EXPECT_NEAR(j.accel[2], -kStandardGravity_m_s2, 1e-5);
    }
  }
}

// Mass such that hover is exactly u = 0.5 (1500 µs): m g = n k_T Ω_max² u.
ArduPilotJsonSettings half_throttle_hover() {
  ArduPilotJsonSettings s = quiet_quad();
  const auto& p = s.physics.airframe.propulsion;
  s.physics.airframe.frame.mass_kg =
      4 * p.thrust_coeff_n_s2 * p.max_speed_rad_s * p.max_speed_rad_s * 0.5 / kStandardGravity_m_s2;
  s.start_height_m = 10;
  s.start_hovering = true;
  return s;
}

TEST(ArduPilotJson, HoverPwmHoldsAltitude) {
  ArduPilotJsonServer server(half_throttle_hover());
  ParsedLine j;
  for (std::uint32_t f = 1; f <= 12000; ++f)  // 10 s at 1200 Hz
    j = parse_like_ardupilot(send(server, f, std::vector<std::uint16_t>(4, 1500)));
  ASSERT_TRUE(j.ok);
  EXPECT_NEAR(j.position[2], -10.0, 0.01);
  EXPECT_NEAR(j.velocity[2], 0.0, 1e-3);
  EXPECT_NEAR(j.accel[2], -kStandardGravity_m_s2, 1e-3);
  // 10 µs more climbs: the test would see a wrong PWM scale.
  ArduPilotJsonServer climb(half_throttle_hover());
  for (std::uint32_t f = 1; f <= 2400; ++f)
    j = parse_like_ardupilot(send(climb, f, std::vector<std::uint16_t>(4, 1510)));
  EXPECT_LT(j.position[2], -10.1);
}

// The battery behind the server. Eq. 12 (no sag): a hover at the PWM that carries m g draws the
// hover's motor power plus the avionics, constant, so the energy is (P_hover + P_avionics) t and
// the charge drawn is I t with I from eq. 12 solved here in the quadratic's textbook form.
TEST(ArduPilotJson, HoverEnergyAndChargeMatchTheClosedForm) {
  ArduPilotJsonSettings s = half_throttle_hover();
  s.physics.avionics_w = 3.0;
  ArduPilotJsonServer server(s);
  for (std::uint32_t f = 1; f <= 1200 * 20; ++f)
    send(server, f, std::vector<std::uint16_t>(4, 1500));
  // 20 s in steps of 1/1200 s on the plant's nanosecond clock (833,333 ns each).
  const double t_s = server.sim_time_s();
  ASSERT_NEAR(t_s, 20.0, 1e-5);
  const double power_w = vehicle::hover(s.physics.airframe).motor_power_w + 3.0;
  const vehicle::Battery& b = s.battery;
  const double v = b.voltage_v, r = b.resistance_ohm;
  const double current_a =
      (v - std::sqrt(v * v - 4 * r * b.stabilised_voltage_v * power_w / v)) / (2 * r);
  EXPECT_NEAR(server.energy().total_j(), power_w * t_s, 1e-4 * power_w * t_s);
  EXPECT_NEAR(server.energy().avionics_j, 3.0 * t_s, 1e-9);
  EXPECT_NEAR(server.energy().soc, 1 - current_a * t_s / (3600 * b.capacity_ah), 1e-6);
  EXPECT_FALSE(server.energy().battery_empty);
  EXPECT_NEAR(server.airborne_s(), t_s, 1e-9);
  EXPECT_NEAR(server.row().energy_wh, server.energy().total_j() / 3600, 1e-12);
}

// With voltage sag (4 cells): the energy the pack gives, summed here step by step as V I dt with
// the cells' open-circuit voltage (Chen and Rincón-Mora's fit, written out again) and the
// current of V I = P, P the plant's motor power read after each step (trapezoid) plus the
// avionics; the charge is the sum of I dt. The sagging voltage slows the rotors, so the hover
// PWM sinks it: the power read back is what the plant really drew.
TEST(ArduPilotJson, SaggingBatteryEnergyIsTheIntegralOfVoltageTimesCurrent) {
  ArduPilotJsonSettings s = half_throttle_hover();
  s.start_height_m = 300;
  s.physics.avionics_w = 3.0;
  s.battery.cells = 4;
  s.battery.internal_resistance_ohm = 0.006;
  s.battery.volt_max_v = 16.8;
  ArduPilotJsonServer server(s);
  const auto ocv_v = [](double soc) {
    return 4 * (-1.031 * std::exp(-35 * soc) + 3.685 + 0.2156 * soc - 0.1178 * soc * soc +
                0.3201 * soc * soc * soc);
  };
  const double dt = 1.0 / 1200, r = 4 * 0.006;
  double soc = 1, energy_j = 0, before_w = server.model().motor_power_w();
  for (std::uint32_t f = 1; f <= 1200 * 20; ++f) {
    send(server, f, std::vector<std::uint16_t>(4, 1500));
    const double after_w = server.model().motor_power_w();
    const double p = 0.5 * (before_w + after_w) + 3.0;
    before_w = after_w;
    const double e = ocv_v(soc);
    const double i = (e - std::sqrt(e * e - 4 * r * p)) / (2 * r);
    energy_j += (e - i * r) * i * dt;
    soc -= i * dt / (3600 * s.battery.capacity_ah);
  }
  EXPECT_NEAR(server.energy().total_j(), energy_j, 2e-3 * energy_j);
  EXPECT_NEAR(server.energy().soc, soc, 1e-6);
  EXPECT_LT(server.energy().voltage_v, ocv_v(server.energy().soc));  // sagging under load
  EXPECT_LT(-server.json_state().position_m_ned.z, 299.0);           // slower rotors: it sinks
  // The rotors turn at the speed without sag times the terminal voltage over volt_max_v.
  ArduPilotJsonSettings steady = s;
  steady.battery.cells = 0;
  ArduPilotJsonServer full(steady);
  for (std::uint32_t f = 1; f <= 1200 * 20; ++f) send(full, f, std::vector<std::uint16_t>(4, 1500));
  EXPECT_NEAR(server.model().state().rotor_rad_s[0] / full.model().state().rotor_rad_s[0],
              server.energy().voltage_v / 16.8, 2e-3);
}

// ArduCopter's quad X_REV (AP_MotorsMatrix.cpp setup_quad_matrix, MOTOR_FRAME_TYPE_BF_X_REV):
// output 1 back-right CCW, 2 front-right CW, 3 back-left CW, 4 front-left CCW.
struct TorqueCase {
  const char* what;
  std::vector<std::uint16_t> pwm;
  int axis;  ///< FRD: 0 roll, 1 pitch, 2 yaw
};

TEST(ArduPilotJson, GyroSignsMatchFrdForTorquesOfKnownDirection) {
  const std::uint16_t lo = 1430, hi = 1490;  // about hover (1460)
  const std::vector<TorqueCase> cases = {
      {"roll right: left rotors faster", {lo, lo, hi, hi}, 0},
      {"pitch up: front rotors faster", {lo, hi, lo, hi}, 1},
      {"yaw right: counter-clockwise rotors faster (their drag turns the body clockwise)",
       {hi, lo, lo, hi},
       2},
  };
  for (const TorqueCase& c : cases) {
    ArduPilotJsonSettings s = quiet_quad();
    s.start_height_m = 50;
    s.start_hovering = true;
    ArduPilotJsonServer server(s);
    ParsedLine j;
    for (std::uint32_t f = 1; f <= 240; ++f) j = parse_like_ardupilot(send(server, f, c.pwm));
    ASSERT_TRUE(j.ok);
    EXPECT_GT(j.gyro[c.axis], 0.05) << c.what;
    EXPECT_GT(j.attitude[c.axis], 0.001) << c.what;
    for (int k = 0; k < 3; ++k)
      if (k != c.axis) {
        EXPECT_LT(std::abs(j.gyro[k]), 0.05 * j.gyro[c.axis]) << c.what << k;
      }
  }
}

TEST(ArduPilotJson, NoseUpMovesSouthAndFullThrottleClimbs) {
  ArduPilotJsonSettings s = quiet_quad();
  s.start_height_m = 50;
  s.start_hovering = true;
  ArduPilotJsonServer server(s);
  ParsedLine j;
  std::uint32_t f = 0;
  for (; f < 120; ++f) j = parse_like_ardupilot(send(server, f + 1, {1440, 1480, 1440, 1480}));
  for (; f < 1200; ++f) j = parse_like_ardupilot(send(server, f + 1, {1700, 1700, 1700, 1700}));
  // Facing north, tilted back: the thrust points south and up.
  EXPECT_LT(j.velocity[0], -0.2);
  EXPECT_LT(std::abs(j.velocity[1]), 0.1 * std::abs(j.velocity[0]));
  EXPECT_LT(j.velocity[2], -1.0);
  EXPECT_LT(j.position[2], -50.5);
}

TEST(ArduPilotJson, TakesOffFromTheGroundAndLandsAgain) {
  ArduPilotJsonServer server(quiet_quad());
  std::uint32_t f = 0;
  for (; f < 1200; ++f) send(server, f + 1, {1300, 1300, 1300, 1300});
  EXPECT_TRUE(server.on_ground());
  for (; f < 2400; ++f) send(server, f + 1, {1600, 1600, 1600, 1600});
  EXPECT_FALSE(server.on_ground());
  EXPECT_GT(server.model().state().position_m.z, 1.0);
  for (; f < 12000; ++f) send(server, f + 1, {1400, 1400, 1400, 1400});
  EXPECT_TRUE(server.on_ground());
  EXPECT_EQ(server.model().state().position_m.z, 0.0);
}

double bearing_deg(const vehicle::Rotor& r) {
  return -std::atan2(r.position_m.y, r.position_m.x) * 180 / 3.14159265358979323846;
}

TEST(ArduPilotJson, MotorMapFollowsArduCopterFrames) {
  // Bundled quad-f450 (front-left counter-clockwise): quad X_REV, outputs in its order.
  const auto ccw = vehicle::rotor_layout(vehicle::RotorLayout::quad_x, 0.225, +1);
  const MotorMap rev = ardupilot_motor_map(ccw, "quad");
  EXPECT_NE(rev.frame.find("FRAME_TYPE 18"), std::string::npos) << rev.frame;
  const double rev_bearing[] = {135, 45, -135, -45};
  for (int m = 0; m < 4; ++m) EXPECT_NEAR(bearing_deg(ccw[rev.rotor[m]]), rev_bearing[m], 1e-9);
  // Front-left clockwise: ArduCopter's default quad X (motor 1 front-right CCW, 2 back-left
  // CCW, 3 front-left CW, 4 back-right CW).
  const auto cw = vehicle::rotor_layout(vehicle::RotorLayout::quad_x, 0.225, -1);
  const MotorMap x = ardupilot_motor_map(cw, "quad");
  EXPECT_NE(x.frame.find("FRAME_TYPE 1)"), std::string::npos) << x.frame;
  const double x_bearing[] = {45, -135, -45, 135};
  const int x_spin[] = {+1, +1, -1, -1};
  for (int m = 0; m < 4; ++m) {
    EXPECT_NEAR(bearing_deg(cw[x.rotor[m]]), x_bearing[m], 1e-9);
    EXPECT_EQ(cw[x.rotor[m]].spin, x_spin[m]);
  }
  // Hexa X needs the front-right rotor counter-clockwise.
  EXPECT_EQ(
      ardupilot_motor_map(vehicle::rotor_layout(vehicle::RotorLayout::hexa_x, 0.275, -1), "hexa")
          .frame_class,
      2);
  EXPECT_THROW(
      ardupilot_motor_map(vehicle::rotor_layout(vehicle::RotorLayout::hexa_x, 0.275, +1), "hexa"),
      base::InputError);
  EXPECT_THROW(
      ardupilot_motor_map(vehicle::rotor_layout(vehicle::RotorLayout::y6, 0.275, +1), "y6"),
      base::InputError);
}

#ifdef SWATH_CONTROL_BINARY
// The program as ArduPilot meets it: UDP datagrams in, JSON lines back to the sender, the summary
// and flight.csv when it stops (--idle-exit here; Ctrl-C by hand).
TEST(ArduPilotJsonProgram, ServesOverUdpAndWritesTheFlight) {
  // A free port: bound by us, released, handed to the program.
  int probe = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(probe, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  socklen_t size = sizeof a;
  ::getsockname(probe, reinterpret_cast<sockaddr*>(&a), &size);
  ::close(probe);
  const int port = ntohs(a.sin_port);
  const std::string out = ::testing::TempDir() + "ardupilot-json-" + std::to_string(::getpid());
  std::filesystem::remove_all(out);
  const std::string command = std::string(SWATH_CONTROL_BINARY) + " ardupilot-json --port " +
                              std::to_string(port) + " --idle-exit 0.5 -o " + out + " 2>&1";
  FILE* program = ::popen(command.c_str(), "r");
  ASSERT_NE(program, nullptr);
  char line[1024];
  ASSERT_NE(std::fgets(line, sizeof line, program), nullptr);  // listening
  EXPECT_NE(std::string(line).find("FRAME_TYPE 18"), std::string::npos) << line;

  int udp = ::socket(AF_INET, SOCK_DGRAM, 0);
  timeval timeout{2, 0};
  ::setsockopt(udp, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  const auto exchange = [&](const std::vector<std::uint8_t>& b) {
    ::sendto(udp, b.data(), b.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
    char reply[4096];
    const ssize_t n = ::recv(udp, reply, sizeof reply, 0);
    return n > 0 ? std::string(reply, static_cast<std::size_t>(n)) : std::string();
  };
  std::string last;
  for (std::uint32_t f = 1; f <= 600; ++f)
    last = exchange(packet_bytes(kServoMagic16, 1200, f, {1000, 1000, 1000, 1000}));
  const ParsedLine j = parse_like_ardupilot(last);
  ASSERT_TRUE(j.ok) << last;
  EXPECT_NEAR(j.timestamp, 0.5, 1e-6);
  EXPECT_EQ(exchange(packet_bytes(kServoMagic16, 1200, 600, {1000, 1000, 1000, 1000})), last);
  const std::vector<std::uint8_t> junk{1, 2, 3};
  ::sendto(udp, junk.data(), junk.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
  ::close(udp);

  std::string rest;
  while (std::fgets(line, sizeof line, program)) rest += line;
  EXPECT_EQ(WEXITSTATUS(::pclose(program)), 0);
  EXPECT_NE(rest.find("served 600 frames (1 resends answered again, 1 bad packets ignored), "
                      "0.5 s simulated"),
            std::string::npos)
      << rest;
  // flight.csv read back: 50 rows a simulated second, at rest on the ground.
  std::ifstream csv(out + "/flight.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("time_s,x_m,y_m,z_m,", 0), 0u) << header;
  int rows = 0;
  double previous = -1;
  while (std::getline(csv, row)) {
    std::istringstream fields(row);
    std::string time, x, y, z;
    std::getline(fields, time, ',');
    std::getline(fields, x, ',');
    std::getline(fields, y, ',');
    std::getline(fields, z, ',');
    EXPECT_GT(std::stod(time), previous);
    previous = std::stod(time);
    EXPECT_EQ(std::stod(z), 0.0) << row;
    ++rows;
  }
  EXPECT_NEAR(rows, 25, 1);
  // The battery's columns and summary.json: on the ground at idle the motors draw nothing, the
  // avionics (quad-f450: 3 W) 0.5 s worth.
  EXPECT_NE(header.find(",energy_wh,soc,battery_v"), std::string::npos) << header;
  std::ifstream summary_file(out + "/summary.json");
  const std::string summary((std::istreambuf_iterator<char>(summary_file)),
                            std::istreambuf_iterator<char>());
  EXPECT_NE(summary.find("\"frames_served\": 600"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"avionics_wh\": 0.0004"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"airborne_s\": 0.0"), std::string::npos) << summary;
  std::filesystem::remove_all(out);
}
#endif

}  // namespace
}  // namespace swath::control
