// waypoints.csv and the planned photos (photos.csv, photos.geojson).
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"

namespace swath::planning {

using base::fixed_text;

std::string waypoints_csv(const SurveyPlan& plan) {
  std::string out = "drone,flight,seq,lat,lon,alt_m,x_m,y_m,action\n";
  for (const Flight& f : flights_of(plan)) {
    const std::string head = std::to_string(f.drone->number) + "," + f.file_stem + ",";
    auto row = [&](std::size_t seq, geometry::Point2 p, double alt, bool has_position,
                   const char* action) {
      out += head + std::to_string(seq) + ",";
      if (has_position) {
        const geometry::GeoPoint g = files::geo(plan, p);
        out += fixed_text(g.lat_deg, 9) + "," + fixed_text(g.lon_deg, 9) + "," +
               fixed_text(alt, 3) + "," + fixed_text(p.x, 3) + "," + fixed_text(p.y, 3);
      } else {
        out += ",,,,";
      }
      out += std::string(",") + action + "\n";
    };
    row(0, f.mission->home, 0.0, true, "home");
    std::size_t seq = 1;
    for (const MissionItem& item : f.mission->items)
      row(seq++, item.position, item.altitude_m, positional(item.kind),
          files::action_name(item.kind));
  }
  return out;
}

std::string photos_csv(const SurveyPlan& plan) {
  std::string out = "drone,flight,line,photo,lat,lon,alt_m,x_m,y_m\n";
  for (const Flight& f : flights_of(plan))
    for (std::size_t k = 0; k < f.photos->size(); ++k) {
      const PhotoPoint& p = (*f.photos)[k];
      const geometry::GeoPoint g = files::geo(plan, p.position);
      out += std::to_string(f.drone->number) + "," + f.file_stem + "," + std::to_string(p.line) +
             "," + std::to_string(k) + "," + fixed_text(g.lat_deg, 9) + "," +
             fixed_text(g.lon_deg, 9) + "," + fixed_text(plan.imaging.altitude_m, 3) + "," +
             fixed_text(p.position.x, 3) + "," + fixed_text(p.position.y, 3) + "\n";
    }
  return out;
}

std::string photos_geojson(const SurveyPlan& plan) {
  using nlohmann::ordered_json;
  ordered_json features = ordered_json::array();
  for (const Flight& f : flights_of(plan))
    for (std::size_t k = 0; k < f.photos->size(); ++k) {
      const PhotoPoint& p = (*f.photos)[k];
      const geometry::GeoPoint g = files::geo(plan, p.position);
      features.push_back(
          {{"type", "Feature"},
           {"properties",
            {{"role", "photo"},
             {"drone", f.drone->number},
             {"flight", f.file_stem},
             {"line", p.line},
             {"photo", k},
             {"altitude_m", base::round_to(plan.imaging.altitude_m, 3)}}},
           {"geometry", {{"type", "Point"}, {"coordinates", {g.lon_deg, g.lat_deg}}}}});
    }
  return base::json_text(ordered_json{{"type", "FeatureCollection"}, {"features", features}}, 1) +
         "\n";
}

}  // namespace swath::planning
