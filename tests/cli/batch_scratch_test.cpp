// `swath batch` keeps its jobs' logs in memory (memfd), not in a folder of the temporary
// directory: nothing there can be guessed, planted or left behind. Checked with TMPDIR pointed at
// a fresh folder: a batch that finishes and one ended by SIGTERM mid-way both leave it empty,
// and a refused area's sentence still reaches batch.csv from its job's log. And whatever a
// directory holds, the batch writes its batch.csv and batch.geojson, a row per entry.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"
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

}  // namespace
}  // namespace swath::test
