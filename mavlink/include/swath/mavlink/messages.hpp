#pragma once
// The MAVLink messages swath speaks (docs/swath-fleet.md), as plain value types.
//
// Each message lists its fields once, in `fields(v)`, in wire order: the base fields sorted by type
// size (largest first, stable within a size, as MAVLink's generators order them), then the
// extension fields in definition order. Every job is done from that one list: encoding, decoding
// (payload.hpp), the CRC_EXTRA seed (crc_extra.hpp) and the text dump. The second argument is the
// field's MAVLink name, which the CRC_EXTRA seed hashes; members carry their unit in their C++ name
// (`lat_degE7`, `alt_mm`, `vx_cm_s`). A layout slip changes CRC_EXTRA, which the tests compare with
// node-mavlink's table, so it cannot go unnoticed.
//
// Only MAVLink v2 "common"/"minimal" messages; enums are plain integers named in comments.

#include <array>
#include <cstdint>
#include <string_view>

namespace swath::mavlink {

/// HEARTBEAT (0): who is there, in which mode; sent by every node at 1 Hz.
struct Heartbeat {
  static constexpr std::uint32_t kId = 0;
  static constexpr std::string_view kName = "HEARTBEAT";
  std::uint32_t custom_mode = 0;   ///< autopilot-specific (ArduCopter: 4 GUIDED, 6 RTL, 9 LAND)
  std::uint8_t type = 0;           ///< MAV_TYPE (2 quadrotor, 6 GCS)
  std::uint8_t autopilot = 0;      ///< MAV_AUTOPILOT (3 ArduPilot, 12 PX4, 8 invalid = a GCS)
  std::uint8_t base_mode = 0;      ///< MAV_MODE_FLAG bits; 0x80 = armed
  std::uint8_t system_status = 0;  ///< MAV_STATE (3 standby, 4 active)
  std::uint8_t mavlink_version = 3;
  template <class V>
  constexpr void fields(V& v) {
    v.field(custom_mode, "custom_mode");
    v.field(type, "type");
    v.field(autopilot, "autopilot");
    v.field(base_mode, "base_mode");
    v.field(system_status, "system_status");
    v.field(mavlink_version, "mavlink_version");
  }
};

/// SYS_STATUS (1): sensors, load, battery voltage and current.
struct SysStatus {
  static constexpr std::uint32_t kId = 1;
  static constexpr std::string_view kName = "SYS_STATUS";
  std::uint32_t onboard_control_sensors_present = 0;
  std::uint32_t onboard_control_sensors_enabled = 0;
  std::uint32_t onboard_control_sensors_health = 0;
  std::uint16_t load_permille = 0;
  std::uint16_t voltage_battery_mV = 0;
  std::int16_t current_battery_cA = 0;  ///< -1: not measured
  std::uint16_t drop_rate_comm_centipercent = 0;
  std::uint16_t errors_comm = 0;
  std::uint16_t errors_count1 = 0;
  std::uint16_t errors_count2 = 0;
  std::uint16_t errors_count3 = 0;
  std::uint16_t errors_count4 = 0;
  std::int8_t battery_remaining_percent = 0;  ///< -1: not known
  std::uint32_t onboard_control_sensors_present_extended = 0;
  std::uint32_t onboard_control_sensors_enabled_extended = 0;
  std::uint32_t onboard_control_sensors_health_extended = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(onboard_control_sensors_present, "onboard_control_sensors_present");
    v.field(onboard_control_sensors_enabled, "onboard_control_sensors_enabled");
    v.field(onboard_control_sensors_health, "onboard_control_sensors_health");
    v.field(load_permille, "load");
    v.field(voltage_battery_mV, "voltage_battery");
    v.field(current_battery_cA, "current_battery");
    v.field(drop_rate_comm_centipercent, "drop_rate_comm");
    v.field(errors_comm, "errors_comm");
    v.field(errors_count1, "errors_count1");
    v.field(errors_count2, "errors_count2");
    v.field(errors_count3, "errors_count3");
    v.field(errors_count4, "errors_count4");
    v.field(battery_remaining_percent, "battery_remaining");
    v.extension(onboard_control_sensors_present_extended,
                "onboard_control_sensors_present_extended");
    v.extension(onboard_control_sensors_enabled_extended,
                "onboard_control_sensors_enabled_extended");
    v.extension(onboard_control_sensors_health_extended, "onboard_control_sensors_health_extended");
  }
};

/// SYSTEM_TIME (2).
struct SystemTime {
  static constexpr std::uint32_t kId = 2;
  static constexpr std::string_view kName = "SYSTEM_TIME";
  std::uint64_t time_unix_us = 0;
  std::uint32_t time_boot_ms = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(time_unix_us, "time_unix_usec");
    v.field(time_boot_ms, "time_boot_ms");
  }
};

/// PARAM_REQUEST_READ (20): asks for one parameter by name (param_index -1) or by index.
struct ParamRequestRead {
  static constexpr std::uint32_t kId = 20;
  static constexpr std::string_view kName = "PARAM_REQUEST_READ";
  std::int16_t param_index = -1;  ///< -1: by param_id
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::array<char, 16> param_id{};  ///< NUL-terminated unless 16 characters long
  template <class V>
  constexpr void fields(V& v) {
    v.field(param_index, "param_index");
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.field(param_id, "param_id");
  }
};

/// PARAM_VALUE (22): one parameter's value, the answer to PARAM_REQUEST_READ. How param_value
/// carries an integer depends on the autopilot: ArduPilot converts it to a float (C cast), PX4
/// copies its bytes (MAV_PROTOCOL_CAPABILITY_PARAM_ENCODE_BYTEWISE).
struct ParamValue {
  static constexpr std::uint32_t kId = 22;
  static constexpr std::string_view kName = "PARAM_VALUE";
  float param_value = 0;
  std::uint16_t param_count = 0;
  std::uint16_t param_index = 0;
  std::array<char, 16> param_id{};
  std::uint8_t param_type = 0;  ///< MAV_PARAM_TYPE (2 int8, 6 int32, 9 real32)
  template <class V>
  constexpr void fields(V& v) {
    v.field(param_value, "param_value");
    v.field(param_count, "param_count");
    v.field(param_index, "param_index");
    v.field(param_id, "param_id");
    v.field(param_type, "param_type");
  }
};

/// PARAM_SET (23): sets one parameter by name; the vehicle answers with its PARAM_VALUE (the value
/// it now holds, which tells whether the set took).
struct ParamSet {
  static constexpr std::uint32_t kId = 23;
  static constexpr std::string_view kName = "PARAM_SET";
  float param_value = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::array<char, 16> param_id{};  ///< NUL-terminated unless 16 characters long
  std::uint8_t param_type = 0;      ///< MAV_PARAM_TYPE
  template <class V>
  constexpr void fields(V& v) {
    v.field(param_value, "param_value");
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.field(param_id, "param_id");
    v.field(param_type, "param_type");
  }
};

/// GPS_RAW_INT (24): the receiver's fix.
struct GpsRawInt {
  static constexpr std::uint32_t kId = 24;
  static constexpr std::string_view kName = "GPS_RAW_INT";
  std::uint64_t time_us = 0;
  std::int32_t lat_degE7 = 0;
  std::int32_t lon_degE7 = 0;
  std::int32_t alt_mm = 0;  ///< above mean sea level
  std::uint16_t eph = 0;    ///< HDOP x 100
  std::uint16_t epv = 0;    ///< VDOP x 100
  std::uint16_t vel_cm_s = 0;
  std::uint16_t cog_cdeg = 0;
  std::uint8_t fix_type = 0;  ///< GPS_FIX_TYPE (3 = 3D)
  std::uint8_t satellites_visible = 0;
  std::int32_t alt_ellipsoid_mm = 0;
  std::uint32_t h_acc_mm = 0;
  std::uint32_t v_acc_mm = 0;
  std::uint32_t vel_acc_mm_s = 0;
  std::uint32_t hdg_acc_degE5 = 0;
  std::uint16_t yaw_cdeg = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(time_us, "time_usec");
    v.field(lat_degE7, "lat");
    v.field(lon_degE7, "lon");
    v.field(alt_mm, "alt");
    v.field(eph, "eph");
    v.field(epv, "epv");
    v.field(vel_cm_s, "vel");
    v.field(cog_cdeg, "cog");
    v.field(fix_type, "fix_type");
    v.field(satellites_visible, "satellites_visible");
    v.extension(alt_ellipsoid_mm, "alt_ellipsoid");
    v.extension(h_acc_mm, "h_acc");
    v.extension(v_acc_mm, "v_acc");
    v.extension(vel_acc_mm_s, "vel_acc");
    v.extension(hdg_acc_degE5, "hdg_acc");
    v.extension(yaw_cdeg, "yaw");
  }
};

/// ATTITUDE (30): roll, pitch, yaw in radians (yaw from north, clockwise), body rates in rad/s.
struct Attitude {
  static constexpr std::uint32_t kId = 30;
  static constexpr std::string_view kName = "ATTITUDE";
  std::uint32_t time_boot_ms = 0;
  float roll_rad = 0, pitch_rad = 0, yaw_rad = 0;
  float rollspeed_rad_s = 0, pitchspeed_rad_s = 0, yawspeed_rad_s = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(time_boot_ms, "time_boot_ms");
    v.field(roll_rad, "roll");
    v.field(pitch_rad, "pitch");
    v.field(yaw_rad, "yaw");
    v.field(rollspeed_rad_s, "rollspeed");
    v.field(pitchspeed_rad_s, "pitchspeed");
    v.field(yawspeed_rad_s, "yawspeed");
  }
};

/// LOCAL_POSITION_NED (32): metres north, east, down of the EKF origin.
struct LocalPositionNed {
  static constexpr std::uint32_t kId = 32;
  static constexpr std::string_view kName = "LOCAL_POSITION_NED";
  std::uint32_t time_boot_ms = 0;
  float x_m = 0, y_m = 0, z_m = 0;
  float vx_m_s = 0, vy_m_s = 0, vz_m_s = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(time_boot_ms, "time_boot_ms");
    v.field(x_m, "x");
    v.field(y_m, "y");
    v.field(z_m, "z");
    v.field(vx_m_s, "vx");
    v.field(vy_m_s, "vy");
    v.field(vz_m_s, "vz");
  }
};

/// GLOBAL_POSITION_INT (33): the fused position; swath's telemetry at 10 Hz.
struct GlobalPositionInt {
  static constexpr std::uint32_t kId = 33;
  static constexpr std::string_view kName = "GLOBAL_POSITION_INT";
  std::uint32_t time_boot_ms = 0;
  std::int32_t lat_degE7 = 0;
  std::int32_t lon_degE7 = 0;
  std::int32_t alt_mm = 0;           ///< above mean sea level
  std::int32_t relative_alt_mm = 0;  ///< above home
  std::int16_t vx_cm_s = 0;          ///< north
  std::int16_t vy_cm_s = 0;          ///< east
  std::int16_t vz_cm_s = 0;          ///< down
  std::uint16_t hdg_cdeg = 0;        ///< 0..35999 from north, clockwise; 65535 = unknown
  template <class V>
  constexpr void fields(V& v) {
    v.field(time_boot_ms, "time_boot_ms");
    v.field(lat_degE7, "lat");
    v.field(lon_degE7, "lon");
    v.field(alt_mm, "alt");
    v.field(relative_alt_mm, "relative_alt");
    v.field(vx_cm_s, "vx");
    v.field(vy_cm_s, "vy");
    v.field(vz_cm_s, "vz");
    v.field(hdg_cdeg, "hdg");
  }
};

/// MISSION_REQUEST (40): the vehicle asks for item `seq` during an upload (ArduPilot asks with this
/// one, not MISSION_REQUEST_INT; either is answered with MISSION_ITEM_INT).
struct MissionRequest {
  static constexpr std::uint32_t kId = 40;
  static constexpr std::string_view kName = "MISSION_REQUEST";
  std::uint16_t seq = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t mission_type = 0;  ///< MAV_MISSION_TYPE (0 mission, 1 fence, 2 rally)
  template <class V>
  constexpr void fields(V& v) {
    v.field(seq, "seq");
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.extension(mission_type, "mission_type");
  }
};

/// MISSION_CURRENT (42).
struct MissionCurrent {
  static constexpr std::uint32_t kId = 42;
  static constexpr std::string_view kName = "MISSION_CURRENT";
  std::uint16_t seq = 0;
  std::uint16_t total = 0;
  std::uint8_t mission_state = 0;
  std::uint8_t mission_mode = 0;
  std::uint32_t mission_id = 0;
  std::uint32_t fence_id = 0;
  std::uint32_t rally_points_id = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(seq, "seq");
    v.extension(total, "total");
    v.extension(mission_state, "mission_state");
    v.extension(mission_mode, "mission_mode");
    v.extension(mission_id, "mission_id");
    v.extension(fence_id, "fence_id");
    v.extension(rally_points_id, "rally_points_id");
  }
};

/// MISSION_REQUEST_LIST (43): the ground station asks for the stored items (a read-back).
struct MissionRequestList {
  static constexpr std::uint32_t kId = 43;
  static constexpr std::string_view kName = "MISSION_REQUEST_LIST";
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t mission_type = 0;  ///< MAV_MISSION_TYPE
  template <class V>
  constexpr void fields(V& v) {
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.extension(mission_type, "mission_type");
  }
};

/// MISSION_COUNT (44): how many items an upload sends, or a read-back will get.
struct MissionCount {
  static constexpr std::uint32_t kId = 44;
  static constexpr std::string_view kName = "MISSION_COUNT";
  std::uint16_t count = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t mission_type = 0;  ///< MAV_MISSION_TYPE
  std::uint32_t opaque_id = 0;    ///< the vehicle's id of the stored plan (0: none given)
  template <class V>
  constexpr void fields(V& v) {
    v.field(count, "count");
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.extension(mission_type, "mission_type");
    v.extension(opaque_id, "opaque_id");
  }
};

/// MISSION_ITEM_REACHED (46).
struct MissionItemReached {
  static constexpr std::uint32_t kId = 46;
  static constexpr std::string_view kName = "MISSION_ITEM_REACHED";
  std::uint16_t seq = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(seq, "seq");
  }
};

/// MISSION_ACK (47): ends a transfer; `type` MAV_MISSION_RESULT (0 accepted, else why not).
struct MissionAck {
  static constexpr std::uint32_t kId = 47;
  static constexpr std::string_view kName = "MISSION_ACK";
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t type = 0;          ///< MAV_MISSION_RESULT
  std::uint8_t mission_type = 0;  ///< MAV_MISSION_TYPE
  std::uint32_t opaque_id = 0;    ///< the vehicle's id of the stored plan (0: none given)
  template <class V>
  constexpr void fields(V& v) {
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.field(type, "type");
    v.extension(mission_type, "mission_type");
    v.extension(opaque_id, "opaque_id");
  }
};

/// MISSION_REQUEST_INT (51): asks for item `seq` (the ground station's read-back).
struct MissionRequestInt {
  static constexpr std::uint32_t kId = 51;
  static constexpr std::string_view kName = "MISSION_REQUEST_INT";
  std::uint16_t seq = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t mission_type = 0;  ///< MAV_MISSION_TYPE
  template <class V>
  constexpr void fields(V& v) {
    v.field(seq, "seq");
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.extension(mission_type, "mission_type");
  }
};

/// MISSION_ITEM_INT (73): one item (x, y = lat, lon in degE7 for global frames; fence vertices:
/// param1 the polygon's vertex count, circles: param1 the radius in metres).
struct MissionItemInt {
  static constexpr std::uint32_t kId = 73;
  static constexpr std::string_view kName = "MISSION_ITEM_INT";
  float param1 = 0, param2 = 0, param3 = 0, param4 = 0;
  std::int32_t x = 0;
  std::int32_t y = 0;
  float z = 0;
  std::uint16_t seq = 0;
  std::uint16_t command = 0;  ///< MAV_CMD
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t frame = 0;  ///< MAV_FRAME
  std::uint8_t current = 0;
  std::uint8_t autocontinue = 0;
  std::uint8_t mission_type = 0;  ///< MAV_MISSION_TYPE
  template <class V>
  constexpr void fields(V& v) {
    v.field(param1, "param1");
    v.field(param2, "param2");
    v.field(param3, "param3");
    v.field(param4, "param4");
    v.field(x, "x");
    v.field(y, "y");
    v.field(z, "z");
    v.field(seq, "seq");
    v.field(command, "command");
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.field(frame, "frame");
    v.field(current, "current");
    v.field(autocontinue, "autocontinue");
    v.extension(mission_type, "mission_type");
  }
};

/// VFR_HUD (74).
struct VfrHud {
  static constexpr std::uint32_t kId = 74;
  static constexpr std::string_view kName = "VFR_HUD";
  float airspeed_m_s = 0, groundspeed_m_s = 0, alt_m = 0, climb_m_s = 0;
  std::int16_t heading_deg = 0;
  std::uint16_t throttle_percent = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(airspeed_m_s, "airspeed");
    v.field(groundspeed_m_s, "groundspeed");
    v.field(alt_m, "alt");
    v.field(climb_m_s, "climb");
    v.field(heading_deg, "heading");
    v.field(throttle_percent, "throttle");
  }
};

/// COMMAND_INT (75): a command with a position (x, y = lat, lon in degE7 for global frames).
struct CommandInt {
  static constexpr std::uint32_t kId = 75;
  static constexpr std::string_view kName = "COMMAND_INT";
  float param1 = 0, param2 = 0, param3 = 0, param4 = 0;
  std::int32_t x = 0;
  std::int32_t y = 0;
  float z = 0;
  std::uint16_t command = 0;  ///< MAV_CMD
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t frame = 0;  ///< MAV_FRAME (6 = global, altitude relative to home, integer lat/lon)
  std::uint8_t current = 0;
  std::uint8_t autocontinue = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(param1, "param1");
    v.field(param2, "param2");
    v.field(param3, "param3");
    v.field(param4, "param4");
    v.field(x, "x");
    v.field(y, "y");
    v.field(z, "z");
    v.field(command, "command");
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.field(frame, "frame");
    v.field(current, "current");
    v.field(autocontinue, "autocontinue");
  }
};

/// COMMAND_LONG (76): a command with seven float parameters.
struct CommandLong {
  static constexpr std::uint32_t kId = 76;
  static constexpr std::string_view kName = "COMMAND_LONG";
  float param1 = 0, param2 = 0, param3 = 0, param4 = 0, param5 = 0, param6 = 0, param7 = 0;
  std::uint16_t command = 0;  ///< MAV_CMD
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t confirmation = 0;  ///< 0 first time, +1 per resend
  template <class V>
  constexpr void fields(V& v) {
    v.field(param1, "param1");
    v.field(param2, "param2");
    v.field(param3, "param3");
    v.field(param4, "param4");
    v.field(param5, "param5");
    v.field(param6, "param6");
    v.field(param7, "param7");
    v.field(command, "command");
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.field(confirmation, "confirmation");
  }
};

/// COMMAND_ACK (77).
struct CommandAck {
  static constexpr std::uint32_t kId = 77;
  static constexpr std::string_view kName = "COMMAND_ACK";
  std::uint16_t command = 0;
  std::uint8_t result =
      0;  ///< MAV_RESULT (0 accepted, 1 temporarily rejected, 2 denied, 4 failed, 5 in progress)
  std::uint8_t progress_percent = 0;
  std::int32_t result_param2 = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(command, "command");
    v.field(result, "result");
    v.extension(progress_percent, "progress");
    v.extension(result_param2, "result_param2");
    v.extension(target_system, "target_system");
    v.extension(target_component, "target_component");
  }
};

/// What SET_POSITION_TARGET_GLOBAL_INT (86) and POSITION_TARGET_GLOBAL_INT (87) share, in wire
/// order; each adds its own last fields.
struct GlobalPositionTarget {
  std::uint32_t time_boot_ms = 0;
  std::int32_t lat_degE7 = 0;
  std::int32_t lon_degE7 = 0;
  float alt_m = 0;  ///< in coordinate_frame's reference (6: above home)
  float vx_m_s = 0, vy_m_s = 0, vz_m_s = 0;
  float afx_m_s2 = 0, afy_m_s2 = 0, afz_m_s2 = 0;
  float yaw_rad = 0, yaw_rate_rad_s = 0;
  std::uint16_t type_mask = 0;  ///< bits of what to ignore (0x0DF8: all but position)

 protected:
  template <class V>
  constexpr void target_fields(V& v) {
    v.field(time_boot_ms, "time_boot_ms");
    v.field(lat_degE7, "lat_int");
    v.field(lon_degE7, "lon_int");
    v.field(alt_m, "alt");
    v.field(vx_m_s, "vx");
    v.field(vy_m_s, "vy");
    v.field(vz_m_s, "vz");
    v.field(afx_m_s2, "afx");
    v.field(afy_m_s2, "afy");
    v.field(afz_m_s2, "afz");
    v.field(yaw_rad, "yaw");
    v.field(yaw_rate_rad_s, "yaw_rate");
    v.field(type_mask, "type_mask");
  }
};

/// SET_POSITION_TARGET_GLOBAL_INT (86): where GUIDED mode flies to.
struct SetPositionTargetGlobalInt : GlobalPositionTarget {
  static constexpr std::uint32_t kId = 86;
  static constexpr std::string_view kName = "SET_POSITION_TARGET_GLOBAL_INT";
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
  std::uint8_t coordinate_frame = 0;
  template <class V>
  constexpr void fields(V& v) {
    target_fields(v);
    v.field(target_system, "target_system");
    v.field(target_component, "target_component");
    v.field(coordinate_frame, "coordinate_frame");
  }
};

/// POSITION_TARGET_GLOBAL_INT (87): the target the vehicle is flying to, as it understood it.
struct PositionTargetGlobalInt : GlobalPositionTarget {
  static constexpr std::uint32_t kId = 87;
  static constexpr std::string_view kName = "POSITION_TARGET_GLOBAL_INT";
  std::uint8_t coordinate_frame = 0;
  template <class V>
  constexpr void fields(V& v) {
    target_fields(v);
    v.field(coordinate_frame, "coordinate_frame");
  }
};

/// BATTERY_STATUS (147).
struct BatteryStatus {
  static constexpr std::uint32_t kId = 147;
  static constexpr std::string_view kName = "BATTERY_STATUS";
  std::int32_t current_consumed_mAh = 0;
  std::int32_t energy_consumed_hJ = 0;
  std::int16_t temperature_cdegC = 0;
  std::array<std::uint16_t, 10> voltages_mV{};
  std::int16_t current_battery_cA = 0;
  std::uint8_t id = 0;
  std::uint8_t battery_function = 0;
  std::uint8_t type = 0;
  std::int8_t battery_remaining_percent = 0;
  std::int32_t time_remaining_s = 0;
  std::uint8_t charge_state = 0;
  std::array<std::uint16_t, 4> voltages_ext_mV{};
  std::uint8_t mode = 0;
  std::uint32_t fault_bitmask = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(current_consumed_mAh, "current_consumed");
    v.field(energy_consumed_hJ, "energy_consumed");
    v.field(temperature_cdegC, "temperature");
    v.field(voltages_mV, "voltages");
    v.field(current_battery_cA, "current_battery");
    v.field(id, "id");
    v.field(battery_function, "battery_function");
    v.field(type, "type");
    v.field(battery_remaining_percent, "battery_remaining");
    v.extension(time_remaining_s, "time_remaining");
    v.extension(charge_state, "charge_state");
    v.extension(voltages_ext_mV, "voltages_ext");
    v.extension(mode, "mode");
    v.extension(fault_bitmask, "fault_bitmask");
  }
};

/// HOME_POSITION (242).
struct HomePosition {
  static constexpr std::uint32_t kId = 242;
  static constexpr std::string_view kName = "HOME_POSITION";
  std::int32_t latitude_degE7 = 0;
  std::int32_t longitude_degE7 = 0;
  std::int32_t altitude_mm = 0;  ///< above mean sea level
  float x_m = 0, y_m = 0, z_m = 0;
  std::array<float, 4> q{};
  float approach_x_m = 0, approach_y_m = 0, approach_z_m = 0;
  std::uint64_t time_us = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(latitude_degE7, "latitude");
    v.field(longitude_degE7, "longitude");
    v.field(altitude_mm, "altitude");
    v.field(x_m, "x");
    v.field(y_m, "y");
    v.field(z_m, "z");
    v.field(q, "q");
    v.field(approach_x_m, "approach_x");
    v.field(approach_y_m, "approach_y");
    v.field(approach_z_m, "approach_z");
    v.extension(time_us, "time_usec");
  }
};

/// EXTENDED_SYS_STATE (245): landed_state MAV_LANDED_STATE (1 on ground, 2 in air, 3 taking off,
/// 4 landing).
struct ExtendedSysState {
  static constexpr std::uint32_t kId = 245;
  static constexpr std::string_view kName = "EXTENDED_SYS_STATE";
  std::uint8_t vtol_state = 0;
  std::uint8_t landed_state = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(vtol_state, "vtol_state");
    v.field(landed_state, "landed_state");
  }
};

/// NAMED_VALUE_FLOAT (251): a companion computer's sensor value, name up to 10 characters.
struct NamedValueFloat {
  static constexpr std::uint32_t kId = 251;
  static constexpr std::string_view kName = "NAMED_VALUE_FLOAT";
  std::uint32_t time_boot_ms = 0;
  float value = 0;
  std::array<char, 10> name{};
  template <class V>
  constexpr void fields(V& v) {
    v.field(time_boot_ms, "time_boot_ms");
    v.field(value, "value");
    v.field(name, "name");
  }
};

/// STATUSTEXT (253): a sentence from the vehicle (e.g. why it refuses to arm).
struct StatusText {
  static constexpr std::uint32_t kId = 253;
  static constexpr std::string_view kName = "STATUSTEXT";
  std::uint8_t severity = 0;  ///< MAV_SEVERITY (0 emergency .. 7 debug)
  std::array<char, 50> text{};
  std::uint16_t id = 0;
  std::uint8_t chunk_seq = 0;
  template <class V>
  constexpr void fields(V& v) {
    v.field(severity, "severity");
    v.field(text, "text");
    v.extension(id, "id");
    v.extension(chunk_seq, "chunk_seq");
  }
};

/// CAMERA_IMAGE_CAPTURED (263): a photo taken, where.
struct CameraImageCaptured {
  static constexpr std::uint32_t kId = 263;
  static constexpr std::string_view kName = "CAMERA_IMAGE_CAPTURED";
  std::uint64_t time_utc_us = 0;
  std::uint32_t time_boot_ms = 0;
  std::int32_t lat_degE7 = 0;
  std::int32_t lon_degE7 = 0;
  std::int32_t alt_mm = 0;
  std::int32_t relative_alt_mm = 0;
  std::array<float, 4> q{};
  std::int32_t image_index = 0;
  std::uint8_t camera_id = 0;
  std::int8_t capture_result = 0;  ///< 1 success
  std::array<char, 205> file_url{};
  template <class V>
  constexpr void fields(V& v) {
    v.field(time_utc_us, "time_utc");
    v.field(time_boot_ms, "time_boot_ms");
    v.field(lat_degE7, "lat");
    v.field(lon_degE7, "lon");
    v.field(alt_mm, "alt");
    v.field(relative_alt_mm, "relative_alt");
    v.field(q, "q");
    v.field(image_index, "image_index");
    v.field(camera_id, "camera_id");
    v.field(capture_result, "capture_result");
    v.field(file_url, "file_url");
  }
};

/// Calls `f(M{})` once per message type above, in id order: the one list of what swath speaks.
template <class F>
constexpr void for_each_message(F&& f) {
  f(Heartbeat{});
  f(SysStatus{});
  f(SystemTime{});
  f(ParamRequestRead{});
  f(ParamValue{});
  f(ParamSet{});
  f(GpsRawInt{});
  f(Attitude{});
  f(LocalPositionNed{});
  f(GlobalPositionInt{});
  f(MissionRequest{});
  f(MissionCurrent{});
  f(MissionRequestList{});
  f(MissionCount{});
  f(MissionItemReached{});
  f(MissionAck{});
  f(MissionRequestInt{});
  f(MissionItemInt{});
  f(VfrHud{});
  f(CommandInt{});
  f(CommandLong{});
  f(CommandAck{});
  f(SetPositionTargetGlobalInt{});
  f(PositionTargetGlobalInt{});
  f(BatteryStatus{});
  f(HomePosition{});
  f(ExtendedSysState{});
  f(NamedValueFloat{});
  f(StatusText{});
  f(CameraImageCaptured{});
}

}  // namespace swath::mavlink
