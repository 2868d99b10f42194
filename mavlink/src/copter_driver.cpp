#include "swath/mavlink/copter_driver.hpp"

#include <algorithm>
#include <cmath>

namespace swath::mavlink {

namespace {
// ArduCopter's ground-station failsafe switch (ArduCopter parameter docs, FS_GCS_ENABLE: 0
// disabled, 1 RTL, 2 continue a mission in AUTO (removed), 3 SmartRTL or RTL, 4 SmartRTL or land,
// 5 land, ...): 0 is the one value with no action when the link is lost.
constexpr const char* kFsGcsEnable = "FS_GCS_ENABLE";
// ArduCopter's fence switch and kinds (AC_Fence: FENCE_ENABLE 0/1; FENCE_TYPE bits 1 maximum
// altitude, 2 circle around home, 4 polygons, 8 minimum altitude). Both INT8.
constexpr const char* kFenceEnable = "FENCE_ENABLE";
constexpr const char* kFenceType = "FENCE_TYPE";
constexpr int kFenceTypePolygon = 4;
// FENCE_OPTIONS (INT16) bit 1: the flight area is the union of the inclusion areas (ArduPilot's
// default is their intersection; swath's envelope takes the union).
constexpr const char* kFenceOptions = "FENCE_OPTIONS";
constexpr int kFenceOptionsUnion = 2;
constexpr std::uint8_t kParamTypeInt16 = 4;
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

// FENCE_TYPE is read first so that its other kinds (the vehicle's own altitude limit or circle)
// stay as the vehicle's owner set them; only the polygon bit is added.
std::optional<std::string> CopterDriver::enable_fence_step() {
  if (fence_type_read_ < 0) {
    fence_type_read_ = read_param(kFenceType);
    // Only with more than one inclusion area: older firmware without the option still takes one.
    if (inclusion_areas() > 1) fence_options_read_ = read_param(kFenceOptions);
  }
  const auto failed = [&](int id, const std::string& name) -> std::optional<std::string> {
    const CommandState c = command_state(id);
    if (c == CommandState::timed_out)
      return "no answer about " + name + " after " + std::to_string(settings_.attempts) + " sends";
    if (c == CommandState::rejected) return "the vehicle kept its own " + name;
    return std::nullopt;
  };
  const bool options = fence_options_read_ >= 0;
  if (auto why = failed(fence_type_read_, kFenceType)) return why;
  if (options)
    if (auto why = failed(fence_options_read_, kFenceOptions)) return why;
  if (command_state(fence_type_read_) != CommandState::accepted ||
      (options && command_state(fence_options_read_) != CommandState::accepted))
    return std::nullopt;
  if (fence_type_set_ < 0) {
    const int type = static_cast<int>(std::lround(state_.params.at(kFenceType)));
    fence_type_set_ = set_param(kFenceType, type | kFenceTypePolygon, kParamTypeInt8);
    if (options) {
      const int o = static_cast<int>(std::lround(state_.params.at(kFenceOptions)));
      fence_options_set_ = set_param(kFenceOptions, o | kFenceOptionsUnion, kParamTypeInt16);
    }
    fence_enable_set_ = set_param(kFenceEnable, 1, kParamTypeInt8);
  }
  bool all = true;
  for (const auto& [id, name] :
       {std::pair{fence_type_set_, kFenceType}, std::pair{fence_options_set_, kFenceOptions},
        std::pair{fence_enable_set_, kFenceEnable}}) {
    if (id < 0) continue;
    if (auto why = failed(id, name)) return why;
    all = all && command_state(id) == CommandState::accepted;
  }
  if (all) return std::string();
  return std::nullopt;
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
