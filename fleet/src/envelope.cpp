#include "swath/fleet/envelope.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/base/yaml_map.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::fleet {

using base::InputError;
using json = nlohmann::json;

namespace {

// On the boundary counts as inside: a fence's edge is still the fence's.
bool inside(const std::vector<std::array<double, 2>>& ring, double x_m, double y_m) {
  std::vector<geometry::Point2> r;
  r.reserve(ring.size());
  for (const auto& [x, y] : ring) r.push_back({x, y});
  return geometry::locate_point({x_m, y_m}, r) != geometry::Containment::outside;
}

// A GeoJSON linear ring: [[lon, lat], ...], at least 3 distinct vertices, closed or not.
std::vector<geometry::GeoPoint> ring_of(const json& coords, const std::string& where) {
  if (!coords.is_array()) throw InputError(where + ": a ring is a list of [lon, lat] positions");
  std::vector<geometry::GeoPoint> out;
  for (const json& p : coords) {
    if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number())
      throw InputError(where + ": a position is [lon, lat] in degrees");
    const double lon = p[0].get<double>(), lat = p[1].get<double>();
    if (!(std::abs(lat) <= 90) || !(std::abs(lon) <= 180))
      throw InputError(where + ": [" + base::shortest_text(lon) + ", " + base::shortest_text(lat) +
                       "] is not a lon/lat in degrees");
    out.push_back({lat, lon, 0});
  }
  if (out.size() > 1 && out.front() == out.back()) out.pop_back();
  if (out.size() < 3) throw InputError(where + ": a fence polygon needs at least 3 vertices");
  return out;
}

// A geometry's polygons (outer rings; holes are refused: give an exclusion instead).
void add_geometry(const json& g, bool inclusion, const std::string& where,
                  std::vector<FencePolygon>& out) {
  const std::string type = g.is_object() ? g.value("type", "") : "";
  const auto polygon = [&](const json& rings) {
    if (!rings.is_array() || rings.empty())
      throw InputError(where + ": a Polygon's coordinates are a list of rings");
    if (rings.size() > 1)
      throw InputError(where + ": a fence polygon with holes; give each hole as an exclusion");
    out.push_back({ring_of(rings[0], where), inclusion});
  };
  if (type == "Polygon") {
    polygon(g.value("coordinates", json()));
  } else if (type == "MultiPolygon") {
    for (const json& p : g.value("coordinates", json::array())) polygon(p);
  } else {
    throw InputError(where + ": a fence is a Polygon or MultiPolygon, not \"" + type + "\"");
  }
}

}  // namespace

std::string LocalEnvelope::refusal_xy(double x_m, double y_m) const {
  if (!inclusions.empty()) {
    bool in = false;
    for (const auto& r : inclusions) in = in || inside(r, x_m, y_m);
    if (!in) return "outside the inclusion fence";
  }
  for (const auto& r : exclusions)
    if (inside(r, x_m, y_m)) return "inside an exclusion fence";
  return "";
}

std::string LocalEnvelope::refusal(const vehicle::Vec3& p) const {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return "not finite";
  if (p.z > ceiling_m + 1e-6)
    return "above the ceiling of " + base::shortest_text(ceiling_m) + " m";
  if (p.z > fence_max_altitude_m + 1e-6)
    return "above the fence's " + base::shortest_text(fence_max_altitude_m) + " m";
  return refusal_xy(p.x, p.y);
}

LocalEnvelope local_envelope(const Envelope& e, const geometry::GeoPoint& origin) {
  LocalEnvelope l;
  l.ceiling_m = e.ceiling_m;
  l.separation_m = e.separation_m;
  l.fence_max_altitude_m = e.fence.max_altitude_m;
  const geometry::LocalFrame frame(origin);
  for (const FencePolygon& p : e.fence.polygons) {
    std::vector<std::array<double, 2>> ring;
    for (const geometry::GeoPoint& g : p.ring_deg) {
      const geometry::Point2 q = frame.to_local(g);
      ring.push_back({q.x, q.y});
    }
    (p.inclusion ? l.inclusions : l.exclusions).push_back(std::move(ring));
  }
  return l;
}

std::vector<FencePolygon> parse_fence_geojson(const std::string& text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception&) {
    throw InputError(source + ": not JSON (a GeoJSON fence: Polygon or MultiPolygon features)");
  }
  std::vector<FencePolygon> out;
  const auto feature = [&](const json& f, const std::string& where) {
    bool inclusion = true;
    if (f.contains("properties") && f["properties"].is_object() &&
        f["properties"].contains("fence")) {
      const json& kind = f["properties"]["fence"];
      if (kind == "exclusion")
        inclusion = false;
      else if (kind != "inclusion")
        throw InputError(where + ": properties.fence is \"inclusion\" or \"exclusion\"");
    }
    add_geometry(f.value("geometry", json()), inclusion, where, out);
  };
  const std::string type = doc.is_object() ? doc.value("type", "") : "";
  if (type == "FeatureCollection") {
    const json features = doc.value("features", json::array());
    for (std::size_t i = 0; i < features.size(); ++i)
      feature(features[i], source + ": features[" + std::to_string(i) + "]");
  } else if (type == "Feature") {
    feature(doc, source);
  } else {
    add_geometry(doc, true, source, out);
  }
  if (out.empty()) throw InputError(source + ": the fence has no polygons");
  return out;
}

Envelope parse_fleet_envelope(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] {
    const YAML::Node doc = base::load_yaml(text, source);
    Envelope e;
    if (!doc.IsMap()) return e;  // parse_fleet_file says what is wrong
    const base::YamlMap root(doc, source, "");
    e.ceiling_m = root.number("ceiling_m", e.ceiling_m, 0, 10000, true);
    e.separation_m = root.number("separation_m", e.separation_m, 0, 1000, true);
    if (root.has("fence")) {
      if (!doc["fence"].IsMap())
        throw InputError(root.where("fence") + ": a mapping {geojson: FILE, max_altitude_m: M}");
      const base::YamlMap f = root.map("fence");
      f.allow({"geojson", "max_altitude_m"});
      if (!f.has("geojson"))
        throw InputError(root.where("fence") + ": no geojson (the fence's polygons)");
      std::filesystem::path p = f.text("geojson", "");
      if (p.is_relative()) p = std::filesystem::path(source).parent_path() / p;
      e.fence.polygons =
          parse_fence_geojson(base::read_text_file(p.string(), "fence file"), p.string());
      if (f.has("max_altitude_m"))
        e.fence.max_altitude_m = f.number("max_altitude_m", 0, 0, 10000, true);
    }
    return e;
  });
}

std::string layers_refusal(int drones, double base_m, double step_m, double ceiling_m) {
  const double top_m = base_m + step_m * static_cast<double>(std::max(0, drones - 1));
  if (top_m <= ceiling_m + 1e-9) return "";
  const int fit = base_m > ceiling_m ? 0 : static_cast<int>((ceiling_m - base_m) / step_m) + 1;
  return "a fleet of " + std::to_string(drones) + " drones needs altitude layers up to " +
         base::shortest_text(top_m) + " m (" + base::shortest_text(base_m) + " m + " +
         base::shortest_text(step_m) + " m apart), above the ceiling of " +
         base::shortest_text(ceiling_m) + " m: at most " + std::to_string(fit) +
         " drones fit (raise ceiling_m or lower separation_m in the fleet file)";
}

}  // namespace swath::fleet
