#pragma once
// MAVLink enum values swath sends or reads (DESIGN.md §18.A), named once.

#include <cstdint>

namespace swath::mavlink {

/// MAV_CMD values (COMMAND_LONG / COMMAND_INT `command`).
enum class Cmd : std::uint16_t {
  nav_return_to_launch = 20,
  nav_land = 21,
  nav_takeoff = 22,       ///< param7: altitude above home, m
  do_set_mode = 176,      ///< param1: 1 (custom mode enabled), param2: custom mode
  do_change_speed = 178,  ///< param1: 1 (ground speed), param2: m/s
  do_reposition = 192,
  do_digicam_control = 203,
  component_arm_disarm = 400,  ///< param1: 1 arm, 0 disarm
  set_message_interval = 511,  ///< param1: message id, param2: interval in microseconds
  request_message = 512,       ///< param1: message id
  image_start_capture = 2000,  ///< param3: number of images (1)
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
inline constexpr double kDegE7 = 1e7;           ///< integer latitudes and longitudes: degrees x 1e7
inline constexpr std::uint8_t kGcsSysid = 255;  ///< DESIGN.md §18.A
inline constexpr std::uint8_t kGcsCompid = 190;

}  // namespace swath::mavlink
