// `swath batch` keeps its jobs' logs in memory (memfd), not in a folder of the temporary
// directory: nothing there can be guessed, planted or left behind. Checked with TMPDIR pointed at
// a fresh folder: a batch that finishes and one ended by SIGTERM mid-way both leave it empty,
// and a refused area's sentence still reaches batch.csv from its job's log.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_runner.hpp"

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
  for (int k = 0; k < 6; ++k)
    fs::copy_file(source_path("share/fields/vineyard.kml"),
                  dir + "/areas/vineyard-" + std::to_string(k) + ".kml");
  const CliRun killed = run_program(
      "sh", "-c 'TMPDIR=" + dir + "/tmp " + SWATH_BINARY + " batch " + dir + "/areas -o " + dir +
                "/out2 --camera sony-ilce-qx1 --altitude 40 --jobs 2 & p=$!; sleep 0.3; "
                "kill -TERM $p; wait $p; echo $?'");
  EXPECT_NE(killed.out, "0\n");  // it was ended, not finished
  EXPECT_EQ(files_in(dir + "/tmp"), 0u);
}

}  // namespace
}  // namespace swath::test
