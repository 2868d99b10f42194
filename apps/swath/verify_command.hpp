#pragma once

#include <optional>
#include <string>
#include <vector>

#include "command.hpp"
#include "swath/geometry/ground.hpp"

namespace swath::apps {

/// `swath verify FILE|DIR... [--exclude Z]... [--area FIELD] [--clearance M] [--terrain DEM]
/// [--drone PROFILE] [--ceiling M] [--separation M] [--json]`: the independent preflight check of
/// written mission files (issue 45, docs/swath-verify.md).
class VerifyCommand : public Command {
 public:
  const char* name() const override { return "verify"; }
  const char* description() const override {
    return "Check written mission files (.plan, .waypoints, Litchi CSV, DJI KMZ) as the autopilot "
           "flies "
           "them: no-fly zones, fences, ceiling, ground, battery, drone separation, photos "
           "(exit 0 all hold, 4 a check fails)";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::vector<std::string> inputs_;
  std::vector<std::string> exclude_;
  std::string area_;
  double clearance_m_ = 5.0;
  std::string terrain_;
  std::string dem_units_;  ///< --dem-units m|ft|us-ft; empty: the DEM's own, else metres
  std::string drone_;
  double ceiling_m_ = 120.0;
  double min_height_m_ = geometry::kLeastHeightAboveGround_m;
  double separation_m_ = 10.0;
  bool json_ = false;
  bool fence_union_ = false;
};

}  // namespace swath::apps
