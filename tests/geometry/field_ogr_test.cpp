// GIS area files through OGR (docs/swath-plan.md), checked against swath's own GeoJSON reader: the
// bundled fields converted by GDAL itself (GDALVectorTranslate, ogr2ogr's library entry point) to
// Shapefile, zipped Shapefile, GeoPackage, KMZ, GPX, FlatGeobuf, GML, and reprojected to the Swiss
// grid (EPSG:2056) and UTM 32N, give the same area to 1e-6; several areas per file are chosen by
// name, position or name field, and refused without a choice naming them.
#include <gdal.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
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

// A FeatureCollection of `count` plots near (lon, lat), each a star-shaped ring of 5-9 vertices at
// random angles and radii (fixed seed), named "plot I" and numbered by an "id" of 100 + I.
std::string random_plots(std::mt19937& rng, int count, double lon, double lat) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::string out = R"({"type": "FeatureCollection", "features": [)";
  for (int i = 0; i < count; ++i) {
    const int n = 5 + static_cast<int>(rng() % 5);
    std::vector<double> angles;
    for (int k = 0; k < n; ++k) angles.push_back(2 * M_PI * (k + 0.8 * unit(rng)) / n);
    const double cx = lon + 0.01 * (i % 5), cy = lat + 0.008 * (i / 5);
    std::string ring;
    for (int k = 0; k <= n; ++k) {
      const double a = angles[static_cast<std::size_t>(k % n)], r = 0.001 + 0.002 * unit(rng);
      char xy[80];
      std::snprintf(xy, sizeof xy, "%s[%.9f, %.9f]", k ? ", " : "", cx + r * std::cos(a),
                    cy + 0.7 * r * std::sin(a));
      ring += xy;
    }
    out += std::string(i ? ",\n" : "\n") + R"({"type": "Feature", "properties": {"name": "plot )" +
           std::to_string(i) + R"(", "id": )" + std::to_string(100 + i) +
           R"(}, "geometry": {"type": "Polygon", "coordinates": [[)" + ring + "]]}}";
  }
  return out + "\n]}\n";
}

// Area `o` chooses of `file`, read from a copy of the file (a path and an inode never read: read
// through GDAL) in a directory of its own under the same name (so its layer has the same name),
// with every message naming the copy turned back to `file`: what a kept read must give.
std::string read_fresh(const fs::path& file, const FieldReadOptions& o, Field* out) {
  static int copies = 0;
  const fs::path dir = scratch() / ("fresh-" + std::to_string(++copies));
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(file.parent_path()))  // a Shapefile's other files
    if (e.path().stem() == file.stem()) fs::copy_file(e.path(), dir / e.path().filename());
  const std::size_t before = area_file_reads(dir / file.filename());
  std::string why = "accepted";
  try {
    *out = read_field(dir / file.filename(), o);
  } catch (const base::InputError& e) {
    why = e.what();
    for (std::size_t at; (at = why.find((dir / file.filename()).string())) != std::string::npos;)
      why.replace(at, (dir / file.filename()).string().size(), file.string());
  }
  EXPECT_EQ(area_file_reads(dir / file.filename()), before + 1) << file;
  return why;
}

void expect_same_area(const Field& kept, const Field& fresh, const std::string& what) {
  ASSERT_EQ(kept.geo_rings.size(), fresh.geo_rings.size()) << what;
  for (std::size_t r = 0; r < kept.geo_rings.size(); ++r) {
    ASSERT_EQ(kept.geo_rings[r].size(), fresh.geo_rings[r].size()) << what;
    for (std::size_t k = 0; k < kept.geo_rings[r].size(); ++k) {
      EXPECT_EQ(kept.geo_rings[r][k].lon_deg, fresh.geo_rings[r][k].lon_deg) << what;
      EXPECT_EQ(kept.geo_rings[r][k].lat_deg, fresh.geo_rings[r][k].lat_deg) << what;
    }
  }
  ASSERT_EQ(kept.polygon.outer.size(), fresh.polygon.outer.size()) << what;
  for (std::size_t k = 0; k < kept.polygon.outer.size(); ++k) {
    EXPECT_EQ(kept.polygon.outer[k].x, fresh.polygon.outer[k].x) << what;
    EXPECT_EQ(kept.polygon.outer[k].y, fresh.polygon.outer[k].y) << what;
  }
}

// `swath batch` reads area after area of one file in each worker: the areas come from the layer
// read first (one read through GDAL), each, asked again, in any order, by position or name, and
// each refusal, as a fresh read of the file gives them; in GeoJSON, and in a GeoPackage and a
// Shapefile in projected CRSs (each read reprojects its own copy of the kept area).
TEST(FieldOgr, TheAreasOfTheFileLastReadAreThoseAFreshReadGives) {
  std::mt19937 rng(52);
  const fs::path plots = scratch() / "plots.geojson";
  std::ofstream(plots) << random_plots(rng, 12, 8.4, 47.3);
  const fs::path swiss = scratch() / "plots-2056.gpkg";
  translate(swiss, plots.string(), {"-f", "GPKG", "-t_srs", "EPSG:2056", "-nln", "fields"});
  const fs::path utm = scratch() / "plots-utm.shp";
  translate(utm, plots.string(), {"-f", "ESRI Shapefile", "-t_srs", "EPSG:32632"});
  for (const fs::path& file : {plots, swiss, utm}) {
    std::vector<std::string> asked;
    for (int i = 0; i < 12; ++i)
      asked.push_back(i % 2 ? std::to_string(i) : "plot " + std::to_string(i));
    asked.insert(asked.end(), {"3", "plot 3", "Atlantis", "12", "0"});
    std::shuffle(asked.begin(), asked.end(), rng);
    std::vector<Field> fresh(asked.size());
    std::vector<std::string> fresh_why;
    for (std::size_t i = 0; i < asked.size(); ++i) {
      FieldReadOptions o;
      o.feature = asked[i];
      fresh_why.push_back(read_fresh(file, o, &fresh[i]));
    }
    for (std::size_t i = 0; i < asked.size(); ++i) {
      FieldReadOptions o;
      o.feature = asked[i];
      EXPECT_EQ(refusal(file, o), fresh_why[i]) << file << " " << asked[i];
      if (fresh_why[i] == "accepted")
        expect_same_area(read_field(file, o), fresh[i], file.string() + " " + asked[i]);
    }
    EXPECT_EQ(area_file_reads(file), 1u) << file;
  }
}

// A file changed since (another size; the same size but written later; another file renamed in
// its place with the same size and time), another name field, or a read in a process forked after
// the last: read again.
TEST(FieldOgr, AChangedFileOtherOptionsOrAnotherProcessReadAgain) {
  std::mt19937 rng(7);
  const fs::path file = scratch() / "changing.geojson";
  const auto expect_fresh = [&](const FieldReadOptions& o, std::size_t reads) {
    Field fresh;
    ASSERT_EQ(read_fresh(file, o, &fresh), "accepted");
    expect_same_area(read_field(file, o), fresh, file.string() + " " + *o.feature);
    EXPECT_EQ(area_file_reads(file), reads);
  };
  FieldReadOptions first, last;
  first.feature = "0";
  std::ofstream(file) << random_plots(rng, 5, 8.4, 47.3);
  expect_fresh(first, 1);
  last.feature = "4";
  expect_fresh(last, 1);
  const auto five = fs::last_write_time(file);
  std::ofstream(file) << random_plots(rng, 6, 8.4, 47.3);  // one plot more, at the same time
  fs::last_write_time(file, five);
  last.feature = "5";
  expect_fresh(last, 2);
  // The same plots one after the other swapped: the same bytes in all, the time 5 s later.
  std::ostringstream whole;
  whole << std::ifstream(file).rdbuf();
  const std::string text = whole.str();
  const std::size_t second = text.find("\n{", text.find("\n{") + 1);
  const std::size_t third = text.find("\n{", second + 1);
  const std::string one = text.substr(text.find("\n{"), second - text.find("\n{"));
  std::string swapped = text.substr(0, text.find("\n{")) + text.substr(second, third - second);
  swapped += one + text.substr(third);
  ASSERT_EQ(swapped.size(), text.size());
  const auto written = fs::last_write_time(file);
  std::ofstream(file) << swapped;
  fs::last_write_time(file, written + std::chrono::seconds(5));
  expect_fresh(first, 3);
  // Another file renamed into its place: the same size and time, another inode.
  const fs::path other = scratch() / "other.geojson";
  std::ofstream(other) << text;
  fs::last_write_time(other, written + std::chrono::seconds(5));
  fs::rename(other, file);
  expect_fresh(first, 4);
  FieldReadOptions by_id;
  by_id.name_field = "id";
  by_id.feature = "103";
  expect_fresh(by_id, 5);
  expect_fresh(first, 6);
  const pid_t child = ::fork();
  if (child == 0) {  // no gtest here: the exit code says it
    const bool again = read_field(file, last).geo_rings.size() == 1 && area_file_reads(file) == 7;
    ::_exit(again ? 0 : 1);
  }
  int status = -1;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_EQ(area_file_reads(file), 6u);
}

}  // namespace
}  // namespace swath::geometry
