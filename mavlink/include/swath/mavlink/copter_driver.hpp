#pragma once
// Flies one ArduCopter over MAVLink from a ground station (DESIGN.md §18.6 and §18.A): keeps the
// link alive, asks for telemetry, sets modes, arms, takes off in GUIDED, flies position targets,
// tells arrival, takes photos, returns or lands. Commands go as COMMAND_LONG and are resent until
// acknowledged (3 sends, 1 s apart, `confirmation` counting the resends); a target outside the
// fence is never sent.
//
// Time is the caller's: poll(now_s) does all I/O and timers, so tests run it on a simulated clock
// and a real run on the wall clock. Angles: latitude and longitude in degrees (WGS84); altitudes
// in metres above home (MAV_FRAME_GLOBAL_RELATIVE_ALT).

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "swath/mavlink/commands.hpp"
#include "swath/mavlink/endpoint.hpp"
#include "swath/mavlink/messages.hpp"

namespace swath::mavlink {

struct DriverSettings {
  std::uint8_t vehicle_sysid = 1;
  std::uint8_t vehicle_compid = 1;
  double heartbeat_period_s = 1.0;   ///< the ground station's HEARTBEAT
  double lost_after_s = 3.0;         ///< vehicle silent this long: link lost
  double ack_timeout_s = 1.0;        ///< resend a command not acknowledged after this
  int attempts = 3;                  ///< sends of one command before it times out
  double position_interval_s = 0.1;  ///< GLOBAL_POSITION_INT rate asked for (10 Hz)
  double status_interval_s = 1.0;    ///< SYS_STATUS, BATTERY_STATUS, EXTENDED_SYS_STATE
  /// A position target is repeated this often until the vehicle reports it (asked with
  /// REQUEST_MESSAGE for POSITION_TARGET_GLOBAL_INT after each send) or, from a vehicle that does
  /// not report it, until arrival, s.
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
  std::uint32_t custom_mode = 0;  ///< CopterMode values
  LandedState landed = LandedState::undefined;
  std::optional<GlobalPositionInt> position;
  std::optional<HomePosition> home;
  std::optional<PositionTargetGlobalInt> target;  ///< the vehicle's report of its GUIDED target
  int battery_remaining_percent = -1;
  std::vector<std::string> status_texts;  ///< every STATUSTEXT, in order
  std::vector<CameraImageCaptured> images;
};

enum class CommandState { pending, accepted, rejected, timed_out };

class CopterDriver {
 public:
  CopterDriver(Link& link, DriverSettings settings = {});

  /// Reads what arrived, updates the state, sends what is due (heartbeat, resends, targets).
  void poll(double now_s);
  const VehicleState& state() const { return state_; }

  /// Commands; each returns an id for command_state(). Sent at the next poll.
  int set_mode(CopterMode mode);
  int arm(bool on = true);
  int takeoff(double altitude_m);
  int set_speed(double ground_speed_m_s);
  int return_to_launch();
  int land();
  int capture_image();
  CommandState command_state(int id) const;
  /// The MAV_RESULT of an acknowledged command (accepted or rejected).
  std::optional<CmdResult> command_result(int id) const;

  /// Flies to a point in GUIDED mode. False, and nothing sent, outside the fence.
  bool go_to(double lat_deg, double lon_deg, double altitude_m);
  /// Within arrival_radius_m of the last target and slower than arrival_speed_m_s.
  bool arrived() const;
  /// Distance to the last target in metres (infinity without position or target).
  double distance_to_target_m() const;
  /// The vehicle reported the last target as its own since it was last sent.
  bool target_confirmed() const { return target_confirmed_; }
  std::uint64_t targets_sent() const { return targets_sent_; }  ///< resends included

  std::uint64_t commands_sent() const { return commands_sent_; }  ///< resends included
  /// Commands not yet acknowledged, rejected or timed out (queued or in flight).
  int commands_pending() const;

 private:
  struct Pending {
    CommandLong message;
    int sends = 0;
    double last_sent_s = -std::numeric_limits<double>::infinity();
    CommandState state = CommandState::pending;
    std::optional<CmdResult> result;
  };
  int enqueue(Cmd cmd, float p1 = 0, float p2 = 0, float p3 = 0, float p7 = 0);
  void on_frame(const Frame& frame, double now_s);
  void on_link_up();
  /// Enqueues a telemetry request unless the same one (command, message id) is still pending.
  void request_telemetry(Cmd cmd, float p1, float p2 = 0);
  void send_due(double now_s);
  /// Whether the vehicle's reported target is target_ (within target_match_m on each axis).
  bool reports_our_target(const PositionTargetGlobalInt& reported) const;

  Endpoint endpoint_;
  DriverSettings settings_;
  VehicleState state_;
  std::vector<Pending> commands_;
  double last_heartbeat_sent_s_ = -std::numeric_limits<double>::infinity();
  std::optional<SetPositionTargetGlobalInt> target_;
  double target_sent_s_ = -std::numeric_limits<double>::infinity();
  bool target_confirmed_ = false;
  std::uint64_t targets_sent_ = 0;
  std::uint64_t commands_sent_ = 0;
};

}  // namespace swath::mavlink
