#pragma once
// The DJI WPML KMZ reader behind parse_mission() (its bytes start a zip archive).

#include <string>

#include "swath/missions/mission.hpp"

namespace swath::missions {

/// wpmz/waylines.wpml of a KMZ: each Placemark a waypoint at wpml:executeHeight in the Folder's
/// executeHeightMode (relativeToStartPoint: above home; WGS84: read as above mean sea level;
/// realTimeFollowSurface: above the ground), its wpml:waypointSpeed, multipleDistance and
/// multipleTiming action groups as triggering from their first waypoint to their last, and
/// finishAction (goHome: return to launch; autoLand: land). Home is the first waypoint.
Mission parse_dji_kmz(const std::string& bytes, const std::string& source);

}  // namespace swath::missions
