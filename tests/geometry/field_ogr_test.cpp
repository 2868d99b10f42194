// GIS area files through OGR (docs/swath-plan.md), checked against swath's own GeoJSON reader: the
// bundled fields converted by GDAL itself (GDALVectorTranslate, ogr2ogr's library entry point) to
// Shapefile, zipped Shapefile, GeoPackage, KMZ, GPX, FlatGeobuf, GML, and reprojected to the Swiss
// grid (EPSG:2056) and UTM 32N, give the same area to 1e-6; several areas per file are chosen by
// name, position or name field, and refused without a choice naming them.
#include <gdal.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "swath/base/input_error.hpp"
#include "swath/geometry/field.hpp"

namespace swath::geometry {
namespace {

namespace fs = std::filesystem;

std::string source(const std::string& relative) {
  return std::string(SWATH_SOURCE_DIR) + "/" + relative;
}

fs::path scratch() {
  // One per process: CTest runs the tests of this file side by side.
  const fs::path dir =
      fs::temp_directory_path() / ("swath-field-ogr-test-" + std::to_string(::getpid()));
  static bool once = [&] {
    fs::remove_all(dir);
    fs::create_directories(dir);
    return true;
  }();
  (void)once;
  return dir;
}

// ogr2ogr DEST SRC ARGS... through GDAL's library API.
void translate(const fs::path& dest, const std::string& src, std::vector<std::string> args) {
  GDALAllRegister();
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  GDALVectorTranslateOptions* options = GDALVectorTranslateOptionsNew(argv.data(), nullptr);
  ASSERT_NE(options, nullptr);
  GDALDatasetH in = GDALOpenEx(src.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  ASSERT_NE(in, nullptr) << src;
  int error = 0;
  GDALDatasetH out = GDALVectorTranslate(dest.string().c_str(), nullptr, 1, &in, options, &error);
  ASSERT_NE(out, nullptr) << dest << ": " << CPLGetLastErrorMsg();
  GDALClose(out);
  GDALClose(in);
  GDALVectorTranslateOptionsFree(options);
}

std::string refusal(const fs::path& path, const FieldReadOptions& o = {}) {
  try {
    read_field(path, o);
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(FieldOgr, EveryFormatAndProjectionGivesTheGeoJsonArea) {
  for (const std::string field : {"meadow.geojson", "vineyard.kml"}) {
    const std::string original = source("share/fields/" + field);
    const double expected = area(read_field(original).polygon);
    struct Case {
      std::string file;
      std::vector<std::string> args;
    };
    const std::vector<Case> cases{
        {field + ".shp", {"-f", "ESRI Shapefile"}},
        {field + ".gpkg", {"-f", "GPKG"}},
        {field + ".kmz", {"-f", "LIBKML"}},
        {field + ".fgb", {"-f", "FlatGeobuf"}},
        {field + ".gml", {"-f", "GML"}},
        {field + ".gpx", {"-f", "GPX", "-nlt", "MULTILINESTRING", "-nln", "tracks"}},
        {field + "-2056.gpkg", {"-f", "GPKG", "-t_srs", "EPSG:2056"}},
        {field + "-utm.shp", {"-f", "ESRI Shapefile", "-t_srs", "EPSG:32632"}},
        {field + "-2056.geojson", {"-f", "GeoJSON", "-t_srs", "EPSG:2056", "-lco", "RFC7946=NO"}},
    };
    for (const Case& c : cases) {
      const fs::path out = scratch() / c.file;
      translate(out, original, c.args);
      const Field f = read_field(out);
      EXPECT_NEAR(area(f.polygon), expected, 1e-6 * expected) << c.file;
      ASSERT_FALSE(f.geo_rings.empty());
      // Back in longitude/latitude: the first vertex lies within 1 m of one of the original's.
      const Field o = read_field(original);
      double nearest = 1e9;
      for (const GeoPoint& g : o.geo_rings[0])
        nearest = std::min(nearest, geodesic_distance_m(g, f.geo_rings[0][0]));
      EXPECT_LT(nearest, 0.01) << c.file;
    }
    // A zipped Shapefile is read straight from the zip.
    const fs::path zip = scratch() / (field + "-zipped.shp.zip");
    translate(zip, original, {"-f", "ESRI Shapefile"});
    EXPECT_NEAR(area(read_field(zip).polygon), expected, 1e-6 * expected);
  }
  // WKT: one polygon in longitude/latitude.
  const fs::path wkt = scratch() / "square.wkt";
  std::ofstream(wkt)
      << "POLYGON ((8.54 47.39, 8.541 47.39, 8.541 47.391, 8.54 47.391, 8.54 47.39))";
  const Field square = read_field(wkt);
  EXPECT_NEAR(area(square.polygon), 75.9 * 111.2 * 1e0, 200.0);  // ~75.9 m × ~111.2 m
}

TEST(FieldOgr, SeveralAreasAreChosenByNamePositionOrField) {
  const fs::path multi = scratch() / "two-fields.gpkg";
  translate(multi, source("share/fields/meadow.geojson"), {"-f", "GPKG", "-nln", "fields"});
  translate(multi, source("share/fields/bowtie.geojson"),
            {"-f", "GPKG", "-nln", "fields", "-append", "-update"});
  const std::string why = refusal(multi);
  EXPECT_NE(why.find("holds 2 areas (Meadow north of the farm, 1); choose one with --feature"),
            std::string::npos)
      << why;
  const double meadow = area(read_field(source("share/fields/meadow.geojson")).polygon);
  const double bowtie = area(read_field(source("share/fields/bowtie.geojson")).polygon);
  FieldReadOptions o;
  o.feature = "Meadow north of the farm";
  EXPECT_NEAR(area(read_field(multi, o).polygon), meadow, 1e-6 * meadow);
  o.feature = "1";
  EXPECT_NEAR(area(read_field(multi, o).polygon), bowtie, 1e-6 * bowtie);
  o.feature = "Atlantis";
  EXPECT_NE(refusal(multi, o).find("no area \"Atlantis\" in layer \"fields\"; its areas are "
                                   "Meadow north of the farm, 1 (or 0 to 1 by position)"),
            std::string::npos)
      << refusal(multi, o);
  o.feature.reset();
  o.name_field = "colour";
  EXPECT_NE(refusal(multi, o).find("has no field \"colour\""), std::string::npos)
      << refusal(multi, o);
  o.name_field.reset();
  o.layer = "roads";
  EXPECT_NE(refusal(multi, o).find("no layer \"roads\"; its layers are fields"), std::string::npos)
      << refusal(multi, o);
  // A GeoJSON (here in the Swiss grid) is chosen from the same way.
  const fs::path swiss = scratch() / "choose-2056.geojson";
  translate(swiss, source("share/fields/meadow.geojson"),
            {"-f", "GeoJSON", "-t_srs", "EPSG:2056", "-lco", "RFC7946=NO"});
  o = {};
  o.feature = "0";
  EXPECT_NEAR(area(read_field(swiss, o).polygon), meadow, 1e-6 * meadow);
}

TEST(FieldOgr, WhatIsNotAnAreaIsRefusedInOneSentence) {
  const fs::path text = scratch() / "notes.gpkg";
  std::ofstream(text) << "these are not the fields you are looking for";
  EXPECT_NE(refusal(text).find("GDAL cannot open it as a vector file"), std::string::npos)
      << refusal(text);
  const fs::path open_line = scratch() / "line.wkt";
  std::ofstream(open_line) << "LINESTRING (8.54 47.39, 8.541 47.39, 8.541 47.391)";
  EXPECT_NE(refusal(open_line).find("a line that does not close"), std::string::npos)
      << refusal(open_line);
  const fs::path point = scratch() / "point.wkt";
  std::ofstream(point) << "POINT (8.54 47.39)";
  EXPECT_NE(refusal(point).find("is a Point, not an area"), std::string::npos) << refusal(point);
  const fs::path bad = scratch() / "bad.wkt";
  std::ofstream(bad) << "POLYGON ((8.54 47.39, 8.541";
  EXPECT_NE(refusal(bad).find("not a WKT geometry"), std::string::npos) << refusal(bad);
  // A second geometry or stray text after the first is refused, not cut off; a trailing line
  // break is not text.
  const std::string square = "POLYGON ((8.54 47.39, 8.541 47.39, 8.541 47.391, 8.54 47.39))";
  const fs::path two = scratch() / "two.wkt";
  std::ofstream(two) << square << "\n" << square << "\n";
  EXPECT_NE(refusal(two).find("text follows the WKT geometry at byte 63"), std::string::npos)
      << refusal(two);
  const fs::path trailing = scratch() / "trailing.wkt";
  std::ofstream(trailing) << square << " junk";
  EXPECT_NE(refusal(trailing).find("text follows the WKT geometry"), std::string::npos)
      << refusal(trailing);
  const fs::path one = scratch() / "one.wkt";
  std::ofstream(one) << square << "\r\n\n";
  EXPECT_GT(area(read_field(one).polygon), 0.0);
}

// Coordinates in another CRS than the file says are refused, not planned somewhere else:
// longitude/latitude labelled Swiss LV95 (EPSG:2056) would lie in the Atlantic; a .prj GDAL
// cannot read is not taken as longitude/latitude. The same field labelled with its real CRS reads.
TEST(FieldOgr, ACrsThatDoesNotFitItsCoordinatesIsRefused) {
  const std::string meadow = source("share/fields/meadow.geojson");
  const fs::path mislabelled = scratch() / "mislabelled.gpkg";
  translate(mislabelled, meadow, {"-f", "GPKG", "-a_srs", "EPSG:2056"});
  EXPECT_NE(refusal(mislabelled).find("outside the area where its CRS (CH1903+ / LV95) is used"),
            std::string::npos)
      << refusal(mislabelled);
  const fs::path labelled = scratch() / "labelled.gpkg";
  translate(labelled, meadow, {"-f", "GPKG", "-a_srs", "EPSG:4326"});
  EXPECT_EQ(refusal(labelled), "accepted");
  const fs::path garbage = scratch() / "garbage.shp";
  translate(garbage, meadow, {"-f", "ESRI Shapefile"});
  std::ofstream(scratch() / "garbage.prj") << "GARBAGE[\"not a CRS\"]";
  EXPECT_NE(refusal(garbage).find("its .prj names no coordinate reference system"),
            std::string::npos)
      << refusal(garbage);
}

}  // namespace
}  // namespace swath::geometry
