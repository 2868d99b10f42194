// swath's mission.geojson (swath/missions/mission_geojson.hpp): random plans' features (fixed
// seeds) written and read back by both of the format's readers — the checked one swath render
// and swath-control use, and the flights swath-energy budget and swath-control fly — give the
// same areas, paths, homes, altitudes and speeds as the value written.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/missions/mission_geojson.hpp"

namespace swath::missions {
namespace {

struct Rng {
  std::mt19937 engine;
  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(engine); }
  int between(int lo, int hi) { return std::uniform_int_distribution<>(lo, hi)(engine); }
  geometry::GeoPoint point() {
    return {base::round_to(uniform(-60, 60), 9), base::round_to(uniform(-170, 170), 9), 0.0};
  }
  GeoRing ring(int lo, int hi) {
    GeoRing r;
    for (int k = between(lo, hi); k > 0; --k) r.push_back(point());
    return r;
  }
};

PlanFeatures random_features(std::uint32_t seed) {
  Rng rng{std::mt19937(seed)};
  PlanFeatures f;
  f.area.push_back(rng.ring(3, 6));
  f.home = rng.point();
  const int drones = rng.between(1, 4);
  for (int d = 1; d <= drones; ++d) {
    PlanFeatures::Path p;
    p.drone = d;
    p.name = rng.between(0, 1) ? "drone " + std::to_string(d * 7) : "";
    p.altitude_m = base::round_to(rng.uniform(1, 120), 3);
    p.speed_m_s = base::round_to(rng.uniform(0, 20), 3);
    p.points = rng.ring(2, 7);
    f.paths.push_back(p);
    if (rng.between(0, 1)) f.drone_homes.push_back({d, rng.point()});
  }
  return f;
}

void expect_same_points(const std::vector<geometry::GeoPoint>& a,
                        const std::vector<geometry::GeoPoint>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].lat_deg, b[k].lat_deg) << what << " " << k;
    EXPECT_EQ(a[k].lon_deg, b[k].lon_deg) << what << " " << k;
  }
}

// ---- The writer against the whole collection as an nlohmann tree, dumped (the writer's former
// way, kept here): the same bytes for random features of every role, rings of 3 to 300 points,
// names that need escaping, numbers that are not finite or whole.

using nlohmann::ordered_json;

ordered_json reference_position(const geometry::GeoPoint& g) {
  return {g.lon_deg, g.lat_deg};
}

ordered_json reference_ring(const GeoRing& ring) {
  ordered_json out = ordered_json::array();
  for (const geometry::GeoPoint& g : ring) out.push_back(reference_position(g));
  out.push_back(out.front());
  return out;
}

ordered_json reference_one_ring(const GeoRing& ring) {
  ordered_json rings = ordered_json::array();
  rings.push_back(reference_ring(ring));
  return rings;
}

ordered_json reference_feature(ordered_json properties, const char* type,
                               ordered_json coordinates) {
  return {{"type", "Feature"},
          {"properties", std::move(properties)},
          {"geometry", {{"type", type}, {"coordinates", std::move(coordinates)}}}};
}

std::string reference_mission_geojson(const PlanFeatures& f) {
  ordered_json features = ordered_json::array();
  ordered_json rings = ordered_json::array();
  for (const GeoRing& ring : f.area) rings.push_back(reference_ring(ring));
  features.push_back(reference_feature({{"role", "area"}}, "Polygon", std::move(rings)));
  for (std::size_t k = 0; k < f.area_pieces.size(); ++k)
    features.push_back(reference_feature({{"role", "area"}, {"piece", k + 1}}, "Polygon",
                                         reference_one_ring(f.area_pieces[k])));
  for (const GeoRing& zone : f.no_fly)
    features.push_back(
        reference_feature({{"role", "no_fly"}}, "Polygon", reference_one_ring(zone)));
  for (std::size_t k = 0; k < f.cells.size(); ++k)
    features.push_back(reference_feature({{"role", "cell"}, {"cell", k}}, "Polygon",
                                         reference_one_ring(f.cells[k])));
  for (const PlanFeatures::Region& r : f.regions)
    features.push_back(reference_feature({{"role", "region"}, {"drone", r.drone}}, "Polygon",
                                         reference_one_ring(r.ring)));
  for (const PlanFeatures::Path& p : f.paths) {
    ordered_json points = ordered_json::array();
    for (const geometry::GeoPoint& g : p.points) points.push_back(reference_position(g));
    features.push_back(reference_feature({{"role", "path"},
                                          {"drone", p.drone},
                                          {"name", p.name},
                                          {"altitude_m", p.altitude_m},
                                          {"speed_m_s", p.speed_m_s}},
                                         "LineString", std::move(points)));
    for (const PlanFeatures::Sweep& s : f.sweeps)
      if (s.drone == p.drone)
        features.push_back(reference_feature(
            {{"role", "sweep"},
             {"drone", s.drone},
             {"line", s.line},
             {"footprint_width_m", s.footprint_width_m}},
            "LineString", {reference_position(s.start), reference_position(s.end)}));
  }
  features.push_back(reference_feature({{"role", "home"}}, "Point", reference_position(f.home)));
  for (const PlanFeatures::DroneHome& h : f.drone_homes)
    features.push_back(reference_feature({{"role", "home"}, {"drone", h.drone}}, "Point",
                                         reference_position(h.at)));
  ordered_json collection = ordered_json::object();
  collection["type"] = "FeatureCollection";
  collection["features"] = std::move(features);
  return base::json_text(collection, 1) + "\n";
}

TEST(MissionGeoJson, TheWriterGivesTheTreesText) {
  const double odd[] = {
      std::nan(""), std::numeric_limits<double>::infinity(), 0.0, -0.0, 3.0, 1e-300, -1e300};
  const char* names[] = {"",
                         "drone 7",
                         "a \"quoted\" \\ name",
                         "@swath-coordinates@",
                         "\"coordinates\": \"@swath-coordinates@\"",
                         "caf\xc3\xa9",
                         "bad \xff",
                         "tab\there"};
  for (std::uint32_t seed = 1; seed <= 300; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    PlanFeatures f = random_features(seed);
    Rng rng{std::mt19937(seed + 1000)};
    if (rng.between(0, 1)) f.area.push_back(rng.ring(3, 300));  // a hole
    if (seed % 3 == 0) f.area.front() = rng.ring(100, 300);
    for (int k = rng.between(0, 2); k > 0; --k) f.area_pieces.push_back(rng.ring(3, 8));
    for (int k = rng.between(0, 2); k > 0; --k) f.no_fly.push_back(rng.ring(3, 8));
    for (int k = rng.between(0, 4); k > 0; --k) f.cells.push_back(rng.ring(3, 8));
    for (const PlanFeatures::Path& p : f.paths) {
      if (rng.between(0, 1)) f.regions.push_back({p.drone, rng.ring(3, 8)});
      for (int line = rng.between(0, 5); line > 0; --line)
        f.sweeps.push_back({p.drone, line, rng.uniform(1, 200), rng.point(), rng.point()});
    }
    for (PlanFeatures::Path& p : f.paths) {
      p.name = names[rng.between(0, 7)];
      if (rng.between(0, 3) == 0) p.altitude_m = odd[rng.between(0, 6)];
      if (rng.between(0, 3) == 0 && !p.points.empty()) p.points[0].lat_deg = odd[rng.between(0, 6)];
    }
    if (seed % 10 == 0) f.paths.front().points.clear();
    if (seed % 11 == 0) f.home.lon_deg = odd[rng.between(0, 6)];
    ASSERT_EQ(mission_geojson(f), reference_mission_geojson(f));
  }
}

TEST(MissionGeoJson, WrittenAndReadBackByTheCheckedReaderGivesTheSameFeatures) {
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    const PlanFeatures f = random_features(seed);
    const PlanFeatures back = parse_mission_geojson(mission_geojson(f), "mission.geojson");
    ASSERT_EQ(back.area.size(), 1u);
    expect_same_points(back.area[0], f.area[0], "area");
    expect_same_points({back.home}, {f.home}, "home");
    ASSERT_EQ(back.paths.size(), f.paths.size()) << seed;
    for (std::size_t i = 0; i < f.paths.size(); ++i) {
      EXPECT_EQ(back.paths[i].drone, f.paths[i].drone);
      EXPECT_EQ(back.paths[i].name, f.paths[i].name);
      EXPECT_EQ(back.paths[i].altitude_m, f.paths[i].altitude_m);
      EXPECT_EQ(back.paths[i].speed_m_s, f.paths[i].speed_m_s);
      expect_same_points(back.paths[i].points, f.paths[i].points, "path");
    }
    ASSERT_EQ(back.drone_homes.size(), f.drone_homes.size()) << seed;
  }
}

// A flight's home is its drone's own where the file gives one, else the plan's; its name the
// path's, else drone-N; every position at the path's altitude and speed.
TEST(MissionGeoJson, TheFlightsReaderAgreesWithTheValueWritten) {
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    const PlanFeatures f = random_features(seed);
    const std::vector<GeoJsonFlight> flights =
        parse_geojson_flights(mission_geojson(f), "mission.geojson");
    ASSERT_EQ(flights.size(), f.paths.size()) << seed;
    for (std::size_t i = 0; i < f.paths.size(); ++i) {
      const PlanFeatures::Path& p = f.paths[i];
      const GeoJsonFlight& g = flights[i];
      EXPECT_EQ(g.drone, p.name.empty() ? "drone-" + std::to_string(p.drone) : p.name);
      geometry::GeoPoint home = f.home;
      for (const PlanFeatures::DroneHome& h : f.drone_homes)
        if (h.drone == p.drone) home = h.at;
      expect_same_points({g.home}, {home}, "home of drone " + std::to_string(p.drone));
      expect_same_points(g.points, p.points, "flight");
      EXPECT_EQ(g.altitudes_m, std::vector<double>(p.points.size(), p.altitude_m));
      EXPECT_EQ(g.speed_m_s, p.speed_m_s);
    }
  }
}

// A hand-written file's bad positions are refused by the same checks as swath's own file: one
// sentence naming the feature, the position and what is wrong (never a library exception).
TEST(MissionGeoJson, TheFlightsReaderRefusesBadPositionsByName) {
  const auto error_of = [](const std::string& coordinates) {
    const std::string text =
        R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"role":"path"},)"
        R"("geometry":{"type":"LineString","coordinates":)" +
        coordinates + "}}]}";
    try {
      parse_geojson_flights(text, "m.geojson");
    } catch (const base::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error_of("[[1,2,30],[1]]"),
            "m.geojson: feature 0, position 1: a position must have at least 2 elements");
  EXPECT_EQ(error_of("[[1,2,30],[1,\"x\",30]]"),
            "m.geojson: feature 0, position 1: latitude must be a number");
  EXPECT_EQ(error_of("[[1,2,30],[1,95,30]]"),
            "m.geojson: feature 0, position 1: latitude must be within ±90 and longitude within "
            "±180 degrees");
  EXPECT_EQ(error_of("[[1,2,30],[1,2,null]]"),
            "m.geojson: feature 0, position 1: altitude must be a number");
  EXPECT_EQ(error_of("[[1,2],[1,2]]"),
            "m.geojson: feature 0: the path has no altitude (give properties.altitude_m or "
            "[lon, lat, alt] positions)");
}

}  // namespace
}  // namespace swath::missions
