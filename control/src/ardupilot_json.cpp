#include "swath/control/ardupilot_json.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"

namespace swath::control {
namespace {

using vehicle::Quat;
using vehicle::Vec3;

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

std::uint16_t read_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
std::uint32_t read_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

// ENU <-> NED and FLU <-> FRD are each their own inverse.
Vec3 enu_to_ned(const Vec3& v) {
  return {v.y, v.x, -v.z};
}
Vec3 flu_to_frd(const Vec3& v) {
  return {v.x, -v.y, -v.z};
}

// ZYX Euler angles (roll, pitch, yaw) of the body FRD to NED rotation of an ENU/FLU attitude,
// read off the images of the FRD axes in NED (the columns of the rotation matrix).
Vec3 euler_ned_rad(const Quat& attitude) {
  const auto column = [&](const Vec3& frd_axis) {
    return enu_to_ned(vehicle::rotate(attitude, flu_to_frd(frd_axis)));
  };
  const Vec3 cx = column({1, 0, 0}), cy = column({0, 1, 0}), cz = column({0, 0, 1});
  return {std::atan2(cy.z, cz.z), -std::asin(std::clamp(cx.z, -1.0, 1.0)), std::atan2(cx.y, cx.x)};
}

// One ArduCopter motor: bearing clockwise from forward (degrees) and spin (+1 CCW from above),
// as AP_MotorsMatrix.cpp lists them; the array index is the motor number - 1.
struct ApMotorDef {
  double bearing_deg;
  int spin;
};
struct ApFrameDef {
  const char* name;
  int frame_class, frame_type;
  std::vector<ApMotorDef> motors;
};

// AP_MotorsMatrix.cpp (ArduPilot 4.7.0-dev, 90700977c5): setup_quad_matrix MOTOR_FRAME_TYPE_X
// and MOTOR_FRAME_TYPE_BF_X_REV, setup_hexa_matrix MOTOR_FRAME_TYPE_X. BF_X_REV is the quad X of
// swath's bundled quad-f450 (front-left rotor counter-clockwise).
const std::vector<ApFrameDef>& ardupilot_frames() {
  static const std::vector<ApFrameDef> defs{
      {"quad X", 1, 1, {{45, +1}, {-135, +1}, {-45, -1}, {135, -1}}},
      {"quad X_REV (Betaflight order, reversed motors)",
       1,
       18,
       {{135, +1}, {45, -1}, {-135, -1}, {-45, +1}}},
      {"hexa X", 2, 1, {{90, -1}, {-90, +1}, {-30, -1}, {150, +1}, {30, +1}, {-150, -1}}},
  };
  return defs;
}

// The angle between two bearings, degrees in [0, 180].
double bearing_gap_deg(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

// Matches each motor of `frame` to the rotor at its bearing (within 10°) with its spin.
std::optional<MotorMap> match_frame(const ApFrameDef& frame,
                                    const std::vector<vehicle::Rotor>& rotors) {
  if (frame.motors.size() != rotors.size()) return std::nullopt;
  MotorMap map{frame.name, frame.frame_class, {}, {}};
  map.frame = std::string(frame.name) + " (FRAME_CLASS " + std::to_string(frame.frame_class) +
              ", FRAME_TYPE " + std::to_string(frame.frame_type) + ")";
  std::vector<bool> used(rotors.size(), false);
  for (const ApMotorDef& m : frame.motors) {
    bool found = false;
    for (std::size_t i = 0; i < rotors.size() && !found; ++i) {
      // swath's body y points left: the clockwise bearing is -atan2(y, x).
      const double bearing =
          -std::atan2(rotors[i].position_m.y, rotors[i].position_m.x) / kRadPerDeg;
      if (used[i] || rotors[i].spin != m.spin || bearing_gap_deg(bearing, m.bearing_deg) > 10)
        continue;
      used[i] = found = true;
      map.rotor.push_back(i);
      map.spin.push_back(m.spin);
    }
    if (!found) return std::nullopt;
  }
  return map;
}

}  // namespace

std::optional<ServoPacket> parse_servo_packet(const std::uint8_t* bytes, std::size_t size) {
  // SIM_JSON.h: struct { uint16_t magic; uint16_t frame_rate; uint32_t frame_count;
  // uint16_t pwm[N]; } with N = 16 (magic 18458) or 32 (29569): 8 + 2N bytes, no padding.
  if (bytes == nullptr || size < 8) return std::nullopt;
  const std::uint16_t magic = read_u16(bytes);
  const std::size_t channels = magic == kServoMagic16 ? 16 : magic == kServoMagic32 ? 32 : 0;
  if (channels == 0 || size != 8 + 2 * channels) return std::nullopt;
  ServoPacket p;
  p.frame_rate_hz = read_u16(bytes + 2);
  p.frame_count = read_u32(bytes + 4);
  if (p.frame_rate_hz == 0) return std::nullopt;
  for (std::size_t c = 0; c < channels; ++c) p.pwm_us.push_back(read_u16(bytes + 8 + 2 * c));
  return p;
}

MotorMap ardupilot_motor_map(const std::vector<vehicle::Rotor>& rotors, const std::string& source) {
  for (const ApFrameDef& f : ardupilot_frames())
    if (auto m = match_frame(f, rotors)) return *m;
  throw base::InputError(
      source + ": its " + std::to_string(rotors.size()) +
      " rotors are not an ArduCopter frame this server knows (quad X or X_REV, hexa X; a hexa_x "
      "layout needs rotors.first_spin cw)");
}

std::string json_line(const JsonState& s) {
  const auto num = [](double v) { return base::shortest_text(v); };
  const auto vec = [&](const Vec3& v) {
    std::string out(1, '[');
    out += num(v.x);
    out += ',';
    out += num(v.y);
    out += ',';
    out += num(v.z);
    out += ']';
    return out;
  };
  return "\n{\"timestamp\":" + num(s.timestamp_s) + ",\"imu\":{\"gyro\":" + vec(s.gyro_rad_s_frd) +
         ",\"accel_body\":" + vec(s.accel_m_s2_frd) + "},\"position\":" + vec(s.position_m_ned) +
         ",\"attitude\":" + vec(s.attitude_rad) + ",\"velocity\":" + vec(s.velocity_m_s_ned) +
         ",\"airspeed\":" + num(s.airspeed_m_s) + "}\n";
}

namespace {
vehicle::FlightModelSettings json_model_settings(const ArduPilotJsonSettings& s) {
  vehicle::FlightModelSettings m;
  m.physics = s.physics;
  // ArduPilot simulates its own IMU, compass, barometer and GPS from the state we send.
  m.physics.sensors.clear();
  m.environment = s.environment;
  m.seed = s.seed;
  // At rest on the ground, facing north (body x forward = ENU y).
  m.initial.attitude = vehicle::axis_angle({0, 0, 1}, std::numbers::pi / 2);
  m.initial.position_m.z = s.start_height_m;
  if (s.start_hovering) m.initial.rotor_rad_s = vehicle::hover(s.physics.airframe).rotor_rad_s;
  return m;
}
}  // namespace

ArduPilotJsonServer::ArduPilotJsonServer(const ArduPilotJsonSettings& settings)
    : settings_(settings),
      map_(ardupilot_motor_map(settings.physics.airframe.rotors, settings.source)),
      model_(json_model_settings(settings)),
      pwm_us_(settings.physics.airframe.rotors.size(), settings.physics.esc.pwm_min_us),
      on_ground_(settings.start_height_m <= 0) {
  const vehicle::Battery& b = settings.battery;
  energy_.soc = b.initial_soc;
  energy_.voltage_v =
      b.cells > 0 ? vehicle::terminal_voltage_v(b, b.initial_soc, 0.0) : b.voltage_v;
  if (b.cells > 0) model_.set_supply_ratio(energy_.voltage_v / b.volt_max_v);
  last_reply_ = json_line(json_state());
}

std::optional<std::string> ArduPilotJsonServer::handle(const std::uint8_t* bytes,
                                                       std::size_t size) {
  const std::optional<ServoPacket> packet = parse_servo_packet(bytes, size);
  if (!packet) {
    ++bad_;
    return std::nullopt;
  }
  return step(*packet);
}

std::string ArduPilotJsonServer::step(const ServoPacket& packet) {
  // SIM_JSON.cpp resends the same servo packet (same frame_count) when no answer came within
  // a second: the step was taken already, only the answer was lost.
  if (last_frame_ && *last_frame_ == packet.frame_count) {
    ++resends_;
    return last_reply_;
  }
  last_frame_ = packet.frame_count;
  for (std::size_t m = 0; m < map_.rotor.size(); ++m) {
    const double pwm = m < packet.pwm_us.size() ? packet.pwm_us[m] : 0.0;
    // Outputs ArduPilot has not enabled read 0: the ESC sees its minimum.
    const double clamped =
        std::clamp(pwm, settings_.physics.esc.pwm_min_us, settings_.physics.esc.pwm_max_us);
    pwm_us_[map_.rotor[m]] = clamped;
    model_.command_pwm(map_.rotor[m], clamped);
  }
  const vehicle::SimTime dt = vehicle::from_seconds(1.0 / packet.frame_rate_hz);
  model_.advance_to(model_.now() + dt);
  ground_contact();
  draw_battery(vehicle::seconds(dt));
  if (!on_ground_) {
    airborne_s_ += vehicle::seconds(dt);
    const double up = vehicle::rotate(model_.state().attitude, {0, 0, 1}).z;
    max_tilt_deg_ = std::max(max_tilt_deg_, std::acos(std::clamp(up, -1.0, 1.0)) / kRadPerDeg);
  }
  ++frames_;
  last_reply_ = json_line(json_state());
  return last_reply_;
}

void ArduPilotJsonServer::ground_contact() {
  vehicle::MultirotorState s = model_.state();
  if (s.position_m.z > 0) {
    on_ground_ = false;
    return;
  }
  // Touching or below the ground: it rests there, level at its heading, where it stood (or
  // where it came down), until the thrust carries it up again.
  if (!on_ground_) ground_xy_m_ = {s.position_m.x, s.position_m.y, 0};
  on_ground_ = true;
  const Vec3 forward = vehicle::rotate(s.attitude, {1, 0, 0});
  s.attitude = vehicle::axis_angle({0, 0, 1}, std::atan2(forward.y, forward.x));
  s.position_m = ground_xy_m_;
  s.velocity_m_s = {};
  s.rate_rad_s = {};
  model_.set_state(s);
}

// The battery over one step: what the motors drew (the plant's own trapezoid sum) and the
// avionics, taken off the state of charge as swath-control run's battery does (eq. 12, or the
// sagging pack's V I = P); with sag the rotors' speed follows the terminal voltage.
void ArduPilotJsonServer::draw_battery(double dt_s) {
  const vehicle::Battery& b = settings_.battery;
  const double motors_j = model_.motor_energy_j();
  const double avionics_j = settings_.physics.avionics_w * dt_s;
  const double power_w = (motors_j - motor_energy_seen_j_ + avionics_j) / dt_s;
  motor_energy_seen_j_ = motors_j;
  energy_.motors_j = motors_j;
  energy_.avionics_j += avionics_j;
  const bool sags = b.cells > 0;
  const double current_a = sags ? vehicle::sag_current_a(b, energy_.soc, power_w)
                                : vehicle::battery_current_a(b, power_w);
  if (!std::isfinite(current_a)) {
    energy_.battery_empty = true;  // counted, the plant flies on: ArduPilot decides
    return;
  }
  if (sags) {
    energy_.voltage_v = vehicle::terminal_voltage_v(b, energy_.soc, current_a);
    model_.set_supply_ratio(energy_.voltage_v / b.volt_max_v);
  }
  energy_.soc = vehicle::soc_after_charge(b, energy_.soc, current_a * dt_s);
}

JsonState ArduPilotJsonServer::json_state() const {
  const vehicle::MultirotorState& s = model_.state();
  JsonState j;
  j.timestamp_s = vehicle::seconds(model_.now());
  j.gyro_rad_s_frd = flu_to_frd(s.rate_rad_s);
  // Specific force: what accelerometers read, acceleration minus gravity; on the ground the
  // ground's push makes it 1 g up.
  const Vec3 up_g{0, 0, vehicle::kStandardGravity_m_s2};
  const Vec3 specific_world = on_ground_ ? up_g : model_.acceleration_m_s2() + up_g;
  j.accel_m_s2_frd = flu_to_frd(vehicle::rotate_inverse(s.attitude, specific_world));
  j.position_m_ned = enu_to_ned(s.position_m);
  j.velocity_m_s_ned = enu_to_ned(s.velocity_m_s);
  j.attitude_rad = euler_ned_rad(s.attitude);
  j.airspeed_m_s = vehicle::norm(s.velocity_m_s - model_.wind_m_s());
  return j;
}

JsonFlightRow ArduPilotJsonServer::row() const {
  const vehicle::MultirotorState& s = model_.state();
  return {vehicle::seconds(model_.now()),
          s.position_m,
          s.velocity_m_s,
          euler_ned_rad(s.attitude),
          pwm_us_,
          model_.motor_power_w(),
          on_ground_,
          energy_.total_j() / 3600.0,
          energy_.soc,
          energy_.voltage_v};
}

}  // namespace swath::control
