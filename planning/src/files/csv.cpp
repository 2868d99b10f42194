// waypoints.csv and the planned photos (photos.csv, photos.geojson).
#include <array>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"

namespace swath::planning {

using base::append_fixed_text;

namespace {

// "lat,lon,alt_m,x_m,y_m" as fixed_text writes them (9, 9, 3, 3, 3 decimals).
void append_point_columns(std::string& out, const geometry::GeoPoint& g, double altitude_m,
                          geometry::Point2 p) {
  append_fixed_text(out, g.lat_deg, 9);
  out += ',';
  append_fixed_text(out, g.lon_deg, 9);
  out += ',';
  append_fixed_text(out, altitude_m, 3);
  out += ',';
  append_fixed_text(out, p.x, 3);
  out += ',';
  append_fixed_text(out, p.y, 3);
}

}  // namespace

std::string waypoints_csv(const SurveyPlan& plan) {
  std::string out = "drone,flight,seq,lat,lon,alt_m,x_m,y_m,action\n";
  for (const Flight& f : flights_of(plan)) {
    const std::string head = std::to_string(f.drone->number) + "," + f.file_stem + ",";
    auto row = [&](std::size_t seq, geometry::Point2 p, double alt, bool has_position,
                   const char* action) {
      out += head;
      base::append_integer_text(out, seq);
      out += ',';
      if (has_position) {
        const geometry::GeoPoint g = files::geo(plan, p);
        append_point_columns(out, g, alt, p);
      } else {
        out += ",,,,";
      }
      out += ',';
      out += action;
      out += '\n';
    };
    row(0, f.mission->home, 0.0, true, "home");
    std::size_t seq = 1;
    for (const MissionItem& item : f.mission->items)
      row(seq++, item.position, item.altitude_m, positional(item.kind),
          files::action_name(item.kind));
  }
  return out;
}

namespace files {

// One pass over the photos for both files: a photo's WGS84 position (LocalFrame::to_geo, most of
// a photo's cost) is computed once. photos.geojson is written directly, not through a JSON tree:
// the same text json_text(tree, 1) gives (every photo a Feature; a flight's name escaped by
// nlohmann once), in a sixth of the time.
PhotoTexts photo_texts(const SurveyPlan& plan) {
  using nlohmann::ordered_json;
  PhotoTexts texts;
  std::string& csv = texts.csv;
  std::string& json = texts.geojson;
  csv = "drone,flight,line,photo,lat,lon,alt_m,x_m,y_m\n";
  std::string altitude;
  base::append_json_number(altitude, base::round_to(plan.imaging.altitude_m, 3));
  json = "{\n \"type\": \"FeatureCollection\",\n \"features\": [";
  bool first = true;
  for (const Flight& f : flights_of(plan)) {
    const std::string csv_head = std::to_string(f.drone->number) + "," + f.file_stem + ",";
    const std::string json_head =
        "\n  {\n   \"type\": \"Feature\",\n   \"properties\": {\n    "
        "\"role\": \"photo\",\n    \"drone\": " +
        std::to_string(f.drone->number) +
        ",\n    \"flight\": " + base::json_text(ordered_json(f.file_stem), 1) + ",\n    \"line\": ";
    for (std::size_t k = 0; k < f.photos->size(); ++k) {
      const PhotoPoint& p = (*f.photos)[k];
      const geometry::GeoPoint g = files::geo_unshared(plan, p.position);
      csv += csv_head;
      base::append_integer_text(csv, p.line);
      csv += ',';
      base::append_integer_text(csv, k);
      csv += ',';
      append_point_columns(csv, g, plan.imaging.altitude_m, p.position);
      csv += '\n';

      json += first ? "" : ",";
      first = false;
      json += json_head;
      base::append_integer_text(json, p.line);
      json += ",\n    \"photo\": ";
      base::append_integer_text(json, k);
      json += ",\n    \"altitude_m\": ";
      json += altitude;
      json +=
          "\n   },\n   \"geometry\": {\n    \"type\": \"Point\",\n    \"coordinates\": [\n     ";
      base::append_json_number(json, g.lon_deg);
      json += ",\n     ";
      base::append_json_number(json, g.lat_deg);
      json += "\n    ]\n   }\n  }";
    }
  }
  json += first ? "]\n}\n" : "\n ]\n}\n";
  return texts;
}

}  // namespace files

std::string photos_csv(const SurveyPlan& plan) {
  return files::photo_texts(plan).csv;
}

std::string photos_geojson(const SurveyPlan& plan) {
  return files::photo_texts(plan).geojson;
}

}  // namespace swath::planning
