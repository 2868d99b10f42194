#include "swath/planning/plan_features.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/utf8.hpp"
#include "swath/planning/survey.hpp"

namespace swath::planning {
namespace {

using base::round_to;
using geometry::GeoPoint;
using geometry::Point2;
using nlohmann::json;
using nlohmann::ordered_json;

// ---- From the plan.

GeoPoint rounded(const GeoPoint& g) {
  return {round_to(g.lat_deg, 9), round_to(g.lon_deg, 9), 0.0};
}

GeoPoint geo(const SurveyPlan& plan, Point2 p) {
  return rounded(plan.request.field.frame->to_geo(p));
}

GeoRing geo_ring(const SurveyPlan& plan, const geometry::Ring& ring) {
  GeoRing out;
  for (const Point2& p : ring) out.push_back(geo(plan, p));
  return out;
}

// ---- Writing.

ordered_json position_json(const GeoPoint& g) {
  return {g.lon_deg, g.lat_deg};
}

// A Polygon's coordinates of one ring. Built with push_back: a braced {ring} would be the ring
// itself under clang and [ring] under GCC (nlohmann's initializer-list ambiguity).
ordered_json ring_json(const GeoRing& ring);
ordered_json one_ring(const GeoRing& ring) {
  ordered_json rings = ordered_json::array();
  rings.push_back(ring_json(ring));
  return rings;
}

ordered_json ring_json(const GeoRing& ring) {
  ordered_json out = ordered_json::array();
  for (const GeoPoint& g : ring) out.push_back(position_json(g));
  out.push_back(out.front());  // RFC 7946 rings are closed
  return out;
}

ordered_json feature(ordered_json properties, const char* type, ordered_json coordinates) {
  return {{"type", "Feature"},
          {"properties", std::move(properties)},
          {"geometry", {{"type", type}, {"coordinates", std::move(coordinates)}}}};
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

}  // namespace

PlanFeatures plan_features(const SurveyPlan& plan) {
  PlanFeatures f;
  const geometry::Polygon& area = plan.request.field.polygon;
  for (std::size_t r = 0; r < 1 && r < geometry::ring_count(area); ++r) {
    GeoRing ring;
    for (const GeoPoint& g : plan.request.field.geo_rings.at(r)) ring.push_back(rounded(g));
    f.area.push_back(std::move(ring));
  }
  // The field's holes stay holes of the area too (a GIS reads the area as it was given).
  for (std::size_t r = 1; r < geometry::ring_count(area); ++r) {
    GeoRing ring;
    for (const GeoPoint& g : plan.request.field.geo_rings.at(r)) ring.push_back(rounded(g));
    f.area.push_back(std::move(ring));
  }
  for (const auto& zone : plan.no_fly_geo) {
    GeoRing ring;
    for (const GeoPoint& g : zone) ring.push_back(rounded(g));
    f.no_fly.push_back(std::move(ring));
  }
  for (const geometry::Ring& piece : plan.extra_pieces)
    f.area_pieces.push_back(geo_ring(plan, piece));
  if (plan.handling == Handling::split)
    for (const geometry::Ring& cell : plan.cells) f.cells.push_back(geo_ring(plan, cell));
  for (const DronePlan& d : plan.drones)
    for (const geometry::Ring& piece : d.work.region)
      f.regions.push_back({d.number, geo_ring(plan, piece)});
  for (const DronePlan& d : plan.drones) {
    const DroneMission& m = d.mission;
    PlanFeatures::Path path;
    path.drone = d.number;
    path.name = d.name;
    path.altitude_m = round_to(plan.imaging.altitude_m, 3);
    path.speed_m_s = round_to(d.speed_m_s, 3);
    for (const Point2& p : m.path) path.points.push_back(geo(plan, p));
    f.paths.push_back(std::move(path));
    for (std::size_t i = 0; i < m.lines.size(); ++i)
      f.sweeps.push_back({d.number, static_cast<int>(i),
                          round_to(plan.imaging.footprint_across_m, 4), geo(plan, m.lines[i].start),
                          geo(plan, m.lines[i].end)});
  }
  f.home = rounded(plan.home);
  for (const DronePlan& d : plan.drones)
    if (!(rounded(d.home_geo) == f.home)) f.drone_homes.push_back({d.number, rounded(d.home_geo)});
  return f;
}

std::string mission_geojson(const PlanFeatures& f) {
  ordered_json features = ordered_json::array();
  ordered_json rings = ordered_json::array();
  for (const GeoRing& ring : f.area) rings.push_back(ring_json(ring));
  features.push_back(feature({{"role", "area"}}, "Polygon", rings));
  for (std::size_t k = 0; k < f.area_pieces.size(); ++k)  // --repair: the other enclosed areas
    features.push_back(
        feature({{"role", "area"}, {"piece", k + 1}}, "Polygon", one_ring(f.area_pieces[k])));
  for (const GeoRing& zone : f.no_fly)
    features.push_back(feature({{"role", "no_fly"}}, "Polygon", one_ring(zone)));
  for (std::size_t k = 0; k < f.cells.size(); ++k)
    features.push_back(feature({{"role", "cell"}, {"cell", k}}, "Polygon", one_ring(f.cells[k])));
  for (const PlanFeatures::Region& r : f.regions)
    features.push_back(
        feature({{"role", "region"}, {"drone", r.drone}}, "Polygon", one_ring(r.ring)));
  for (const PlanFeatures::Path& p : f.paths) {
    ordered_json points = ordered_json::array();
    for (const GeoPoint& g : p.points) points.push_back(position_json(g));
    features.push_back(feature({{"role", "path"},
                                {"drone", p.drone},
                                {"name", p.name},
                                {"altitude_m", p.altitude_m},
                                {"speed_m_s", p.speed_m_s}},
                               "LineString", points));
    for (const PlanFeatures::Sweep& s : f.sweeps)
      if (s.drone == p.drone)
        features.push_back(feature({{"role", "sweep"},
                                    {"drone", s.drone},
                                    {"line", s.line},
                                    {"footprint_width_m", s.footprint_width_m}},
                                   "LineString", {position_json(s.start), position_json(s.end)}));
  }
  features.push_back(feature({{"role", "home"}}, "Point", position_json(f.home)));
  for (const PlanFeatures::DroneHome& h : f.drone_homes)
    features.push_back(
        feature({{"role", "home"}, {"drone", h.drone}}, "Point", position_json(h.at)));
  return base::json_text(ordered_json{{"type", "FeatureCollection"}, {"features", features}}, 1) +
         "\n";
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

PlanFigures plan_figures(const SurveyPlan& plan) {
  PlanFigures out;
  out.covered_fraction = round_to(plan.coverage.covered_fraction, 6);
  out.lines = static_cast<int>(plan.sweep.lines.size());
  for (const DronePlan& d : plan.drones)
    out.drones.push_back({d.number, d.name, round_to(d.mission.path_length_m, 3),
                          round_to(d.mission.flight_time_s, 2)});
  return out;
}

PlanFigures parse_plan_figures(const std::string& summary_text, const std::string& source) {
  const json root = base::parse_json_document(summary_text, source);
  PlanFigures out;
  const json& coverage = base::json_member(root, "coverage", source);
  out.covered_fraction = base::json_number(base::json_member(coverage, "covered_fraction", source),
                                           source + ": coverage.covered_fraction");
  const json& sweep = base::json_member(root, "sweep", source);
  out.lines = static_cast<int>(base::json_integer(base::json_member(sweep, "lines", source), 0,
                                                  1'000'000, source + ": sweep.lines"));
  const json& drones =
      base::json_array(base::json_member(root, "drones", source), source + ": drones");
  for (std::size_t i = 0; i < drones.size(); ++i) {
    const std::string where = source + ": drones[" + std::to_string(i) + "]";
    PlanFigures::Drone d;
    d.drone = drone_of(drones[i], where);
    if (const json* name = base::json_find(drones[i], "name"))
      d.name = base::valid_utf8(base::json_string(*name, where + ": name"));
    d.path_length_m = base::json_number(base::json_member(drones[i], "path_length_m", where),
                                        where + ": path_length_m");
    d.flight_time_s = base::json_number(base::json_member(drones[i], "flight_time_s", where),
                                        where + ": flight_time_s");
    out.drones.push_back(std::move(d));
  }
  return out;
}

}  // namespace swath::planning
