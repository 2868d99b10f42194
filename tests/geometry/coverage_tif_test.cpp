// coverage.tif (docs/swath-plan.md): the coverage grid against a brute-force count with exact point
// location in each footprint polygon, its sums against the photos' total footprint and the area's
// own area, and the GeoTIFF read back by GDAL: bands equal, every cell placed by PROJ where
// swath's local frame (GeographicLib) puts it.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <random>

#include "meadow_survey.hpp"
#include "swath/geometry/geotiff.hpp"
#include "swath/geometry/polygon.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/planning/coverage_grid.hpp"
#include "swath/planning/survey.hpp"

namespace swath::planning {
namespace {

// Photos over a point: each footprint as a polygon, located exactly.
int brute_count(const SurveyPlan& plan, geometry::Point2 p) {
  int n = 0;
  const DronePlan& d = plan.drones.at(0);
  const double a = plan.imaging.footprint_across_m / 2, l = plan.imaging.footprint_along_m / 2;
  for (const PhotoPoint& photo : d.photos) {
    const SweepLine& line = d.mission.lines.at(static_cast<std::size_t>(photo.line));
    const double heading = std::atan2(line.end.y - line.start.y, line.end.x - line.start.x);
    const double c = std::cos(heading), s = std::sin(heading);
    std::vector<geometry::Point2> ring;
    for (const auto& [u, v] : {std::pair{l, a}, {-l, a}, {-l, -a}, {l, -a}})
      ring.push_back({photo.position.x + u * c - v * s, photo.position.y + u * s + v * c});
    n += geometry::locate_point(p, ring) != geometry::Containment::outside;
  }
  return n;
}

TEST(CoverageGrid, CountsEqualABruteForceAndSumToTheFootprintsAndTheArea) {
  const SurveyPlan plan = plan_survey(test::meadow_request(60));
  const CoverageGrid g = coverage_grid(plan, 0.5);
  ASSERT_GT(g.width, 100);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> col(0, g.width - 1), row(0, g.height - 1);
  for (int k = 0; k < 400; ++k) {
    const int i = col(rng), j = row(rng);
    const geometry::Point2 c{g.west_m + (i + 0.5) * g.cell_m, g.north_m - (j + 0.5) * g.cell_m};
    EXPECT_EQ(g.photos[static_cast<std::size_t>(j * g.width + i)], brute_count(plan, c))
        << i << "," << j;
    const bool in = geometry::locate_point(c, plan.area.outer) != geometry::Containment::outside;
    EXPECT_EQ(g.inside[static_cast<std::size_t>(j * g.width + i)], in ? 1 : 0);
  }
  double photo_cells = 0, inside_cells = 0, covered_inside = 0;
  for (std::size_t k = 0; k < g.photos.size(); ++k) {
    photo_cells += g.photos[k];
    inside_cells += g.inside[k];
    covered_inside += g.inside[k] && g.photos[k] > 0;
  }
  const double cell2 = g.cell_m * g.cell_m;
  const double footprints = static_cast<double>(plan.drones[0].photos.size()) *
                            plan.imaging.footprint_across_m * plan.imaging.footprint_along_m;
  EXPECT_NEAR(photo_cells * cell2 / footprints, 1.0, 0.005);  // every footprint on the grid
  EXPECT_NEAR(inside_cells * cell2 / geometry::area(plan.area), 1.0, 0.005);
  EXPECT_GE(covered_inside / inside_cells, plan.coverage.covered_fraction - 0.002);
}

TEST(CoverageTif, GdalReadsTheBandsBackAndProjPlacesEveryCellWhereTheLocalFrameDoes) {
  const SurveyPlan plan = plan_survey(test::meadow_request(60));
  const CoverageGrid g = coverage_grid(plan, 2.0);
  geometry::LocalRaster r;
  r.origin = plan.request.field.frame->origin();
  r.west_m = g.west_m;
  r.north_m = g.north_m;
  r.cell_m = g.cell_m;
  r.width = g.width;
  r.height = g.height;
  r.bands.emplace_back("photos", g.photos);
  r.bands.emplace_back("area", std::vector<std::uint16_t>(g.inside.begin(), g.inside.end()));
  const std::string bytes = geometry::geotiff_bytes(r);
  EXPECT_EQ(geometry::geotiff_bytes(r), bytes);  // same raster, same bytes
  GDALAllRegister();
  const std::string path = "/vsimem/coverage-test.tif";
  VSILFILE* f = VSIFileFromMemBuffer(
      path.c_str(), reinterpret_cast<GByte*>(const_cast<char*>(bytes.data())), bytes.size(), FALSE);
  VSIFCloseL(f);
  GDALDataset* d = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER);
  ASSERT_NE(d, nullptr);
  ASSERT_EQ(d->GetRasterCount(), 2);
  ASSERT_EQ(d->GetRasterXSize(), g.width);
  for (int b = 1; b <= 2; ++b) {
    std::vector<std::uint16_t> back(g.photos.size());
    ASSERT_EQ(d->GetRasterBand(b)->RasterIO(GF_Read, 0, 0, g.width, g.height, back.data(), g.width,
                                            g.height, GDT_UInt16, 0, 0),
              CE_None);
    EXPECT_EQ(back, r.bands[static_cast<std::size_t>(b - 1)].second);
  }
  EXPECT_STREQ(d->GetRasterBand(1)->GetDescription(), "photos");
  double gt[6];
  ASSERT_EQ(d->GetGeoTransform(gt), CE_None);
  OGRSpatialReference wgs84;
  wgs84.importFromEPSG(4326);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference tif(*d->GetSpatialRef());
  tif.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&tif, &wgs84));
  ASSERT_TRUE(ct);
  for (const auto& [i, j] :
       {std::pair{0, 0}, {g.width - 1, 0}, {0, g.height - 1}, {g.width / 2, g.height / 3}}) {
    double x = gt[0] + (i + 0.5) * gt[1], y = gt[3] + (j + 0.5) * gt[5];
    const geometry::GeoPoint want = plan.request.field.frame->to_geo({x, y});
    ASSERT_TRUE(ct->Transform(1, &x, &y));
    const double north_m = (y - want.lat_deg) * 111'320.0;
    const double east_m = (x - want.lon_deg) * 111'320.0 * std::cos(want.lat_deg * M_PI / 180);
    EXPECT_LT(std::hypot(north_m, east_m), 0.001) << i << "," << j;
  }
  GDALClose(d);
  VSIUnlink(path.c_str());
}

}  // namespace
}  // namespace swath::planning
