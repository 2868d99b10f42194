#pragma once
// UNTESTED ON PX4: written from PX4's and MAVLink's documentation, checked only against swath's
// own fake PX4 (FakeCopter with autopilot px4), which encodes the same reading of the documents —
// so the tests check the driver against our reading, not against PX4. Confirm in PX4 SITL before
// flying it (docs/swath-fleet.md, "PX4 (second; confirm in PX4 SITL)").
//
// Flies one PX4 multicopter over MAVLink on the shared Driver (link, telemetry, commands resent
// until acknowledged, parameter reads). Per docs/swath-fleet.md:
//   - modes: DO_SET_MODE (176) param1 = 1 (MAV_MODE_FLAG_CUSTOM_MODE_ENABLED), param2 = PX4 main
//     mode, param3 = sub mode (PX4 Commander reads them so); HEARTBEAT custom_mode carries main
//     mode in bits 16–23 and sub mode in bits 24–31 (px4::custom_mode, commands.hpp);
//   - go to: COMMAND_INT (75) DO_REPOSITION (192), frame 6 (GLOBAL_RELATIVE_ALT_INT), param1 = −1
//     (default speed), param2 = 1 (MAV_DO_REPOSITION_FLAGS_CHANGE_MODE: PX4 switches to Hold,
//     AUTO.LOITER, and flies there), param4 = NaN (keep the yaw behaviour); a command, so it is
//     acknowledged and resent like the others (no target repetition as for ArduCopter);
//   - take-off: NAV_TAKEOFF (22) as COMMAND_LONG, param7 above mean sea level (PX4's Takeoff-mode
//     documentation; MAVLink leaves COMMAND_LONG's altitude frame open, ArduCopter reads it above
//     home): home's altitude + the altitude asked; params 4–6 NaN (current yaw and place: finite
//     values would be taken as a place); PX4 climbs in AUTO.TAKEOFF and then holds (AUTO.LOITER);
//   - the mode go_to flies in is Hold (AUTO.LOITER); returning: AUTO.RTL or AUTO.LAND;
//   - safety check at connect: reads COM_DL_LOSS_T (s of silence before the data-link-loss
//     failsafe) and NAV_DLL_ACT (its action: 0 disabled, 1 Hold, 2 Return, 3 Land, 5 Terminate,
//     6 Disarm); warns when NAV_DLL_ACT is 0 — PX4's default — or either cannot be read. PX4 sends
//     integer parameters byte for byte in PARAM_VALUE's float (params_bytewise).

#include "swath/mavlink/driver.hpp"

namespace swath::mavlink {

class Px4Driver final : public Driver {
 public:
  Px4Driver(Link& link, DriverSettings settings = {});

  /// DO_SET_MODE to a PX4 custom mode (px4::kHold, px4::kRtl, ...).
  int set_mode(std::uint32_t px4_custom_mode);
  /// NAV_TAKEOFF to `altitude_m` above home (sent above sea level; needs HOME_POSITION, asked at
  /// connect: before it, param7 is NaN and PX4 climbs to its MIS_TAKEOFF_ALT).
  int takeoff(double altitude_m) override;

  int enter_guided() override { return set_mode(px4::kHold); }
  bool in_guided() const override;
  std::string guided_name() const override { return "Hold (AUTO.LOITER)"; }
  bool returning() const override;

  /// DO_REPOSITION to a point. False, and nothing sent, outside the fence.
  bool go_to(double lat_deg, double lon_deg, double altitude_m) override;
  /// The last DO_REPOSITION was accepted.
  bool target_confirmed() const override;

 private:
  std::vector<std::string> safety_params() const override;
  std::string unread_consequence() const override;
  std::vector<std::string> safety_warnings() const override;
  bool params_bytewise() const override { return true; }

  int reposition_ = -1;  ///< the last DO_REPOSITION's command id
};

}  // namespace swath::mavlink
