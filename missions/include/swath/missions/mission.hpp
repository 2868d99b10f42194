#pragma once
// Mission files as an autopilot or a flight app reads them (issue 45): one value type for QGC
// .plan, WPL 110 .waypoints, Litchi CSV, and the readers, independent of swath's planner (they
// read the bytes written, not the plan that wrote them).

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::missions {

/// What an item's altitude is measured from.
enum class AltitudeFrame {
  relative,  ///< above home (MAV_FRAME_GLOBAL_RELATIVE_ALT 3, Litchi altitudemode 0)
  amsl,      ///< above mean sea level (MAV_FRAME_GLOBAL 0)
  terrain,   ///< above the ground under the point (MAV_FRAME_GLOBAL_TERRAIN_ALT 10)
  none,      ///< a command without a position
};

/// One mission item as MAVLink's MISSION_ITEM_INT carries it.
struct Item {
  int command = 0;  ///< MAV_CMD
  int frame = 0;    ///< MAV_FRAME as written
  AltitudeFrame altitude_frame = AltitudeFrame::none;
  std::array<double, 4> params{};  ///< param1-4 (NaN where the file leaves them empty)
  geometry::GeoPoint position;     ///< lat_deg, lon_deg (0, 0: none or "here")
  double altitude_m = 0.0;         ///< param7, in altitude_frame
  std::string place;               ///< "drone-1.plan: item 7", for messages
};

/// The autopilot a file is written for: its fences' storage and breach rules differ.
enum class Autopilot {
  unknown,    ///< Litchi, DJI, a QGC plan of another firmwareType
  ardupilot,  ///< a QGC plan's firmwareType 3 (MAV_AUTOPILOT_ARDUPILOTMEGA), a WPL 110 file
  px4,        ///< a QGC plan's firmwareType 12
};

/// A fence circle: its centre and radius.
struct FenceCircle {
  geometry::GeoPoint centre;
  double radius_m = 0.0;
};

/// One drone's mission file.
struct Mission {
  std::string source;  ///< the file name, for messages
  std::string format;  ///< "QGC plan", "WPL 110", "Litchi CSV", "DJI WPML"
  Autopilot autopilot = Autopilot::unknown;
  geometry::GeoPoint home;
  double home_amsl_m = 0.0;  ///< home's height above mean sea level as the file gives it
  bool home_amsl_known = false;
  std::vector<Item> items;
  std::vector<std::vector<geometry::GeoPoint>> inclusion_fences, exclusion_fences;
  std::vector<FenceCircle> inclusion_circles, exclusion_circles;
  std::vector<geometry::GeoPoint> rally_points;
  double cruise_speed_m_s = 0.0;  ///< the file's speed before any DO_CHANGE_SPEED; 0: none
  /// A fixed wing (a QGC plan's vehicleType 1): it flies through its waypoints on turns of its
  /// radius and never stops at them, so no stopping margin is drawn past them.
  bool fixed_wing = false;
  /// The file's own return-to-launch height above home (a DJI KMZ's globalRTHHeight): a return
  /// climbs to it when lower, as with FlightModel::rtl_altitude_m, which it replaces.
  std::optional<double> return_altitude_m;
};

/// Is this MAV_CMD a position the vehicle flies to (waypoint, take-off, land, loiter)?
bool is_navigation(int command);

/// An item's altitude above home, metres: relative as written, AMSL less the home's AMSL altitude
/// (`home_amsl_m`; empty: unknown, and an AMSL item throws base::InputError naming it), terrain
/// plus the ground's height above home under the item (`ground_above_home_m`; 0: flat ground).
double above_home_m(const Item& item, std::optional<double> home_amsl_m,
                    double ground_above_home_m = 0.0);

/// The file's home altitude above mean sea level, when it gives one.
std::optional<double> home_amsl_m(const Mission& mission);

/// Reads a mission by its content: "QGC WPL 110" starts a WPL file, a JSON object with fileType
/// "Plan" a QGC plan, a header with latitude,longitude,altitude(m) a Litchi CSV, a zip archive a
/// DJI WPML KMZ (its wpmz/waylines.wpml). A complex QGC item
/// (a survey) is flattened into its simple items. Throws base::InputError naming the file, the
/// place (item, line) and the problem.
Mission parse_mission(const std::string& text, const std::string& source);
Mission read_mission(const std::string& path);

/// Is `text` a WPL 110 fence or rally file (Mission Planner's): rows of fence return point
/// (5000), fence vertices and circles (5001-5004) and rally points (5100) only, whatever its name?
bool is_wpl_fence_file(const std::string& text);

/// A WPL 110 fence (5001-5004) or rally (5100) file's polygons, circles and points, added to
/// `mission` (a fence or rally file beside the drones' files); its fence return point (5000) is
/// not flown by a copter and is passed over.
void add_wpl_fences(Mission& mission, const std::string& text, const std::string& source);

}  // namespace swath::missions
