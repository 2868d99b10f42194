#include "swath/mavlink/copter_driver.hpp"

#include <algorithm>
#include <cmath>

namespace swath::mavlink {

namespace {
// ArduCopter's ground-station failsafe switch (ArduCopter parameter docs, FS_GCS_ENABLE: 0
// disabled, 1 RTL, 2 continue a mission in AUTO (removed), 3 SmartRTL or RTL, 4 SmartRTL or land,
// 5 land, ...): 0 is the one value with no action when the link is lost.
constexpr const char* kFsGcsEnable = "FS_GCS_ENABLE";
}  // namespace

CopterDriver::CopterDriver(Link& link, DriverSettings settings)
    : Driver(link, std::move(settings)) {}

int CopterDriver::set_mode(CopterMode mode) {
  return enqueue(Cmd::do_set_mode, kModeFlagCustomEnabled, static_cast<float>(mode));
}
int CopterDriver::takeoff(double altitude_m) {
  // ArduCopter reads NAV_TAKEOFF's param7 above home whatever the command's frame.
  return enqueue(Cmd::nav_takeoff, 0, 0, 0, static_cast<float>(altitude_m));
}

bool CopterDriver::in_guided() const {
  return state_.custom_mode == static_cast<std::uint32_t>(CopterMode::guided);
}
bool CopterDriver::returning() const {
  return state_.custom_mode == static_cast<std::uint32_t>(CopterMode::rtl) ||
         state_.custom_mode == static_cast<std::uint32_t>(CopterMode::land);
}

bool CopterDriver::go_to(double lat_deg, double lon_deg, double altitude_m) {
  if (!set_target(lat_deg, lon_deg, altitude_m)) return false;
  target_sent_s_ = -std::numeric_limits<double>::infinity();  // at the next poll
  return true;
}

std::vector<std::string> CopterDriver::safety_params() const {
  return {kFsGcsEnable};
}

std::string CopterDriver::unread_consequence() const {
  return "whether the vehicle returns on a lost link is unknown";
}

std::vector<std::string> CopterDriver::safety_warnings() const {
  const auto it = state_.params.find(kFsGcsEnable);
  if (it != state_.params.end() && it->second == 0)
    return {std::string(kFsGcsEnable) +
            " is 0: ArduCopter will not return to launch when the link is lost"};
  return {};
}

void CopterDriver::send_target(double now_s) {
  // ArduCopter re-plans a GUIDED leg from its stopping point, at rest, on every target it is
  // sent before the last was reached (AC_WPNav::set_wp_destination_NEU_cm): a target repeated
  // each second would hold a 10 m/s leg near 2.5 m/s (WPNAV_ACCEL). So the target is
  // repeated only until the vehicle reports it as its own (POSITION_TARGET_GLOBAL_INT, asked for
  // after each send; a lost target or a lost report shows as no match): while the question is
  // pending nothing is resent. A vehicle that refuses the question gets the target each second.
  if (!state_.link_alive || !target_ || target_confirmed_ || arrived() || !in_guided() ||
      now_s - target_sent_s_ < settings_.target_resend_s)
    return;
  const auto asking = [&](const Pending& p) {
    return p.state == CommandState::pending && p.kind == Pending::Kind::command_long &&
           p.message.command == static_cast<std::uint16_t>(Cmd::request_message) &&
           p.message.param1 == static_cast<float>(PositionTargetGlobalInt::kId);
  };
  if (std::any_of(commands_.begin(), commands_.end(), asking)) return;
  SetPositionTargetGlobalInt t;
  t.lat_degE7 = target_->lat_degE7;
  t.lon_degE7 = target_->lon_degE7;
  t.alt_m = target_->alt_m;
  t.type_mask = kTypeMaskPositionOnly;
  t.target_system = settings_.vehicle_sysid;
  t.target_component = settings_.vehicle_compid;
  t.coordinate_frame = kFrameGlobalRelativeAltInt;
  endpoint_.send(t);
  ++targets_sent_;
  target_sent_s_ = now_s;
  enqueue(Cmd::request_message, static_cast<float>(PositionTargetGlobalInt::kId));
}

}  // namespace swath::mavlink
