#include "verify_inputs.hpp"

#include <cstdlib>
#include <cstring>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/geometry/classification.hpp"
#include "swath/geometry/field.hpp"

namespace swath::apps {

namespace {

// A zone whose ring crosses or touches itself (a bow-tie, a spike back along an edge) has no
// inside the planner and the check agree on: refused with the place, as an area's crossing is.
void refuse_crossing_zone(const geometry::Field& zone, const std::string& name) {
  const auto crossing = geometry::find_crossing(geometry::Polygon{zone.polygon.outer, {}});
  if (!crossing) return;
  const geometry::GeoPoint p = zone.frame->to_geo(crossing->point);
  std::ostringstream s;
  s.precision(8);
  s << name << ": the no-fly zone crosses itself at " << p.lat_deg << ", " << p.lon_deg
    << " (lat, lon); a zone must be a simple polygon: fix the vertex order";
  throw base::InputError(s.str());
}

}  // namespace

// Every area of each file is a zone (each feature of a FeatureCollection, each part of a
// MultiPolygon): `swath plan --exclude` and `swath verify --exclude` read them alike. A feature
// that is no polygon (a power line, a mast's point) is refused, not skipped.
std::vector<preflight::Zone> zones_from_files(const std::vector<std::string>& paths) {
  std::vector<preflight::Zone> zones;
  for (const std::string& path : paths) {
    geometry::FieldReadOptions listing;
    listing.only_areas_as = "a no-fly zone";
    const auto areas = geometry::list_areas(path, listing);
    for (const geometry::AreaEntry& entry : areas) {
      geometry::FieldReadOptions options;
      if (areas.size() > 1) options.feature = std::to_string(entry.index);
      const geometry::Field field = geometry::read_field(path, options);
      const std::string name =
          areas.size() > 1 ? path + " feature " + std::to_string(entry.index) : path;
      refuse_crossing_zone(field, name);
      zones.push_back({name, field.geo_rings.at(0)});
    }
  }
  return zones;
}

void add_area(const std::string& path, preflight::CheckOptions& options) {
  const geometry::Field field = geometry::read_field(path);
  if (field.geo_rings.empty())
    throw base::InputError(path + ": --area needs an area on the map, not local metres");
  options.area.push_back(field.geo_rings.front());
  for (std::size_t k = 1; k < field.geo_rings.size(); ++k)
    options.zones.push_back({"hole " + std::to_string(k) + " of " + path, field.geo_rings[k]});
}

void verify_before_writing(const std::vector<std::pair<std::string, std::string>>& files,
                           const preflight::CheckOptions& options) {
  const char* env = std::getenv("SWATH_PLAN_VERIFY");
  if (env != nullptr && std::strcmp(env, "0") == 0) return;
  const preflight::Report report = preflight::verify_files(files, options);
  if (report.ok()) return;
  const preflight::Violation& v = report.violations.front();
  std::string more;
  if (report.violations.size() > 1)
    more = " (and " + std::to_string(report.violations.size() - 1) + " more violation(s))";
  std::string hint;
  if (v.check == "ceiling") hint = "; give --ceiling M to fly higher where a permit allows it";
  // Litchi flies a split flight's parts from home and back, later than the .plan flies the
  // same waypoints: the other drones are elsewhere by then.
  if (v.check == "separation" && v.text.find("-litchi-") != std::string::npos)
    hint =
        "; Litchi flies each part of a split flight from home and back: fewer waypoints (a "
        "larger --waypoint-spacing) keep it in one part, or leave out --litchi";
  throw base::InputError("the plan's files fail the preflight check (" + v.check + "): " + v.text +
                         more + "; nothing written" + hint);
}

}  // namespace swath::apps
