#pragma once
// What mission.geojson holds (docs/formats.md), as plain data in WGS84: the one in-memory form of a
// plan's geometry, and the format's writer and reader side by side with the other mission formats'.
// swath plan writes it (planning::plan_features builds the value), the pictures are drawn from it,
// and `swath render DIR` and swath-control read a written file back into it (checked: a
// hand-edited file is input like any other, docs/reliability.md). Positions are rounded to 1e-9
// degrees (~0.1 mm), as written, so a picture drawn before and after writing is the same picture.

#include <string>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::missions {

using GeoRing = std::vector<geometry::GeoPoint>;  ///< open (first vertex not repeated)

struct PlanFeatures {
  /// The area: outer ring then holes; then --repair's further enclosed areas, one ring each.
  std::vector<GeoRing> area;
  std::vector<GeoRing> area_pieces;
  std::vector<GeoRing> no_fly;  ///< holes and --exclude zones, as given (role "no_fly")
  std::vector<GeoRing> cells;   ///< split: the cells swept one by one
  struct Region {
    int drone = 0;  ///< 1-based
    GeoRing ring;
  };
  std::vector<Region> regions;  ///< region division: each drone's share of the area
  struct Path {
    int drone = 0;
    std::string name;  ///< the drone's (fleet) name; absent in older files: empty
    double altitude_m = 0, speed_m_s = 0;
    std::vector<geometry::GeoPoint> points;  ///< home to home
  };
  std::vector<Path> paths;
  struct Sweep {
    int drone = 0;
    int line = 0;  ///< 0-based, in flying order
    double footprint_width_m = 0;
    geometry::GeoPoint start, end;
  };
  std::vector<Sweep> sweeps;
  geometry::GeoPoint home;  ///< the plan's (fleet's) home
  struct DroneHome {
    int drone = 0;
    geometry::GeoPoint at;
  };
  std::vector<DroneHome> drone_homes;  ///< drones whose own home differs from `home`
};

/// mission.geojson: a FeatureCollection with `role` area, no_fly, cell, region, path, sweep and
/// home (the plan's, and one per drone whose own home differs, with its "drone").
std::string mission_geojson(const PlanFeatures& features);

/// Reads mission.geojson back. Throws base::InputError naming `source`, the feature and the
/// problem (not JSON, no area, a position that is not [lon, lat], a role of the wrong geometry,
/// a drone number out of range). Features of unknown roles are skipped.
PlanFeatures parse_mission_geojson(const std::string& text, const std::string& source);

/// One drone's flight in a mission GeoJSON, as swath-energy budget and swath-control fly it.
struct GeoJsonFlight {
  std::string drone;        ///< the path's "name"; else "drone-N" (its "drone", or its place)
  geometry::GeoPoint home;  ///< its own home, the plan's, or the path's first position
  std::vector<geometry::GeoPoint> points;  ///< the path's positions, in flight order
  std::vector<double> altitudes_m;         ///< one per position: altitude_m, or its third number
  double speed_m_s = 0;                    ///< the path's speed_m_s; 0: none given
};

/// The flights of any FeatureCollection whose LineString features have role "path": swath's
/// mission.geojson, or one written by hand (no area needed; positions [lon, lat, alt] where the
/// path gives no altitude_m). Throws base::InputError naming `source`, the feature and the
/// problem; a collection with no path is refused.
std::vector<GeoJsonFlight> parse_geojson_flights(const std::string& text,
                                                 const std::string& source);

}  // namespace swath::missions
