// GeoJSON (RFC 7946): Polygon, MultiPolygon with one part, Feature, FeatureCollection with one
// polygonal feature. Positions are [longitude, latitude(, altitude)].
#include <nlohmann/json.hpp>

#include "raw_field.hpp"
#include "swath/base/json_document.hpp"

namespace swath::geometry::detail {
namespace {

using nlohmann::json;

std::string type_of(const json& j) {
  if (j.is_object() && j.contains("type") && j["type"].is_string())
    return j["type"].get<std::string>();
  return {};
}

RawRing parse_ring(const json& ring, const std::string& source, const std::string& name) {
  if (!ring.is_array()) fail(source, name + " is not an array of positions");
  RawRing out;
  out.name = name;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const json& position = ring[i];
    if (!position.is_array() || position.size() < 2 || !position[0].is_number() ||
        !position[1].is_number())
      fail(source, name + ", position " + std::to_string(i) +
                       ": a position must be an array [longitude, latitude] of numbers");
    out.points.push_back({position[0].get<double>(), position[1].get<double>()});
  }
  return out;
}

RawField parse_polygon_coordinates(const json& coordinates, const std::string& source,
                                   const std::string& where) {
  if (!coordinates.is_array() || coordinates.empty())
    fail(source, where + ": \"coordinates\" must be a non-empty array of rings");
  RawField field;
  for (std::size_t r = 0; r < coordinates.size(); ++r) {
    const std::string name = where + (r == 0 ? ", outer ring" : ", hole " + std::to_string(r - 1)) +
                             " (ring " + std::to_string(r) + ")";
    field.rings.push_back(parse_ring(coordinates[r], source, name));
  }
  return field;
}

bool is_polygonal(const std::string& type) {
  return type == "Polygon" || type == "MultiPolygon";
}

RawField parse_geometry(const json& geometry, const std::string& source, const std::string& where) {
  const std::string type = type_of(geometry);
  if (!geometry.is_object() || type.empty())
    fail(source, where + " has no geometry object with a \"type\"");
  if (!is_polygonal(type)) {
    const bool miscased = lower(type) == "polygon" || lower(type) == "multipolygon";
    fail(source, where + "'s geometry is a " + shown(type) +
                     "; an area must be a Polygon or a MultiPolygon with one part" +
                     (miscased ? " (GeoJSON's type names are case-sensitive)" : ""));
  }
  if (!geometry.contains("coordinates")) fail(source, where + " has no \"coordinates\"");
  const json& coordinates = geometry["coordinates"];
  if (type == "Polygon") return parse_polygon_coordinates(coordinates, source, where);
  if (!coordinates.is_array() || coordinates.size() != 1)
    fail(source, where + (where == "the MultiPolygon" ? " has " : " is a MultiPolygon with ") +
                     std::to_string(coordinates.is_array() ? coordinates.size() : 0) +
                     " parts; swath plans one connected area: swath batch plans each part, "
                     "--feature INDEX one of them");
  return parse_polygon_coordinates(coordinates[0], source, where);
}

}  // namespace

GeojsonCollection geojson_collection(const std::string& text, const std::string& source) {
  const json root = base::parse_json_document(text, source);
  const json* features = type_of(root) == "FeatureCollection" && root.contains("features")
                             ? &root["features"]
                             : nullptr;
  if (!features || !features->is_array()) return {};
  GeojsonCollection out{features->size(), false};
  for (const json& f : *features)
    out.polygonal = out.polygonal || (f.is_object() && f.contains("geometry") &&
                                      is_polygonal(type_of(f["geometry"])));
  return out;
}

RawField parse_geojson(const std::string& text, const std::string& source) {
  const json root = base::parse_json_document(text, source);
  const std::string type = type_of(root);
  if (type.empty()) fail(source, "not a GeoJSON object (no \"type\" member at the top level)");

  if (type == "FeatureCollection") {
    if (!root.contains("features") || !root["features"].is_array())
      fail(source, "the FeatureCollection has no \"features\" array");
    const json& features = root["features"];
    std::vector<std::size_t> polygonal;
    for (std::size_t i = 0; i < features.size(); ++i) {
      const json& f = features[i];
      if (f.is_object() && f.contains("geometry") && is_polygonal(type_of(f["geometry"])))
        polygonal.push_back(i);
    }
    if (polygonal.empty())
      fail(source, "the FeatureCollection has no Polygon or MultiPolygon feature");
    if (polygonal.size() > 1)
      fail(source, "features " + std::to_string(polygonal[0]) + " and " +
                       std::to_string(polygonal[1]) +
                       " are both areas; choose one with --feature NAME or INDEX");
    const std::string where = "feature " + std::to_string(polygonal[0]);
    return parse_geometry(features[polygonal[0]]["geometry"], source, where);
  }
  if (type == "Feature") {
    if (!root.contains("geometry") || !root["geometry"].is_object())
      fail(source, "the Feature has no geometry");
    return parse_geometry(root["geometry"], source, "the Feature");
  }
  // A polygonal top-level geometry is named by its type ("the Polygon, hole 0"); any other as
  // the GeoJSON ("the GeoJSON's geometry is a Point", not "the Point is a Point").
  return parse_geometry(root, source, is_polygonal(type) ? "the " + type : "the GeoJSON");
}

}  // namespace swath::geometry::detail
