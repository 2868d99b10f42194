#pragma once
// The DJI WPML KMZ reader behind parse_mission() (its bytes start a zip archive).

#include <string>

#include "swath/missions/mission.hpp"

namespace swath::missions {

/// wpmz/waylines.wpml of a KMZ: every Folder a wayline, flown one after another in the file's
/// order; each Placemark a waypoint at wpml:executeHeight in its Folder's
/// executeHeightMode (relativeToStartPoint: above home; WGS84: read as above mean sea level;
/// realTimeFollowSurface: above the ground), its wpml:waypointSpeed, multipleDistance and
/// multipleTiming action groups as triggering from their first waypoint to their last, and
/// finishAction (goHome: return to launch at globalRTHHeight, Mission::return_altitude_m;
/// autoLand: land). Home is the first waypoint; takeOffSecurityHeight is a NAV_TAKEOFF in place
/// before it.
Mission parse_dji_kmz(const std::string& bytes, const std::string& source);

}  // namespace swath::missions
