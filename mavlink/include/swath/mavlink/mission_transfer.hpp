#pragma once
// MAVLink's mission protocol from the ground station's side (docs/swath-fleet.md), for one
// mission_type at a time: an upload (MISSION_COUNT, then each MISSION_ITEM_INT the vehicle asks
// for with MISSION_REQUEST or MISSION_REQUEST_INT, until its MISSION_ACK) and a read-back
// (MISSION_REQUEST_LIST, MISSION_COUNT, a MISSION_REQUEST_INT per item, our MISSION_ACK). What
// was sent last is sent again when nothing answers for `timeout_s`, `attempts` sends in all; then
// the transfer fails, as it does on a MISSION_ACK that is not "accepted". swath uploads fences
// with it (MAV_MISSION_TYPE_FENCE) and reads them back before a vehicle may arm.
//
// Time is the caller's, as in Driver: on_frame and send_due take the clock.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "swath/mavlink/commands.hpp"
#include "swath/mavlink/endpoint.hpp"
#include "swath/mavlink/messages.hpp"

namespace swath::mavlink {

class MissionTransfer {
 public:
  enum class State { idle, uploading, reading, done, failed };

  MissionTransfer(Endpoint& endpoint, std::uint8_t vehicle_sysid, std::uint8_t vehicle_compid,
                  double timeout_s, int attempts);

  /// Starts an upload of `items` (their seq, targets and mission_type are set here).
  void upload(std::vector<MissionItemInt> items, MissionType type, double now_s);
  /// Starts a read-back; items() holds what came once state() is done.
  void read(MissionType type, double now_s);
  /// Takes the frame if it belongs to the transfer in progress (true), else leaves it.
  bool on_frame(const Frame& frame, double now_s);
  /// Resends what is unanswered, or fails the transfer after `attempts` sends.
  void send_due(double now_s);

  State state() const { return state_; }
  /// Why the transfer failed, one phrase ("the vehicle answered MISSION_ACK 4 (no space)").
  const std::string& error() const { return error_; }
  /// The items read back (read), or sent (upload).
  const std::vector<MissionItemInt>& items() const { return items_; }
  /// Frames the transfer sent again after a timeout.
  int resends() const { return resends_; }

 private:
  enum class Last { count, item, request_list, request_item };
  void send(Last what, std::uint16_t seq, double now_s, bool resend = false);
  void fail(std::string why);
  bool for_us(std::uint8_t target_system, std::uint8_t mission_type) const;

  Endpoint& endpoint_;
  std::uint8_t sysid_, compid_;
  double timeout_s_;
  int attempts_;
  State state_ = State::idle;
  MissionType type_ = MissionType::fence;
  std::vector<MissionItemInt> items_;
  std::uint16_t expected_ = 0;  // read-back: the count the vehicle announced
  Last last_ = Last::count;
  std::uint16_t last_seq_ = 0;
  int sends_ = 0;  // of what was sent last
  double last_sent_s_ = -std::numeric_limits<double>::infinity();
  int resends_ = 0;
  std::string error_;
};

/// A MAV_MISSION_RESULT's name ("no space"), or its number.
std::string mission_result_name(std::uint8_t result);

/// "" when `read` holds the items `sent` (same count; each item's command, latitude and longitude
/// exactly, param1 within 1e-3: a vertex count or a radius); else one phrase naming the first
/// difference ("item 2 (MAV_CMD 5001) reads back at 47.3980120, 8.5456000, sent at ...").
/// Frames and altitudes are not compared: ArduPilot stores fence points without them and reads
/// them back in MAV_FRAME_GLOBAL at 0.
std::string fence_difference(const std::vector<MissionItemInt>& sent,
                             const std::vector<MissionItemInt>& read);

}  // namespace swath::mavlink
