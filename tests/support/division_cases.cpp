#include "division_cases.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "field_shapes.hpp"
#include "local_field.hpp"
#include "swath/base/file_text.hpp"
#include "swath/geometry/field.hpp"
#include "swath/planning/camera.hpp"
#include "swath/vehicle/drone.hpp"

namespace swath::test {

namespace {

// A photogrammetry request at 60 m over `field` with `camera`, divided as asked among three equal
// drones (home: the plan's) or the given fleet.
planning::SurveyRequest division_request(const geometry::Field& field,
                                         const planning::Camera& camera,
                                         planning::DivisionMode division, planning::Balance balance,
                                         const std::optional<vehicle::Fleet>& fleet) {
  planning::SurveyRequest r;
  r.field = field;
  r.camera = camera;
  planning::PhotogrammetryMode m;
  m.altitude_m = 60;
  r.mode = m;
  r.division = division;
  r.balance = balance;
  if (!fleet) {
    r.fleet = vehicle::equal_fleet(3, {});
    r.fleet->home = geometry::GeoPoint{std::numeric_limits<double>::quiet_NaN(), 0, 0};
  } else {
    r.home = fleet->home;
    r.fleet = *fleet;
  }
  return r;
}

}  // namespace

std::vector<DivisionCase> division_cases(const std::string& source_dir,
                                         planning::DivisionMode division,
                                         planning::Balance balance) {
  struct Field {
    std::string file;
    geometry::GeoPoint fleet_home;
  };
  const vehicle::Fleet quads = vehicle::parse_fleet(
      base::read_text_file(source_dir + "/share/fleets/three-quads.yaml", "fleet file", 1 << 20),
      "three-quads.yaml");
  const std::vector<Field> fields{{"meadow.geojson", quads.home},
                                  {"vineyard.kml", {46.2276, 7.5917, 0}},
                                  {"orchard.csv", {52.4035, -0.9525, 0}}};
  std::vector<DivisionCase> out;
  for (const Field& f : fields)
    for (const bool equal : {true, false}) {
      std::optional<vehicle::Fleet> fleet;
      if (!equal) {
        fleet = quads;
        const double dlat = f.fleet_home.lat_deg - quads.home.lat_deg,
                     dlon = f.fleet_home.lon_deg - quads.home.lon_deg;
        fleet->home = f.fleet_home;
        for (vehicle::Drone& d : fleet->drones)
          if (d.home)
            d.home = geometry::GeoPoint{d.home->lat_deg + dlat, d.home->lon_deg + dlon, 0};
      }
      planning::SurveyRequest r =
          division_request(geometry::read_field(source_dir + "/share/fields/" + f.file),
                           planning::find_camera("sony-ilce-qx1", source_dir + "/share/cameras"),
                           division, balance, fleet);
      out.push_back({f.file, equal ? "3 equal" : "three-quads", std::move(r)});
    }
  return out;
}

std::vector<DivisionCase> corpus_division_cases(const std::string& source_dir, std::uint64_t seed,
                                                int per_family, planning::DivisionMode division,
                                                planning::Balance balance) {
  const vehicle::Fleet quads = vehicle::parse_fleet(
      base::read_text_file(source_dir + "/share/fleets/three-quads.yaml", "fleet file", 1 << 20),
      "three-quads.yaml");
  const planning::Camera camera =
      planning::find_camera("sony-ilce-qx1", source_dir + "/share/cameras");
  std::vector<DivisionCase> out;
  for (const CorpusShape& shape : split_corpus(seed, per_family)) {
    const geometry::Field field = local_field(shape.area);
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (const geometry::Point2& p : shape.area.outer) {
      x0 = std::min(x0, p.x);
      y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x);
      y1 = std::max(y1, p.y);
    }
    for (const bool equal : {true, false}) {
      std::optional<vehicle::Fleet> fleet;
      if (!equal) {
        fleet = quads;
        fleet->home = field.frame->to_geo({x0 - 40, y0 - 40});
        for (vehicle::Drone& d : fleet->drones)
          if (d.home) d.home = field.frame->to_geo({x1 + 40, (y0 + y1) / 2});
      }
      planning::SurveyRequest r = division_request(field, camera, division, balance, fleet);
      r.concave = planning::ConcaveMode::split;
      out.push_back({shape.family + " " + std::to_string(shape.index),
                     equal ? "3 equal" : "three-quads", std::move(r)});
    }
  }
  return out;
}

planning::SurveyRequest undivided(const planning::SurveyRequest& request) {
  planning::SurveyRequest r = request;
  r.fleet.reset();
  return r;
}

double max_over_min_flight(const planning::SurveyPlan& plan) {
  double longest = 0, shortest = std::numeric_limits<double>::infinity();
  for (const planning::DronePlan& d : plan.drones) {
    if (d.mission.lines.empty()) continue;
    // Balanced before the altitude layers were laid: their extra climb and descent apart.
    const double t =
        d.mission.flight_time_s - d.layer_m * (1 / d.climb_speed_m_s + 1 / d.descent_speed_m_s);
    longest = std::max(longest, t);
    shortest = std::min(shortest, t);
  }
  return shortest > 0 && std::isfinite(shortest) ? longest / shortest : 0.0;
}

}  // namespace swath::test
