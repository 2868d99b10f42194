// Violations planted for tests/architecture (never compiled): a library below planning that
// includes its headers. A comment naming #include "swath/planning/plan_features.hpp" is not one.
#include "swath/missions/mission_geojson.hpp"
#include "swath/planning/plan_features.hpp"

namespace swath::control {

int paths(const std::string& text) {
  return static_cast<int>(missions::parse_mission_geojson(text, "m.geojson").paths.size());
}

}  // namespace swath::control
