#include "swath/mavlink/driver.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <set>

#include "swath/geometry/local_frame.hpp"

namespace swath::mavlink {
namespace {

std::int32_t to_degE7(double deg) {
  return static_cast<std::int32_t>(std::lround(deg * kDegE7));
}

// A PARAM_VALUE's value. ArduPilot converts every parameter to the float it sends; PX4 copies an
// integer's bytes into the float's (MAVLink's parameter protocol, "bytewise" encoding): its INT32
// 2 arrives as the float whose bits are 2, 2.8e-45, which read as a number is 0.
double param_number(const ParamValue& v, bool bytewise) {
  if (!bytewise) return v.param_value;
  const auto bits = std::bit_cast<std::uint32_t>(v.param_value);
  switch (v.param_type) {
    case 1:  // MAV_PARAM_TYPE_UINT8
      return static_cast<std::uint8_t>(bits);
    case kParamTypeInt8:
      return static_cast<std::int8_t>(static_cast<std::uint8_t>(bits));
    case 3:  // UINT16
      return static_cast<std::uint16_t>(bits);
    case 4:  // INT16
      return static_cast<std::int16_t>(static_cast<std::uint16_t>(bits));
    case 5:  // UINT32
      return bits;
    case kParamTypeInt32:
      return static_cast<std::int32_t>(bits);
    default:  // REAL32, and what a float cannot carry bytewise
      return v.param_value;
  }
}

}  // namespace

// Parameter reads and sets are answered by PARAM_VALUE, by name: they are not commands.
bool Driver::is_param(const Pending& p) {
  return p.kind == Pending::Kind::param_read || p.kind == Pending::Kind::param_set;
}

Driver::Driver(Link& link, DriverSettings settings)
    : endpoint_(link, kGcsSysid, kGcsCompid),
      settings_(std::move(settings)),
      transfer_(endpoint_, settings_.vehicle_sysid, settings_.vehicle_compid,
                settings_.ack_timeout_s, settings_.attempts) {}

int Driver::enqueue(const CommandLong& message) {
  Pending p;
  p.message = message;
  p.message.target_system = settings_.vehicle_sysid;
  p.message.target_component = settings_.vehicle_compid;
  commands_.push_back(p);
  return static_cast<int>(commands_.size()) - 1;
}

int Driver::enqueue(Cmd cmd, float p1, float p2, float p3, float p7) {
  CommandLong m;
  m.command = static_cast<std::uint16_t>(cmd);
  m.param1 = p1;
  m.param2 = p2;
  m.param3 = p3;
  m.param7 = p7;
  return enqueue(m);
}

int Driver::enqueue(const CommandInt& message) {
  Pending p;
  p.kind = Pending::Kind::command_int;
  p.int_message = message;
  p.int_message.target_system = settings_.vehicle_sysid;
  p.int_message.target_component = settings_.vehicle_compid;
  p.message.command = message.command;  // what its COMMAND_ACK names
  commands_.push_back(p);
  return static_cast<int>(commands_.size()) - 1;
}

int Driver::read_param(const std::string& name) {
  Pending p;
  p.kind = Pending::Kind::param_read;
  p.param_name = name.substr(0, p.param.param_id.size());
  p.param.param_index = -1;
  p.param.target_system = settings_.vehicle_sysid;
  p.param.target_component = settings_.vehicle_compid;
  std::copy(p.param_name.begin(), p.param_name.end(), p.param.param_id.begin());
  commands_.push_back(p);
  return static_cast<int>(commands_.size()) - 1;
}

int Driver::set_param(const std::string& name, double value, std::uint8_t param_type) {
  Pending p;
  p.kind = Pending::Kind::param_set;
  p.param_name = name.substr(0, p.param_set.param_id.size());
  p.param_set.param_value = static_cast<float>(value);
  p.param_set.param_type = param_type;
  p.param_set.target_system = settings_.vehicle_sysid;
  p.param_set.target_component = settings_.vehicle_compid;
  std::copy(p.param_name.begin(), p.param_name.end(), p.param_set.param_id.begin());
  commands_.push_back(p);
  return static_cast<int>(commands_.size()) - 1;
}

int Driver::inclusion_areas() const {
  int areas = 0;
  for (std::size_t i = 0; i < fence_items_.size();) {
    const MissionItemInt& m = fence_items_[i];
    const auto cmd = static_cast<Cmd>(m.command);
    const bool polygon = cmd == Cmd::nav_fence_polygon_vertex_inclusion ||
                         cmd == Cmd::nav_fence_polygon_vertex_exclusion;
    areas +=
        cmd == Cmd::nav_fence_polygon_vertex_inclusion || cmd == Cmd::nav_fence_circle_inclusion;
    i += polygon ? std::max<std::size_t>(1, static_cast<std::size_t>(m.param1)) : 1;
  }
  return areas;
}

void Driver::upload_fence(std::vector<MissionItemInt> items) {
  fence_items_ = std::move(items);
  fence_state_ = FenceState::uploading;
  fence_asked_ = false;
  fence_error_.clear();
  fence_read_back_.clear();
}

// Upload, read back, compare, enable: one step per poll, with the link up.
void Driver::fence_step(double now_s) {
  using S = MissionTransfer::State;
  switch (fence_state_) {
    case FenceState::uploading:
      if (!fence_asked_) {
        if (!state_.link_alive) return;
        transfer_.upload(fence_items_, MissionType::fence, now_s);
        fence_asked_ = true;
        return;
      }
      if (transfer_.state() == S::failed) {
        fence_state_ = FenceState::failed;
        fence_error_ = "upload: " + transfer_.error();
      } else if (transfer_.state() == S::done) {
        fence_sent_ = transfer_.items();
        fence_state_ = FenceState::reading_back;
        transfer_.read(MissionType::fence, now_s);
      }
      return;
    case FenceState::reading_back:
      if (transfer_.state() == S::failed) {
        fence_state_ = FenceState::failed;
        fence_error_ = "read-back: " + transfer_.error();
      } else if (transfer_.state() == S::done) {
        fence_read_back_ = transfer_.items();
        const std::string diff = fence_difference(transfer_items_sent(), fence_read_back_);
        if (diff.empty()) {
          fence_state_ = FenceState::enabling;
        } else {
          fence_state_ = FenceState::failed;
          fence_error_ = "the fence read back differs from the one sent: " + diff;
        }
      }
      return;
    case FenceState::enabling:
      if (const std::optional<std::string> r = enable_fence_step()) {
        fence_state_ = r->empty() ? FenceState::verified : FenceState::failed;
        fence_error_ = *r;
      }
      return;
    case FenceState::none:
    case FenceState::verified:
    case FenceState::failed:
      return;
  }
}

int Driver::arm(bool on) {
  return enqueue(Cmd::component_arm_disarm, on ? 1.0f : 0.0f);
}
int Driver::set_speed(double ground_speed_m_s) {
  return enqueue(Cmd::do_change_speed, 1, static_cast<float>(ground_speed_m_s));
}
int Driver::return_to_launch() {
  target_.reset();
  return enqueue(Cmd::nav_return_to_launch);
}
int Driver::land() {
  target_.reset();
  return enqueue(Cmd::nav_land);
}
int Driver::capture_image() {
  return enqueue(Cmd::image_start_capture, 0, 0, 1);
}

CommandState Driver::command_state(int id) const {
  return commands_.at(static_cast<std::size_t>(id)).state;
}
std::optional<CmdResult> Driver::command_result(int id) const {
  return commands_.at(static_cast<std::size_t>(id)).result;
}

int Driver::commands_pending() const {
  return static_cast<int>(std::count_if(commands_.begin(), commands_.end(), [](const Pending& p) {
    return !is_param(p) && p.state == CommandState::pending;
  }));
}

bool Driver::set_target(double lat_deg, double lon_deg, double altitude_m) {
  if (settings_.inside_fence && !settings_.inside_fence(lat_deg, lon_deg)) return false;
  target_ = Target{to_degE7(lat_deg), to_degE7(lon_deg), static_cast<float>(altitude_m)};
  target_confirmed_ = false;
  return true;
}

bool Driver::reports_our_target(const PositionTargetGlobalInt& reported) const {
  if (!target_) return false;
  const double horizontal =
      geometry::geodesic_distance_m({reported.lat_degE7 / kDegE7, reported.lon_degE7 / kDegE7},
                                    {target_->lat_degE7 / kDegE7, target_->lon_degE7 / kDegE7});
  if (horizontal > settings_.target_match_m) return false;
  // ArduCopter reports its target above sea level (MAV_FRAME_GLOBAL, 0; GLOBAL_INT, 5); ours is
  // above home, which GLOBAL_POSITION_INT gives as its two altitudes' difference.
  double above_home_m = reported.alt_m;
  if (reported.coordinate_frame == 0 || reported.coordinate_frame == 5) {
    if (!state_.position) return true;  // the horizontal match is all there is to compare
    above_home_m -= (state_.position->alt_mm - state_.position->relative_alt_mm) / 1000.0;
  }
  return std::abs(above_home_m - target_->alt_m) <= settings_.target_match_m;
}

double Driver::distance_to_target_m() const {
  if (!target_ || !state_.position) return std::numeric_limits<double>::infinity();
  const double horizontal = geometry::geodesic_distance_m(
      {state_.position->lat_degE7 / kDegE7, state_.position->lon_degE7 / kDegE7},
      {target_->lat_degE7 / kDegE7, target_->lon_degE7 / kDegE7});
  const double vertical = state_.position->relative_alt_mm / 1000.0 - target_->alt_m;
  return std::hypot(horizontal, vertical);
}

bool Driver::arrived() const {
  if (!target_ || !state_.position) return false;
  const GlobalPositionInt& p = *state_.position;
  const double speed_m_s = std::sqrt(double(p.vx_cm_s) * p.vx_cm_s + double(p.vy_cm_s) * p.vy_cm_s +
                                     double(p.vz_cm_s) * p.vz_cm_s) /
                           100.0;
  return distance_to_target_m() <= settings_.arrival_radius_m &&
         speed_m_s < settings_.arrival_speed_m_s;
}

void Driver::request_telemetry(Cmd cmd, float p1, float p2) {
  // At most one pending request per message: a link that flaps while a set is still waiting to
  // go out must not add another set each time it comes up.
  for (const Pending& p : commands_)
    if (p.state == CommandState::pending && p.kind == Pending::Kind::command_long &&
        p.message.command == static_cast<std::uint16_t>(cmd) && p.message.param1 == p1)
      return;
  enqueue(cmd, p1, p2);
}

void Driver::on_link_up() {
  // Telemetry rates and home are asked again after every loss: the vehicle may have rebooted.
  const auto interval = [&](std::uint32_t id, double s) {
    request_telemetry(Cmd::set_message_interval, static_cast<float>(id),
                      static_cast<float>(s * 1e6));
  };
  interval(GlobalPositionInt::kId, settings_.position_interval_s);
  interval(SysStatus::kId, settings_.status_interval_s);
  interval(BatteryStatus::kId, settings_.status_interval_s);
  interval(ExtendedSysState::kId, settings_.status_interval_s);
  request_telemetry(Cmd::request_message, static_cast<float>(HomePosition::kId));
  // The safety check, once per driver: it reads parameters, it never holds a command back.
  if (!safety_started_) {
    safety_started_ = true;
    for (const std::string& name : safety_params()) safety_reads_.push_back(read_param(name));
  }
}

void Driver::on_param_value(const ParamValue& value) {
  const auto end = std::find(value.param_id.begin(), value.param_id.end(), '\0');
  const std::string name(value.param_id.begin(), end);
  const double number = param_number(value, params_bytewise());
  state_.params[name] = number;
  for (Pending& p : commands_) {
    if (!is_param(p) || p.state != CommandState::pending || p.param_name != name) continue;
    if (p.kind == Pending::Kind::param_read) {
      p.state = CommandState::accepted;
    } else if (p.sends > 0) {  // the value the vehicle holds now: ours, or it kept its own
      const double asked = p.param_set.param_value;
      p.state = std::abs(number - asked) <= 1e-6 * std::max(1.0, std::abs(asked))
                    ? CommandState::accepted
                    : CommandState::rejected;
    }
  }
}

void Driver::finish_safety_check() {
  if (safety_reads_.empty()) return;
  std::vector<std::string> unread;
  for (int id : safety_reads_) {
    const Pending& p = commands_.at(static_cast<std::size_t>(id));
    if (p.state == CommandState::pending) return;  // still asking
    if (p.state != CommandState::accepted) unread.push_back(p.param_name);
  }
  safety_reads_.clear();
  for (const std::string& name : unread)
    state_.warnings.push_back("could not read " + name + " (no answer to " +
                              std::to_string(settings_.attempts) +
                              " requests): " + unread_consequence());
  // The drivers warn about nothing but a failsafe read as off.
  std::vector<std::string> found = safety_warnings();
  failsafe_off_ = !found.empty();
  for (std::string& w : found) state_.warnings.push_back(std::move(w));
}

void Driver::on_frame(const Frame& frame, double now_s) {
  if (frame.header.sysid != settings_.vehicle_sysid) return;
  if (transfer_.on_frame(frame, now_s)) return;
  if (const auto hb = unpack<Heartbeat>(frame)) {
    if (frame.header.compid != settings_.vehicle_compid) return;
    state_.last_heard_s = now_s;
    state_.armed = (hb->base_mode & kModeFlagArmed) != 0;
    state_.custom_mode = hb->custom_mode;
    state_.autopilot = hb->autopilot;
    if (!state_.link_alive) {
      state_.link_alive = true;
      on_link_up();
    }
  } else if (const auto ack = unpack<CommandAck>(frame)) {
    // The oldest pending command of that number is the one acknowledged.
    for (Pending& p : commands_) {
      if (is_param(p) || p.state != CommandState::pending || p.sends == 0 ||
          p.message.command != ack->command)
        continue;
      const auto result = static_cast<CmdResult>(ack->result);
      if (result == CmdResult::in_progress) break;  // a final ack follows
      p.result = result;
      p.state = result == CmdResult::accepted ? CommandState::accepted : CommandState::rejected;
      break;
    }
  } else if (const auto pos = unpack<GlobalPositionInt>(frame)) {
    state_.position = *pos;
  } else if (const auto target = unpack<PositionTargetGlobalInt>(frame)) {
    state_.target = *target;
    if (reports_our_target(*target)) target_confirmed_ = true;
  } else if (const auto home = unpack<HomePosition>(frame)) {
    state_.home = *home;
  } else if (const auto ext = unpack<ExtendedSysState>(frame)) {
    state_.landed = static_cast<LandedState>(ext->landed_state);
  } else if (const auto sys = unpack<SysStatus>(frame)) {
    // BATTERY_STATUS is the battery's own report (per battery); SYS_STATUS's copy only until it
    // comes.
    if (!state_.battery_status_heard)
      state_.battery_remaining_percent = sys->battery_remaining_percent;
  } else if (const auto battery = unpack<BatteryStatus>(frame)) {
    if (battery->id == 0 && battery->battery_remaining_percent >= 0) {  // -1: not known
      state_.battery_status_heard = true;
      state_.battery_remaining_percent = battery->battery_remaining_percent;
    }
  } else if (const auto text = unpack<StatusText>(frame)) {
    const auto end = std::find(text->text.begin(), text->text.end(), '\0');
    state_.status_texts.emplace_back(text->text.begin(), end);
  } else if (const auto image = unpack<CameraImageCaptured>(frame)) {
    state_.images.push_back(*image);
  } else if (const auto param = unpack<ParamValue>(frame)) {
    on_param_value(*param);
  }
}

void Driver::send_due(double now_s) {
  if (now_s - last_heartbeat_sent_s_ >= settings_.heartbeat_period_s) {
    endpoint_.send(gcs_heartbeat());
    last_heartbeat_sent_s_ = now_s;
  }
  if (!state_.link_alive) return;  // commands wait for the vehicle; their clock starts at sending
  // A COMMAND_ACK names only the command number: one command of each number in flight at a
  // time, or an acknowledgement of the second would be taken for a lost first. (A PARAM_VALUE
  // names its parameter: reads need no such turn.)
  using Kind = Pending::Kind;
  std::set<std::uint16_t> in_flight;
  for (const Pending& p : commands_)
    if (!is_param(p) && p.state == CommandState::pending && p.sends > 0)
      in_flight.insert(p.message.command);
  const std::size_t n = commands_.size();
  for (std::size_t i = 0; i < n; ++i) {
    Pending& p = commands_[i];
    if (p.state != CommandState::pending || now_s - p.last_sent_s < settings_.ack_timeout_s)
      continue;
    if (!is_param(p) && p.sends == 0 && !in_flight.insert(p.message.command).second)
      continue;  // waits its turn
    if (p.sends >= settings_.attempts) {
      p.state = CommandState::timed_out;
      // Telemetry is what the link is for (without positions no arrival is ever seen): its
      // requests are asked again, as new commands, until the vehicle answers.
      const auto cmd = static_cast<Cmd>(p.message.command);
      if (p.kind == Kind::command_long &&
          (cmd == Cmd::set_message_interval ||
           (cmd == Cmd::request_message && p.message.param1 == HomePosition::kId)))
        request_telemetry(cmd, p.message.param1, p.message.param2);  // may reallocate: p unused
      continue;
    }
    switch (p.kind) {
      case Kind::command_long:
        p.message.confirmation = static_cast<std::uint8_t>(p.sends);
        endpoint_.send(p.message);
        break;
      case Kind::command_int:  // COMMAND_INT has no confirmation counter
        endpoint_.send(p.int_message);
        break;
      case Kind::param_read:
        endpoint_.send(p.param);
        break;
      case Kind::param_set:
        endpoint_.send(p.param_set);
        break;
    }
    ++p.sends;
    if (!is_param(p)) ++commands_sent_;
    p.last_sent_s = now_s;
  }
  send_target(now_s);
  transfer_.send_due(now_s);
}

void Driver::poll(double now_s, const std::vector<Frame>& first) {
  for (const Frame& f : first) on_frame(f, now_s);
  for (const Frame& f : endpoint_.receive()) on_frame(f, now_s);
  if (state_.link_alive && now_s - state_.last_heard_s > settings_.lost_after_s) {
    state_.link_alive = false;
    ++state_.links_lost;
  }
  fence_step(now_s);
  send_due(now_s);
  finish_safety_check();
}

}  // namespace swath::mavlink
