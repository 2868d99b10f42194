#include "swath/mavlink/fake_copter.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "swath/geometry/local_frame.hpp"
#include "swath/mavlink/messages.hpp"

namespace swath::mavlink {
namespace {

std::int32_t degE7(double deg) {
  return static_cast<std::int32_t>(std::lround(deg * kDegE7));
}
std::int16_t cm_s(double m_s) {
  return static_cast<std::int16_t>(std::lround(m_s * 100));
}

}  // namespace

FakeCopter::FakeCopter(Link& link, FakeCopterSettings settings)
    : endpoint_(link, settings.sysid, 1), settings_(settings), speed_m_s_(settings.speed_m_s) {
  if (px4())
    params_ = {{"COM_DL_LOSS_T", 10}, {"NAV_DLL_ACT", 2}};
  else
    params_ = {{"FS_GCS_ENABLE", 1}, {"FENCE_ENABLE", 0}, {"FENCE_TYPE", 7}, {"FENCE_OPTIONS", 0}};
  for (const auto& [name, value] : settings_.params) params_[name] = value;
}

std::uint32_t FakeCopter::custom_mode() const {
  if (!px4()) return static_cast<std::uint32_t>(mode_);
  switch (mode_) {
    case CopterMode::guided:  // Hold; climbing after NAV_TAKEOFF: AUTO.TAKEOFF
      return landed_ == LandedState::takeoff ? px4::kTakeoff : px4::kHold;
    case CopterMode::rtl:
      return px4::kRtl;
    case CopterMode::land:
      return px4::kLand;
    case CopterMode::stabilize:
      break;
  }
  return px4::kPosctl;
}

std::optional<CopterMode> FakeCopter::failsafe_mode() const {
  if (px4()) {  // NAV_DLL_ACT: 0 disabled, 1 Hold, 2 Return, 3 Land (5, 6: not modelled)
    switch (std::lround(params_.at("NAV_DLL_ACT"))) {
      case 1:
        return CopterMode::guided;
      case 2:
        return CopterMode::rtl;
      case 3:
        return CopterMode::land;
      default:
        return std::nullopt;
    }
  }
  if (params_.at("FS_GCS_ENABLE") == 0) return std::nullopt;
  return CopterMode::rtl;
}

double FakeCopter::failsafe_after_s() const {
  return px4() ? params_.at("COM_DL_LOSS_T") : settings_.gcs_failsafe_s;
}

void FakeCopter::acknowledge(std::uint16_t command, CmdResult result) {
  endpoint_.send(CommandAck{.command = command,
                            .result = static_cast<std::uint8_t>(result),
                            .target_system = kGcsSysid,
                            .target_component = kGcsCompid});
}

double FakeCopter::param(const std::string& name) const {
  const auto it = params_.find(name);
  return it == params_.end() ? std::nan("") : it->second;
}

void FakeCopter::on_param_request(const ParamRequestRead& r) {
  ++param_requests_received_;
  const auto end = std::find(r.param_id.begin(), r.param_id.end(), '\0');
  const auto it = params_.find(std::string(r.param_id.begin(), end));
  if (it == params_.end()) return;  // as ArduPilot: an unknown name gets no answer
  send_param(it);
}

// As ArduPilot: a known parameter is set and its PARAM_VALUE sent back; an unknown one is ignored.
void FakeCopter::on_param_set(const ParamSet& p) {
  const auto end = std::find(p.param_id.begin(), p.param_id.end(), '\0');
  const auto it = params_.find(std::string(p.param_id.begin(), end));
  if (it == params_.end()) return;
  it->second = px4() ? std::bit_cast<std::int32_t>(p.param_value) : p.param_value;
  send_param(it);
}

void FakeCopter::send_param(std::map<std::string, double>::const_iterator it) {
  ParamValue v;
  std::copy(it->first.begin(), it->first.end(), v.param_id.begin());
  v.param_count = static_cast<std::uint16_t>(params_.size());
  v.param_index = static_cast<std::uint16_t>(std::distance(params_.cbegin(), it));
  if (px4()) {  // INT32, its bytes in the float (PX4's bytewise encoding)
    v.param_type = kParamTypeInt32;
    v.param_value = std::bit_cast<float>(static_cast<std::int32_t>(std::lround(it->second)));
  } else {  // ArduPilot: the value converted to float, FS_GCS_ENABLE an INT8
    v.param_type = kParamTypeInt8;
    v.param_value = static_cast<float>(it->second);
  }
  endpoint_.send(v);
}

void FakeCopter::on_command_int(const CommandInt& c, double) {
  if (static_cast<Cmd>(c.command) != Cmd::do_reposition) {  // the only one the drivers send so
    acknowledge(c.command, CmdResult::unsupported);
    return;
  }
  ++received_[c.command];
  // DO_REPOSITION, frame 6 (above home): airborne and armed, with the change-mode flag, the
  // vehicle switches to Hold (ArduCopter: GUIDED) and flies there; param1 > 0 sets the speed.
  CmdResult result = CmdResult::accepted;
  if (c.frame != kFrameGlobalRelativeAltInt) {
    result = CmdResult::unsupported;
  } else if (!armed_ || landed_ == LandedState::on_ground ||
             (mode_ != CopterMode::guided && (static_cast<std::uint32_t>(c.param2) & 1u) == 0)) {
    result = CmdResult::denied;
  } else {
    mode_ = CopterMode::guided;
    if (c.param1 > 0) speed_m_s_ = c.param1;
    const geometry::LocalFrame local({settings_.home_lat_deg, settings_.home_lon_deg});
    const geometry::Point2 p = local.to_local({c.x / kDegE7, c.y / kDegE7});
    target_east_m_ = p.x;
    target_north_m_ = p.y;
    target_alt_m_ = c.z;
    has_target_ = true;
    leg_speed_m_s_ = 0;
    leg_planned_ = false;
    ++targets_received_;
  }
  acknowledge(c.command, result);
}

void FakeCopter::cut_link(double from_s, double until_s) {
  cut_from_s_ = from_s;
  cut_until_s_ = until_s;
}

int FakeCopter::commands_received(Cmd cmd) const {
  const auto it = received_.find(static_cast<std::uint16_t>(cmd));
  return it == received_.end() ? 0 : it->second;
}

void FakeCopter::to_geodetic(double north_m, double east_m, double& lat_deg,
                             double& lon_deg) const {
  const geometry::LocalFrame frame({settings_.home_lat_deg, settings_.home_lon_deg});
  const geometry::GeoPoint p = frame.to_geo({east_m, north_m});
  lat_deg = p.lat_deg;
  lon_deg = p.lon_deg;
}

void FakeCopter::send_status_text(const std::string& text) {
  StatusText t;
  t.severity = 3;  // MAV_SEVERITY_ERROR
  std::copy_n(text.begin(), std::min(text.size(), t.text.size()), t.text.begin());
  endpoint_.send(t);
}

void FakeCopter::on_command(const CommandLong& c, double now_s) {
  ++received_[c.command];
  CmdResult result = CmdResult::accepted;
  const bool on_ground = landed_ == LandedState::on_ground;
  switch (static_cast<Cmd>(c.command)) {
    case Cmd::do_set_mode: {
      auto mode = static_cast<CopterMode>(std::lround(c.param2));
      if (px4()) {  // param2 main mode, param3 sub mode
        const std::uint32_t asked = px4::custom_mode(static_cast<std::uint8_t>(c.param2),
                                                     static_cast<std::uint8_t>(c.param3));
        if (asked == px4::kHold)
          mode = CopterMode::guided;
        else if (asked == px4::kRtl)
          mode = CopterMode::rtl;
        else if (asked == px4::kLand)
          mode = CopterMode::land;
        else if (asked == px4::kPosctl)
          mode = CopterMode::stabilize;
        else {
          result = CmdResult::unsupported;
          break;
        }
      }
      if (!refuse_mode_.empty() && mode == refused_mode_) {
        send_status_text(refuse_mode_);
        result = CmdResult::failed;
        break;
      }
      mode_ = mode;
      if (mode_ == CopterMode::guided) has_target_ = false;  // GUIDED holds position first
      leg_planned_ = false;
      break;
    }
    case Cmd::component_arm_disarm:
      if (c.param1 == 1.0f) {
        if (!refuse_arm_.empty() && now_s < refuse_arm_until_s_) {
          send_status_text(refuse_arm_);
          result = CmdResult::failed;
        } else if (mode_ != CopterMode::guided || !on_ground) {
          result = CmdResult::denied;
        } else {
          armed_ = true;
        }
      } else {
        result = on_ground ? CmdResult::accepted : CmdResult::denied;
        if (on_ground) armed_ = false;
      }
      break;
    case Cmd::nav_takeoff:
      // ArduCopter: in GUIDED, param7 above home. PX4: from any mode (it switches to
      // AUTO.TAKEOFF, then holds), param7 above sea level, NaN: MIS_TAKEOFF_ALT (2.5 m).
      if (!armed_ || (!px4() && mode_ != CopterMode::guided) || !on_ground) {
        result = CmdResult::failed;
      } else {
        if (px4()) mode_ = CopterMode::guided;
        landed_ = LandedState::takeoff;
        leg_planned_ = false;
        has_target_ = true;
        target_north_m_ = north_m_;
        target_east_m_ = east_m_;
        target_alt_m_ = !px4()                 ? c.param7
                        : std::isnan(c.param7) ? 2.5
                                               : c.param7 - settings_.home_amsl_m;
      }
      break;
    case Cmd::do_change_speed:
      if (c.param2 > 0) speed_m_s_ = c.param2;
      break;
    case Cmd::nav_return_to_launch:
      if (on_ground)
        result = CmdResult::failed;
      else
        mode_ = CopterMode::rtl;
      break;
    case Cmd::nav_land:
      if (on_ground)
        result = CmdResult::failed;
      else
        mode_ = CopterMode::land;
      break;
    case Cmd::set_message_interval:
      interval_s_[static_cast<std::uint32_t>(c.param1)] = c.param2 / 1e6;
      break;
    case Cmd::request_message:
      if (static_cast<std::uint32_t>(c.param1) == HomePosition::kId) {
        HomePosition h;
        h.latitude_degE7 = degE7(settings_.home_lat_deg);
        h.longitude_degE7 = degE7(settings_.home_lon_deg);
        h.altitude_mm = static_cast<std::int32_t>(std::lround(settings_.home_amsl_m * 1000));
        h.q = {1, 0, 0, 0};
        h.time_us = static_cast<std::uint64_t>(now_s * 1e6);
        endpoint_.send(h);
      } else if (static_cast<std::uint32_t>(c.param1) == PositionTargetGlobalInt::kId) {
        // As ArduCopter: its GUIDED target above sea level, nothing when it has none (the
        // request is still accepted).
        if (mode_ == CopterMode::guided && has_target_ && landed_ != LandedState::on_ground) {
          PositionTargetGlobalInt t;
          double lat = 0, lon = 0;
          to_geodetic(target_north_m_, target_east_m_, lat, lon);
          t.time_boot_ms = static_cast<std::uint32_t>(now_s * 1000);
          t.lat_degE7 = degE7(lat);
          t.lon_degE7 = degE7(lon);
          t.alt_m = static_cast<float>(settings_.home_amsl_m + target_alt_m_);
          t.type_mask = 0xFFF8;
          t.coordinate_frame = 0;  // MAV_FRAME_GLOBAL
          endpoint_.send(t);
        }
      } else {
        result = CmdResult::unsupported;
      }
      break;
    case Cmd::image_start_capture: {
      CameraImageCaptured image;
      image.time_boot_ms = static_cast<std::uint32_t>(now_s * 1000);
      double lat = 0, lon = 0;
      to_geodetic(north_m_, east_m_, lat, lon);
      image.lat_degE7 = degE7(lat);
      image.lon_degE7 = degE7(lon);
      image.relative_alt_mm = static_cast<std::int32_t>(std::lround(alt_m_ * 1000));
      image.image_index = images_++;
      image.capture_result = 1;
      endpoint_.send(image);
      break;
    }
    default:
      result = CmdResult::unsupported;
  }
  acknowledge(c.command, result);
}

void FakeCopter::on_frame(const Frame& frame, double now_s) {
  if (frame.header.sysid != kGcsSysid) return;
  if (unpack<Heartbeat>(frame)) {
    if (gcs_heartbeats_++ > 0)
      longest_gcs_silence_s_ = std::max(longest_gcs_silence_s_, now_s - last_gcs_heartbeat_s_);
    last_gcs_heartbeat_s_ = now_s;
    gcs_seen_ = true;
  } else if (const auto c = unpack<CommandLong>(frame)) {
    if (c->target_system != settings_.sysid) return;
    if (commands_to_lose_ > 0) {
      --commands_to_lose_;
      return;
    }
    if (c->command == lose_first_sends_of_ && c->confirmation == 0) return;
    on_command(*c, now_s);
  } else if (const auto ci = unpack<CommandInt>(frame)) {
    if (ci->target_system != settings_.sysid) return;
    if (commands_to_lose_ > 0) {
      --commands_to_lose_;
      return;
    }
    on_command_int(*ci, now_s);
  } else if (const auto r = unpack<ParamRequestRead>(frame)) {
    if (r->target_system != settings_.sysid || drop_param_requests_) return;
    on_param_request(*r);
  } else if (const auto ps = unpack<ParamSet>(frame)) {
    if (ps->target_system != settings_.sysid) return;
    on_param_set(*ps);
  } else if (on_mission_frame(frame)) {
    return;
  } else if (const auto t = unpack<SetPositionTargetGlobalInt>(frame)) {
    if (t->target_system != settings_.sysid || mode_ != CopterMode::guided ||
        landed_ == LandedState::on_ground)
      return;
    if (targets_to_lose_ > 0) {
      --targets_to_lose_;
      return;
    }
    ++targets_received_;
    leg_speed_m_s_ = 0;  // re-planned from rest (only felt with accel_m_s2)
    // ArduCopter keeps the speed limit for a leg that follows a reached one (WPNAV_RADIUS 2 m);
    // otherwise it re-initialises the waypoint controller at WPNAV_SPEED.
    const bool reached = std::hypot(target_north_m_ - north_m_, target_east_m_ - east_m_) <= 2.0 &&
                         std::hypot(v_north_m_s_, v_east_m_s_) < 0.5;
    leg_max_m_s_ = leg_planned_ && reached ? speed_m_s_ : settings_.speed_m_s;
    leg_planned_ = true;
    const geometry::LocalFrame local({settings_.home_lat_deg, settings_.home_lon_deg});
    const geometry::Point2 p = local.to_local({t->lat_degE7 / kDegE7, t->lon_degE7 / kDegE7});
    target_east_m_ = p.x;
    target_north_m_ = p.y;
    target_alt_m_ = t->alt_m;
    has_target_ = true;
  }
}

// The fence's mission protocol, as ArduPilot's MissionItemProtocol_Fence answers it.
bool FakeCopter::on_mission_frame(const Frame& frame) {
  const auto fence = static_cast<std::uint8_t>(MissionType::fence);
  const auto ack = [&](MissionResult r) {
    endpoint_.send(MissionAck{.target_system = kGcsSysid,
                              .target_component = kGcsCompid,
                              .type = static_cast<std::uint8_t>(r),
                              .mission_type = fence});
  };
  const auto request = [&](std::uint16_t seq) {
    endpoint_.send(MissionRequest{.seq = seq,
                                  .target_system = kGcsSysid,
                                  .target_component = kGcsCompid,
                                  .mission_type = fence});
  };
  const auto lost = [&] {
    ++mission_received_;
    if (mission_to_lose_ == 0) return false;
    --mission_to_lose_;
    --mission_received_;
    return true;
  };
  if (const auto c = unpack<MissionCount>(frame)) {
    if (c->target_system != settings_.sysid || c->mission_type != fence) return true;
    if (lost()) return true;
    if (fence_refusal_) {
      ack(*fence_refusal_);
      fence_refusal_.reset();
      return true;
    }
    incoming_.clear();
    incoming_count_ = c->count;
    receiving_ = c->count > 0;
    if (receiving_) {
      request(0);
    } else {
      fence_.clear();
      ack(MissionResult::accepted);
    }
    return true;
  }
  if (const auto item = unpack<MissionItemInt>(frame)) {
    if (item->target_system != settings_.sysid || item->mission_type != fence) return true;
    if (lost()) return true;
    if (!receiving_) {  // a resend of the last item after its acknowledgement was lost
      ack(MissionResult::accepted);
      return true;
    }
    if (item->seq != incoming_.size()) {  // out of turn: asks again for the one it expects
      request(static_cast<std::uint16_t>(incoming_.size()));
      return true;
    }
    const auto cmd = static_cast<Cmd>(item->command);
    if (cmd != Cmd::nav_fence_polygon_vertex_inclusion &&
        cmd != Cmd::nav_fence_polygon_vertex_exclusion && cmd != Cmd::nav_fence_circle_inclusion &&
        cmd != Cmd::nav_fence_circle_exclusion) {
      receiving_ = false;
      ack(MissionResult::unsupported);
      return true;
    }
    MissionItemInt stored = *item;
    stored.frame = 0;  // ArduPilot keeps lat/lon only and reads them back in MAV_FRAME_GLOBAL at 0
    stored.z = 0;
    if (static_cast<int>(item->seq) == corrupt_seq_) stored.x += 1000;  // 1e-4 degrees north
    incoming_.push_back(stored);
    if (incoming_.size() < incoming_count_) {
      request(static_cast<std::uint16_t>(incoming_.size()));
    } else {
      fence_ = incoming_;
      receiving_ = false;
      ack(MissionResult::accepted);
    }
    return true;
  }
  if (const auto list = unpack<MissionRequestList>(frame)) {
    if (list->target_system != settings_.sysid || list->mission_type != fence) return true;
    if (lost()) return true;
    endpoint_.send(MissionCount{.count = static_cast<std::uint16_t>(fence_.size()),
                                .target_system = kGcsSysid,
                                .target_component = kGcsCompid,
                                .mission_type = fence});
    return true;
  }
  if (const auto r = unpack<MissionRequestInt>(frame)) {
    if (r->target_system != settings_.sysid || r->mission_type != fence) return true;
    if (lost()) return true;
    if (r->seq >= fence_.size()) {
      ack(MissionResult::invalid_sequence);
      return true;
    }
    MissionItemInt out = fence_[r->seq];
    out.target_system = kGcsSysid;
    out.target_component = kGcsCompid;
    endpoint_.send(out);
    return true;
  }
  if (const auto a = unpack<MissionAck>(frame)) {
    if (a->target_system == settings_.sysid) ++mission_received_;
    return true;
  }
  return false;
}

void FakeCopter::move(double dt_s) {
  v_north_m_s_ = v_east_m_s_ = v_up_m_s_ = 0;
  if (!armed_) return;
  battery_percent_ = std::max(0.0, battery_percent_ - settings_.battery_drain_percent_s * dt_s);
  if (mode_ == CopterMode::rtl) {  // home at the current altitude, then land
    has_target_ = true;
    target_north_m_ = target_east_m_ = 0;
    target_alt_m_ = alt_m_;
    if (std::hypot(north_m_, east_m_) < 0.5) mode_ = CopterMode::land;
  }
  if (mode_ == CopterMode::land) {
    landed_ = LandedState::landing;
    v_up_m_s_ = -settings_.descent_m_s;
    alt_m_ = std::max(0.0, alt_m_ - settings_.descent_m_s * dt_s);
    if (alt_m_ <= 0) {
      landed_ = LandedState::on_ground;
      armed_ = false;
      has_target_ = false;
    }
    return;
  }
  if (!has_target_) return;
  const double dn = target_north_m_ - north_m_, de = target_east_m_ - east_m_;
  const double d = std::hypot(dn, de);
  double speed = settings_.speed_per_leg && mode_ == CopterMode::guided && leg_planned_
                     ? leg_max_m_s_
                     : speed_m_s_;
  if (settings_.accel_m_s2 > 0) {
    leg_speed_m_s_ = std::min(speed, leg_speed_m_s_ + settings_.accel_m_s2 * dt_s);
    speed = leg_speed_m_s_;
  }
  const double step = std::min(d, speed * dt_s);
  if (d > 0) {
    north_m_ += dn / d * step;
    east_m_ += de / d * step;
    v_north_m_s_ = dn / d * step / dt_s;
    v_east_m_s_ = de / d * step / dt_s;
  }
  const double dz = target_alt_m_ - alt_m_;
  const double climb = std::clamp(dz, -settings_.climb_m_s * dt_s, settings_.climb_m_s * dt_s);
  alt_m_ += climb;
  v_up_m_s_ = climb / dt_s;
  if (landed_ == LandedState::takeoff && alt_m_ >= 0.95 * target_alt_m_)
    landed_ = LandedState::in_air;
}

void FakeCopter::send_telemetry(double now_s) {
  const auto due = [&](std::uint32_t id, double default_interval_s) {
    const auto it = interval_s_.find(id);
    const double interval = it == interval_s_.end() ? default_interval_s : it->second;
    if (interval <= 0) return false;
    auto [last, fresh] = last_sent_s_.try_emplace(id, now_s);
    if (!fresh && now_s - last->second < interval - 1e-9) return false;
    last->second = now_s;
    return true;
  };
  if (due(Heartbeat::kId, 1.0)) {
    endpoint_.send(Heartbeat{.custom_mode = custom_mode(),
                             .type = kMavTypeQuadrotor,
                             .autopilot = px4() ? kAutopilotPx4 : kAutopilotArdupilot,
                             .base_mode = static_cast<std::uint8_t>(kModeFlagCustomEnabled |
                                                                    (armed_ ? kModeFlagArmed : 0)),
                             .system_status = static_cast<std::uint8_t>(armed_ ? 4 : 3)});
  }
  if (due(GlobalPositionInt::kId, 0)) {  // nothing until asked, as with SRx rates at 0
    double lat = 0, lon = 0;
    to_geodetic(north_m_, east_m_, lat, lon);
    endpoint_.send(GlobalPositionInt{
        .time_boot_ms = static_cast<std::uint32_t>(now_s * 1000),
        .lat_degE7 = degE7(lat),
        .lon_degE7 = degE7(lon),
        .alt_mm = static_cast<std::int32_t>(std::lround((settings_.home_amsl_m + alt_m_) * 1000)),
        .relative_alt_mm = static_cast<std::int32_t>(std::lround(alt_m_ * 1000)),
        .vx_cm_s = cm_s(v_north_m_s_),
        .vy_cm_s = cm_s(v_east_m_s_),
        .vz_cm_s = cm_s(-v_up_m_s_),
        .hdg_cdeg = 0});
  }
  if (due(ExtendedSysState::kId, 0))
    endpoint_.send(ExtendedSysState{.landed_state = static_cast<std::uint8_t>(landed_)});
  if (due(SysStatus::kId, 0)) {
    SysStatus s;
    s.voltage_battery_mV = static_cast<std::uint16_t>(std::lround(14800 + 10 * battery_percent_));
    s.current_battery_cA = -1;
    s.battery_remaining_percent = static_cast<std::int8_t>(std::lround(battery_percent_));
    endpoint_.send(s);
  }
  if (due(BatteryStatus::kId, 0)) {
    BatteryStatus b;
    b.id = 0;
    b.voltages_mV.fill(UINT16_MAX);  // not known per cell
    b.voltages_mV[0] = static_cast<std::uint16_t>(std::lround(14800 + 10 * battery_percent_));
    b.current_battery_cA = -1;
    b.battery_remaining_percent = static_cast<std::int8_t>(std::lround(battery_percent_));
    endpoint_.send(b);
  }
}

void FakeCopter::step(double now_s) {
  const double dt = started_ ? now_s - last_step_s_ : 0;
  started_ = true;
  last_step_s_ = now_s;
  if (link_cut(now_s)) {
    (void)endpoint_.receive();  // what arrives during the cut is lost
  } else {
    for (const Frame& f : endpoint_.receive()) on_frame(f, now_s);
  }
  if (dt > 0) move(dt);
  const bool airborne = landed_ != LandedState::on_ground;
  const std::optional<CopterMode> failsafe = failsafe_mode();
  if (armed_ && airborne && gcs_seen_ && now_s - last_gcs_heartbeat_s_ > failsafe_after_s() &&
      mode_ == CopterMode::guided && failsafe) {
    mode_ = *failsafe;                  // the GCS (data-link-loss) failsafe
    if (mode_ == CopterMode::guided) {  // PX4's Hold: stays where it is
      target_north_m_ = north_m_;
      target_east_m_ = east_m_;
      target_alt_m_ = alt_m_;
    }
  }
  if (!link_cut(now_s)) send_telemetry(now_s);
}

}  // namespace swath::mavlink
