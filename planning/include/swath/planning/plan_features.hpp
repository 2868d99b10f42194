#pragma once
// What mission.geojson holds (docs/formats.md), as plain data in WGS84: the one in-memory form of a
// plan's geometry. The GeoJSON writer serialises it, the pictures are drawn from it, and
// `swath render DIR` reads a written file back into it (checked: a hand-edited file is input like
// any other, docs/reliability.md). Positions are rounded to 1e-9 degrees (~0.1 mm), as written, so
// a picture drawn before and after writing is the same picture.

#include <optional>
#include <string>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::planning {

struct SurveyPlan;

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

/// The features of a plan.
PlanFeatures plan_features(const SurveyPlan& plan);

/// mission.geojson: a FeatureCollection with `role` area, no_fly, cell, region, path, sweep and
/// home (the plan's, and one per drone whose own home differs, with its "drone").
std::string mission_geojson(const PlanFeatures& features);

/// Reads mission.geojson back. Throws base::InputError naming `source`, the feature and the
/// problem (not JSON, no area, a position that is not [lon, lat], a role of the wrong geometry,
/// a drone number out of range). Features of unknown roles are skipped.
PlanFeatures parse_mission_geojson(const std::string& text, const std::string& source);

/// The figures the pictures print, from summary.json (docs/formats.md).
struct PlanFigures {
  double covered_fraction = 0;
  int lines = 0;
  struct Drone {
    int drone = 0;
    std::string name;
    double path_length_m = 0, flight_time_s = 0;
  };
  std::vector<Drone> drones;
};

/// The figures of a plan, rounded as summary.json writes them.
PlanFigures plan_figures(const SurveyPlan& plan);

/// Reads them from summary.json; throws base::InputError naming `source` and the key.
PlanFigures parse_plan_figures(const std::string& summary_text, const std::string& source);

}  // namespace swath::planning
