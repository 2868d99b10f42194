// swath plan and no-fly zones: zones across the boundary, overlapping, outside the area, in
// files of several, with lines or points, self-crossing; the home and the zones' clearance; line
// extensions (--turnaround) against the clearance band. Asserted on the written files parsed back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "cli_runner.hpp"
#include "swath/base/number_text.hpp"

namespace swath::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

TEST(PlanCli, ZonesAcrossTheBoundaryAndOverlappingAreCutOut) {
  const std::string out = fresh_dir("zones-cut");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --exclude "
      "tests/fixtures/zone-across-boundary.geojson --exclude share/zones/meadow-pond.geojson "
      "--exclude tests/fixtures/zone-overlapping-pond.geojson -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("warning: no-fly zone tests/fixtures/zone-across-boundary.geojson "
                         "crosses the area's boundary; no-fly zone share/zones/meadow-pond.geojson "
                         "and no-fly zone tests/fixtures/zone-overlapping-pond.geojson overlap; "
                         "planned the area less the zones, 1 part(s)"),
            std::string::npos)
      << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(s["area"]["no_fly_zones"], 3);
  EXPECT_EQ(s["coverage"]["line_length_outside_m"].get<double>(), 0.0);
  EXPECT_EQ(s["coverage"]["transit_outside_m"].get<double>(), 0.0);
  EXPECT_GE(s["coverage"]["covered_fraction"].get<double>(), 0.999);
  EXPECT_GE(s["flight"]["min_no_fly_distance_m"].get<double>(), 5.0 - 1e-6);
  // The oracle: a 400 x 400 grid over the meadow's box in degrees (uniform in area to 1e-4 over
  // 500 m), each sample tested against the rings as read from the files by ray casting.
  auto ring_of = [](const std::string& path) {
    json g = json::parse(read_text(source_path(path)));
    if (g.contains("features")) g = g["features"][0];
    if (g.contains("geometry")) g = g["geometry"];
    std::vector<std::pair<double, double>> ring;
    for (const json& c : g["coordinates"][0])
      ring.push_back({c[0].get<double>(), c[1].get<double>()});
    return ring;
  };
  auto inside = [](const std::vector<std::pair<double, double>>& r, double x, double y) {
    bool in = false;
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
      if ((r[i].second > y) != (r[j].second > y) &&
          x < r[j].first +
                  (y - r[j].second) * (r[i].first - r[j].first) / (r[i].second - r[j].second))
        in = !in;
    return in;
  };
  const auto meadow = ring_of("share/fields/meadow.geojson");
  const std::vector<std::vector<std::pair<double, double>>> zones{
      ring_of("tests/fixtures/zone-across-boundary.geojson"),
      ring_of("share/zones/meadow-pond.geojson"),
      ring_of("tests/fixtures/zone-overlapping-pond.geojson")};
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const auto& [x, y] : meadow) {
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  long in_meadow = 0, left = 0;
  for (int i = 0; i < 400; ++i)
    for (int j = 0; j < 400; ++j) {
      const double x = x0 + (x1 - x0) * (i + 0.5) / 400, y = y0 + (y1 - y0) * (j + 0.5) / 400;
      if (!inside(meadow, x, y)) continue;
      ++in_meadow;
      bool free = true;
      for (const auto& z : zones) free &= !inside(z, x, y);
      left += free;
    }
  const double meadow_m2 = 100694.358;  // the meadow alone (as PlanCli.AShapefileInTheSwiss...)
  EXPECT_NEAR(s["area"]["area_m2"].get<double>(), meadow_m2 * double(left) / double(in_meadow),
              0.005 * meadow_m2);
}

// A zone wholly outside the area was said to "cross the area's boundary or each other": it is
// said to lie outside, the area is planned whole (the meadow's own area) and the transits keep
// out of the zone; beside a zone across the boundary, each is named for what it is.
TEST(PlanCli, AZoneOutsideTheAreaIsSaidToLieOutside) {
  const std::string out = fresh_dir("zone-outside"), both = fresh_dir("zone-outside-across");
  const std::string plan =
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --exclude "
      "tests/fixtures/zone-outside-area.geojson ";
  const CliRun run = run_swath(plan + "-o " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("warning: no-fly zone tests/fixtures/zone-outside-area.geojson lies "
                         "outside the area; the area is planned "
                         "whole, 100694.4 m², and transits keep out of the zones"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(run.err.find("cross"), std::string::npos) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_NEAR(s["area"]["area_m2"].get<double>(), 100694.358, 0.01);
  EXPECT_EQ(s["area"]["no_fly_zones"], 1);
  EXPECT_GE(s["flight"]["min_no_fly_distance_m"].get<double>(), 5.0 - 1e-6);
  const CliRun run2 =
      run_swath(plan + "--exclude tests/fixtures/zone-across-boundary.geojson -o " + both);
  ASSERT_EQ(run2.exit_code, 0) << run2.err;
  EXPECT_NE(
      run2.err.find("warning: no-fly zone tests/fixtures/zone-outside-area.geojson lies "
                    "outside the area; no-fly zone tests/fixtures/zone-across-boundary.geojson "
                    "crosses the area's boundary; planned the area less the zones, 1 part(s)"),
      std::string::npos)
      << run2.err;
}

TEST(PlanCli, NoFlyZoneFromExcludeIsAvoided) {
  const std::string out = fresh_dir("exclude");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --exclude "
      "share/zones/meadow-pond.geojson -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(s["area"]["no_fly_zones"], 1);
  EXPECT_EQ(s["area"]["handling"], "split");
  EXPECT_EQ(s["coverage"]["line_length_outside_m"].get<double>(), 0.0);  // nothing over the pond
  EXPECT_EQ(s["coverage"]["transit_outside_m"].get<double>(), 0.0);
  // The meadow less the 60 x 56 m pond.
  EXPECT_LT(s["area"]["area_m2"].get<double>(), 100694.358 - 3000);
  EXPECT_GE(s["coverage"]["covered_fraction"].get<double>(), 0.999);
}

// Every polygon of an --exclude file is a zone: the features of a FeatureCollection and the parts
// of a MultiPolygon (a file of two zones planned only its first).
TEST(PlanCli, EveryZoneOfAnExcludeFileIsAvoided) {
  const std::string out = fresh_dir("exclude-several");
  std::filesystem::create_directories(out);
  const std::string pond =
      "[[8.5418,47.3983],[8.5426,47.3983],[8.5426,47.3988],[8.5418,47.3988],"
      "[8.5418,47.3983]]";
  const std::string barn =
      "[[8.5432,47.3978],[8.5436,47.3978],[8.5436,47.3981],[8.5432,47.3981],"
      "[8.5432,47.3978]]";
  const std::string features =
      R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
      R"("geometry":{"type":"Polygon","coordinates":[)" +
      pond +
      R"(]}},{"type":"Feature","properties":{},"geometry":{"type":"Polygon",)"
      R"("coordinates":[)" +
      barn + "]}}]}";
  const std::string multi = R"({"type":"Feature","properties":{},"geometry":{"type":)"
                            R"("MultiPolygon","coordinates":[[)" +
                            pond + "],[" + barn + "]]}}";
  for (const auto& [name, text] : {std::pair{"features", features}, std::pair{"multi", multi}}) {
    SCOPED_TRACE(name);
    const std::string zones = out + "/" + name + ".geojson";
    std::ofstream(zones) << text;
    const std::string dir = out + "/" + name;
    const CliRun run = run_swath(
        "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --exclude " + zones +
        " -o " + dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const json s = json::parse(read_text(dir + "/summary.json"));
    EXPECT_EQ(s["area"]["no_fly_zones"], 2);
    EXPECT_GE(s["flight"]["min_no_fly_distance_m"].get<double>(), 5.0 - 1e-3);
  }
}

// A square of about 200 x 200 m (8.5400 to 8.5427 E, 47.3980 to 47.3998 N) and zone files
// beside it, written into `dir`.
struct ZoneFiles {
  std::string dir;
  std::string area;
  explicit ZoneFiles(const std::string& name) : dir(fresh_dir(name)), area(dir + "/area.geojson") {
    fs::create_directories(dir);
    std::ofstream(area) << R"({"type":"Polygon","coordinates":[[[8.54,47.398],[8.5427,47.398],)"
                           R"([8.5427,47.3998],[8.54,47.3998],[8.54,47.398]]]})";
  }
  std::string write(const std::string& file, const std::string& text) const {
    std::ofstream(dir + "/" + file) << text;
    return dir + "/" + file;
  }
  CliRun plan(const std::string& zones, const std::string& more = "") const {
    return run_swath("plan " + area + " --camera sony-ilce-qx1 --altitude 50 --exclude " + zones +
                     " " + more + " -o " + dir + "/out");
  }
};

std::string geojson_feature(const std::string& name, const std::string& geometry) {
  return R"({"type":"Feature","properties":{"name":")" + name + R"("},"geometry":)" + geometry +
         "}";
}

const std::string kPond =
    R"({"type":"Polygon","coordinates":[[[8.5415,47.3985],[8.5419,47.3985],[8.5419,47.3988],)"
    R"([8.5415,47.3988],[8.5415,47.3985]]]})";

// The latitude and longitude a message gives after `marker` ("LAT, LON (lat, lon)").
std::pair<double, double> lat_lon_after(const std::string& text, const std::string& marker) {
  const std::size_t at = text.find(marker);
  double lat = NAN, lon = NAN;
  if (at != std::string::npos)
    std::sscanf(text.c_str() + at + marker.size(), "%lf, %lf", &lat, &lon);
  return {lat, lon};
}

// A square zone file, [lon0, lon1] x [lat0, lat1].
std::string square_zone(double lon0, double lat0, double lon1, double lat1) {
  std::ostringstream s;
  s.precision(10);
  s << R"({"type":"Polygon","coordinates":[[[)" << lon0 << "," << lat0 << "],[" << lon1 << ","
    << lat0 << "],[" << lon1 << "," << lat1 << "],[" << lon0 << "," << lat1 << "],[" << lon0 << ","
    << lat0 << "]]]}";
  return s.str();
}

// Metres east and north of ZoneFiles' area's south-west corner (8.54, 47.398), near enough.
constexpr double kEast_m_per_deg = 75540, kNorth_m_per_deg = 111180;

// Distance from a point to the box [x0, x1] x [y0, y1], metres.
double to_box_m(double x, double y, double x0, double y0, double x1, double y1) {
  return std::hypot(std::max({x0 - x, 0.0, x - x1}), std::max({y0 - y, 0.0, y - y1}));
}

// --turnaround extends each line past both ends; where that would enter a zone's clearance band
// (a zone inside the area, one just past its east edge) the extension stops at the band, and
// elsewhere it is flown whole (every turnaround with a zone inside the area was refused: "item 30
// comes within 4.97 m of no-fly zone ...", or "finds no way round ... lower --clearance").
TEST(PlanCli, TurnaroundsStopAtTheZonesClearanceBand) {
  const ZoneFiles files("zones-turnaround");
  // Metres from the area's south-west corner: the middle zone 30 x 30 m, the east one 8 m past
  // the east edge (204 m), 45 m tall.
  const double mx0 = 87, my0 = 85, mx1 = 117, my1 = 115, ex0 = 212, ey0 = 45, ex1 = 230, ey1 = 90;
  auto zone = [&](const std::string& name, double x0, double y0, double x1, double y1) {
    return files.write(name,
                       square_zone(8.54 + x0 / kEast_m_per_deg, 47.398 + y0 / kNorth_m_per_deg,
                                   8.54 + x1 / kEast_m_per_deg, 47.398 + y1 / kNorth_m_per_deg));
  };
  const std::string middle = zone("middle.geojson", mx0, my0, mx1, my1);
  const std::string east = zone("east.geojson", ex0, ey0, ex1, ey1);
  const CliRun run = files.plan(middle + " --exclude " + east, "--turnaround 20 --angle 90");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json summary = json::parse(read_text(files.dir + "/out/summary.json"));
  EXPECT_GE(summary["flight"]["min_no_fly_distance_m"].get<double>(), 5.0 - 0.005);
  const json mission = json::parse(read_text(files.dir + "/out/mission.geojson"));
  double west_most_m = 0, east_free_m = 0, east_cut_m = 0;
  std::size_t ends = 0;
  for (const json& f : mission["features"]) {
    if (f["properties"].value("role", "") != "sweep") continue;
    for (const json& c : f["geometry"]["coordinates"]) {
      const double x = (c[0].get<double>() - 8.54) * kEast_m_per_deg;
      const double y = (c[1].get<double>() - 47.398) * kNorth_m_per_deg;
      ++ends;
      EXPECT_GE(to_box_m(x, y, mx0, my0, mx1, my1), 5.0 - 0.05) << x << ", " << y;
      EXPECT_GE(to_box_m(x, y, ex0, ey0, ex1, ey1), 5.0 - 0.05) << x << ", " << y;
      west_most_m = std::max(west_most_m, -x);
      if (y > ey0 && y < ey1) east_cut_m = std::max(east_cut_m, x - 204);
      if (y < ey0 - 5 || y > ey1 + 5) east_free_m = std::max(east_free_m, x - 204);
    }
  }
  ASSERT_GT(ends, 8u);
  EXPECT_NEAR(west_most_m, 20, 0.5);  // the turnaround, whole where nothing is near
  EXPECT_NEAR(east_free_m, 20, 0.5);
  EXPECT_NEAR(east_cut_m, 3, 0.5);  // beside the east zone: up to its band, 8 - 5 m
  const CliRun verify =
      run_swath("verify " + files.dir + "/out --exclude " + middle + " --exclude " + east);
  EXPECT_EQ(verify.exit_code, 0) << verify.out << verify.err;
}

// A home within a zone's clearance, or so near it that the drone stopping there at 5 m/s (5 m at
// 2.5 m/s^2) runs into the clearance, is refused naming the home, how far it is from which zone
// and what to change (the plan's check refused it as "item 1 comes within 3.35 m" or "item 76
// (its stopping margin) comes within 4.77 m", naming no home); the clearance it names plans.
TEST(PlanCli, AHomeNearAZoneIsRefusedSayingHowFar) {
  const ZoneFiles files("zones-home-near");
  const std::string middle =
      files.write("middle.geojson", square_zone(8.54115, 47.39877, 8.54155, 47.39904));
  auto home_south_of = [&](double metres) {
    std::ostringstream s;
    s.precision(10);
    s << 47.39877 - metres / kNorth_m_per_deg << ",8.54135";
    return s.str();
  };
  const std::string near = "swath plan: --home ";
  for (const double metres : {3.0, 7.8}) {
    SCOPED_TRACE(metres);
    const std::string home = home_south_of(metres);
    const CliRun run = files.plan(middle, "--home " + home);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_FALSE(fs::exists(files.dir + "/out"));
    const std::string head = near + home + " lies ";
    ASSERT_EQ(run.err.rfind(head, 0), 0u) << run.err;
    const double said_m = std::stod(run.err.substr(head.size()));
    EXPECT_NEAR(said_m, metres, 0.1) << run.err;
    const std::string why = " m from no-fly zone " + middle +
                            ", less than the 10.0 m it must keep (the 5.0 m --clearance and the "
                            "5.0 m its drone may run on past home as it stops); move --home at "
                            "least 10.0 m from the zone";
    EXPECT_NE(run.err.find(why), std::string::npos) << run.err;
    if (metres < 5) {
      EXPECT_TRUE(run.err.ends_with("at least 10.0 m from the zone\n")) << run.err;
      continue;
    }
    const std::string lower = ", or lower --clearance to ";
    const std::size_t at = run.err.find(lower);
    ASSERT_NE(at, std::string::npos) << run.err;
    const std::string clearance = run.err.substr(at + lower.size(), 3);
    EXPECT_EQ(run.err.substr(at + lower.size() + 3), " m\n");
    EXPECT_NEAR(std::stod(clearance), said_m - 5, 0.1);
    const CliRun lowered = files.plan(middle, "--home " + home + " --clearance " + clearance);
    EXPECT_EQ(lowered.exit_code, 0) << lowered.err;
  }
  const CliRun far = files.plan(middle, "--home " + home_south_of(12));
  EXPECT_EQ(far.exit_code, 0) << far.err;
}

// A zone of a file of several whose vertices lie on one line is named as every other message
// names a zone's ring ("feature 1, outer ring (ring 0)"), not as an area ("area 1, outer ring").
TEST(PlanCli, AFlatZoneOfSeveralIsNamedByItsFeature) {
  const ZoneFiles files("zones-flat");
  auto feature = [](const std::string& geometry) {
    return R"({"type":"Feature","properties":{},"geometry":)" + geometry + "}";
  };
  const std::string zones = files.write(
      "zones.geojson", R"({"type":"FeatureCollection","features":[)" +
                           feature(square_zone(8.5405, 47.3985, 8.541, 47.399)) + "," +
                           feature(R"({"type":"Polygon","coordinates":[[[8.5411,47.3985],)"
                                   R"([8.5412,47.3986],[8.5413,47.3987],[8.5411,47.3985]]]})") +
                           "]}");
  const CliRun run = files.plan(zones);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(run.err, "swath plan: " + zones +
                         ": feature 1, outer ring (ring 0) encloses no area (its vertices lie on "
                         "one line)\n");
  EXPECT_FALSE(fs::exists(files.dir + "/out"));
}

// A power line or a mast in an --exclude file beside a polygon was skipped unseen (the plan flew
// over the line): such a file is refused, naming the feature, its type and where it lies, in each
// reader a zone file can take (GeoJSON, KML, a GIS file through GDAL), nothing written.
TEST(PlanCli, ZoneFilesWithLinesOrPointsAreRefused) {
  const ZoneFiles files("zones-not-polygons");
  const std::string line = geojson_feature(
      "power line", R"({"type":"LineString","coordinates":[[8.541,47.3975],[8.541,47.4003]]})");
  const std::string mast =
      geojson_feature("mast", R"({"type":"Point","coordinates":[8.542,47.399]})");
  const std::string pond = geojson_feature("pond", kPond);
  auto collection = [](const std::string& a, const std::string& b, const std::string& c) {
    return R"({"type":"FeatureCollection","features":[)" + a + "," + b + "," + c + "]}";
  };
  const std::string kml_pond =
      "<Placemark><name>pond</name><Polygon><outerBoundaryIs><LinearRing><coordinates>8.5415,"
      "47.3985 8.5419,47.3985 8.5419,47.3988 8.5415,47.3988 8.5415,47.3985</coordinates>"
      "</LinearRing></outerBoundaryIs></Polygon></Placemark>";
  const std::string track =
      "<trk><name>pond</name><trkseg><trkpt lat=\"47.3985\" lon=\"8.5415\"/><trkpt "
      "lat=\"47.3985\" lon=\"8.5419\"/><trkpt lat=\"47.3988\" lon=\"8.5419\"/><trkpt "
      "lat=\"47.3988\" lon=\"8.5415\"/><trkpt lat=\"47.3985\" lon=\"8.5415\"/></trkseg></trk>";
  const std::string gpx_head =
      "<?xml version=\"1.0\"?><gpx version=\"1.1\" creator=\"test\" "
      "xmlns=\"http://www.topografix.com/GPX/1/1\">";
  struct Case {
    std::string file, text, feature, type;
    double lat, lon;
  };
  const std::vector<Case> cases{
      {"line.geojson", collection(pond, line, mast), "feature 1 (\"power line\")", "LineString",
       47.3975, 8.541},
      {"point.geojson", collection(mast, pond, line), "feature 0 (\"mast\")", "Point", 47.399,
       8.542},
      {"line.kml",
       "<?xml version=\"1.0\"?><kml xmlns=\"http://www.opengis.net/kml/2.2\"><Document>" +
           kml_pond +
           "<Placemark><name>power line</name><LineString><coordinates>8.541,47.3975 "
           "8.541,47.4003</coordinates></LineString></Placemark></Document></kml>",
       "feature 1 (\"power line\")", "LineString", 47.3975, 8.541},
      {"mast.gpx",
       gpx_head + "<wpt lat=\"47.399\" lon=\"8.542\"><name>mast</name></wpt>" + track + "</gpx>",
       "feature 0 (\"mast\") of layer \"waypoints\"", "Point", 47.399, 8.542}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string zones = files.write(c.file, c.text);
    const CliRun run = files.plan(zones);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    const std::string said = zones + ": " + c.feature + " is a " + c.type;
    EXPECT_NE(run.err.find(said), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("; a no-fly zone must be a polygon (buffer lines and points into "
                           "polygons first)"),
              std::string::npos)
        << run.err;
    const auto [lat, lon] =
        lat_lon_after(run.err, said + (c.type == "Point" ? " at " : " starting at "));
    EXPECT_NEAR(lat, c.lat, 1e-6) << run.err;
    EXPECT_NEAR(lon, c.lon, 1e-6) << run.err;
    EXPECT_FALSE(fs::exists(files.dir + "/out"));
  }
  // The GPX track alone is a zone: its track points (a layer GDAL derives) are no features.
  const CliRun run = files.plan(files.write("pond.gpx", gpx_head + track + "</gpx>"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(json::parse(read_text(files.dir + "/out/summary.json"))["area"]["no_fly_zones"], 1);
}

// A bow-tie zone, or one with a spike out and back along one line, was planned and then blamed
// on swath's own files by the preflight check: refused up front with the crossing's place, as an
// area's crossing is; in a file of several zones, the feature is named.
TEST(PlanCli, SelfCrossingZonesAreRefusedWithTheCrossing) {
  const ZoneFiles files("zones-crossing");
  const std::string bowtie =
      R"({"type":"Polygon","coordinates":[[[8.541,47.3985],[8.542,47.399],[8.542,47.3985],)"
      R"([8.541,47.399],[8.541,47.3985]]]})";
  const std::string spike =
      R"({"type":"Polygon","coordinates":[[[8.541,47.3985],[8.542,47.3985],[8.542,47.399],)"
      R"([8.5415,47.399],[8.5415,47.3995],[8.5415,47.399],[8.541,47.399],[8.541,47.3985]]]})";
  const std::string both = R"({"type":"FeatureCollection","features":[)" +
                           geojson_feature("pond", kPond) + "," +
                           geojson_feature("bowtie", bowtie) + "]}";
  struct Case {
    std::string file, text, named;
    double lat_lo, lat_hi, lon;
  };
  const std::vector<Case> cases{
      {"bowtie.geojson", bowtie, "bowtie.geojson", 47.39875, 47.39875, 8.5415},
      {"spike.geojson", spike, "spike.geojson", 47.399, 47.3995, 8.5415},
      {"two.geojson", both, "two.geojson feature 1", 47.39875, 47.39875, 8.5415}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const CliRun run = files.plan(files.write(c.file, c.text));
    EXPECT_EQ(run.exit_code, 2) << run.err;
    const std::string said = files.dir + "/" + c.named + ": the no-fly zone crosses itself at ";
    ASSERT_NE(run.err.find(said), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find("preflight"), std::string::npos) << run.err;
    const auto [lat, lon] = lat_lon_after(run.err, said);
    EXPECT_GE(lat, c.lat_lo - 1e-6) << run.err;
    EXPECT_LE(lat, c.lat_hi + 1e-6) << run.err;
    EXPECT_NEAR(lon, c.lon, 1e-6) << run.err;
    EXPECT_FALSE(fs::exists(files.dir + "/out"));
  }
}

// A home inside a zone or on its edge was refused as a leg that "finds no way round": it is
// named as the problem, up front.
TEST(PlanCli, AHomeInOrOnAZoneIsRefused) {
  const ZoneFiles files("zones-home");
  const std::string zone = files.write(
      "zone.geojson",
      R"({"type":"Polygon","coordinates":[[[8.5405,47.3985],[8.541,47.3985],[8.541,47.399],)"
      R"([8.5405,47.399],[8.5405,47.3985]]]})");
  for (const std::string home : {"47.39875,8.54075", "47.3985,8.5405", "47.39875,8.541"}) {
    SCOPED_TRACE(home);
    const CliRun run = files.plan(zone, "--home " + home);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_EQ(run.err, "swath plan: --home " + home +
                           " lies inside (or on the edge of) no-fly zone " + zone +
                           "; give a home outside the zones\n");
    EXPECT_FALSE(fs::exists(files.dir + "/out"));
  }
}

// Without --home, the home was the area's south-west-most vertex even where a zone cut the area
// there (the take-off on the zone's edge, refused by the preflight check): it is the
// south-west-most vertex that keeps the clearance, or the area is refused saying why.
TEST(PlanCli, TheDefaultHomeKeepsTheClearanceFromTheZones) {
  const ZoneFiles files("zones-default-home");
  const std::string west = files.write(
      "west.geojson",
      R"({"type":"Polygon","coordinates":[[[8.5395,47.3975],[8.542,47.3975],[8.542,47.4003],)"
      R"([8.5395,47.4003],[8.5395,47.3975]]]})");
  const CliRun run = files.plan(west);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(files.dir + "/out/summary.json"));
  EXPECT_NEAR(s["home"]["lat_deg"].get<double>(), 47.398, 1e-9);  // the south-east corner
  EXPECT_NEAR(s["home"]["lon_deg"].get<double>(), 8.5427, 1e-9);
  EXPECT_GE(s["flight"]["min_no_fly_distance_m"].get<double>(), 5.0 - 1e-6);
  // Four small zones about 3 m in from the four corners: no vertex keeps 5 m.
  std::string corners = R"({"type":"MultiPolygon","coordinates":[)";
  const double lons[] = {8.54003, 8.54254}, lats[] = {47.39802, 47.39969};
  for (int k = 0; k < 4; ++k) {
    const double x = lons[k % 2], y = lats[k / 2];
    std::ostringstream r;
    r.precision(10);
    r << (k ? "," : "") << "[[[" << x << "," << y << "],[" << x + 0.00013 << "," << y << "],["
      << x + 0.00013 << "," << y + 0.00009 << "],[" << x << "," << y + 0.00009 << "],[" << x << ","
      << y << "]]]";
    corners += r.str();
  }
  const CliRun refused = files.plan(files.write("corners.geojson", corners + "]}"));
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_EQ(refused.err, "swath plan: " + files.area +
                             ": every vertex of the area lies within 5.0 m (--clearance) of a "
                             "no-fly zone, so none can be the default home; give --home LAT,LON "
                             "clear of the zones, or lower --clearance\n");
}

// A wide clearance round a zone keeps the lines off much of the area: the warning names the
// clearance first (it blamed narrow or pointed parts alone), and summary.json's coverage is the
// share the warning gives.
TEST(PlanCli, CoverageLostToAZonesClearanceIsSaidSo) {
  const std::string out = fresh_dir("zones-clearance-coverage");
  const CliRun run = run_swath(
      "plan share/fields/meadow.geojson --camera sony-ilce-qx1 --altitude 50 --exclude "
      "share/zones/meadow-pond.geojson --clearance 60 -o " +
      out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json s = json::parse(read_text(out + "/summary.json"));
  const double covered = s["coverage"]["covered_fraction"].get<double>();
  ASSERT_LT(covered, 0.95);
  EXPECT_NE(run.err.find("warning: the photos cover " + base::fixed_text(100 * covered, 2) +
                         " % of the area"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("the lines keep --clearance (60.0 m) from the holes and no-fly zones, "
                         "or parts of it"),
            std::string::npos)
      << run.err;
}

}  // namespace
}  // namespace swath::test
