#include "swath/mavlink/copter_driver.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "swath/geometry/local_frame.hpp"

namespace swath::mavlink {
namespace {

std::int32_t to_degE7(double deg) {
  return static_cast<std::int32_t>(std::lround(deg * kDegE7));
}

}  // namespace

CopterDriver::CopterDriver(Link& link, DriverSettings settings)
    : endpoint_(link, kGcsSysid, kGcsCompid), settings_(std::move(settings)) {}

int CopterDriver::enqueue(Cmd cmd, float p1, float p2, float p3, float p7) {
  Pending p;
  p.message.command = static_cast<std::uint16_t>(cmd);
  p.message.target_system = settings_.vehicle_sysid;
  p.message.target_component = settings_.vehicle_compid;
  p.message.param1 = p1;
  p.message.param2 = p2;
  p.message.param3 = p3;
  p.message.param7 = p7;
  commands_.push_back(p);
  return static_cast<int>(commands_.size()) - 1;
}

int CopterDriver::set_mode(CopterMode mode) {
  return enqueue(Cmd::do_set_mode, kModeFlagCustomEnabled, static_cast<float>(mode));
}
int CopterDriver::arm(bool on) {
  return enqueue(Cmd::component_arm_disarm, on ? 1.0f : 0.0f);
}
int CopterDriver::takeoff(double altitude_m) {
  return enqueue(Cmd::nav_takeoff, 0, 0, 0, static_cast<float>(altitude_m));
}
int CopterDriver::set_speed(double ground_speed_m_s) {
  return enqueue(Cmd::do_change_speed, 1, static_cast<float>(ground_speed_m_s));
}
int CopterDriver::return_to_launch() {
  target_.reset();
  return enqueue(Cmd::nav_return_to_launch);
}
int CopterDriver::land() {
  target_.reset();
  return enqueue(Cmd::nav_land);
}
int CopterDriver::capture_image() {
  return enqueue(Cmd::image_start_capture, 0, 0, 1);
}

CommandState CopterDriver::command_state(int id) const {
  return commands_.at(static_cast<std::size_t>(id)).state;
}
std::optional<CmdResult> CopterDriver::command_result(int id) const {
  return commands_.at(static_cast<std::size_t>(id)).result;
}

int CopterDriver::commands_pending() const {
  return static_cast<int>(std::count_if(commands_.begin(), commands_.end(), [](const Pending& p) {
    return p.state == CommandState::pending;
  }));
}

bool CopterDriver::go_to(double lat_deg, double lon_deg, double altitude_m) {
  if (settings_.inside_fence && !settings_.inside_fence(lat_deg, lon_deg)) return false;
  SetPositionTargetGlobalInt t;
  t.lat_degE7 = to_degE7(lat_deg);
  t.lon_degE7 = to_degE7(lon_deg);
  t.alt_m = static_cast<float>(altitude_m);
  t.type_mask = kTypeMaskPositionOnly;
  t.target_system = settings_.vehicle_sysid;
  t.target_component = settings_.vehicle_compid;
  t.coordinate_frame = kFrameGlobalRelativeAltInt;
  target_ = t;
  target_sent_s_ = -std::numeric_limits<double>::infinity();  // at the next poll
  target_confirmed_ = false;
  return true;
}

bool CopterDriver::reports_our_target(const PositionTargetGlobalInt& reported) const {
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

double CopterDriver::distance_to_target_m() const {
  if (!target_ || !state_.position) return std::numeric_limits<double>::infinity();
  const double horizontal = geometry::geodesic_distance_m(
      {state_.position->lat_degE7 / kDegE7, state_.position->lon_degE7 / kDegE7},
      {target_->lat_degE7 / kDegE7, target_->lon_degE7 / kDegE7});
  const double vertical = state_.position->relative_alt_mm / 1000.0 - target_->alt_m;
  return std::hypot(horizontal, vertical);
}

bool CopterDriver::arrived() const {
  if (!target_ || !state_.position) return false;
  const GlobalPositionInt& p = *state_.position;
  const double speed_m_s = std::sqrt(double(p.vx_cm_s) * p.vx_cm_s + double(p.vy_cm_s) * p.vy_cm_s +
                                     double(p.vz_cm_s) * p.vz_cm_s) /
                           100.0;
  return distance_to_target_m() <= settings_.arrival_radius_m &&
         speed_m_s < settings_.arrival_speed_m_s;
}

void CopterDriver::request_telemetry(Cmd cmd, float p1, float p2) {
  // At most one pending request per message: a link that flaps while a set is still waiting to
  // go out must not add another set each time it comes up.
  for (const Pending& p : commands_)
    if (p.state == CommandState::pending && p.message.command == static_cast<std::uint16_t>(cmd) &&
        p.message.param1 == p1)
      return;
  enqueue(cmd, p1, p2);
}

void CopterDriver::on_link_up() {
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
}

void CopterDriver::on_frame(const Frame& frame, double now_s) {
  if (frame.header.sysid != settings_.vehicle_sysid) return;
  if (const auto hb = unpack<Heartbeat>(frame)) {
    if (frame.header.compid != settings_.vehicle_compid) return;
    state_.last_heard_s = now_s;
    if (!state_.link_alive) {
      state_.link_alive = true;
      on_link_up();
    }
    state_.armed = (hb->base_mode & kModeFlagArmed) != 0;
    state_.custom_mode = hb->custom_mode;
  } else if (const auto ack = unpack<CommandAck>(frame)) {
    // The oldest pending command of that number is the one acknowledged.
    for (Pending& p : commands_) {
      if (p.state != CommandState::pending || p.sends == 0 || p.message.command != ack->command)
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
    state_.battery_remaining_percent = sys->battery_remaining_percent;
  } else if (const auto text = unpack<StatusText>(frame)) {
    const auto end = std::find(text->text.begin(), text->text.end(), '\0');
    state_.status_texts.emplace_back(text->text.begin(), end);
  } else if (const auto image = unpack<CameraImageCaptured>(frame)) {
    state_.images.push_back(*image);
  }
}

void CopterDriver::send_due(double now_s) {
  if (now_s - last_heartbeat_sent_s_ >= settings_.heartbeat_period_s) {
    endpoint_.send(Heartbeat{.custom_mode = 0,
                             .type = kMavTypeGcs,
                             .autopilot = kAutopilotInvalid,
                             .base_mode = 0,
                             .system_status = 4});
    last_heartbeat_sent_s_ = now_s;
  }
  if (!state_.link_alive) return;  // commands wait for the vehicle; their clock starts at sending
  // A COMMAND_ACK names only the command number: one command of each number in flight at a
  // time, or an acknowledgement of the second would be taken for a lost first.
  std::set<std::uint16_t> in_flight;
  for (const Pending& p : commands_)
    if (p.state == CommandState::pending && p.sends > 0) in_flight.insert(p.message.command);
  const std::size_t n = commands_.size();
  for (std::size_t i = 0; i < n; ++i) {
    Pending& p = commands_[i];
    if (p.state != CommandState::pending || now_s - p.last_sent_s < settings_.ack_timeout_s)
      continue;
    if (p.sends == 0 && !in_flight.insert(p.message.command).second) continue;  // waits its turn
    if (p.sends >= settings_.attempts) {
      p.state = CommandState::timed_out;
      // Telemetry is what the link is for (without positions no arrival is ever seen): its
      // requests are asked again, as new commands, until the vehicle answers.
      const auto cmd = static_cast<Cmd>(p.message.command);
      if (cmd == Cmd::set_message_interval ||
          (cmd == Cmd::request_message && p.message.param1 == HomePosition::kId))
        request_telemetry(cmd, p.message.param1, p.message.param2);  // may reallocate: p unused
      continue;
    }
    p.message.confirmation = static_cast<std::uint8_t>(p.sends);
    endpoint_.send(p.message);
    ++p.sends;
    ++commands_sent_;
    p.last_sent_s = now_s;
  }
  // ArduCopter re-plans a GUIDED leg from its stopping point, at rest, on every target it is
  // sent before the last was reached (AC_WPNav::set_wp_destination_NEU_cm): a target repeated
  // each second would hold a 10 m/s leg near 2.5 m/s (WPNAV_ACCEL). So the target is
  // repeated only until the vehicle reports it as its own (POSITION_TARGET_GLOBAL_INT, asked for
  // after each send; a lost target or a lost report shows as no match): while the question is
  // pending nothing is resent. A vehicle that refuses the question gets the target each second.
  if (!target_ || target_confirmed_ || arrived() ||
      state_.custom_mode != static_cast<std::uint32_t>(CopterMode::guided) ||
      now_s - target_sent_s_ < settings_.target_resend_s)
    return;
  const auto asking = [&](const Pending& p) {
    return p.state == CommandState::pending &&
           p.message.command == static_cast<std::uint16_t>(Cmd::request_message) &&
           p.message.param1 == static_cast<float>(PositionTargetGlobalInt::kId);
  };
  if (std::any_of(commands_.begin(), commands_.end(), asking)) return;
  endpoint_.send(*target_);
  ++targets_sent_;
  target_sent_s_ = now_s;
  enqueue(Cmd::request_message, static_cast<float>(PositionTargetGlobalInt::kId));
}

void CopterDriver::poll(double now_s) {
  for (const Frame& f : endpoint_.receive()) on_frame(f, now_s);
  if (state_.link_alive && now_s - state_.last_heard_s > settings_.lost_after_s) {
    state_.link_alive = false;
    ++state_.links_lost;
  }
  send_due(now_s);
}

}  // namespace swath::mavlink
