// UNTESTED ON PX4 (px4_driver.hpp): every number below is from PX4's or MAVLink's documents.
#include "swath/mavlink/px4_driver.hpp"

#include <cmath>
#include <limits>

namespace swath::mavlink {

namespace {
// PX4 parameter reference (docs.px4.io, "Parameter Reference"): COM_DL_LOSS_T, INT32, seconds
// without a GCS heartbeat before the data link counts as lost (default 10); NAV_DLL_ACT, INT32,
// the action then: 0 Disabled (the default), 1 Hold, 2 Return, 3 Land, 5 Terminate, 6 Disarm.
constexpr const char* kLossTimeout = "COM_DL_LOSS_T";
constexpr const char* kLossAction = "NAV_DLL_ACT";
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
}  // namespace

Px4Driver::Px4Driver(Link& link, DriverSettings settings) : Driver(link, std::move(settings)) {}

int Px4Driver::set_mode(std::uint32_t px4_custom_mode) {
  return enqueue(Cmd::do_set_mode, kModeFlagCustomEnabled,
                 static_cast<float>(px4::main_mode(px4_custom_mode)),
                 static_cast<float>(px4::sub_mode(px4_custom_mode)));
}

int Px4Driver::takeoff(double altitude_m) {
  CommandLong m;
  m.command = static_cast<std::uint16_t>(Cmd::nav_takeoff);
  m.param4 = kNaN;  // yaw: keep
  m.param5 = kNaN;  // latitude, longitude: here
  m.param6 = kNaN;
  m.param7 =
      state_.home ? static_cast<float>(state_.home->altitude_mm / 1000.0 + altitude_m) : kNaN;
  return enqueue(m);
}

bool Px4Driver::in_guided() const {
  return state_.custom_mode == px4::kHold || state_.custom_mode == px4::kTakeoff;
}
bool Px4Driver::returning() const {
  return state_.custom_mode == px4::kRtl || state_.custom_mode == px4::kLand;
}

bool Px4Driver::go_to(double lat_deg, double lon_deg, double altitude_m) {
  if (!set_target(lat_deg, lon_deg, altitude_m)) return false;
  CommandInt c;
  c.command = static_cast<std::uint16_t>(Cmd::do_reposition);
  c.frame = kFrameGlobalRelativeAltInt;
  c.param1 = -1;                     // ground speed: the default (DO_CHANGE_SPEED's, if set)
  c.param2 = kRepositionChangeMode;  // switch to Hold and fly there
  c.param3 = 0;                      // loiter radius: planes only
  c.param4 = kNaN;                   // yaw: the current yaw behaviour
  c.x = target_->lat_degE7;
  c.y = target_->lon_degE7;
  c.z = target_->alt_m;
  reposition_ = enqueue(c);
  ++targets_sent_;
  return true;
}

bool Px4Driver::target_confirmed() const {
  return reposition_ >= 0 && command_state(reposition_) == CommandState::accepted;
}

std::vector<std::string> Px4Driver::safety_params() const {
  return {kLossTimeout, kLossAction};
}

std::string Px4Driver::unread_consequence() const {
  return "PX4's lost-link failsafe is unknown";
}

std::vector<std::string> Px4Driver::safety_warnings() const {
  std::vector<std::string> out;
  const auto action = state_.params.find(kLossAction);
  if (action != state_.params.end() && action->second == 0) {
    const auto timeout = state_.params.find(kLossTimeout);
    out.push_back(std::string(kLossAction) +
                  " is 0 (disabled): PX4 takes no action when the link is lost" +
                  (timeout == state_.params.end()
                       ? std::string()
                       : std::string(" (lost after ") + kLossTimeout + " = " +
                             std::to_string(std::lround(timeout->second)) + " s of silence)"));
  }
  return out;
}

}  // namespace swath::mavlink
