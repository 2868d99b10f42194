#pragma once
// What flying one vehicle over MAVLink from a ground station shares between autopilots
// (docs/swath-fleet.md): keeps the link alive, asks for telemetry, queues commands and resends each
// until it is answered (3 sends, 1 s apart), reads parameters the same way (PARAM_REQUEST_READ
// resent until PARAM_VALUE names it), runs the safety check at connect, keeps the vehicle's state
// and tells arrival. A target outside the fence is never sent. What differs per autopilot (modes,
// how a position target goes, take-off altitude, which parameters the safety check reads) is in
// CopterDriver (ArduCopter) and Px4Driver (PX4, untested on PX4 itself).
//
// Time is the caller's: poll(now_s) does all I/O and timers, so tests run it on a simulated clock
// and a real run on the wall clock. Angles: latitude and longitude in degrees (WGS84); altitudes
// in metres above home (MAV_FRAME_GLOBAL_RELATIVE_ALT).

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "swath/mavlink/commands.hpp"
#include "swath/mavlink/endpoint.hpp"
#include "swath/mavlink/messages.hpp"
#include "swath/mavlink/mission_transfer.hpp"

namespace swath::mavlink {

struct DriverSettings {
  std::uint8_t vehicle_sysid = 1;
  std::uint8_t vehicle_compid = 1;
  double heartbeat_period_s = 1.0;   ///< the ground station's HEARTBEAT
  double lost_after_s = 3.0;         ///< vehicle silent this long: link lost
  double ack_timeout_s = 1.0;        ///< resend a command (or parameter read) unanswered this long
  int attempts = 3;                  ///< sends of one command before it times out
  double position_interval_s = 0.1;  ///< GLOBAL_POSITION_INT rate asked for (10 Hz)
  double status_interval_s = 1.0;    ///< SYS_STATUS, BATTERY_STATUS, EXTENDED_SYS_STATE
  /// A position target is repeated this often until the vehicle reports it (asked with
  /// REQUEST_MESSAGE for POSITION_TARGET_GLOBAL_INT after each send) or, from a vehicle that does
  /// not report it, until arrival, s. (ArduCopter; PX4's DO_REPOSITION is a command, acknowledged.)
  double target_resend_s = 1.0;
  double target_match_m = 1.0;     ///< a reported target this close (each axis' distance) is ours
  double arrival_radius_m = 1.5;   ///< arrived: this close to the target ...
  double arrival_speed_m_s = 0.5;  ///< ... and this slow
  /// Whether a point (latitude, longitude in degrees) is inside the fence; empty: no fence.
  std::function<bool(double lat_deg, double lon_deg)> inside_fence;
};

/// What the ground station knows of the vehicle, from its messages.
struct VehicleState {
  bool link_alive = false;
  double last_heard_s = -std::numeric_limits<double>::infinity();
  int links_lost = 0;  ///< times the link was declared lost
  bool armed = false;
  std::uint32_t custom_mode = 0;  ///< the autopilot's mode number (CopterMode, px4::custom_mode)
  std::uint8_t autopilot = 0;     ///< HEARTBEAT's MAV_AUTOPILOT (3 ArduPilot, 12 PX4)
  LandedState landed = LandedState::undefined;
  std::optional<GlobalPositionInt> position;
  std::optional<HomePosition> home;
  std::optional<PositionTargetGlobalInt> target;  ///< the vehicle's report of its GUIDED target
  int battery_remaining_percent = -1;  ///< BATTERY_STATUS (battery 0), else SYS_STATUS; -1: unknown
  bool battery_status_heard = false;   ///< a BATTERY_STATUS with a remaining charge came
  std::vector<std::string> status_texts;  ///< every STATUSTEXT, in order
  std::vector<CameraImageCaptured> images;
  std::map<std::string, double> params;  ///< parameters read (PARAM_VALUE), decoded
  /// The safety check's findings at connect (a lost-link failsafe off, or unreadable), in order.
  std::vector<std::string> warnings;
};

enum class CommandState { pending, accepted, rejected, timed_out };

/// Where a fence upload stands (Driver::upload_fence): sent, read back and compared, then enabled
/// on the vehicle; or failed (fence_error() says why).
enum class FenceState { none, uploading, reading_back, enabling, verified, failed };

/// The ground station's HEARTBEAT (docs/swath-fleet.md: type GCS 6, autopilot INVALID 8, active).
constexpr Heartbeat gcs_heartbeat() {
  return Heartbeat{.custom_mode = 0,
                   .type = kMavTypeGcs,
                   .autopilot = kAutopilotInvalid,
                   .base_mode = 0,
                   .system_status = 4};
}

class Driver {
 public:
  virtual ~Driver() = default;
  Driver(const Driver&) = delete;
  Driver& operator=(const Driver&) = delete;

  /// Reads what arrived, updates the state, sends what is due (heartbeat, resends, targets).
  /// `first`: frames read from the link by someone else, taken before what arrives now.
  void poll(double now_s, const std::vector<Frame>& first = {});
  const VehicleState& state() const { return state_; }

  /// Commands; each returns an id for command_state(). Sent at the next poll.
  int arm(bool on = true);
  /// Take-off to `altitude_m` above home (each autopilot reads the altitude its own way).
  virtual int takeoff(double altitude_m) = 0;
  int set_speed(double ground_speed_m_s);
  int return_to_launch();
  int land();
  int capture_image();
  /// Reads parameter `name` (up to 16 characters); accepted once its PARAM_VALUE came (the value
  /// in state().params), timed_out after `attempts` unanswered requests.
  int read_param(const std::string& name);
  /// Sets parameter `name` (PARAM_SET, resent like a command); accepted once a PARAM_VALUE of
  /// that name carries `value`, rejected when it carries another (the vehicle kept its own).
  int set_param(const std::string& name, double value, std::uint8_t param_type);
  CommandState command_state(int id) const;
  /// The MAV_RESULT of an acknowledged command (accepted or rejected).
  std::optional<CmdResult> command_result(int id) const;

  // The mode go_to flies in: GUIDED (ArduCopter), Hold = AUTO.LOITER (PX4).
  /// Switches to it.
  virtual int enter_guided() = 0;
  /// The vehicle is in it (PX4: or taking off, which ends in it).
  virtual bool in_guided() const = 0;
  /// Its name for messages ("GUIDED").
  virtual std::string guided_name() const = 0;
  /// The vehicle returns or lands on its own (RTL or LAND).
  virtual bool returning() const = 0;

  /// Flies to a point. False, and nothing sent, outside the fence.
  virtual bool go_to(double lat_deg, double lon_deg, double altitude_m) = 0;
  /// Within arrival_radius_m of the last target and slower than arrival_speed_m_s.
  bool arrived() const;
  /// Distance to the last target in metres (infinity without position or target).
  double distance_to_target_m() const;
  /// The vehicle took the last target as its own (ArduCopter: reported it; PX4: accepted it).
  virtual bool target_confirmed() const { return target_confirmed_; }
  std::uint64_t targets_sent() const { return targets_sent_; }  ///< resends included

  /// The safety check's verdict: true when it read the lost-link failsafe as off (the check's
  /// warning says which parameter), false when on or unreadable; nothing while it still reads.
  std::optional<bool> failsafe_off() const { return failsafe_off_; }

  /// Uploads a fence (mission protocol, MAV_MISSION_TYPE_FENCE: `items` are
  /// NAV_FENCE_POLYGON_VERTEX_* and NAV_FENCE_CIRCLE_* items; seq and targets are set here), reads
  /// it back and compares (fence_difference), then enables it the autopilot's way
  /// (enable_fence_step). Starts at the next poll with the link up.
  void upload_fence(std::vector<MissionItemInt> items);
  FenceState fence_state() const { return fence_state_; }
  /// Why the fence failed, one phrase.
  const std::string& fence_error() const { return fence_error_; }
  /// What the vehicle sent back (after reading_back).
  const std::vector<MissionItemInt>& fence_read_back() const { return fence_read_back_; }
  /// Mission-protocol frames sent again after a timeout.
  int fence_resends() const { return transfer_.resends(); }

  /// COMMAND_LONGs and COMMAND_INTs sent, resends included (parameter reads not counted).
  std::uint64_t commands_sent() const { return commands_sent_; }
  /// Commands not yet acknowledged, rejected or timed out (queued or in flight; parameter reads
  /// not counted).
  int commands_pending() const;

 protected:
  Driver(Link& link, DriverSettings settings);

  struct Target {
    std::int32_t lat_degE7 = 0, lon_degE7 = 0;
    float alt_m = 0;  ///< above home
  };
  /// The command queue's entries: one retry loop for COMMAND_LONG, COMMAND_INT and parameter reads.
  struct Pending {
    enum class Kind { command_long, command_int, param_read, param_set } kind = Kind::command_long;
    CommandLong message;  ///< COMMAND_LONG; its `command` also names a COMMAND_INT's
    CommandInt int_message;
    ParamRequestRead param;
    ParamSet param_set;
    std::string param_name;
    int sends = 0;
    double last_sent_s = -std::numeric_limits<double>::infinity();
    CommandState state = CommandState::pending;
    std::optional<CmdResult> result;
  };
  int enqueue(Cmd cmd, float p1 = 0, float p2 = 0, float p3 = 0, float p7 = 0);
  int enqueue(const CommandLong& message);
  int enqueue(const CommandInt& message);
  /// Sets target_ unless outside the fence (then false).
  bool set_target(double lat_deg, double lon_deg, double altitude_m);

  /// The parameters the safety check reads at the first connection.
  virtual std::vector<std::string> safety_params() const = 0;
  /// What a safety parameter never answered leaves unknown: the end of its "could not read NAME
  /// (no answer to N requests): ..." warning.
  virtual std::string unread_consequence() const = 0;
  /// The warnings from the values read (state_.params; an unread name is absent there).
  virtual std::vector<std::string> safety_warnings() const = 0;
  /// Sends the position target when due (ArduCopter); nothing by default.
  virtual void send_target(double /*now_s*/) {}
  /// Inclusion areas in the fence uploaded (a polygon's vertices count once, a circle once).
  int inclusion_areas() const;
  /// One step of enabling a verified fence on the vehicle: pending (nullopt), done (""), or
  /// failed (why). Default: nothing to enable.
  virtual std::optional<std::string> enable_fence_step() { return std::string(); }
  /// PARAM_VALUE carries integers byte for byte (PX4) rather than converted (ArduPilot).
  virtual bool params_bytewise() const { return false; }

  Endpoint endpoint_;
  DriverSettings settings_;
  VehicleState state_;
  std::vector<Pending> commands_;
  std::optional<Target> target_;
  bool target_confirmed_ = false;
  std::uint64_t targets_sent_ = 0;

 private:
  void on_frame(const Frame& frame, double now_s);
  void on_link_up();
  void on_param_value(const ParamValue& value);
  /// Enqueues a telemetry request unless the same one (command, message id) is still pending.
  void request_telemetry(Cmd cmd, float p1, float p2 = 0);
  void send_due(double now_s);
  /// Once every safety read is answered or timed out: the warnings.
  void finish_safety_check();
  /// Whether the vehicle's reported target is target_ (within target_match_m on each axis).
  bool reports_our_target(const PositionTargetGlobalInt& reported) const;

  double last_heartbeat_sent_s_ = -std::numeric_limits<double>::infinity();
  std::uint64_t commands_sent_ = 0;
  bool safety_started_ = false;
  std::vector<int> safety_reads_;  ///< read_param ids of the check in progress
  std::optional<bool> failsafe_off_;
  void fence_step(double now_s);
  static bool is_param(const Pending& p);
  /// The items as the transfer sent them (seq and targets filled in).
  const std::vector<MissionItemInt>& transfer_items_sent() const { return fence_sent_; }
  std::vector<MissionItemInt> fence_sent_;
  MissionTransfer transfer_;
  FenceState fence_state_ = FenceState::none;
  bool fence_asked_ = false;
  std::vector<MissionItemInt> fence_items_;
  std::vector<MissionItemInt> fence_read_back_;
  std::string fence_error_;
};

}  // namespace swath::mavlink
