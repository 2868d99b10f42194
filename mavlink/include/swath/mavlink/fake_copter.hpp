#pragma once
// A stand-in for ArduCopter on a MAVLink link, for tests and demos where SITL cannot be built
// (CI): it answers what CopterDriver sends the way ArduCopter documents — HEARTBEAT at 1 Hz with
// mode and armed flag, telemetry at the intervals asked by SET_MESSAGE_INTERVAL, COMMAND_ACK for
// every COMMAND_LONG, arming only in GUIDED on the ground (or a refusal with a STATUSTEXT),
// take-off to the asked altitude, GUIDED position targets at the set speed (optionally with an
// acceleration, each target received restarting the leg at rest as ArduCopter's does; the target
// reported as POSITION_TARGET_GLOBAL_INT on REQUEST_MESSAGE, above sea level), RTL (home, then
// land) and LAND with disarm on the ground, a photo per IMAGE_START_CAPTURE, and the ground-station
// failsafe: airborne without a GCS HEARTBEAT for 5 s it returns to launch (FS_GCS_ENABLE = 1).
// Faults for tests: a cut link, lost commands, a refusal to arm or to enter a mode, parameter
// requests left unanswered. It answers PARAM_REQUEST_READ for the failsafe parameters and
// PARAM_SET for those it has (ArduPilot: FENCE_ENABLE 0, FENCE_TYPE 7, FENCE_OPTIONS 0 by default),
// and the mission protocol for fences (MAV_MISSION_TYPE_FENCE): an upload is asked item by item
// with MISSION_REQUEST, as ArduPilot asks, stored and acknowledged; a read-back answers
// MISSION_REQUEST_LIST and MISSION_REQUEST_INT from what is stored (frame 0, altitude 0, as
// ArduPilot). Fence faults for tests: a refusal (MISSION_ACK with an error), mission messages lost
// on the way, a vertex stored moved (what a read-back must catch).
//
// A PX4 flavour (autopilot = px4) speaks as PX4's documents say PX4 does (HEARTBEAT autopilot 12,
// custom_mode main/sub modes, DO_SET_MODE param2/param3, NAV_TAKEOFF above sea level climbing in
// AUTO.TAKEOFF and then holding, COMMAND_INT DO_REPOSITION flying there in Hold, integer
// parameters byte for byte, the data-link-loss failsafe by COM_DL_LOSS_T and NAV_DLL_ACT). It
// checks Px4Driver against our reading of those documents, not against PX4 (px4_driver.hpp).
//
// Kinematics are deliberately simple (constant speeds, no inertia): it checks the driver's
// protocol, not flight; swath-fleet's simulated backend and swath-control model flight.

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "swath/mavlink/commands.hpp"
#include "swath/mavlink/endpoint.hpp"
#include "swath/mavlink/messages.hpp"

namespace swath::mavlink {

enum class FakeAutopilot { ardupilot, px4 };

struct FakeCopterSettings {
  FakeAutopilot autopilot = FakeAutopilot::ardupilot;
  double home_lat_deg = 47.397742;  ///< WGS84
  double home_lon_deg = 8.545594;
  double home_amsl_m = 488.0;
  std::uint8_t sysid = 1;
  double speed_m_s = 10.0;      ///< horizontal speed until DO_CHANGE_SPEED
  double climb_m_s = 2.5;       ///< take-off and climb
  double descent_m_s = 1.0;     ///< landing
  double gcs_failsafe_s = 5.0;  ///< FS_GCS_TIMEOUT (ArduPilot flavour)
  /// Parameters answered to PARAM_REQUEST_READ, over the flavour's defaults: ArduPilot
  /// FS_GCS_ENABLE 1 (RTL on a lost link, 0: no failsafe); PX4 COM_DL_LOSS_T 10 (s) and
  /// NAV_DLL_ACT 2 (Return; 0: no failsafe, 3: Land; PX4's own default is 0).
  std::map<std::string, double> params;
  double battery_drain_percent_s = 0.05;  ///< while armed
  /// Horizontal acceleration, m/s² (> 0), or 0: at speed at once. With it every GUIDED target
  /// received restarts the leg at rest, as ArduCopter re-plans a leg from its stopping point on
  /// each SET_POSITION_TARGET_GLOBAL_INT (AC_WPNav::set_wp_destination_NEU_cm).
  double accel_m_s2 = 0;
  /// ArduCopter's GUIDED speed: a leg flies at the DO_CHANGE_SPEED in force when its target
  /// arrived (a DO_CHANGE_SPEED mid-leg only sets the next leg's), and at speed_m_s (WPNAV_SPEED)
  /// for the first target after entering GUIDED or taking off and for a target re-sent before
  /// the last was reached (ModeGuided::set_speed_xy_cms, AC_WPNav::set_wp_destination_NEU_cm).
  /// false: every DO_CHANGE_SPEED applies at once.
  bool speed_per_leg = false;
};

class FakeCopter {
 public:
  FakeCopter(Link& link, FakeCopterSettings settings = {});

  /// Reads commands, moves for the time since the last step, sends what is due.
  void step(double now_s);

  // Faults.
  /// Neither sends nor receives from `from_s` until `until_s` (what arrives meanwhile is lost).
  void cut_link(double from_s, double until_s);
  /// The next `n` COMMAND_LONGs or COMMAND_INTs are lost on the way (so their acknowledgements
  /// never come).
  void lose_commands(int n) { commands_to_lose_ += n; }
  /// Every first send (confirmation 0) of `cmd` is lost on the way: its resend, 1 s later, is
  /// the first the vehicle sees.
  void lose_first_sends(Cmd cmd) { lose_first_sends_of_ = static_cast<std::uint16_t>(cmd); }
  /// The next `n` SET_POSITION_TARGET_GLOBAL_INTs are lost on the way.
  void lose_targets(int n) { targets_to_lose_ += n; }
  /// Every PARAM_REQUEST_READ is lost on the way.
  void drop_param_requests() { drop_param_requests_ = true; }
  /// Refuses to arm, with this STATUSTEXT (ArduCopter's "PreArm: ..." sentences), until the
  /// vehicle's clock (step's now_s, seconds) reaches `until_s`: a check that clears on its own
  /// (the EKF's position after boot) as against one that never does (an uncalibrated compass).
  void refuse_arm(std::string why, double until_s = std::numeric_limits<double>::infinity()) {
    refuse_arm_ = std::move(why);
    refuse_arm_until_s_ = until_s;
  }
  /// Refuses DO_SET_MODE to `mode` (the ack FAILED), with this STATUSTEXT.
  void refuse_mode(CopterMode mode, std::string why) {
    refused_mode_ = mode;
    refuse_mode_ = std::move(why);
  }

  /// The next fence upload is answered with MISSION_ACK `result` (a MAV_MISSION_RESULT) at its
  /// MISSION_COUNT; nothing is stored.
  void refuse_fence(MissionResult result) { fence_refusal_ = result; }
  /// The next `n` mission-protocol messages from the ground station are lost on the way.
  void lose_mission_messages(int n) { mission_to_lose_ += n; }
  /// Stores fence item `seq` of every upload 0.0001 degrees (about 11 m) north of where it was
  /// sent: a read-back shows the vertex moved.
  void corrupt_fence_vertex(int seq) { corrupt_seq_ = seq; }

  // Truth, for tests.
  /// The fence items stored (the last complete upload).
  const std::vector<MissionItemInt>& fence_items() const { return fence_; }
  /// Mission-protocol messages received (lost ones not).
  int mission_messages_received() const { return mission_received_; }
  /// A parameter's value (NaN when it has none).
  double param(const std::string& name) const;
  double north_m() const { return north_m_; }
  double east_m() const { return east_m_; }
  double altitude_m() const { return alt_m_; }  ///< above home
  bool armed() const { return armed_; }
  CopterMode mode() const { return mode_; }
  LandedState landed_state() const { return landed_; }
  double speed_setting_m_s() const { return speed_m_s_; }
  /// The HEARTBEAT custom_mode it sends (its flavour's encoding of mode()).
  std::uint32_t custom_mode() const;
  /// The ground station's HEARTBEATs received, and the longest time between two of them (the
  /// vehicle's clock, s; 0 before the second).
  int gcs_heartbeats_received() const { return gcs_heartbeats_; }
  double longest_gcs_silence_s() const { return longest_gcs_silence_s_; }
  /// PARAM_REQUEST_READs received (resends included, lost ones not).
  int param_requests_received() const { return param_requests_received_; }
  /// COMMAND_LONGs and COMMAND_INTs received by command number (resends included, lost ones not).
  int commands_received(Cmd cmd) const;
  int position_targets_received() const { return targets_received_; }
  int images_taken() const { return images_; }
  /// Latitude and longitude in degrees of a point north_m, east_m of home.
  void to_geodetic(double north_m, double east_m, double& lat_deg, double& lon_deg) const;

 private:
  void on_frame(const Frame& frame, double now_s);
  void on_command(const CommandLong& c, double now_s);
  void on_command_int(const CommandInt& c, double now_s);
  void on_param_request(const ParamRequestRead& r);
  void on_param_set(const ParamSet& p);
  void send_param(std::map<std::string, double>::const_iterator it);
  /// A mission-protocol frame from the ground station (true: it was one).
  bool on_mission_frame(const Frame& frame);
  void acknowledge(std::uint16_t command, CmdResult result);
  bool px4() const { return settings_.autopilot == FakeAutopilot::px4; }
  /// The lost-link failsafe's mode per the parameters (none: stays), and its delay, s.
  std::optional<CopterMode> failsafe_mode() const;
  double failsafe_after_s() const;
  void send_status_text(const std::string& text);
  void move(double dt_s);
  void send_telemetry(double now_s);
  bool link_cut(double now_s) const { return now_s >= cut_from_s_ && now_s < cut_until_s_; }

  Endpoint endpoint_;
  FakeCopterSettings settings_;
  double last_step_s_ = 0;
  bool started_ = false;
  double cut_from_s_ = 0, cut_until_s_ = 0;
  int commands_to_lose_ = 0;
  int targets_to_lose_ = 0;
  std::uint16_t lose_first_sends_of_ = 0xFFFF;  // none
  std::string refuse_arm_;
  double refuse_arm_until_s_ = 0;
  CopterMode refused_mode_ = CopterMode::stabilize;
  std::string refuse_mode_;  // "": no mode refused
  bool drop_param_requests_ = false;
  std::optional<MissionResult> fence_refusal_;
  int mission_to_lose_ = 0;
  int corrupt_seq_ = -1;
  int mission_received_ = 0;
  std::vector<MissionItemInt> fence_;     // stored
  std::vector<MissionItemInt> incoming_;  // an upload in progress
  std::uint16_t incoming_count_ = 0;
  bool receiving_ = false;
  int param_requests_received_ = 0;
  std::map<std::string, double> params_;  // the flavour's defaults with settings.params over them
  double last_gcs_heartbeat_s_ = 0;
  bool gcs_seen_ = false;
  int gcs_heartbeats_ = 0;
  double longest_gcs_silence_s_ = 0;

  bool armed_ = false;
  CopterMode mode_ = CopterMode::stabilize;
  LandedState landed_ = LandedState::on_ground;
  double north_m_ = 0, east_m_ = 0, alt_m_ = 0;
  double v_north_m_s_ = 0, v_east_m_s_ = 0, v_up_m_s_ = 0;
  double leg_speed_m_s_ = 0;  // with accel_m_s2: the speed reached on this leg
  double leg_max_m_s_ = 0;    // with speed_per_leg: this leg's planned speed
  bool leg_planned_ = false;  // with speed_per_leg: a GUIDED leg since GUIDED or take-off
  double target_north_m_ = 0, target_east_m_ = 0, target_alt_m_ = 0;
  bool has_target_ = false;
  double speed_m_s_;
  double battery_percent_ = 100;
  int targets_received_ = 0;
  int images_ = 0;
  std::map<std::uint16_t, int> received_;
  std::map<std::uint32_t, double> interval_s_;  // message id -> interval asked
  std::map<std::uint32_t, double> last_sent_s_;
};

}  // namespace swath::mavlink
