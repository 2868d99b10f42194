#include "swath/planning/plan_features.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

#include "files/common.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/utf8.hpp"
#include "swath/planning/survey.hpp"
#include "swath/planning/survey_steps.hpp"

namespace swath::planning {
namespace {

using base::round_to;
using files::rounded;
using geometry::GeoPoint;
using geometry::Point2;
using nlohmann::json;

// ---- From the plan.

// files::geo() as the writers have it (shared within a files::GeoMemo).
GeoPoint geo(const SurveyPlan& plan, Point2 p) {
  return files::geo(plan, p);
}

GeoRing geo_ring(const SurveyPlan& plan, const geometry::Ring& ring) {
  GeoRing out;
  for (const Point2& p : ring) out.push_back(geo(plan, p));
  return out;
}

// ---- Reading summary.json (checked).

int drone_of(const json& properties, const std::string& where) {
  return static_cast<int>(base::json_integer(base::json_member(properties, "drone", where), 1, 1000,
                                             where + ": drone"));
}

}  // namespace

std::vector<GeoRing> lined_area(const SurveyPlan& plan) {
  std::vector<GeoRing> out;
  for (const geometry::Ring& ring : steps::lined_rings(plan)) out.push_back(geo_ring(plan, ring));
  return out;
}

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
    path.altitude_m = round_to(files::map_altitude_m(plan, d), 3);
    path.speed_m_s = round_to(d.speed_m_s, 3);
    for (const Point2& p : files::map_path(d)) path.points.push_back(geo(plan, p));
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
