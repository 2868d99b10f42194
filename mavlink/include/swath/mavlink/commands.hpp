#pragma once
// MAVLink enum values swath sends or reads (docs/swath-fleet.md), named once.

#include <cstdint>

namespace swath::mavlink {

/// MAV_CMD values (COMMAND_LONG / COMMAND_INT `command`).
enum class Cmd : std::uint16_t {
  nav_waypoint = 16,      ///< param1: hold, s; param5-7: position
  nav_loiter_turns = 18,  ///< param1: turns; param3: radius, m (negative: counter-clockwise)
  nav_loiter_time = 19,   ///< param1: hold, s
  nav_return_to_launch = 20,
  nav_land = 21,
  nav_takeoff = 22,       ///< param7: altitude above home, m
  nav_delay = 93,         ///< param1: seconds
  condition_delay = 112,  ///< param1: seconds
  condition_yaw = 115,
  do_set_mode = 176,      ///< param1: 1 (custom mode enabled), param2: custom mode
  do_jump = 177,          ///< param1: the item (sequence number) to go to; param2: repeats
  do_change_speed = 178,  ///< param1: 0/1 horizontal, 2 climb, 3 descent speed; param2: m/s
  do_land_start = 189,
  do_reposition = 192,
  do_set_roi_location = 195,
  do_set_roi_none = 197,
  do_set_roi = 201,
  do_digicam_configure = 202,
  do_digicam_control = 203,
  do_mount_configure = 204,
  do_mount_control = 205,
  do_set_cam_trigg_dist = 206,  ///< param1: distance, m (0: stop)
  component_arm_disarm = 400,   ///< param1: 1 arm, 0 disarm
  set_message_interval = 511,   ///< param1: message id, param2: interval in microseconds
  request_message = 512,        ///< param1: message id
  do_gimbal_manager_pitchyaw = 1000,
  do_gimbal_manager_configure = 1001,
  image_start_capture = 2000,  ///< param2: interval, s; param3: number of images (1)
  image_stop_capture = 2001,
  nav_fence_polygon_vertex_inclusion = 5001,
  nav_fence_polygon_vertex_exclusion = 5002,
  nav_fence_circle_inclusion = 5003,
  nav_fence_circle_exclusion = 5004,
  nav_rally_point = 5100,
};

/// MAV_FRAME values of mission items: what param7 (altitude) is measured from.
enum class MavFrame : std::uint8_t {
  global = 0,               ///< above mean sea level
  mission = 2,              ///< no position (a command)
  global_relative_alt = 3,  ///< above home
  global_int = 5,           ///< as global, integer positions
  global_relative_alt_int = 6,
  global_terrain_alt = 10,  ///< above the ground under the point
  global_terrain_alt_int = 11,
};

/// MAV_MISSION_TYPE values (the mission protocol's `mission_type`).
enum class MissionType : std::uint8_t { mission = 0, fence = 1, rally = 2 };

/// MAV_MISSION_RESULT values (MISSION_ACK `type`) swath names.
enum class MissionResult : std::uint8_t {
  accepted = 0,
  error = 1,
  unsupported_frame = 2,
  unsupported = 3,
  no_space = 4,
  invalid = 5,
  invalid_sequence = 13,
  denied = 14,
  operation_cancelled = 15,
};

/// MAV_RESULT values (COMMAND_ACK `result`).
enum class CmdResult : std::uint8_t {
  accepted = 0,
  temporarily_rejected = 1,
  denied = 2,
  unsupported = 3,
  failed = 4,
  in_progress = 5,
};

/// ArduCopter's flight modes (HEARTBEAT `custom_mode`).
enum class CopterMode : std::uint32_t { stabilize = 0, guided = 4, rtl = 6, land = 9 };

/// PX4's flight modes as HEARTBEAT `custom_mode` carries them: PX4's `union px4_custom_mode`
/// (PX4-Autopilot src/modules/commander/px4_custom_mode.h) lays a uint16 `reserved`, a uint8
/// `main_mode` and a uint8 `sub_mode` over the little-endian uint32, so the main mode is bits 16–23
/// and the sub mode bits 24–31. Main modes (enum PX4_CUSTOM_MAIN_MODE): MANUAL 1, ALTCTL 2,
/// POSCTL 3, AUTO 4, ACRO 5, OFFBOARD 6; AUTO's sub modes (PX4_CUSTOM_SUB_MODE_AUTO): READY 1,
/// TAKEOFF 2, LOITER 3 (shown as "Hold"), MISSION 4, RTL 5, LAND 6. Untested on PX4 itself.
namespace px4 {
inline constexpr std::uint8_t kMainPosctl = 3;
inline constexpr std::uint8_t kMainAuto = 4;
inline constexpr std::uint8_t kMainOffboard = 6;
inline constexpr std::uint8_t kSubTakeoff = 2;
inline constexpr std::uint8_t kSubLoiter = 3;
inline constexpr std::uint8_t kSubMission = 4;
inline constexpr std::uint8_t kSubRtl = 5;
inline constexpr std::uint8_t kSubLand = 6;
constexpr std::uint32_t custom_mode(std::uint8_t main_mode, std::uint8_t sub_mode = 0) {
  return std::uint32_t{main_mode} << 16 | std::uint32_t{sub_mode} << 24;
}
constexpr std::uint8_t main_mode(std::uint32_t custom_mode) {
  return static_cast<std::uint8_t>(custom_mode >> 16);
}
constexpr std::uint8_t sub_mode(std::uint32_t custom_mode) {
  return static_cast<std::uint8_t>(custom_mode >> 24);
}
inline constexpr std::uint32_t kHold = custom_mode(kMainAuto, kSubLoiter);
inline constexpr std::uint32_t kTakeoff = custom_mode(kMainAuto, kSubTakeoff);
inline constexpr std::uint32_t kRtl = custom_mode(kMainAuto, kSubRtl);
inline constexpr std::uint32_t kLand = custom_mode(kMainAuto, kSubLand);
inline constexpr std::uint32_t kPosctl = custom_mode(kMainPosctl);
}  // namespace px4

/// MAV_LANDED_STATE (EXTENDED_SYS_STATE `landed_state`).
enum class LandedState : std::uint8_t {
  undefined = 0,
  on_ground = 1,
  in_air = 2,
  takeoff = 3,
  landing = 4,
};

inline constexpr std::uint8_t kModeFlagArmed = 0x80;          ///< HEARTBEAT base_mode
inline constexpr std::uint8_t kModeFlagCustomEnabled = 0x01;  ///< HEARTBEAT base_mode
inline constexpr std::uint8_t kFrameGlobalRelativeAltInt =
    6;  ///< MAV_FRAME: lat/lon degE7, m above home
inline constexpr std::uint16_t kTypeMaskPositionOnly =
    0x0DF8;  ///< SET_POSITION_TARGET_*: ignore all but position
inline constexpr std::uint8_t kMavTypeQuadrotor = 2;
inline constexpr std::uint8_t kMavTypeGcs = 6;
inline constexpr std::uint8_t kAutopilotArdupilot = 3;
inline constexpr std::uint8_t kAutopilotInvalid = 8;
inline constexpr std::uint8_t kAutopilotPx4 = 12;
/// MAV_DO_REPOSITION_FLAGS_CHANGE_MODE (DO_REPOSITION param2): switch to the mode that flies it.
inline constexpr float kRepositionChangeMode = 1;
/// MAV_PARAM_TYPE (PARAM_VALUE param_type) values swath reads.
inline constexpr std::uint8_t kParamTypeInt8 = 2;
inline constexpr std::uint8_t kParamTypeInt32 = 6;
inline constexpr std::uint8_t kParamTypeReal32 = 9;
inline constexpr double kDegE7 = 1e7;           ///< integer latitudes and longitudes: degrees x 1e7
inline constexpr std::uint8_t kGcsSysid = 255;  ///< docs/swath-fleet.mdA
inline constexpr std::uint8_t kGcsCompid = 190;

}  // namespace swath::mavlink
