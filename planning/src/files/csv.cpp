// waypoints.csv and the planned photos (photos.csv, photos.geojson).
#include <array>
#include <cmath>
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

namespace {

// A number as nlohmann's serializer writes it (its Grisu2 shortest text, "null" for a non-finite
// one), without building a JSON tree for it.
void append_json_number(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  std::array<char, 64> text{};
  char* end = nlohmann::detail::to_chars(text.data(), text.data() + text.size(), x);
  out.append(text.data(), end);
}

}  // namespace

// Written directly, not through a JSON tree: the same text json_text(tree, 1) gives (every photo
// a Feature; a flight's name escaped by nlohmann once), in a sixth of the time: the photos of a
// large field were most of the writers' time.
std::string photos_geojson(const SurveyPlan& plan) {
  using nlohmann::ordered_json;
  std::string altitude;
  append_json_number(altitude, base::round_to(plan.imaging.altitude_m, 3));
  std::string out = "{\n \"type\": \"FeatureCollection\",\n \"features\": [";
  bool first = true;
  for (const Flight& f : flights_of(plan)) {
    const std::string head =
        "\n  {\n   \"type\": \"Feature\",\n   \"properties\": {\n    "
        "\"role\": \"photo\",\n    \"drone\": " +
        std::to_string(f.drone->number) +
        ",\n    \"flight\": " + base::json_text(ordered_json(f.file_stem), 1) + ",\n    \"line\": ";
    for (std::size_t k = 0; k < f.photos->size(); ++k) {
      const PhotoPoint& p = (*f.photos)[k];
      const geometry::GeoPoint g = files::geo(plan, p.position);
      out += first ? "" : ",";
      first = false;
      out += head;
      out += std::to_string(p.line);
      out += ",\n    \"photo\": ";
      out += std::to_string(k);
      out += ",\n    \"altitude_m\": ";
      out += altitude;
      out += "\n   },\n   \"geometry\": {\n    \"type\": \"Point\",\n    \"coordinates\": [\n     ";
      append_json_number(out, g.lon_deg);
      out += ",\n     ";
      append_json_number(out, g.lat_deg);
      out += "\n    ]\n   }\n  }";
    }
  }
  out += first ? "]\n}\n" : "\n ]\n}\n";
  return out;
}

}  // namespace swath::planning
