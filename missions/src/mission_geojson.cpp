#include "swath/missions/mission_geojson.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/utf8.hpp"

namespace swath::missions {
namespace {

using geometry::GeoPoint;
using nlohmann::json;
using nlohmann::ordered_json;

// ---- Writing.

ordered_json feature(ordered_json properties, const char* type, ordered_json coordinates) {
  return {{"type", "Feature"},
          {"properties", std::move(properties)},
          {"geometry", {{"type", type}, {"coordinates", std::move(coordinates)}}}};
}

// ---- The coordinates' text, as json_text(tree, 1) writes them as the value of a feature's
// "geometry"."coordinates" (its members at 5 spaces, its closing bracket at 4).

constexpr int kCoordinatesIndent = 4;
constexpr const char* kCoordinatesMark = "@swath-coordinates@";

// [lon, lat] as an array whose opening bracket stands on a line indented by `indent`.
void append_position(std::string& out, const GeoPoint& g, int indent) {
  out += "[\n";
  out.append(indent + 1, ' ');
  base::append_json_number(out, g.lon_deg);
  out += ",\n";
  out.append(indent + 1, ' ');
  base::append_json_number(out, g.lat_deg);
  out += '\n';
  out.append(indent, ' ');
  out += ']';
}

// The positions (and the first again when `closed`: RFC 7946 rings are closed).
void append_positions(std::string& out, const std::vector<GeoPoint>& points, bool closed,
                      int indent) {
  if (points.empty()) {
    out += "[]";
    return;
  }
  out += "[\n";
  const std::size_t n = points.size() + (closed ? 1 : 0);
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) out += ",\n";
    out.append(indent + 1, ' ');
    append_position(out, points[k < points.size() ? k : 0], indent + 1);
  }
  out += '\n';
  out.append(indent, ' ');
  out += ']';
}

void append_rings(std::string& out, const std::vector<GeoRing>& rings, int indent) {
  if (rings.empty()) {
    out += "[]";
    return;
  }
  out += "[\n";
  for (std::size_t k = 0; k < rings.size(); ++k) {
    if (k > 0) out += ",\n";
    out.append(indent + 1, ' ');
    append_positions(out, rings[k], true, indent + 1);
  }
  out += '\n';
  out.append(indent, ' ');
  out += ']';
}

// ---- Reading (checked).

GeoPoint position_of(const json& c, const std::string& where) {
  base::json_array(c, where + ": a position", 2);
  const GeoPoint g{base::json_number(c[1], where + ": latitude"),
                   base::json_number(c[0], where + ": longitude"), 0.0};
  if (std::abs(g.lat_deg) > 90 || std::abs(g.lon_deg) > 180)
    throw base::InputError(where +
                           ": latitude must be within ±90 and longitude within ±180 degrees");
  return g;
}

std::vector<GeoPoint> positions_of(const json& coordinates, const std::string& where,
                                   std::size_t min_size) {
  base::json_array(coordinates, where + ": coordinates", min_size);
  std::vector<GeoPoint> out;
  for (std::size_t i = 0; i < coordinates.size(); ++i)
    out.push_back(position_of(coordinates[i], where + ", position " + std::to_string(i)));
  return out;
}

GeoRing ring_of(const json& coordinates, const std::string& where) {
  GeoRing ring = positions_of(coordinates, where, 4);
  if (ring.front() == ring.back()) ring.pop_back();
  return ring;
}

std::vector<GeoRing> polygon_of(const json& geometry, const std::string& where) {
  if (base::json_string(base::json_member(geometry, "type", where), where + ": type") != "Polygon")
    throw base::InputError(where + ": expected a Polygon");
  const json& rings = base::json_array(base::json_member(geometry, "coordinates", where),
                                       where + ": coordinates", 1);
  std::vector<GeoRing> out;
  for (std::size_t r = 0; r < rings.size(); ++r)
    out.push_back(ring_of(rings[r], where + ", ring " + std::to_string(r)));
  return out;
}

const json& line_of(const json& geometry, const std::string& where) {
  if (base::json_string(base::json_member(geometry, "type", where), where + ": type") !=
      "LineString")
    throw base::InputError(where + ": expected a LineString");
  return base::json_member(geometry, "coordinates", where);
}

int drone_of(const json& properties, const std::string& where) {
  return static_cast<int>(base::json_integer(base::json_member(properties, "drone", where), 1, 1000,
                                             where + ": drone"));
}

// ---- Reading any mission GeoJSON's flights (lenient: only the paths and homes matter).

// Checked lookups: a hand-edited file is input like any other (no const operator[], no value()
// that throws a library type_error for a member of another type).
std::string text_or(const json& object, const char* key, const std::string& fallback) {
  const json* v = base::json_find(object, key);
  return v != nullptr && v->is_string() ? v->get<std::string>() : fallback;
}

const json& member_or_null(const json& object, const char* key) {
  static const json null;
  const json* v = base::json_find(object, key);
  return v != nullptr ? *v : null;
}

std::string role_of(const json& feature) {
  return text_or(member_or_null(feature, "properties"), "role", "");
}

// The plan's home, and each drone's own where it differs (swath writes those with "drone").
struct Homes {
  std::optional<GeoPoint> plan;
  std::map<long long, GeoPoint> drones;
};

Homes homes_of(const json& features, const std::string& source) {
  Homes out;
  for (std::size_t i = 0; i < features.size(); ++i) {
    const json& f = features[i];
    if (role_of(f) != "home") continue;
    const GeoPoint at = position_of(member_or_null(member_or_null(f, "geometry"), "coordinates"),
                                    source + ": feature " + std::to_string(i));
    const json& drone = member_or_null(member_or_null(f, "properties"), "drone");
    if (drone.is_number_integer()) {
      out.drones[drone.get<long long>()] = at;
    } else {
      out.plan = at;
    }
  }
  return out;
}

GeoJsonFlight flight_of(const json& f, const Homes& homes, std::size_t index,
                        const std::string& where) {
  const json& geometry = member_or_null(f, "geometry");
  const json& coords = member_or_null(geometry, "coordinates");
  if (text_or(geometry, "type", "") != "LineString" || !coords.is_array() || coords.size() < 2)
    throw base::InputError(where + ": a path is a LineString of at least two positions");
  const json& props = member_or_null(f, "properties");
  GeoJsonFlight m;
  const json& drone = member_or_null(props, "drone");
  m.drone =
      drone.is_number_integer() && drone.get<long long>() >= 0 && drone.get<long long>() < 1'000'000
          ? "drone-" + std::to_string(drone.get<long long>())
          : "drone-" + std::to_string(index + 1);
  if (const json* name = base::json_find(props, "name");
      name && name->is_string() && !name->get<std::string>().empty())
    m.drone = base::valid_utf8(name->get<std::string>());
  const auto own =
      drone.is_number_integer() ? homes.drones.find(drone.get<long long>()) : homes.drones.end();
  m.home = own != homes.drones.end() ? own->second
           : homes.plan              ? *homes.plan
                                     : position_of(coords[0], where);
  const bool has_alt = base::json_find(props, "altitude_m") != nullptr;
  const double alt =
      has_alt ? base::json_number(member_or_null(props, "altitude_m"), where + ": altitude_m")
              : 0.0;
  m.speed_m_s = base::json_find(props, "speed_m_s")
                    ? base::json_number(member_or_null(props, "speed_m_s"), where + ": speed_m_s")
                    : 0.0;
  if (m.speed_m_s < 0) throw base::InputError(where + ": speed_m_s must be >= 0");
  for (std::size_t k = 0; k < coords.size(); ++k) {
    const std::string at = where + ", position " + std::to_string(k);
    m.points.push_back(position_of(coords[k], at));
    double a = alt;
    if (!has_alt) {
      if (coords[k].size() < 3)
        throw base::InputError(where +
                               ": the path has no altitude (give properties.altitude_m or "
                               "[lon, lat, alt] positions)");
      a = base::json_number(coords[k][2], at + ": altitude");
    }
    m.altitudes_m.push_back(a);
  }
  return m;
}

}  // namespace

std::string mission_geojson(const PlanFeatures& f) {
  // The features as a tree, but each geometry's coordinates a mark (in document order), written
  // directly afterwards: the outline's and the paths' positions as tree nodes were most of the
  // writer's time.
  std::vector<std::string> coordinates;
  const auto mark = [&coordinates](std::string text) {
    coordinates.push_back(std::move(text));
    return ordered_json(kCoordinatesMark);
  };
  const auto polygon = [](const std::vector<GeoRing>& rings) {
    std::string text;
    append_rings(text, rings, kCoordinatesIndent);
    return text;
  };
  const auto line = [](const std::vector<GeoPoint>& points) {
    std::string text;
    append_positions(text, points, false, kCoordinatesIndent);
    return text;
  };
  const auto point = [](const GeoPoint& g) {
    std::string text;
    append_position(text, g, kCoordinatesIndent);
    return text;
  };
  ordered_json features = ordered_json::array();
  features.push_back(feature({{"role", "area"}}, "Polygon", mark(polygon(f.area))));
  for (std::size_t k = 0; k < f.area_pieces.size(); ++k)  // --repair: the other enclosed areas
    features.push_back(feature({{"role", "area"}, {"piece", k + 1}}, "Polygon",
                               mark(polygon({f.area_pieces[k]}))));
  for (const GeoRing& zone : f.no_fly)
    features.push_back(feature({{"role", "no_fly"}}, "Polygon", mark(polygon({zone}))));
  for (std::size_t k = 0; k < f.cells.size(); ++k)
    features.push_back(
        feature({{"role", "cell"}, {"cell", k}}, "Polygon", mark(polygon({f.cells[k]}))));
  for (const PlanFeatures::Region& r : f.regions)
    features.push_back(
        feature({{"role", "region"}, {"drone", r.drone}}, "Polygon", mark(polygon({r.ring}))));
  for (const PlanFeatures::Path& p : f.paths) {
    features.push_back(feature({{"role", "path"},
                                {"drone", p.drone},
                                {"name", p.name},
                                {"altitude_m", p.altitude_m},
                                {"speed_m_s", p.speed_m_s}},
                               "LineString", mark(line(p.points))));
    for (const PlanFeatures::Sweep& s : f.sweeps)
      if (s.drone == p.drone)
        features.push_back(feature({{"role", "sweep"},
                                    {"drone", s.drone},
                                    {"line", s.line},
                                    {"footprint_width_m", s.footprint_width_m}},
                                   "LineString", mark(line({s.start, s.end}))));
  }
  features.push_back(feature({{"role", "home"}}, "Point", mark(point(f.home))));
  for (const PlanFeatures::DroneHome& h : f.drone_homes)
    features.push_back(feature({{"role", "home"}, {"drone", h.drone}}, "Point", mark(point(h.at))));
  // Moved in, not copied (a braced list copies: the whole collection twice).
  ordered_json collection = ordered_json::object();
  collection["type"] = "FeatureCollection";
  collection["features"] = std::move(features);
  const std::string tree = base::json_text(collection, 1) + "\n";
  // The marks in order. A mark as a "coordinates" value cannot be a name's text: there every
  // quote is escaped.
  const std::string marked = "\"coordinates\": \"" + std::string(kCoordinatesMark) + '"';
  std::string out;
  std::size_t size = tree.size();
  for (const std::string& c : coordinates) size += c.size();
  out.reserve(size);
  std::size_t from = 0;
  for (const std::string& c : coordinates) {
    const std::size_t at = tree.find(marked, from);
    const std::size_t value = at + marked.size() - std::strlen(kCoordinatesMark) - 2;
    out.append(tree, from, value - from);
    out += c;
    from = at + marked.size();
  }
  out.append(tree, from, std::string::npos);
  return out;
}

PlanFeatures parse_mission_geojson(const std::string& text, const std::string& source) {
  const json root = base::parse_json_document(text, source);
  const json& features =
      base::json_array(base::json_member(root, "features", source), source + ": features");
  PlanFeatures f;
  bool has_area = false, has_home = false;
  for (std::size_t i = 0; i < features.size(); ++i) {
    const std::string where = source + ": feature " + std::to_string(i);
    const json& feature = features[i];
    const json* properties = base::json_find(feature, "properties");
    const json* role_json = properties ? base::json_find(*properties, "role") : nullptr;
    if (role_json == nullptr || !role_json->is_string()) continue;  // not one of swath's
    const std::string& role = role_json->get_ref<const std::string&>();
    const json& geometry = base::json_member(feature, "geometry", where);
    if (role == "area") {
      std::vector<GeoRing> rings = polygon_of(geometry, where);
      if (base::json_find(*properties, "piece")) {
        f.area_pieces.push_back(std::move(rings.front()));
      } else if (!has_area) {
        f.area = std::move(rings);
        has_area = true;
      }
    } else if (role == "no_fly") {
      f.no_fly.push_back(std::move(polygon_of(geometry, where).front()));
    } else if (role == "cell") {
      f.cells.push_back(std::move(polygon_of(geometry, where).front()));
    } else if (role == "region") {
      f.regions.push_back({drone_of(*properties, where), polygon_of(geometry, where).front()});
    } else if (role == "path") {
      PlanFeatures::Path p;
      p.drone = drone_of(*properties, where);
      if (const json* n = base::json_find(*properties, "name"); n && n->is_string())
        p.name = base::valid_utf8(n->get<std::string>());
      if (const json* a = base::json_find(*properties, "altitude_m"))
        p.altitude_m = base::json_number(*a, where + ": altitude_m");
      if (const json* s = base::json_find(*properties, "speed_m_s"))
        p.speed_m_s = base::json_number(*s, where + ": speed_m_s");
      p.points = positions_of(line_of(geometry, where), where, 2);
      f.paths.push_back(std::move(p));
    } else if (role == "sweep") {
      PlanFeatures::Sweep s;
      s.drone = drone_of(*properties, where);
      if (const json* l = base::json_find(*properties, "line"))
        s.line = static_cast<int>(base::json_integer(*l, 0, 1'000'000, where + ": line"));
      s.footprint_width_m =
          base::json_number(base::json_member(*properties, "footprint_width_m", where),
                            where + ": footprint_width_m");
      if (!(s.footprint_width_m >= 0))
        throw base::InputError(where + ": footprint_width_m must be >= 0");
      const std::vector<GeoPoint> ends = positions_of(line_of(geometry, where), where, 2);
      s.start = ends.front();
      s.end = ends.back();
      f.sweeps.push_back(s);
    } else if (role == "home") {
      if (base::json_string(base::json_member(geometry, "type", where), where + ": type") !=
          "Point")
        throw base::InputError(where + ": the home is a Point");
      const GeoPoint at = position_of(base::json_member(geometry, "coordinates", where), where);
      if (base::json_find(*properties, "drone")) {
        f.drone_homes.push_back({drone_of(*properties, where), at});
      } else {
        f.home = at;
        has_home = true;
      }
    }
  }
  if (!has_area) throw base::InputError(source + ": no feature with role \"area\"");
  if (!has_home) f.home = f.area.front().front();
  return f;
}

std::vector<GeoJsonFlight> parse_geojson_flights(const std::string& text,
                                                 const std::string& source) {
  const json root = base::parse_json_document(text, source);
  const json& features = member_or_null(root, "features");
  if (!features.is_array())
    throw base::InputError(source + ": a mission GeoJSON is a FeatureCollection with 'features'");
  const Homes homes = homes_of(features, source);
  std::vector<GeoJsonFlight> out;
  for (std::size_t i = 0; i < features.size(); ++i)
    if (role_of(features[i]) == "path")
      out.push_back(
          flight_of(features[i], homes, out.size(), source + ": feature " + std::to_string(i)));
  if (out.empty())
    throw base::InputError(source + ": no feature with role 'path' (a drone's flight)");
  return out;
}

}  // namespace swath::missions
