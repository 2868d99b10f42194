#include "verify_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/range_check.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/geometry/field.hpp"
#include "swath/planning/limits.hpp"
#include "swath/preflight/verify.hpp"
#include "verify_inputs.hpp"

namespace swath::apps {
namespace {

namespace fs = std::filesystem;
using base::InputError;

bool mission_name(const std::string& name) {
  auto ends = [&](const char* tail) {
    const std::string t(tail);
    return name.size() >= t.size() && name.compare(name.size() - t.size(), t.size(), t) == 0;
  };
  return ends(".plan") || ends(".waypoints") || ends(".csv") || ends(".kmz") ||
         ends("summary.json");
}

// Every FILE as given, every DIR's mission files (and summary.json) in name order.
std::vector<std::pair<std::string, std::string>> read_inputs(const std::vector<std::string>& in) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const std::string& path : in) {
    if (!fs::is_directory(path)) {
      files.push_back({path, base::read_text_file(path, "mission file")});
      continue;
    }
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path))
      if (entry.is_regular_file() && mission_name(entry.path().filename().string()))
        names.push_back(entry.path().string());
    std::sort(names.begin(), names.end());
    if (names.empty()) throw InputError(path + ": the directory holds no mission file");
    for (const std::string& n : names)
      files.push_back({n, base::read_text_file(n, "mission file")});
  }
  return files;
}

}  // namespace

void VerifyCommand::setup(CLI::App& app) {
  app.add_option("INPUT", inputs_,
                 "Mission files (.plan, .waypoints, -litchi.csv or its parts -litchi-N.csv, .kmz) "
                 "or plan directories (every mission file in it; twins must agree with their "
                 ".plan)")
      ->required();
  app.add_option("--exclude", exclude_,
                 "A no-fly zone file (every polygon in it is a zone); repeat for more");
  app.add_option("--area", area_,
                 "The surveyed area: its holes are zones, and a leg with the camera on that never "
                 "meets it is a transit");
  app.add_option("--clearance", clearance_m_, "Metres kept from every zone (default 5)");
  app.add_option("--terrain", terrain_,
                 "DEM of the ground (GeoTIFF, any GDAL raster): the ceiling and the least height "
                 "above the ground along every leg");
  app.add_option("--dem-units", dem_units_,
                 "The unit of the DEM's heights: m (default), ft (0.3048 m) or us-ft (US survey "
                 "foot, 1200/3937 m); a DEM that declares its unit is read in it, and a "
                 "--dem-units that contradicts it is refused")
      ->check(CLI::IsMember({"m", "ft", "us-ft"}));
  app.add_option("--drone", drone_,
                 "Drone profile YAML (as swath-energy budget): the battery check");
  app.add_option("--ceiling", ceiling_m_,
                 "Highest flight, metres above the ground (above home without --terrain); "
                 "default 120, the common legal limit");
  app.add_option("--min-height", min_height_m_,
                 "With --terrain: least height above the ground on cruise legs (default " +
                     base::fixed_text(geometry::kLeastHeightAboveGround_m, 0) + " m)");
  app.add_option("--separation", separation_m_,
                 "Least 3-D distance between two drones at the same time (default 10 m)");
  app.add_flag("--fence-union", fence_union_,
               "ArduPilot files: inside one inclusion fence is inside (FENCE_OPTIONS bit 2 set); "
               "without it the vehicle must stay inside every one, as ArduPilot by default and "
               "PX4 require");
  app.add_flag("--json", json_, "Print the report as one JSON object");
}

int VerifyCommand::run() {
  preflight::CheckOptions options;
  using planning::limits::kCeiling_m;
  using planning::limits::kClearance_m;
  base::check_range(clearance_m_, kClearance_m, "--clearance");
  base::check_range(ceiling_m_, kCeiling_m, "--ceiling");  // the range swath plan's --ceiling has
  base::check_range(min_height_m_, kClearance_m, "--min-height");
  base::check_range(separation_m_, kClearance_m, "--separation");
  options.clearance_m = clearance_m_;
  options.ceiling_m = ceiling_m_;
  options.min_height_m = min_height_m_;
  options.separation_m = separation_m_;
  options.fence_union = fence_union_;
  options.zones = zones_from_files(exclude_);
  if (!area_.empty()) add_area(area_, options);
  if (!dem_units_.empty() && terrain_.empty())
    throw InputError("--dem-units needs --terrain DEM (the ground's heights)");
  if (!terrain_.empty())
    options.ground = geometry::dem_ground(terrain_, geometry::DemHeights::geoid,
                                          geometry::dem_unit_m(dem_units_));
  if (!drone_.empty()) options.drone = energy::read_drone_profile(drone_);
  const preflight::Report report = preflight::verify_files(read_inputs(inputs_), options);
  std::cout << (json_ ? preflight::report_json(report) : preflight::report_text(report));
  return report.ok() ? base::kExitSuccess : base::kExitNotCompleted;
}

}  // namespace swath::apps
