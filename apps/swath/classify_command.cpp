#include "classify_command.hpp"

#include <algorithm>
#include <iostream>
#include <nlohmann/json.hpp>

#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/geometry/area_facts.hpp"
#include "swath/geometry/field.hpp"

namespace swath::apps {
namespace {

using base::fixed_text;
using base::round_to;

using geometry::Field;
using geometry::Point2;
using geometry::RingIndex;
using nlohmann::ordered_json;

std::string ring_name(std::size_t ring) {
  return ring == 0 ? "outer ring" : "hole " + std::to_string(ring - 1);
}

// The vertex as the file numbers it (0-based position in its ring).
std::size_t file_position(const Field& field, RingIndex v) {
  return field.source_index[v.ring][v.index];
}

std::pair<std::size_t, std::size_t> edge_positions(const Field& field, RingIndex e) {
  // Named by its end positions in increasing order, whichever way normalisation turned the ring.
  const std::size_t n = field.source_index[e.ring].size();
  const std::size_t a = file_position(field, e);
  const std::size_t b = file_position(field, {e.ring, (e.index + 1) % n});
  return {std::min(a, b), std::max(a, b)};
}

ordered_json point_json(const Field& field, Point2 p) {
  ordered_json j;
  if (field.frame) {
    const geometry::GeoPoint g = field.frame->to_geo(p);
    j["lat_deg"] = round_to(g.lat_deg, 9);
    j["lon_deg"] = round_to(g.lon_deg, 9);
  }
  j["x_m"] = round_to(p.x, 4);
  j["y_m"] = round_to(p.y, 4);
  return j;
}

std::string point_text(const Field& field, Point2 p) {
  if (!field.frame) return fixed_text(p.x, 3) + ", " + fixed_text(p.y, 3) + " (x, y m)";
  const geometry::GeoPoint g = field.frame->to_geo(p);
  return fixed_text(g.lat_deg, 7) + ", " + fixed_text(g.lon_deg, 7) + " (lat, lon)";
}

ordered_json edge_json(const Field& field, RingIndex e) {
  const auto [from, to] = edge_positions(field, e);
  return {{"ring", e.ring}, {"from_position", from}, {"to_position", to}};
}

std::string edge_text(const Field& field, RingIndex e) {
  const auto [from, to] = edge_positions(field, e);
  return "the " + ring_name(e.ring) + "'s edge " + std::to_string(from) + "-" + std::to_string(to);
}

// Reflex vertices in the file's order (normalisation may have reversed a ring).
std::vector<RingIndex> reflex_in_file_order(const Field& field, std::vector<RingIndex> reflex) {
  std::sort(reflex.begin(), reflex.end(), [&](RingIndex a, RingIndex b) {
    return a.ring < b.ring ||
           (a.ring == b.ring && file_position(field, a) < file_position(field, b));
  });
  return reflex;
}

ordered_json to_json(const Field& field, const geometry::AreaFacts& facts) {
  ordered_json j;
  j["file"] = field.source;
  j["type"] = std::string(to_string(facts.classification.type));
  j["vertices"] = facts.vertex_count;
  j["holes"] = field.polygon.holes.size();
  j["area_m2"] = facts.area_m2 ? ordered_json(round_to(*facts.area_m2, 3)) : ordered_json();
  j["perimeter_m"] = round_to(facts.perimeter_m, 4);
  if (facts.regularity) {
    j["regularity"] = round_to(facts.regularity->overall, 6);
    j["angle_regularity"] = round_to(facts.regularity->angle, 6);
    j["edge_regularity"] = round_to(facts.regularity->edge, 6);
  } else {
    j["regularity"] = nullptr;
  }
  j["centroid"] = facts.centroid ? point_json(field, *facts.centroid) : ordered_json();
  j["min_height_m"] = round_to(facts.min_height.height_m, 4);
  j["sweep_bearing_deg"] = round_to(geometry::line_bearing_deg(facts.min_height.angle_deg), 6);
  j["sweep_angle_local_deg"] = round_to(facts.min_height.angle_deg, 6);
  ordered_json reflex = ordered_json::array();
  for (const RingIndex& v : reflex_in_file_order(field, facts.classification.reflex_vertices)) {
    ordered_json r = {{"ring", v.ring}, {"position", file_position(field, v)}};
    r.update(point_json(field, geometry::ring_at(field.polygon, v.ring)[v.index]));
    reflex.push_back(r);
  }
  j["reflex_vertices"] = reflex;
  if (auto c = facts.classification.crossing) {
    if (edge_positions(field, c->edge_b) < edge_positions(field, c->edge_a))
      std::swap(c->edge_a, c->edge_b);
    j["crossing"] = {{"edge_a", edge_json(field, c->edge_a)},
                     {"edge_b", edge_json(field, c->edge_b)},
                     {"point", point_json(field, c->point)}};
  } else {
    j["crossing"] = nullptr;
  }
  return j;
}

void print_text(const Field& field, const geometry::AreaFacts& facts) {
  const auto& c = facts.classification;
  auto row = [](const char* label, const std::string& value) {
    std::printf("  %-16s %s\n", label, value.c_str());
  };
  std::printf("%s: %s area\n", field.source.c_str(), std::string(to_string(c.type)).c_str());
  row("vertices", std::to_string(facts.vertex_count) +
                      (field.polygon.holes.empty()
                           ? ""
                           : " in " + std::to_string(field.polygon.holes.size() + 1) + " rings"));
  if (facts.area_m2)
    row("area",
        fixed_text(*facts.area_m2, 2) + " m² (" + fixed_text(*facts.area_m2 / 1e4, 4) + " ha)");
  row("perimeter", fixed_text(facts.perimeter_m, 2) + " m");
  if (facts.regularity)
    row("regularity", fixed_text(facts.regularity->overall, 4) + " (angles " +
                          fixed_text(facts.regularity->angle, 4) + ", edges " +
                          fixed_text(facts.regularity->edge, 4) + ")");
  if (facts.centroid) row("centroid", point_text(field, *facts.centroid));
  row("min height", fixed_text(facts.min_height.height_m, 2) + " m, sweep lines at bearing " +
                        fixed_text(geometry::line_bearing_deg(facts.min_height.angle_deg), 2) +
                        "° (" + fixed_text(facts.min_height.angle_deg, 2) + "° CCW from east)");
  if (c.type == geometry::AreaType::concave) {
    std::string list = std::to_string(c.reflex_vertices.size());
    for (const RingIndex& v : reflex_in_file_order(field, c.reflex_vertices)) {
      list += "\n                   " + ring_name(v.ring) + " position " +
              std::to_string(file_position(field, v)) + " at " +
              point_text(field, geometry::ring_at(field.polygon, v.ring)[v.index]);
    }
    row("reflex vertices", list);
  }
  if (auto x = c.crossing) {
    if (edge_positions(field, x->edge_b) < edge_positions(field, x->edge_a))
      std::swap(x->edge_a, x->edge_b);
    row("crossing", edge_text(field, x->edge_a) + " meets " + edge_text(field, x->edge_b) + " at " +
                        point_text(field, x->point));
    std::printf("  planning refuses this area: reorder its vertices so that no edges cross\n");
  }
}

}  // namespace

void ClassifyCommand::setup(CLI::App& app) {
  app.add_option("FIELD", field_path_,
                 "Area file: .geojson/.json (lon, lat), .kml, .csv, or any GIS file GDAL reads "
                 "(.shp, .zip, .gpkg, .kmz, .gpx, .fgb, .gml, .wkt; projected ones reprojected)")
      ->required();
  area_choice_.add_options(app);
  app.add_flag("--json", json_, "Print one JSON object instead of text");
  app.add_flag("--local", local_, "CSV columns are x,y in local metres instead of lon,lat");
}

int ClassifyCommand::run() {
  geometry::FieldReadOptions options;
  options.local_metres = local_;
  area_choice_.apply(options);
  const Field field = geometry::read_field(field_path_, options);
  const geometry::AreaFacts facts = geometry::describe_area(field.polygon);
  if (json_) {
    std::cout << base::json_text(to_json(field, facts), 2) << '\n';
  } else {
    print_text(field, facts);
  }
  return base::kExitSuccess;
}

}  // namespace swath::apps
