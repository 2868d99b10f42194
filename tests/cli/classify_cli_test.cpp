// `swath classify`: this input gives this output, and these bad inputs give these messages.
#include <gtest/gtest.h>

#include <GeographicLib/PolygonArea.hpp>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace swath::test {
namespace {

using nlohmann::json;

json classify_json(const std::string& args) {
  const CliRun run = run_swath("classify " + args + " --json");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  return json::parse(run.out);
}

TEST(ClassifyCli, LocalYardMatchesClosedForms) {
  // 120 x 80 rectangle with a 120 x 30 gable: area 9600 + 1800, centroid y (9600*40 +
  // 1800*90)/11400.
  const json j = classify_json("share/fields/yard-local.csv --local");
  EXPECT_EQ(j["type"], "convex");
  EXPECT_EQ(j["vertices"], 5);
  EXPECT_DOUBLE_EQ(j["area_m2"].get<double>(), 11400.0);
  EXPECT_NEAR(j["perimeter_m"].get<double>(), 280.0 + 2 * std::hypot(60.0, 30.0), 1e-4);
  EXPECT_NEAR(j["centroid"]["x_m"].get<double>(), 60.0, 1e-4);
  EXPECT_NEAR(j["centroid"]["y_m"].get<double>(), (9600 * 40.0 + 1800 * 90.0) / 11400, 1e-4);
  EXPECT_FALSE(j["centroid"].contains("lat_deg"));
  EXPECT_DOUBLE_EQ(j["min_height_m"].get<double>(), 110.0);
  EXPECT_DOUBLE_EQ(j["sweep_angle_local_deg"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["sweep_bearing_deg"].get<double>(), 90.0);
  EXPECT_TRUE(j["reflex_vertices"].empty());
  EXPECT_TRUE(j["crossing"].is_null());
}

TEST(ClassifyCli, MeadowAreaAgreesWithTheGeodesicArea) {
  const json j = classify_json("share/fields/meadow.geojson");
  EXPECT_EQ(j["type"], "convex");
  EXPECT_EQ(j["vertices"], 5);
  // Independent truth: GeographicLib's geodesic polygon area of the file's coordinates.
  GeographicLib::PolygonArea geodesic(GeographicLib::Geodesic::WGS84());
  for (auto [lon, lat] : {std::pair{8.54010, 47.39702},
                          {8.54452, 47.39741},
                          {8.54498, 47.39935},
                          {8.54236, 47.40021},
                          {8.53987, 47.39904}})
    geodesic.AddPoint(lat, lon);
  double perimeter = 0, area = 0;
  geodesic.Compute(false, true, perimeter, area);
  EXPECT_NEAR(j["area_m2"].get<double>(), std::abs(area), 1e-5 * std::abs(area));
  EXPECT_NEAR(j["perimeter_m"].get<double>(), perimeter, 1e-5 * perimeter);
  EXPECT_NEAR(j["centroid"]["lat_deg"].get<double>(), 47.3985, 0.0005);
  EXPECT_NEAR(j["centroid"]["lon_deg"].get<double>(), 8.5424, 0.0005);
  const double bearing = j["sweep_bearing_deg"].get<double>();
  const double angle = j["sweep_angle_local_deg"].get<double>();
  EXPECT_NEAR(std::fmod(bearing + angle, 180.0), 90.0, 1e-5);
}

TEST(ClassifyCli, VineyardWithPondIsConcaveWithTheHoleCornersReflex) {
  const json j = classify_json("share/fields/vineyard.kml");
  EXPECT_EQ(j["type"], "concave");
  EXPECT_EQ(j["holes"], 1);
  ASSERT_EQ(j["reflex_vertices"].size(), 5u);
  EXPECT_EQ(j["reflex_vertices"][0]["ring"], 0);
  EXPECT_EQ(j["reflex_vertices"][0]["position"], 3);
  EXPECT_NEAR(j["reflex_vertices"][0]["lat_deg"].get<double>(), 46.23018, 1e-8);
  EXPECT_NEAR(j["reflex_vertices"][0]["lon_deg"].get<double>(), 7.59460, 1e-8);
  for (int k = 1; k < 5; ++k) {
    EXPECT_EQ(j["reflex_vertices"][k]["ring"], 1);
    EXPECT_EQ(j["reflex_vertices"][k]["position"], k - 1);
  }
}

TEST(ClassifyCli, BowtieIsReportedWithItsCrossingAndExitsZero) {
  const json j = classify_json("share/fields/bowtie.geojson");
  EXPECT_EQ(j["type"], "self-intersecting");
  EXPECT_TRUE(j["area_m2"].is_null());
  EXPECT_EQ(j["crossing"]["edge_a"]["from_position"], 0);
  EXPECT_EQ(j["crossing"]["edge_a"]["to_position"], 1);
  EXPECT_EQ(j["crossing"]["edge_b"]["from_position"], 2);
  EXPECT_EQ(j["crossing"]["edge_b"]["to_position"], 3);
  EXPECT_NEAR(j["crossing"]["point"]["lat_deg"].get<double>(), 48.13825, 1e-6);
  EXPECT_NEAR(j["crossing"]["point"]["lon_deg"].get<double>(), 11.577, 1e-9);
}

TEST(ClassifyCli, TextReportGivesTheSameFigures) {
  const CliRun run = run_swath("classify share/fields/yard-local.csv --local");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_NE(run.out.find("share/fields/yard-local.csv: convex area\n"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("  area             11400.00 m² (1.1400 ha)\n"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find(
                "  min height       110.00 m, sweep lines at bearing 90.00° (0.00° CCW from east)"),
            std::string::npos)
      << run.out;
  const CliRun orchard = run_swath("classify share/fields/orchard.csv");
  EXPECT_NE(orchard.out.find("reflex vertices  2\n"), std::string::npos) << orchard.out;
  EXPECT_NE(orchard.out.find("outer ring position 3 at 52.4053000, -0.9480000 (lat, lon)"),
            std::string::npos);
  const CliRun bowtie = run_swath("classify share/fields/bowtie.geojson");
  EXPECT_EQ(bowtie.exit_code, 0);
  EXPECT_NE(
      bowtie.out.find(
          "the outer ring's edge 0-1 meets the outer ring's edge 2-3 at 48.1382500, 11.5770000"),
      std::string::npos)
      << bowtie.out;
}

// Google Earth names every new polygon "Untitled Polygon": a name that several areas share is
// refused naming their positions (it planned the last of them), and a position chooses one.
TEST(ClassifyCli, ANameSharedByAreasIsRefusedNamingTheirPositions) {
  const std::string dir = fresh_dir("classify-dupnames");
  std::filesystem::create_directories(dir);
  const std::string triangle = "8.5401,47.39702 8.54452,47.39741 8.54498,47.39935 8.5401,47.39702";
  const std::string second = "8.5501,47.39702 8.55452,47.39741 8.55498,47.39935 8.5501,47.39702";
  const auto placemark = [](const std::string& ring) {
    return "<Placemark><name>Untitled Polygon</name><Polygon><outerBoundaryIs><LinearRing>"
           "<coordinates>" +
           ring + "</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>";
  };
  std::ofstream(dir + "/untitled.kml")
      << R"(<?xml version="1.0"?><kml xmlns="http://www.opengis.net/kml/2.2"><Document>)" +
             placemark(triangle) + placemark(second) + placemark(triangle) + "</Document></kml>";
  const std::string file = dir + "/untitled.kml";
  {
    const CliRun run = run_swath("classify " + file + " --feature 'Untitled Polygon'");
    EXPECT_EQ(run.exit_code, 2) << run.out;
    EXPECT_NE(run.err.find(file + ": 3 areas of layer \"untitled\" are named \"Untitled "
                                  "Polygon\" (positions 0, 1, 2); give the position (0-based) "
                                  "instead, e.g. --feature 0"),
              std::string::npos)
        << run.err;
    const json chosen = classify_json(file + " --feature 1");
    EXPECT_NEAR(chosen["centroid"]["lon_deg"].get<double>(), 8.5532, 1e-3);
  }
  const std::string out = dir + "/plan";
  const CliRun plan = run_swath("plan " + dir + "/untitled.kml --feature 'Untitled Polygon' " +
                                "--camera sony-ilce-qx1 --altitude 60 -o " + out);
  EXPECT_EQ(plan.exit_code, 2) << plan.err;
  EXPECT_NE(plan.err.find("(positions 0, 1, 2); give the position (0-based) instead"),
            std::string::npos)
      << plan.err;
  EXPECT_FALSE(std::filesystem::exists(out) && !std::filesystem::is_empty(out));
}

TEST(ClassifyCli, SameInputSameBytes) {
  EXPECT_EQ(run_swath("classify share/fields/vineyard.kml --json").out,
            run_swath("classify share/fields/vineyard.kml --json").out);
}

struct BadInput {
  std::string name;
  std::string args;
  std::string fragment;
  friend void PrintTo(const BadInput& b, std::ostream* os) { *os << "swath classify " << b.args; }
};

class ClassifyBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(ClassifyBadInput, ExitsTwoWithOneSentenceNamingFileAndPlace) {
  const CliRun run = run_swath("classify " + GetParam().args);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(run.out, "") << "no partial output";
  EXPECT_NE(run.err.find(GetParam().fragment), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << "one line: " << run.err;
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, ClassifyBadInput,
    ::testing::Values(
        BadInput{"missing", "tests/fixtures/missing.geojson",
                 "swath classify: tests/fixtures/missing.geojson: cannot open the area file"},
        BadInput{"empty", "tests/fixtures/empty.geojson",
                 "tests/fixtures/empty.geojson: the file is empty"},
        BadInput{"truncated_json", "tests/fixtures/truncated.geojson",
                 "truncated.geojson: line 1, column 89: invalid JSON"},
        BadInput{"broken_kml", "tests/fixtures/broken.kml",
                 "broken.kml: line 4, column 3: invalid XML"},
        BadInput{"point", "tests/fixtures/point.geojson",
                 "point.geojson: the GeoJSON's geometry is a Point; an area must be a Polygon"},
        BadInput{"two_vertices", "tests/fixtures/two-vertices.csv",
                 "two-vertices.csv: outer ring (ring 0) has 2 distinct vertices"},
        BadInput{"collinear", "tests/fixtures/collinear.csv",
                 "collinear.csv: outer ring (ring 0) encloses no area"},
        BadInput{"nan", "tests/fixtures/nan.csv",
                 "nan.csv: outer ring (ring 0), position 2 (line 4): coordinate is not a finite"},
        BadInput{"latitude", "tests/fixtures/latitude.csv",
                 "latitude.csv: outer ring (ring 0), position 2 (line 4): latitude 91"},
        BadInput{"hole_outside", "tests/fixtures/hole-outside.geojson",
                 "hole 0 (ring 1) is a hole that lies outside the outer ring"},
        BadInput{"directory", "share", "share: is a directory"},
        BadInput{"unknown_type", "README.md", "unknown file type '.md'"},
        BadInput{"no_field", "", "FIELD is required"},
        BadInput{"unknown_flag", "share/fields/meadow.geojson --bogus", "--bogus"}),
    [](const ::testing::TestParamInfo<BadInput>& param_info) { return param_info.param.name; });

TEST(SwathCli, HelpDocumentsCommandsAndExitCodes) {
  const CliRun top = run_swath("--help");
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_NE(top.out.find("classify"), std::string::npos);
  EXPECT_NE(top.out.find("Exit codes: 0 success; 2 bad input"), std::string::npos) << top.out;
  const CliRun sub = run_swath("classify --help");
  EXPECT_EQ(sub.exit_code, 0);
  EXPECT_NE(sub.out.find("--json"), std::string::npos);
  EXPECT_NE(sub.out.find("--local"), std::string::npos);
  EXPECT_EQ(run_swath("").exit_code, 2);
  EXPECT_EQ(run_swath("frobnicate").exit_code, 2);
}

}  // namespace
}  // namespace swath::test
