#pragma once
// Flies one ArduCopter over MAVLink from a ground station (docs/swath-fleet.md), on the
// shared Driver (link, telemetry, commands resent until acknowledged, parameter reads): modes by
// DO_SET_MODE with ArduCopter's mode numbers, take-off in GUIDED (NAV_TAKEOFF, param7 above home),
// position targets as SET_POSITION_TARGET_GLOBAL_INT repeated until the vehicle reports them; the
// safety check at connect reads FS_GCS_ENABLE and warns when it is 0 (no return on a lost link) or
// cannot be read. An uploaded fence is enabled as ArduCopter expects it: FENCE_TYPE read and set
// again with its polygon bit (4) added, FENCE_ENABLE set to 1 (PARAM_SET, each confirmed by the
// PARAM_VALUE it answers with).

#include "swath/mavlink/driver.hpp"

namespace swath::mavlink {

class CopterDriver final : public Driver {
 public:
  CopterDriver(Link& link, DriverSettings settings = {});

  int set_mode(CopterMode mode);
  int takeoff(double altitude_m) override;

  int enter_guided() override { return set_mode(CopterMode::guided); }
  bool in_guided() const override;
  std::string guided_name() const override { return "GUIDED"; }
  bool returning() const override;

  /// Flies to a point in GUIDED mode. False, and nothing sent, outside the fence.
  bool go_to(double lat_deg, double lon_deg, double altitude_m) override;

 private:
  std::vector<std::string> safety_params() const override;
  std::string unread_consequence() const override;
  std::vector<std::string> safety_warnings() const override;
  void send_target(double now_s) override;
  std::optional<std::string> enable_fence_step() override;

  int fence_type_read_ = -1, fence_type_set_ = -1, fence_enable_set_ = -1;
  int fence_options_read_ = -1, fence_options_set_ = -1;

  double target_sent_s_ = -std::numeric_limits<double>::infinity();
};

}  // namespace swath::mavlink
