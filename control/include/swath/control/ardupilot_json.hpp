#pragma once
// swath's multirotor as the physics of ArduPilot's JSON SITL interface (ArduPilot
// libraries/SITL/SIM_JSON.cpp, libraries/SITL/examples/JSON/readme.md; docs/swath-control.md,
// "ArduPilot's controller on swath's plant"). ArduPilot sends one binary servo packet per physics
// step; the answer is one line of JSON with the state after stepping 1/frame_rate seconds. The
// class knows nothing of sockets: the program's UDP loop hands it the datagram bytes.
//
// Frames of the JSON (ArduPilot's): world NED (x north, y east, z down) about the start point,
// body FRD (x forward, y right, z down); swath's plant is world ENU / body FLU.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swath/vehicle/battery.hpp"
#include "swath/vehicle/flight_model.hpp"

namespace swath::control {

/// ArduPilot's servo packet (SIM_JSON.h servo_packet_16 / servo_packet_32, little-endian, packed
/// by layout: uint16 magic, uint16 frame_rate, uint32 frame_count, uint16 pwm[16|32]).
struct ServoPacket {
  std::uint16_t frame_rate_hz = 0;
  std::uint32_t frame_count = 0;
  std::vector<std::uint16_t> pwm_us;  ///< 16 or 32 channels, servo output 1 first
};
inline constexpr std::uint16_t kServoMagic16 = 18458;
inline constexpr std::uint16_t kServoMagic32 = 29569;

/// The packet in `bytes`, or nothing when its size and magic are not one of the two layouts or
/// its frame rate is 0.
std::optional<ServoPacket> parse_servo_packet(const std::uint8_t* bytes, std::size_t size);

/// For each ArduCopter motor (motor 1 = servo output 1 first), the index of the swath rotor it
/// drives, and the spin ArduCopter's mixer expects of it (+1 counter-clockwise seen from above).
/// ArduCopter's frames (AP_MotorsMatrix.cpp, MOTOR_FRAME_TYPE_X): quad X (FRAME_CLASS 1) and hexa X
/// (FRAME_CLASS 2), chosen by the rotor count; rotors are matched by their bearing from the centre
/// of mass. Throws base::InputError naming `source` when the rotors are not such a frame.
struct MotorMap {
  std::string frame;               ///< "quad X" or "hexa X"
  int frame_class = 0;             ///< ArduCopter's FRAME_CLASS
  std::vector<std::size_t> rotor;  ///< rotor[m]: the rotor of ArduCopter motor m + 1
  std::vector<int> spin;           ///< spin[m]: ArduCopter's spin for motor m + 1
};
MotorMap ardupilot_motor_map(const std::vector<vehicle::Rotor>& rotors, const std::string& source);

/// What the JSON line carries, in ArduPilot's frames.
struct JsonState {
  double timestamp_s = 0;
  vehicle::Vec3 gyro_rad_s_frd, accel_m_s2_frd;  ///< body rates; specific force
  vehicle::Vec3 position_m_ned, velocity_m_s_ned;
  vehicle::Vec3 attitude_rad;  ///< roll, pitch, yaw (ZYX Euler of body FRD to NED)
  double airspeed_m_s = 0;     ///< through the air (swath's wind), along the body's path
};
/// One line as SIM_JSON.cpp parses it: no space after ':' (its parser steps over `"key":`),
/// vectors as [a,b,c], "\n" first and last (ArduPilot takes the text between the last two
/// newlines, so the leading one makes the very first reply usable too).
std::string json_line(const JsonState& state);

struct ArduPilotJsonSettings {
  vehicle::VehiclePhysics physics = vehicle::default_vehicle();
  vehicle::Environment environment;
  std::uint64_t seed = 1;
  std::string source = "vehicle";  ///< names the vehicle in messages
  /// The vehicle file's battery (energy::parse_battery_section): fed by the motors and the
  /// avionics every step, as swath-control run feeds it (without a flight computer: ArduPilot's
  /// runs elsewhere). With voltage sag (cells > 0) the motors' speed follows the terminal voltage
  /// as in run's plant; ArduPilot is sent no voltage, so nothing compensates.
  vehicle::Battery battery;
  /// Where it starts: on the ground (0) or this high with the rotors at rest, or at the hover
  /// speed of still air (vehicle::hover) with `start_hovering` (tests: free fall, hover).
  double start_height_m = 0;
  bool start_hovering = false;
};

/// One row of the flight (the program's CSV), swath's frames.
struct JsonFlightRow {
  double time_s = 0;
  vehicle::Vec3 position_m_enu, velocity_m_s_enu, attitude_rad;  ///< attitude: roll, pitch, yaw NED
  std::vector<double> pwm_us;                                    ///< per swath rotor
  double motor_power_w = 0;
  bool on_ground = true;
  double energy_wh = 0;  ///< drawn from the battery so far (motors + avionics)
  double soc = 0;        ///< the battery's state of charge
  double battery_v = 0;  ///< terminal voltage (with sag), else the pack's nominal voltage
};

/// What the battery gave over the flight so far. The energy is what the loads drew (the motors'
/// electrical power, trapezoid per plant sub-step, plus the avionics' constant power), as
/// swath-control run's summary counts it; the state of charge is the charge the battery's
/// current (eq. 12, or the sagging pack's V I = P) took off the capacity.
struct JsonEnergy {
  double motors_j = 0, avionics_j = 0;
  double soc = 1;
  double voltage_v = 0;        ///< terminal voltage at the last step
  bool battery_empty = false;  ///< the battery could not deliver the power at some step
  double total_j() const { return motors_j + avionics_j; }
};

class ArduPilotJsonServer {
 public:
  /// Starts at rest on the ground at the origin, facing north. Throws base::InputError when the
  /// vehicle's rotors are not an ArduCopter frame (ardupilot_motor_map).
  explicit ArduPilotJsonServer(const ArduPilotJsonSettings& settings);

  /// Handles one datagram: a servo packet steps the plant by 1/frame_rate (a repeated
  /// frame_count is a resend: the same state is answered again without stepping) and returns the
  /// JSON line; anything else is counted in bad_packets() and gets no answer.
  std::optional<std::string> handle(const std::uint8_t* bytes, std::size_t size);
  /// The JSON line after stepping with `packet` (resends answered without stepping).
  std::string step(const ServoPacket& packet);

  const MotorMap& motor_map() const { return map_; }
  const vehicle::FlightModel& model() const { return model_; }
  JsonState json_state() const;
  JsonFlightRow row() const;
  bool on_ground() const { return on_ground_; }

  const JsonEnergy& energy() const { return energy_; }
  /// Seconds of simulated time off the ground; the largest tilt while off it, degrees.
  double airborne_s() const { return airborne_s_; }
  double max_tilt_deg() const { return max_tilt_deg_; }

  long long frames_served() const { return frames_; }
  long long resends() const { return resends_; }
  long long bad_packets() const { return bad_; }
  double sim_time_s() const { return vehicle::seconds(model_.now()); }

 private:
  void ground_contact();
  void draw_battery(double dt_s);

  ArduPilotJsonSettings settings_;
  MotorMap map_;
  vehicle::FlightModel model_;
  std::optional<std::uint32_t> last_frame_;
  std::string last_reply_;
  std::vector<double> pwm_us_;  ///< per swath rotor, as last commanded
  vehicle::Vec3 ground_xy_m_;   ///< where it rests while on the ground
  bool on_ground_ = true;
  JsonEnergy energy_;
  double motor_energy_seen_j_ = 0;  ///< model_.motor_energy_j() at the last battery step
  double airborne_s_ = 0, max_tilt_deg_ = 0;
  long long frames_ = 0, resends_ = 0, bad_ = 0;
};

}  // namespace swath::control
