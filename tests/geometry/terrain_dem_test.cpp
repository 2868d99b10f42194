// Terrain following over DEMs GDAL itself writes (docs/swath-plan.md): GeoTIFFs in UTM 32N
// of closed-form grounds (a slope, a ridge, a pit). The reader is checked against the closed form
// at the UTM coordinates GeographicLib computes (independent of PROJ, which the reader uses);
// the plans are checked by sampling that closed form along every leg as flown: the height above
// ground stays within the tolerance everywhere, and equals the altitude asked for at every
// waypoint.
#include <gdal.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>
#include <unistd.h>

#include <GeographicLib/UTMUPS.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>

#include "meadow_survey.hpp"
#include "swath/base/input_error.hpp"
#include "swath/geometry/ground.hpp"
#include "swath/planning/survey.hpp"
#include "swath/planning/survey_files.hpp"

namespace swath::geometry {
namespace {

namespace fs = std::filesystem;
using Surface = std::function<double(double east_m, double north_m)>;

fs::path dem_scratch() {
  const fs::path dir =
      fs::temp_directory_path() / ("swath-terrain-dem-test-" + std::to_string(::getpid()));
  static bool once = [&] {
    fs::remove_all(dir);
    fs::create_directories(dir);
    return true;
  }();
  (void)once;
  return dir;
}

struct Utm {
  double east_m = 0, north_m = 0;
};

Utm utm32(double lat_deg, double lon_deg) {
  int zone = 0;
  bool north = true;
  Utm u;
  GeographicLib::UTMUPS::Forward(lat_deg, lon_deg, zone, north, u.east_m, u.north_m, 32);
  return u;
}

// The meadow's centre in UTM 32N: the surfaces are centred there.
const Utm kCentre = utm32(47.3986, 8.5424);

// A GeoTIFF (EPSG:32632) of `f` at pixel centres, `pixel_m` pixels over a square of `half_m`
// around the centre; pixels where `hole` says so are nodata.
fs::path write_dem(const std::string& name, const Surface& f, double pixel_m = 2.0,
                   double half_m = 1500.0, const std::function<bool(double, double)>& hole = {},
                   const char* unit = "", double per_metre = 1.0) {
  GDALAllRegister();
  const fs::path path = dem_scratch() / (name + ".tif");
  const int n = static_cast<int>(2 * half_m / pixel_m);
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* d = gtiff->Create(path.c_str(), n, n, 1, GDT_Float32, nullptr);
  const double x0 = kCentre.east_m - half_m, y0 = kCentre.north_m + half_m;
  double gt[6] = {x0, pixel_m, 0, y0, 0, -pixel_m};
  d->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(32632);
  d->SetSpatialRef(&srs);
  GDALRasterBand* band = d->GetRasterBand(1);
  band->SetNoDataValue(-9999);
  band->SetUnitType(unit);
  std::vector<float> row(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double e = x0 + (i + 0.5) * pixel_m, no = y0 - (j + 0.5) * pixel_m;
      row[static_cast<std::size_t>(i)] =
          hole && hole(e - kCentre.east_m, no - kCentre.north_m)
              ? -9999.0F
              : static_cast<float>(per_metre * f(e - kCentre.east_m, no - kCentre.north_m));
    }
    EXPECT_EQ(band->RasterIO(GF_Write, 0, j, n, 1, row.data(), n, 1, GDT_Float32, 0, 0), CE_None);
  }
  GDALClose(d);
  return path;
}

double at(const Surface& f, const GeoPoint& g) {
  const Utm u = utm32(g.lat_deg, g.lon_deg);
  return f(u.east_m - kCentre.east_m, u.north_m - kCentre.north_m);
}

const Surface kSlope = [](double e, double n) { return 420.0 + 0.08 * e - 0.05 * n; };
// A ridge running north-north-east across the field, 40 m high, and a pit 30 m deep.
const Surface kRidge = [](double e, double n) {
  const double d = 0.97 * e - 0.24 * n;
  return 400.0 + 40.0 * std::exp(-d * d / (2 * 60.0 * 60.0));
};
const Surface kPit = [](double e, double n) {
  return 380.0 - 30.0 * std::exp(-(e * e + n * n) / (2 * 70.0 * 70.0));
};

TEST(DemGround, AGeoTiffInUtmGivesTheSurfaceAtEveryPoint) {
  const auto ground = dem_ground(write_dem("slope", kSlope).string());
  EXPECT_NEAR(ground->resolution_m(), 1.0, 1e-9);  // half the 2 m pixel
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> lat(47.390, 47.406), lon(8.530, 8.555);
  std::vector<GeoPoint> points;
  for (int k = 0; k < 500; ++k) points.push_back({lat(rng), lon(rng), 0});
  const std::vector<double> h = ground->heights_m(points);
  ASSERT_EQ(h.size(), points.size());
  // A plane: bilinear interpolation is exact, so what is left is PROJ against GeographicLib.
  for (std::size_t k = 0; k < points.size(); ++k)
    EXPECT_NEAR(h[k], at(kSlope, points[k]), 1e-3) << k;
}

TEST(DemGround, HeightsInFeetComeBackInMetresAndAnUnknownUnitIsRefused) {
  const auto ft = dem_ground(write_dem("feet", kSlope, 2.0, 1500.0, {}, "ft", 1 / 0.3048).string());
  const auto us = dem_ground(
      write_dem("us-feet", kSlope, 2.0, 1500.0, {}, "US survey foot", 3937.0 / 1200.0).string());
  const GeoPoint p{47.3990, 8.5430, 0};
  EXPECT_NEAR(ft->heights_m({p})[0], at(kSlope, p), 1e-3);
  EXPECT_NEAR(us->heights_m({p})[0], at(kSlope, p), 1e-3);
  EXPECT_THROW(dem_ground(write_dem("fathoms", kSlope, 2.0, 1500.0, {}, "fathom").string()),
               base::InputError);
}

TEST(DemGround, OutsideTheRasterAndNextToNodataThereIsNoHeight) {
  const auto ground = dem_ground(write_dem("holey", kSlope, 2.0, 1500.0, [](double e, double n) {
                                   return std::abs(e - 200) < 10 && std::abs(n) < 10;
                                 }).string());
  const GeoPoint far{47.6, 8.54, 0};  // 22 km north
  const std::vector<double> h = ground->heights_m({far, {47.3986, 8.5424, 0}});
  EXPECT_TRUE(std::isnan(h[0]));
  EXPECT_FALSE(std::isnan(h[1]));
  // The hole: 200 m east of the centre.
  const double lon_200 = 8.5424 + 200 / (111'320.0 * std::cos(47.3986 * M_PI / 180));
  EXPECT_TRUE(std::isnan(ground->heights_m({{47.3986, lon_200, 0}})[0]));
}

TEST(DemGround, BadFilesAreRefusedNamingThem) {
  const fs::path text = dem_scratch() / "not-a-dem.tif";
  { std::ofstream(text) << "hello"; }
  for (const std::string& path : {text.string(), (dem_scratch() / "absent.tif").string(),
                                  std::string(SWATH_SOURCE_DIR) + "/share/fields/meadow.geojson"}) {
    try {
      dem_ground(path);
      ADD_FAILURE() << path << " accepted";
    } catch (const base::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

// An ESRI ASCII grid in UTM metres whose .prj was left behind is read as degrees: it said "the
// DEM has no height at" the home, as if the DEM missed the area. One in degrees still reads.
TEST(DemGround, AProjectedGridWithoutItsPrjIsRefusedAsHavingNoCrs) {
  const fs::path utm = dem_scratch() / "utm-no-prj.asc";
  std::ofstream(utm) << "ncols 2\nnrows 2\nxllcorner " << kCentre.east_m << "\nyllcorner "
                     << kCentre.north_m << "\ncellsize 5\nNODATA_value -9999\n400 400\n400 400\n";
  try {
    dem_ground(utm.string())->heights_m({{47.3986, 8.5424}});
    ADD_FAILURE() << "read";
  } catch (const base::InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(utm.string() + ": the DEM has no coordinate reference system", 0), 0u) << m;
    EXPECT_NE(m.find("give its CRS in a .prj file beside it"), std::string::npos) << m;
  }
  const fs::path degrees = dem_scratch() / "degrees-no-prj.asc";
  std::ofstream(degrees) << "ncols 2\nnrows 2\nxllcorner 8.54\nyllcorner 47.39\ncellsize 0.01\n"
                            "NODATA_value -9999\n400 400\n400 400\n";
  EXPECT_NEAR(dem_ground(degrees.string())->heights_m({{47.40, 8.55}}).at(0), 400.0, 1e-9);
}

TEST(DemGround, EllipsoidalHeightsLoseTheEgm96Undulation) {
  // EGM96 at (0, 0): N = 17.16 m (NGA's published value); the 15' grid interpolates it.
  EXPECT_NEAR(geoid_undulation_m({{0, 0, 0}})[0], 17.16, 0.05);
  const GeoPoint zurich{47.3986, 8.5424, 0};
  const double n = geoid_undulation_m({zurich})[0];
  EXPECT_GT(n, 46.0);  // Central Europe: the geoid is ~47 m above the ellipsoid
  EXPECT_LT(n, 49.0);
  const fs::path dem = write_dem("ellipsoidal", [](double, double) { return 500.0; });
  const double h = dem_ground(dem.string(), DemHeights::ellipsoid)->heights_m({zurich})[0];
  EXPECT_NEAR(h, 500.0 - n, 1e-9);
}

// Every flight of the plan over `f`: each waypoint at `agl` above the ground, and every 0.5 m of
// every leg after take-off within the tolerance of it (plus the DEM's bilinear error, < 0.01 m
// for these surfaces at 2 m pixels). Returns the waypoints added.
std::size_t check_plan(const Surface& f, const std::string& name, double tolerance_m,
                       double pixel_m = 2.0, double half_m = 1500.0,
                       std::vector<GeoPoint>* flown = nullptr) {
  planning::SurveyRequest r = test::meadow_request(60);
  r.terrain = planning::TerrainRequest{dem_ground(write_dem(name, f, pixel_m, half_m).string()),
                                       tolerance_m, planning::AltitudeFrame::relative};
  const planning::SurveyPlan plan = planning::plan_survey(r);
  const LocalFrame& frame = *plan.request.field.frame;
  EXPECT_TRUE(plan.terrain.has_value());
  for (const planning::DronePlan& d : plan.drones) {
    const double home_ground = at(f, frame.to_geo(d.mission.home));
    if (flown) flown->push_back(frame.to_geo(d.mission.home));
    std::optional<planning::MissionItem> prev;
    for (const planning::MissionItem& item : d.mission.items) {
      if (item.kind != planning::ItemKind::waypoint) continue;
      if (flown) flown->push_back(frame.to_geo(item.position));
      const double ground = at(f, frame.to_geo(item.position));
      EXPECT_NEAR(item.altitude_m + home_ground - ground, 60.0, 0.01) << name;
      EXPECT_NEAR(item.altitude_amsl_m, ground + 60.0, 0.01) << name;
      if (prev) {
        const Point2 a = prev->position, b = item.position;
        const double length = std::hypot(b.x - a.x, b.y - a.y);
        const int n = std::max(1, static_cast<int>(length / 0.5));
        for (int k = 0; k <= n; ++k) {
          const double t = static_cast<double>(k) / n;
          const Point2 p{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
          const double flown_amsl_m =
              home_ground + prev->altitude_m + t * (item.altitude_m - prev->altitude_m);
          const double agl = flown_amsl_m - at(f, frame.to_geo(p));
          EXPECT_LE(std::abs(agl - 60.0), tolerance_m + 0.01)
              << name << " at " << p.x << "," << p.y;
        }
      }
      prev = item;
    }
  }
  EXPECT_GE(plan.terrain->agl_min_m, 60.0 - tolerance_m - 1e-9);
  EXPECT_LE(plan.terrain->agl_max_m, 60.0 + tolerance_m + 1e-9);
  return plan.terrain->waypoints_added;
}

TEST(TerrainPlan, ASlopesLegsNeedNoWaypointsAndARidgeAndAPitGetThemWithinTheTolerance) {
  // A plane under a straight leg: linear, no waypoint within the legs. One is added: above home,
  // ending the way home, which RTL's level flight at the last height would not keep over a slope.
  EXPECT_EQ(check_plan(kSlope, "plan-slope", 1.0), 1u);
  const std::size_t ridge_2 = check_plan(kRidge, "plan-ridge", 2.0);
  const std::size_t ridge_05 = check_plan(kRidge, "plan-ridge-fine", 0.5);
  const std::size_t pit = check_plan(kPit, "plan-pit", 2.0);
  EXPECT_GT(ridge_2, 10u);
  EXPECT_GT(ridge_05, ridge_2);  // a tighter tolerance needs more waypoints
  EXPECT_GT(pit, 4u);
}

TEST(TerrainPlan, ALandingFliesHomeOverTheGroundAndDescendsFromAboveHome) {
  planning::SurveyRequest r = test::meadow_request(60);
  r.land = true;
  r.terrain = planning::TerrainRequest{dem_ground(write_dem("land", kPit).string()), 2.0,
                                       planning::AltitudeFrame::relative};
  const planning::SurveyPlan plan = planning::plan_survey(r);
  const auto& items = plan.drones.at(0).mission.items;
  std::size_t land = 0;
  while (land < items.size() && items[land].kind != planning::ItemKind::land) ++land;
  ASSERT_LT(land, items.size());
  std::size_t before = land;
  while (before > 0 && items[before - 1].kind != planning::ItemKind::waypoint) --before;
  ASSERT_GT(before, 0u);
  const planning::MissionItem& last = items[before - 1];
  EXPECT_NEAR(std::hypot(last.position.x - plan.drones[0].mission.home.x,
                         last.position.y - plan.drones[0].mission.home.y),
              0.0, 1e-6);
  EXPECT_NEAR(last.altitude_m, 60.0, 1e-9);  // above home, which is the ground there
}

TEST(TerrainPlan, TheFramesWriteTheirAltitudes) {
  planning::SurveyRequest r = test::meadow_request(60);
  const auto ground = dem_ground(write_dem("frames", kRidge).string());
  for (const auto frame : {planning::AltitudeFrame::relative, planning::AltitudeFrame::amsl,
                           planning::AltitudeFrame::terrain}) {
    r.terrain = planning::TerrainRequest{ground, 2.0, frame};
    const planning::SurveyPlan plan = planning::plan_survey(r);
    const auto flights = planning::flights_of(plan);
    const std::string wpl = planning::wpl_110(plan, flights.at(0));
    // Row 0: the home at the ground's height above sea level; then the items.
    std::istringstream in(wpl);
    std::string line;
    std::getline(in, line);
    std::vector<std::vector<double>> rows;
    while (std::getline(in, line)) {
      std::istringstream cells(line);
      std::vector<double> row;
      for (double v; cells >> v;) row.push_back(v);
      rows.push_back(row);
    }
    const double home_ground = at(kRidge, plan.drones[0].home_geo);
    EXPECT_NEAR(rows.at(0)[10], home_ground, 0.01);
    const int want_frame = frame == planning::AltitudeFrame::relative ? 3
                           : frame == planning::AltitudeFrame::amsl   ? 0
                                                                      : 10;
    int waypoints = 0;
    for (std::size_t k = 1; k < rows.size(); ++k) {
      if (rows[k][3] != 16) continue;  // NAV_WAYPOINT
      ++waypoints;
      EXPECT_EQ(rows[k][2], want_frame);
      const double under = at(kRidge, {rows[k][8], rows[k][9], 0});
      const double agl = frame == planning::AltitudeFrame::relative
                             ? rows[k][10] + home_ground - under
                         : frame == planning::AltitudeFrame::amsl ? rows[k][10] - under
                                                                  : rows[k][10];
      EXPECT_NEAR(agl, 60.0, 0.02) << "row " << k;
    }
    EXPECT_GT(waypoints, 20);
    const std::string kml = planning::mission_kml(plan);
    EXPECT_NE(kml.find(frame == planning::AltitudeFrame::terrain ? "<altitudeMode>relativeToGround"
                                                                 : "<altitudeMode>absolute"),
              std::string::npos);
  }
}

TEST(TerrainPlan, ADemThatMissesTheAreaIsRefusedWithThePlace) {
  planning::SurveyRequest r = test::meadow_request(60);
  r.terrain = planning::TerrainRequest{dem_ground(write_dem("small", kSlope, 2.0, 100.0).string()),
                                       2.0, planning::AltitudeFrame::relative};
  try {
    planning::plan_survey(r);
    ADD_FAILURE() << "planned";
  } catch (const base::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the DEM has no height at ("), std::string::npos)
        << e.what();
  }
}

// A DEM much finer and larger than the area (0.5 m pixels over 1.2 km, 5.8 million pixels) is
// read only where the flights go: the tiles read lie in the UTM box of every waypoint and home,
// grown by a tile and its rim on each side (the bilinear samples and the neighbour check reach a
// pixel beyond), and the plan is still exact. Bounded by the reads, not by a time.
TEST(TerrainPlan, AFineDemIsReadOnlyWhereTheFlightsGo) {
  constexpr double kPixel_m = 0.5, kHalf_m = 600.0;
  std::vector<GeoPoint> flown;
  check_plan(kRidge, "fine", 2.0, kPixel_m, kHalf_m, &flown);
  const DemReads reads = dem_reads((dem_scratch() / "fine.tif").string());
  ASSERT_FALSE(flown.empty());
  double west = 1e300, east = -1e300, south = 1e300, north = -1e300;
  for (const GeoPoint& g : flown) {
    const Utm u = utm32(g.lat_deg, g.lon_deg);
    west = std::min(west, u.east_m), east = std::max(east, u.east_m);
    south = std::min(south, u.north_m), north = std::max(north, u.north_m);
  }
  constexpr double kGrow_m = (64 + 2) * kPixel_m;
  const double columns = (east - west + 2 * kGrow_m) / kPixel_m;
  const double rows = (north - south + 2 * kGrow_m) / kPixel_m;
  const double box_tiles = std::ceil(columns / 64 + 1) * std::ceil(rows / 64 + 1);
  const double dem_pixels = std::pow(2 * kHalf_m / kPixel_m, 2);
  EXPECT_GT(reads.tiles, 0u);
  EXPECT_LE(static_cast<double>(reads.tiles), box_tiles);
  EXPECT_LE(static_cast<double>(reads.pixels), box_tiles * 66 * 66);
  EXPECT_LT(static_cast<double>(reads.pixels), 0.5 * dem_pixels);
  std::cout << "fine DEM: " << reads.tiles << " tiles, " << reads.pixels << " of " << dem_pixels
            << " pixels read; box " << box_tiles << " tiles\n";
}

// A grid written as text: `rows` x `cols` at 0.0002 degrees (~15 m), 400 m plus a gentle slope,
// `set` changing some pixels.
fs::path text_grid(const std::string& name, const std::function<void(int, int, double&)>& set) {
  std::string t = "ncols 20\nnrows 20\nxllcorner 8.540\nyllcorner 47.396\ncellsize 0.0002\n";
  for (int j = 0; j < 20; ++j) {
    for (int i = 0; i < 20; ++i) {
      double h = 400.0 + 0.5 * i + 0.25 * j;
      set(i, j, h);
      t += (i ? " " : "") + std::to_string(h);
    }
    t += "\n";
  }
  const fs::path path = dem_scratch() / (name + ".asc");
  std::ofstream(path) << t;
  return path;
}

std::string dem_refusal(const fs::path& grid) {
  try {
    dem_ground(grid.string())->heights_m({{47.398, 8.542, 0}});
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "";
}

// A one-pixel needle or pit far beyond its neighbours (a void filled with 0 among hills, a stray
// 3000) is refused naming its row and column; a cliff (every pixel on one side 600 m higher) and a
// one-pixel bump under the limit (250 m here: ten 15 m pixels is less) are ground.
TEST(DemGround, AOnePixelNeedleOrPitIsRefusedWithItsRowAndColumnButACliffIsGround) {
  const std::string pit = dem_refusal(text_grid("pit", [](int i, int j, double& h) {
    if (i == 13 && j == 4) h = 0.0;
  }));
  EXPECT_NE(pit.find("the ground at row 5, column 14 is 0 m"), std::string::npos) << pit;
  EXPECT_NE(pit.find("below every pixel around it"), std::string::npos) << pit;
  const std::string needle = dem_refusal(text_grid("needle", [](int i, int j, double& h) {
    if (i == 2 && j == 17) h = 3000.0;
  }));
  EXPECT_NE(needle.find("row 18, column 3 is 3000 m"), std::string::npos) << needle;
  EXPECT_NE(needle.find("above every pixel around it"), std::string::npos) << needle;
  EXPECT_EQ(dem_refusal(text_grid("cliff",
                                  [](int i, int, double& h) {
                                    if (i >= 10) h += 600.0;
                                  })),
            "");
  EXPECT_EQ(dem_refusal(text_grid("bump",
                                  [](int i, int j, double& h) {
                                    if (i == 8 && j == 8) h += 240.0;
                                  })),
            "");
}

}  // namespace
}  // namespace swath::geometry
