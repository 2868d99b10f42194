// `swath batch` keeps its jobs' logs in memory (memfd), not in a folder of the temporary
// directory: nothing there can be guessed, planted or left behind. Checked with TMPDIR pointed at
// a fresh folder: a batch that finishes and one ended by SIGTERM mid-way both leave it empty,
// and a refused area's sentence still reaches batch.csv from its job's log. And whatever a
// directory holds, the batch writes its batch.csv and batch.geojson, a row per entry, and its
// jobs are those GDAL's listing of each file alone gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "swath/base/csv_text.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/utf8.hpp"

namespace swath::test {
namespace {

namespace fs = std::filesystem;

std::size_t files_in(const std::string& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(BatchScratch, JobLogsLeaveNothingInTheTemporaryDirectory) {
  const std::string dir = fresh_dir("batch-scratch");
  fs::create_directories(dir + "/tmp");
  fs::create_directories(dir + "/areas");
  fs::copy_file(source_path("share/fields/meadow.geojson"), dir + "/areas/meadow.geojson");
  fs::copy_file(source_path("share/fields/bowtie.geojson"), dir + "/areas/bowtie.geojson");
  const CliRun r =
      run_program("env", "TMPDIR=" + dir + "/tmp " + SWATH_BINARY + " batch " + dir + "/areas -o " +
                             dir + "/out --camera sony-ilce-qx1 --altitude 60 --jobs 2");
  EXPECT_EQ(r.exit_code, 3) << r.err;  // the bowtie is refused
  const std::string csv = read_text(dir + "/out/batch.csv");
  EXPECT_NE(csv.find("crosses"), std::string::npos) << csv;  // its sentence, from the job's log
  EXPECT_EQ(files_in(dir + "/tmp"), 0u);

  // Ended by SIGTERM while its jobs run: still nothing left there.
  for (int k = 0; k < 24; ++k)  // seconds of work: the signal comes mid-way
    fs::copy_file(source_path("share/fields/vineyard.kml"),
                  dir + "/areas/vineyard-" + std::to_string(k) + ".kml");
  const CliRun killed = run_program(
      "sh", "-c 'TMPDIR=" + dir + "/tmp " + SWATH_BINARY + " batch " + dir + "/areas -o " + dir +
                "/out2 --camera sony-ilce-qx1 --altitude 40 --jobs 2 & p=$!; sleep 0.3; "
                "kill -TERM $p; wait $p; echo $?'");
  EXPECT_NE(killed.out, "0\n");  // it was ended, not finished
  EXPECT_EQ(files_in(dir + "/tmp"), 0u);
}

TEST(BatchScratch, EveryEntryIsARowWhateverItIs) {
  const std::string dir = fresh_dir("batch-rows");
  fs::create_directories(dir + "/areas");
  fs::copy_file(source_path("share/fields/meadow.geojson"), dir + "/areas/meadow.geojson");
  fs::copy_file(source_path("share/fields/meadow.geojson"), dir + "/areas/batch.csv.geojson");
  fs::create_symlink("loop.geojson", dir + "/areas/loop.geojson");  // a link to itself
  std::ofstream(dir + "/areas/picture.geojson", std::ios::binary)
      << std::string("\x89PNG\r\n\x1a\n\xff\xfe\x00\x01", 12);
  const CliRun r =
      run_swath("batch " + dir + "/areas -o " + dir + "/out --camera sony-ilce-qx1 --altitude 60");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  ASSERT_TRUE(fs::is_regular_file(dir + "/out/batch.csv"));
  const auto rows = csv_rows(read_text(dir + "/out/batch.csv"));
  ASSERT_EQ(rows.size(), 5u);  // the header and four entries
  const std::string csv = read_text(dir + "/out/batch.csv");
  EXPECT_EQ(base::valid_utf8(csv), csv);
  EXPECT_EQ(csv.find("last read"), std::string::npos) << csv;  // no bytes of the file echoed
  const auto geojson = nlohmann::json::parse(read_text(dir + "/out/batch.geojson"));
  ASSERT_EQ(geojson["features"].size(), 4u);
  int planned = 0;
  for (const auto& f : geojson["features"]) {
    planned += f["properties"]["status"] == "planned";
    EXPECT_NE(f["properties"]["directory"], "batch.csv");  // never the batch's own file
  }
  EXPECT_EQ(planned, 2);
}

// A square ring of side 0.001 degrees at (lon, lat), as GeoJSON coordinates.
std::string square(double lon, double lat) {
  std::ostringstream out;
  out.precision(12);
  out << "[[" << lon << ", " << lat << "], [" << lon + 0.001 << ", " << lat << "], [" << lon + 0.001
      << ", " << lat + 0.001 << "], [" << lon << ", " << lat + 0.001 << "], [" << lon << ", " << lat
      << "]]";
  return out.str();
}

std::string feature(const std::string& name, const std::string& geometry) {
  return R"({"type": "Feature", "properties": {"name": ")" + name + R"("}, "geometry": )" +
         geometry + "}";
}

std::string collection(const std::vector<std::string>& features) {
  std::string out = R"({"type": "FeatureCollection", "features": [)";
  for (std::size_t i = 0; i < features.size(); ++i) out += (i ? ", " : "") + features[i];
  return out + "]}";
}

// A directory's GeoJSON files of every shape that decides how many areas a file holds: the
// batch's jobs for the directory are, file by file, the ones `swath batch FILE` lists alone (by
// GDAL; a file GDAL cannot list is one job without --feature, as in a directory it is), whether
// the batch reads a file of one polygon itself or asks GDAL.
TEST(BatchScratch, ADirectorysJobsAreThoseGdalListsForEachFileAlone) {
  const std::string dir = fresh_dir("batch-listing");
  fs::create_directories(dir + "/areas");
  const std::string polygon = R"({"type": "Polygon", "coordinates": [)" + square(8.5, 47.3) + "]}";
  const auto at = [](double lon, double lat) {
    return R"({"type": "Polygon", "coordinates": [)" + square(lon, lat) + "]}";
  };
  const std::string two_parts = R"({"type": "MultiPolygon", "coordinates": [[)" +
                                square(8.5, 47.3) + "], [" + square(8.51, 47.3) + "]]}";
  const std::string one_part =
      R"({"type": "MultiPolygon", "coordinates": [[)" + square(8.5, 47.3) + "]]}";
  const std::string track = R"({"type": "LineString", "coordinates": )" + square(8.52, 47.3) + "}";
  const std::map<std::string, std::string> files{
      {"a-polygon.geojson", polygon},
      {"b-feature.geojson", feature("b one", polygon)},
      {"c-collection.json", collection({feature("c one", polygon)})},
      {"d-two.geojson",
       collection({feature("d first", polygon), feature("d second", at(8.51, 47.3))})},
      {"e-multi.geojson", collection({feature("e multi", two_parts)})},
      {"f-track.geojson", collection({feature("f field", polygon), feature("f track", track)})},
      {"g-null.geojson", collection({feature("g empty", "null"), feature("g field", polygon)})},
      {"h-twice.geojson", R"({"type": "Feature", "properties": {"name": "h"}, "geometry": )" +
                              polygon + R"(, "geometry": )" + two_parts + "}"},
      {"i-cut.geojson", polygon.substr(0, 40)},
      {"j-case.geojson",
       feature("j", R"({"type": "polygon", "coordinates": [)" + square(8.5, 47.3) + "]}")},
      {"k-one-part.geojson", collection({feature("k one", one_part)})},
      {"l-bare-multi.geojson", two_parts},
      {"m-polygon.kml", "<kml/>"},
      // Member names in another case: GDAL's reader takes them for GeoJSON's own.
      {"n-Type.geojson", R"({"Type": "FeatureCollection", "type": "Polygon", "coordinates": [)" +
                             square(8.5, 47.3) + R"(], "features": [)" + feature("n one", polygon) +
                             ", " + feature("n two", at(8.51, 47.3)) + "]}"},
      {"o-Geometry.geojson", collection({R"({"type": "Feature", "properties": {"name": "o"}, )"
                                         R"("geometry": )" +
                                         polygon + R"(, "Geometry": )" + two_parts + "}"})},
      {"p-Type-first.geojson", R"({"Type": "MultiPolygon", "type": "Polygon", "coordinates": [)" +
                                   square(8.5, 47.3) + "]}"},
  };
  for (const auto& [name, text] : files) std::ofstream(dir + "/areas/" + name) << text;
  const std::string opts = " --camera sony-ilce-qx1 --altitude 60";
  std::string expected;
  for (const auto& [name, text] : files) {
    const std::string file = dir + "/areas/" + name;
    const CliRun alone = run_swath("batch " + file + " -o " + dir + "/out --emit-jobs" + opts);
    if (alone.exit_code == 0) {
      expected += alone.out;
    } else {
      EXPECT_EQ(alone.exit_code, 2) << name << ": " << alone.err;
      expected += std::string(SWATH_BINARY) + " plan " + file + opts + " -o " + dir + "/out/" +
                  fs::path(name).stem().string() + "\n";
    }
  }
  const CliRun all = run_swath("batch " + dir + "/areas -o " + dir + "/out --emit-jobs" + opts);
  ASSERT_EQ(all.exit_code, 0) << all.err;
  EXPECT_EQ(all.out, expected);
  EXPECT_NE(all.out.find("--feature 1"), std::string::npos);  // some file holds several
}

// Two areas of one name (Google Earth names every new polygon "Untitled Polygon") are planned
// into distinct sub-directories, each with --feature its position.
TEST(BatchScratch, AreasOfOneNameGetDistinctDirectories) {
  const std::string dir = fresh_dir("batch-dupnames");
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/dupnames.geojson";
  const auto at = [](double lon) {
    return R"({"type": "Polygon", "coordinates": [)" + square(lon, 47.3) + "]}";
  };
  std::ofstream(file) << collection(
      {feature("Untitled Polygon", at(8.5)), feature("Untitled Polygon", at(8.51))});
  const CliRun run = run_swath("batch " + file + " -o " + dir + "/out --emit-jobs" +
                               " --camera sony-ilce-qx1 --altitude 60");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::istringstream lines(run.out);
  std::vector<std::string> jobs;
  for (std::string line; std::getline(lines, line);) jobs.push_back(line);
  ASSERT_EQ(jobs.size(), 2u) << run.out;
  const std::vector<std::string> dirs{"Untitled_Polygon", "Untitled_Polygon-2"};
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string tail = " -o " + dir + "/out/" + dirs[i];
    EXPECT_NE(jobs[i].find("--feature " + std::to_string(i) + " "), std::string::npos) << jobs[i];
    EXPECT_EQ(jobs[i].substr(jobs[i].size() - std::min(tail.size(), jobs[i].size())), tail);
  }
}

const std::string kPlanOptions = " --camera sony-ilce-qx1 --altitude 60";

// A directory of areas: meadow and bowtie (which crosses itself) from share/fields.
std::string areas_dir(const std::string& dir) {
  fs::create_directories(dir + "/areas");
  fs::copy_file(source_path("share/fields/meadow.geojson"), dir + "/areas/meadow.geojson");
  return dir + "/areas";
}

// The plan options are checked once, as swath plan checks them, before any area is listed or
// planned: one sentence, exit 2, nothing written (each area's row said it again, exit 3).
TEST(BatchScratch, PlanOptionsAreRefusedBeforeAnythingIsWritten) {
  const std::string dir = fresh_dir("batch-options");
  const std::string areas = areas_dir(dir);
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--camera nope --altitude 60", "--camera nope"},
      {"--camera sony-ilce-qx1 --altitude -5", "--altitude -5"},
      {kPlanOptions + " --home 95,8", "--home '95,8'"},
      {kPlanOptions + " --terrain " + dir + "/none.asc", "none.asc: cannot open"},
      {kPlanOptions + " --exclude " + dir + "/none.geojson", "none.geojson: cannot open"},
      {"--camera sony-ilce-qx1", "needs --altitude M or --gsd CM"},
      {kPlanOptions + " --dem-heights ellipsoid", "--dem-heights needs --terrain"},
  };
  for (const auto& [options, said] : cases) {
    const CliRun r = run_swath("batch " + areas + " -o " + dir + "/out " + options);
    EXPECT_EQ(r.exit_code, 2) << options << ": " << r.err;
    EXPECT_NE(r.err.find(said), std::string::npos) << options << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/out")) << options;
  }
  const CliRun emitted =
      run_swath("batch " + areas + " -o " + dir + "/out --emit-jobs --camera nope --altitude 60");
  EXPECT_EQ(emitted.exit_code, 2) << emitted.err;
  EXPECT_EQ(emitted.out, "");  // no command line that would fail
  // swath plan refuses --dem-heights without a DEM as it refuses --dem-units.
  const CliRun plan = run_swath("plan " + areas + "/meadow.geojson -o " + dir + "/out" +
                                kPlanOptions + " --dem-heights geoid");
  EXPECT_EQ(plan.exit_code, 2) << plan.err;
  EXPECT_NE(plan.err.find("--dem-heights needs --terrain"), std::string::npos) << plan.err;
}

// The directory of each area in batch.csv, by area name.
std::map<std::string, std::string> area_directories(const std::string& output) {
  std::map<std::string, std::string> dirs;
  const auto rows = csv_rows(read_text(output + "/batch.csv"));
  for (std::size_t i = 1; i < rows.size(); ++i) dirs[rows[i][0]] = rows[i][3];
  return dirs;
}

// An area's directory is never the area path nor a directory holding it: -o anc for anc/fields/
// planned the area "fields" into anc/fields, among the areas, and the next batch planned its
// mission.geojson, photos.csv, ... as areas. Such an area gets the next free name.
TEST(BatchScratch, NoAreaIsPlannedIntoTheDirectoryOfAreas) {
  const std::string dir = fresh_dir("batch-own-dir");
  const std::string areas = dir + "/anc/fields";
  fs::create_directories(areas);
  fs::copy_file(source_path("share/fields/meadow.geojson"), areas + "/fields.geojson");
  fs::copy_file(source_path("share/fields/meadow.geojson"), areas + "/A.geojson");
  for (int run = 0; run < 2; ++run) {
    const CliRun r = run_swath("batch " + areas + " -o " + dir + "/anc" + kPlanOptions);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("2 of 2 areas planned"), std::string::npos) << r.out;
    const auto dirs = area_directories(dir + "/anc");
    EXPECT_EQ(dirs.at("fields"), "fields-2");
    EXPECT_EQ(dirs.at("A"), "A");
    EXPECT_EQ(files_in(areas), 2u);  // the two area files alone
  }
  // A single file's directory, -o its parent's parent.
  fs::create_directories(dir + "/src-only/src");
  fs::copy_file(source_path("share/fields/meadow.geojson"), dir + "/src-only/src/src.geojson");
  const CliRun r = run_swath("batch " + dir + "/src-only/src/src.geojson -o " + dir + "/src-only" +
                             kPlanOptions);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(area_directories(dir + "/src-only").at("src"), "src-2");
  EXPECT_EQ(files_in(dir + "/src-only/src"), 1u);
}

// An output directory that cannot be created, or that lies in the directory of areas (whose next
// batch would plan batch.csv and batch.geojson as areas), is bad input: exit 2, nothing written.
// A missing or empty area file is refused with swath plan's sentence.
TEST(BatchScratch, OutputAndAreaPathsAreRefusedAsSwathPlanRefusesThem) {
  const std::string dir = fresh_dir("batch-output");
  const std::string areas = areas_dir(dir);
  std::ofstream(dir + "/afile") << "x";
  for (const std::string& out : {dir + "/afile", dir + "/afile/sub"}) {
    const CliRun r = run_swath("batch " + areas + " -o " + out + kPlanOptions);
    EXPECT_EQ(r.exit_code, 2) << out << ": " << r.err;
    EXPECT_NE(r.err.find(out + ": cannot create the output directory"), std::string::npos) << r.err;
  }
  EXPECT_EQ(read_text(dir + "/afile"), "x");
  for (const std::string& out : {areas, areas + "/", areas + "/out"}) {
    const CliRun r = run_swath("batch " + areas + " -o " + out + kPlanOptions);
    EXPECT_EQ(r.exit_code, 2) << out << ": " << r.err;
    EXPECT_NE(r.err.find("inside the directory of areas"), std::string::npos) << r.err;
  }
  EXPECT_EQ(files_in(areas), 1u);  // meadow alone: no batch.csv, no area directory
  const CliRun missing = run_swath("batch " + dir + "/none -o " + dir + "/out" + kPlanOptions);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("none: cannot open the area file"), std::string::npos) << missing.err;
  std::ofstream(dir + "/empty.geojson").flush();
  const CliRun empty =
      run_swath("batch " + dir + "/empty.geojson -o " + dir + "/out" + kPlanOptions);
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.err.find("empty.geojson: the file is empty"), std::string::npos) << empty.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

// A feature without geometry or with a point's is a row of its own, refused saying why (it was
// left out and the batch said "4 of 4 areas planned", exit 0); the areas keep their positions.
TEST(BatchScratch, FeaturesThatAreNoAreaAreRefusedRows) {
  const std::string dir = fresh_dir("batch-gaps");
  fs::create_directories(dir);
  const auto at = [](double lon) {
    return R"({"type": "Polygon", "coordinates": [)" + square(lon, 47.3) + "]}";
  };
  std::ofstream(dir + "/gaps.geojson") << collection(
      {feature("nogeom", "null"), feature("a", at(8.5)),
       feature("pt", R"({"type": "Point", "coordinates": [8.52, 47.3]})"), feature("b", at(8.51))});
  const CliRun r = run_swath("batch " + dir + "/gaps.geojson -o " + dir + "/out" + kPlanOptions);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  const auto rows = csv_rows(read_text(dir + "/out/batch.csv"));
  ASSERT_EQ(rows.size(), 5u);
  const std::vector<std::string> names{"nogeom", "a", "pt", "b"}, index{"", "0", "", "1"},
      status{"refused", "planned", "refused", "planned"};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(rows[i + 1][0], names[i]);
    EXPECT_EQ(rows[i + 1][2], index[i]);
    EXPECT_EQ(rows[i + 1][4], status[i]);
  }
  const std::string csv = read_text(dir + "/out/batch.csv");
  EXPECT_NE(csv.find("feature 0 (\"\"nogeom\"\") has no geometry"), std::string::npos) << csv;
  EXPECT_NE(csv.find("feature 2 (\"\"pt\"\") is a Point"), std::string::npos) << csv;
  const auto geojson = nlohmann::json::parse(read_text(dir + "/out/batch.geojson"));
  ASSERT_EQ(geojson["features"].size(), 4u);
  EXPECT_TRUE(geojson["features"][2]["geometry"].is_null());
  const CliRun emitted =
      run_swath("batch " + dir + "/gaps.geojson -o " + dir + "/out --emit-jobs" + kPlanOptions);
  EXPECT_EQ(emitted.exit_code, 0);
  EXPECT_EQ(std::count(emitted.out.begin(), emitted.out.end(), '\n'), 2);
  EXPECT_NE(emitted.err.find("warning: " + dir + "/gaps.geojson: feature 2"), std::string::npos)
      << emitted.err;
}

// A file the user put in an area's directory is never replaced, nor removed by the next batch:
// the area's row is refused with swath plan's sentence naming it (it was replaced, exit 0, then
// listed in .swath-plan.files and deleted by a rerun that no longer planned the area).
TEST(BatchScratch, AUsersFileInAnAreasDirectorySurvivesTheBatchAndTheNext) {
  const std::string dir = fresh_dir("batch-user-file");
  const std::string areas = areas_dir(dir);
  fs::create_directories(dir + "/out/meadow");
  const std::string notes = "MY OWN NOTES\n";
  std::ofstream(dir + "/out/meadow/photos.csv") << notes;
  const CliRun r = run_swath("batch " + areas + " -o " + dir + "/out" + kPlanOptions);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  const auto rows = csv_rows(read_text(dir + "/out/batch.csv"));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1][4], "refused");
  const std::string csv = read_text(dir + "/out/batch.csv");  // the message holds commas
  EXPECT_NE(csv.find("meadow/photos.csv: a file swath did not write"), std::string::npos) << csv;
  EXPECT_EQ(read_text(dir + "/out/meadow/photos.csv"), notes);
  EXPECT_EQ(files_in(dir + "/out/meadow"), 1u);  // nothing of the plan beside it
  fs::create_directories(dir + "/other");
  fs::copy_file(source_path("share/fields/meadow.geojson"), dir + "/other/field.geojson");
  const CliRun next = run_swath("batch " + dir + "/other -o " + dir + "/out" + kPlanOptions);
  EXPECT_EQ(next.exit_code, 0) << next.err;
  EXPECT_EQ(read_text(dir + "/out/meadow/photos.csv"), notes);
}

// swath plan counts a file's areas as --feature and swath batch do (the area listing): a closed
// line is an area, an empty polygon is none. A polygon, a point and a closed line were planned as
// the polygon alone, exit 0; a polygon, a closed line and an empty polygon were "features 0 and
// 2 are both areas" (the empty one, which --feature calls no area).
TEST(BatchScratch, PlanCountsAreasAsBatchAndFeatureDo) {
  const std::string dir = fresh_dir("batch-count");
  fs::create_directories(dir);
  const std::string polygon = R"({"type": "Polygon", "coordinates": [)" + square(8.5, 47.3) + "]}";
  const std::string line = R"({"type": "LineString", "coordinates": [[8.52, 47.3], [8.522, 47.3],)"
                           R"( [8.522, 47.301], [8.52, 47.3]]})";
  const std::string point = R"({"type": "Point", "coordinates": [8.53, 47.3]})";
  const std::string empty = R"({"type": "Polygon", "coordinates": []})";
  std::ofstream(dir + "/mix3.geojson")
      << collection({feature("A", polygon), feature("pt", point), feature("ln", line)});
  std::ofstream(dir + "/mix3b.geojson")
      << collection({feature("A", polygon), feature("ln", line), feature("none", empty)});
  std::ofstream(dir + "/lone.geojson") << collection({feature("pt", point), feature("ln", line)});
  for (const std::string name : {"mix3", "mix3b"}) {
    const std::string file = dir + "/" + name + ".geojson";
    const CliRun plan = run_swath("plan " + file + " -o " + dir + "/p-" + name + kPlanOptions);
    EXPECT_EQ(plan.exit_code, 2) << name << ": " << plan.err;
    EXPECT_NE(plan.err.find(file + ": features 0 and 1 are both areas"), std::string::npos)
        << plan.err;
    EXPECT_FALSE(fs::exists(dir + "/p-" + name));
    const CliRun batch = run_swath("batch " + file + " -o " + dir + "/b-" + name + kPlanOptions);
    const auto rows = csv_rows(read_text(dir + "/b-" + name + "/batch.csv"));
    const auto planned = std::count_if(rows.begin(), rows.end(),
                                       [](const auto& row) { return row[4] == "planned"; });
    EXPECT_EQ(planned, 2) << name;
  }
  // The lone area, a closed line beside a point, is planned as --feature 0 plans it.
  const CliRun lone =
      run_swath("plan " + dir + "/lone.geojson -o " + dir + "/p-lone" + kPlanOptions);
  ASSERT_EQ(lone.exit_code, 0) << lone.err;
  const CliRun chosen =
      run_swath("plan " + dir + "/lone.geojson --feature 0 -o " + dir + "/p-chosen" + kPlanOptions);
  ASSERT_EQ(chosen.exit_code, 0) << chosen.err;
  EXPECT_EQ(read_text(dir + "/p-lone/mission.geojson"),
            read_text(dir + "/p-chosen/mission.geojson"));
}

// A rerun into the same -o: the area directories of the batch before that this batch does not
// plan into (a file renamed away, an area now refused or timed out) lose their plan, so that no
// complete plan sits under a row that failed; what the user put there stays.
TEST(BatchScratch, AreaDirectoriesOfFailedOrGoneAreasLoseTheirPlans) {
  const std::string dir = fresh_dir("batch-stale");
  const std::string areas = areas_dir(dir);
  fs::copy_file(source_path("share/fields/meadow.geojson"), areas + "/gone.geojson");
  fs::copy_file(source_path("share/fields/meadow.geojson"), areas + "/kept.geojson");
  const std::string out = dir + "/out";
  ASSERT_EQ(run_swath("batch " + areas + " -o " + out + kPlanOptions).exit_code, 0);
  ASSERT_TRUE(fs::exists(out + "/meadow/.swath-plan.files"));
  std::ofstream(out + "/kept/notes.txt") << "mine";
  fs::create_directories(out + "/mine");  // no batch's
  fs::remove(areas + "/gone.geojson");
  fs::remove(areas + "/kept.geojson");
  fs::copy_file(source_path("share/fields/bowtie.geojson"), areas + "/meadow.geojson",
                fs::copy_options::overwrite_existing);
  const CliRun r = run_swath("batch " + areas + " -o " + out + kPlanOptions);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_EQ(csv_rows(read_text(out + "/batch.csv")).at(1).at(4), "refused");
  EXPECT_FALSE(fs::exists(out + "/meadow"));
  EXPECT_FALSE(fs::exists(out + "/gone"));
  EXPECT_EQ(directory_files(out + "/kept").size(), 1u);  // notes.txt alone
  EXPECT_TRUE(fs::is_directory(out + "/mine"));

  // An area that runs out of time: its directory holds no plan, the old one removed.
  fs::copy_file(source_path("share/fields/meadow.geojson"), areas + "/meadow.geojson",
                fs::copy_options::overwrite_existing);
  ASSERT_EQ(run_swath("batch " + areas + " -o " + out + kPlanOptions).exit_code, 0);
  ASSERT_TRUE(fs::exists(out + "/meadow/.swath-plan.files"));
  const CliRun late =
      run_swath("batch " + areas + " -o " + out + kPlanOptions + " --timeout-s 0.001");
  EXPECT_EQ(late.exit_code, 3) << late.err;
  EXPECT_EQ(csv_rows(read_text(out + "/batch.csv")).at(1).at(4), "timed-out");
  EXPECT_FALSE(fs::exists(out + "/meadow"));
}

// batch.csv's directory column names the directory as it is on disk (a name starting with '-'
// is no formula a spreadsheet runs: it holds no brackets); the area's name keeps the apostrophe
// that stops a spreadsheet running it. batch.geojson has batch.csv's columns, counts as integers.
TEST(BatchScratch, TablesNameTheRealDirectoryAndAgree) {
  const std::string dir = fresh_dir("batch-tables");
  fs::create_directories(dir + "/areas");
  fs::copy_file(source_path("share/fields/meadow.geojson"), dir + "/areas/-dash.geojson");
  const CliRun r = run_swath("batch " + dir + "/areas -o " + dir + "/out" + kPlanOptions);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = csv_rows(read_text(dir + "/out/batch.csv"));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1][0], "'-dash");
  EXPECT_EQ(rows[1][3], "-dash");
  EXPECT_TRUE(fs::exists(dir + "/out/" + rows[1][3] + "/summary.json"));
  const auto props =
      nlohmann::json::parse(read_text(dir + "/out/batch.geojson"))["features"][0]["properties"];
  EXPECT_EQ(props["area"], "-dash");
  for (std::size_t c = 7; c < 12; ++c) {  // lines, photos, path_length_m, flight_time_s, drones
    ASSERT_TRUE(props.contains(rows[0][c])) << rows[0][c];
    EXPECT_NEAR(props[rows[0][c]].get<double>(), std::stod(rows[1][c]), 5e-4) << rows[0][c];
  }
  for (const char* count : {"lines", "photos", "drones"})
    EXPECT_TRUE(props[count].is_number_integer()) << count << ": " << props[count];
}

// batch.csv guards the user's text as OWASP lists: an area's name starting with =, +, -, @, a tab
// or a carriage return gets a leading apostrophe (a negative number for a name too), one starting
// with none stays as it is; the numbers swath writes (index, exit code, the measures) never get
// one. batch.geojson has the names as they are.
TEST(BatchScratch, TablesGuardTheUsersTextAsOwaspListsAndNoNumber) {
  using nlohmann::json;
  const std::string dir = fresh_dir("batch-guard");
  fs::create_directories(dir + "/areas");
  const std::vector<std::string> names{"=a", "+b", "-c", "@d", "\te", "\rf", "-5", "plain"};
  json features = json::array();
  for (std::size_t k = 0; k < names.size(); ++k) {
    const double w = 8.54 + 0.002 * static_cast<double>(k), e = w + 0.001, s = 47.397, n = s + 7e-4;
    const json ring = {{w, s}, {e, s}, {e, n}, {w, n}, {w, s}};
    features.push_back({{"type", "Feature"},
                        {"properties", {{"name", names[k]}}},
                        {"geometry", {{"type", "Polygon"}, {"coordinates", {ring}}}}});
  }
  std::ofstream(dir + "/areas/plots.geojson")
      << json{{"type", "FeatureCollection"}, {"features", features}}.dump();
  const CliRun r = run_swath("batch " + dir + "/areas -o " + dir + "/out" + kPlanOptions);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_text(dir + "/out/batch.csv");
  base::CsvText csv(text, "batch.csv", base::CsvText::Records::quoted_breaks);
  ASSERT_TRUE(csv.next());
  const std::vector<std::string> header = csv.cells();
  const json geojson = json::parse(read_text(dir + "/out/batch.geojson"))["features"];
  for (std::size_t k = 0; k < names.size(); ++k) {
    ASSERT_TRUE(csv.next()) << text;
    const std::vector<std::string>& cells = csv.cells();
    ASSERT_EQ(cells.size(), header.size()) << text;
    EXPECT_EQ(cells[0], (names[k] == "plain" ? "" : "'") + names[k]);
    EXPECT_EQ(geojson[k]["properties"]["area"], names[k]);
    for (std::size_t c = 0; c < header.size(); ++c) {
      if (header[c] == "area" || header[c] == "file" || header[c] == "directory" ||
          header[c] == "status" || header[c] == "message")
        continue;
      double value = 0;
      EXPECT_TRUE(base::parse_number(cells[c], value)) << header[c] << ": " << cells[c];
    }
  }
}

// The user's batch.csv in -o is never replaced: the batch is refused naming it before any area
// is planned, exit 2, nothing written.
TEST(BatchScratch, AUsersBatchCsvIsRefusedBeforeAnyAreaIsPlanned) {
  const std::string dir = fresh_dir("batch-users-csv");
  const std::string areas = areas_dir(dir);
  fs::create_directories(dir + "/out");
  const std::string mine = "MY OWN TABLE\n";
  std::ofstream(dir + "/out/batch.csv") << mine;
  const CliRun r = run_swath("batch " + areas + " -o " + dir + "/out" + kPlanOptions);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "swath batch: " + dir +
                       "/out/batch.csv: a file swath did not write (no .swath-batch.files here "
                       "lists it) would be replaced; move it, or choose another -o\n");
  EXPECT_EQ(directory_files(dir + "/out"),
            (std::map<std::string, std::string>{{"batch.csv", mine}}));
}

}  // namespace
}  // namespace swath::test
