#include "swath/mavlink/mission_transfer.hpp"

#include <cmath>
#include <cstdio>
#include <optional>

namespace swath::mavlink {

namespace {

std::string degE7_text(std::int32_t lat, std::int32_t lon) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.7f, %.7f", lat / kDegE7, lon / kDegE7);
  return buf;
}

const char* last_name(int last) {
  switch (last) {
    case 0:
      return "MISSION_COUNT";
    case 1:
      return "MISSION_ITEM_INT";
    case 2:
      return "MISSION_REQUEST_LIST";
    default:
      return "MISSION_REQUEST_INT";
  }
}

}  // namespace

std::string mission_result_name(std::uint8_t result) {
  switch (static_cast<MissionResult>(result)) {
    case MissionResult::accepted:
      return "accepted";
    case MissionResult::error:
      return "error";
    case MissionResult::unsupported_frame:
      return "unsupported frame";
    case MissionResult::unsupported:
      return "unsupported command";
    case MissionResult::no_space:
      return "no space";
    case MissionResult::invalid:
      return "invalid";
    case MissionResult::invalid_sequence:
      return "invalid sequence";
    case MissionResult::denied:
      return "denied";
    case MissionResult::operation_cancelled:
      return "operation cancelled";
  }
  return std::to_string(result);
}

std::string fence_difference(const std::vector<MissionItemInt>& sent,
                             const std::vector<MissionItemInt>& read) {
  if (sent.size() != read.size())
    return std::to_string(read.size()) + " items read back, " + std::to_string(sent.size()) +
           " sent";
  for (std::size_t i = 0; i < sent.size(); ++i) {
    const MissionItemInt& s = sent[i];
    const MissionItemInt& r = read[i];
    const std::string item =
        "item " + std::to_string(i) + " (MAV_CMD " + std::to_string(s.command) + ")";
    if (r.command != s.command) return item + " reads back as MAV_CMD " + std::to_string(r.command);
    if (r.x != s.x || r.y != s.y)
      return item + " reads back at " + degE7_text(r.x, r.y) + ", sent at " + degE7_text(s.x, s.y);
    if (!(std::abs(r.param1 - s.param1) <= 1e-3f))
      return item + " reads back with param1 " + std::to_string(r.param1) + ", sent " +
             std::to_string(s.param1);
  }
  return "";
}

MissionTransfer::MissionTransfer(Endpoint& endpoint, std::uint8_t vehicle_sysid,
                                 std::uint8_t vehicle_compid, double timeout_s, int attempts)
    : endpoint_(endpoint),
      sysid_(vehicle_sysid),
      compid_(vehicle_compid),
      timeout_s_(timeout_s),
      attempts_(attempts) {}

void MissionTransfer::upload(std::vector<MissionItemInt> items, MissionType type, double now_s) {
  items_ = std::move(items);
  type_ = type;
  for (std::size_t i = 0; i < items_.size(); ++i) {
    MissionItemInt& m = items_[i];
    m.seq = static_cast<std::uint16_t>(i);
    m.target_system = sysid_;
    m.target_component = compid_;
    m.mission_type = static_cast<std::uint8_t>(type);
  }
  state_ = State::uploading;
  error_.clear();
  send(Last::count, 0, now_s);
}

void MissionTransfer::read(MissionType type, double now_s) {
  items_.clear();
  type_ = type;
  expected_ = 0;
  state_ = State::reading;
  error_.clear();
  send(Last::request_list, 0, now_s);
}

void MissionTransfer::send(Last what, std::uint16_t seq, double now_s, bool resend) {
  const auto t = static_cast<std::uint8_t>(type_);
  switch (what) {
    case Last::count:
      endpoint_.send(MissionCount{.count = static_cast<std::uint16_t>(items_.size()),
                                  .target_system = sysid_,
                                  .target_component = compid_,
                                  .mission_type = t});
      break;
    case Last::item:
      endpoint_.send(items_.at(seq));
      break;
    case Last::request_list:
      endpoint_.send(MissionRequestList{
          .target_system = sysid_, .target_component = compid_, .mission_type = t});
      break;
    case Last::request_item:
      endpoint_.send(MissionRequestInt{
          .seq = seq, .target_system = sysid_, .target_component = compid_, .mission_type = t});
      break;
  }
  // An answer to the vehicle (or a new question) starts its own count of sends; a resend after a
  // timeout adds to it.
  if (!resend) sends_ = 0;
  last_ = what;
  last_seq_ = seq;
  ++sends_;
  last_sent_s_ = now_s;
}

void MissionTransfer::fail(std::string why) {
  state_ = State::failed;
  error_ = std::move(why);
}

bool MissionTransfer::for_us(std::uint8_t target_system, std::uint8_t mission_type) const {
  return (target_system == endpoint_.sysid() || target_system == 0) &&
         mission_type == static_cast<std::uint8_t>(type_);
}

bool MissionTransfer::on_frame(const Frame& frame, double now_s) {
  if (state_ != State::uploading && state_ != State::reading) return false;
  if (frame.header.sysid != sysid_) return false;
  if (const auto ack = unpack<MissionAck>(frame)) {
    if (!for_us(ack->target_system, ack->mission_type)) return false;
    if (ack->type == static_cast<std::uint8_t>(MissionResult::accepted)) {
      if (state_ == State::uploading) state_ = State::done;
    } else {
      fail("the vehicle answered MISSION_ACK " + std::to_string(ack->type) + " (" +
           mission_result_name(ack->type) + ")");
    }
    return true;
  }
  if (state_ == State::uploading) {
    std::optional<std::uint16_t> seq;
    if (const auto r = unpack<MissionRequest>(frame);
        r && for_us(r->target_system, r->mission_type))
      seq = r->seq;
    else if (const auto ri = unpack<MissionRequestInt>(frame);
             ri && for_us(ri->target_system, ri->mission_type))
      seq = ri->seq;
    if (!seq) return false;
    if (*seq >= items_.size()) {
      fail("the vehicle asked for item " + std::to_string(*seq) + " of " +
           std::to_string(items_.size()));
      return true;
    }
    send(Last::item, *seq, now_s);
    return true;
  }
  // Reading back.
  if (const auto c = unpack<MissionCount>(frame)) {
    if (!for_us(c->target_system, c->mission_type) || last_ != Last::request_list) return false;
    expected_ = c->count;
    if (expected_ == 0) {
      endpoint_.send(MissionAck{.target_system = sysid_,
                                .target_component = compid_,
                                .type = static_cast<std::uint8_t>(MissionResult::accepted),
                                .mission_type = static_cast<std::uint8_t>(type_)});
      state_ = State::done;
    } else {
      send(Last::request_item, 0, now_s);
    }
    return true;
  }
  if (const auto item = unpack<MissionItemInt>(frame)) {
    if (!for_us(item->target_system, item->mission_type)) return false;
    if (last_ != Last::request_item || item->seq != items_.size()) return true;  // a late copy
    items_.push_back(*item);
    if (items_.size() == expected_) {
      endpoint_.send(MissionAck{.target_system = sysid_,
                                .target_component = compid_,
                                .type = static_cast<std::uint8_t>(MissionResult::accepted),
                                .mission_type = static_cast<std::uint8_t>(type_)});
      state_ = State::done;
    } else {
      send(Last::request_item, static_cast<std::uint16_t>(items_.size()), now_s);
    }
    return true;
  }
  return false;
}

void MissionTransfer::send_due(double now_s) {
  if (state_ != State::uploading && state_ != State::reading) return;
  if (now_s - last_sent_s_ < timeout_s_) return;
  if (sends_ >= attempts_) {
    fail("no answer to " + std::string(last_name(static_cast<int>(last_))) +
         (last_ == Last::item || last_ == Last::request_item ? " " + std::to_string(last_seq_)
                                                             : std::string()) +
         " after " + std::to_string(sends_) + " sends");
    return;
  }
  ++resends_;
  send(last_, last_seq_, now_s, true);
}

}  // namespace swath::mavlink
