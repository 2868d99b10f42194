// Job lines safe for any shell (apps/common/shell_text.hpp): the real /bin/sh, bash and GNU
// parallel are the oracles. Random words of every byte but the control characters, shell
// metacharacters weighted up, come back from each as they went in; a word with a line break is
// refused, and `swath batch --emit-jobs` over a file named to inject a command prints nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "shell_text.hpp"
#include "swath/base/input_error.hpp"

namespace swath::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> hostile_words(std::size_t count, unsigned seed) {
  const std::string meta = " '\"\\$`;&|<>(){}[]*?!#~%^=,:@+-\t";
  std::mt19937 rng(seed);
  std::vector<std::string> words = {"",     "'", "''", "-n", "a b", "$(touch x)",
                                    "`id`", "#", "~",  "--", "*",   "é ü"};
  while (words.size() < count) {
    std::string w;
    const std::size_t length = 1 + rng() % 24;
    for (std::size_t i = 0; i < length; ++i) {
      if (rng() % 2) {
        w += meta[rng() % meta.size()];
      } else {
        char c = static_cast<char>(0x20 + rng() % 0xe0);  // printable ASCII and high bytes
        if (c == 0x7f) c = 'x';
        w += c;
      }
    }
    words.push_back(w);
  }
  for (std::string& w : words)  // tabs are control characters: refused, tested below
    for (char& c : w)
      if (c == '\t') c = ' ';
  return words;
}

// Runs the job lines `lines` (each printing its word and a NUL) through `runner` and splits
// what they print at the NULs.
std::vector<std::string> run_jobs(const std::vector<std::string>& lines, const std::string& runner,
                                  const std::string& options = "") {
  const std::string dir = fresh_dir("shell-text-jobs");
  fs::create_directories(dir);
  std::ofstream jobs(dir + "/jobs.txt", std::ios::binary);
  for (const std::string& l : lines) jobs << l << "\n";
  jobs.close();
  const CliRun r = run_program(runner, options + dir + "/jobs.txt");
  EXPECT_EQ(r.exit_code, 0) << runner << ": " << r.err;
  std::vector<std::string> words;
  std::string w;
  for (const char c : r.out) {
    if (c == '\0') {
      words.push_back(w);
      w.clear();
    } else {
      w += c;
    }
  }
  return words;
}

TEST(ShellText, EveryWordComesBackFromShParallelAndBash) {
  const std::vector<std::string> words = hostile_words(200, 48);
  std::vector<std::string> lines;
  for (const std::string& w : words) lines.push_back("printf '%s\\0' " + apps::shell_word(w));
  EXPECT_EQ(run_jobs(lines, "sh"), words);
  EXPECT_EQ(run_jobs(lines, "bash"), words);
  EXPECT_EQ(run_jobs(lines, "parallel", "--will-cite -j1 -k -a "), words);
}

TEST(ShellText, AWordWithAControlCharacterIsRefused) {
  for (const std::string& w : std::vector<std::string>{"b\ntouch X #", "a\rb", "tab\there",
                                                       std::string("nul\0x", 5), "del\x7f"}) {
    try {
      apps::shell_word(w);
      ADD_FAILURE() << "accepted a control character";
    } catch (const base::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("control character"), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

TEST(ShellText, CsvTextIsNeverAFormulaAndReadsBackAsWritten) {
  EXPECT_EQ(apps::csv_field("=HYPERLINK(\"x\")"), "\"'=HYPERLINK(\"\"x\"\")\"");
  EXPECT_EQ(apps::csv_field("+1"), "'+1");
  EXPECT_EQ(apps::csv_field("-2,3"), "\"'-2,3\"");
  EXPECT_EQ(apps::csv_field("@SUM(A1)"), "'@SUM(A1)");
  EXPECT_EQ(apps::csv_field("\t=1+2"), "'\t=1+2");
  EXPECT_EQ(apps::csv_field("\r=1+2"), "\"'\r=1+2\"");
  EXPECT_EQ(apps::csv_field("-5"), "'-5");  // text, not a number: the caller writes numbers
  EXPECT_EQ(apps::csv_field("meadow, north"), "\"meadow, north\"");
  EXPECT_EQ(apps::csv_field("a-b=c"), "a-b=c");  // only the first character makes a formula
  EXPECT_EQ(apps::csv_field(""), "");
}

TEST(ShellText, BatchEmitsNoJobForAFileNamedToInjectACommand) {
  const std::string dir = fresh_dir("shell-text-batch");
  fs::create_directories(dir + "/areas");
  const std::string meadow = read_text(source_path("share/fields/meadow.geojson"));
  std::ofstream(dir + "/areas/plain.geojson") << meadow;
  std::ofstream(dir + "/areas/b\ntouch INJECTED #.geojson") << meadow;
  ASSERT_TRUE(fs::exists(dir + "/areas/b\ntouch INJECTED #.geojson"));
  const CliRun r = run_swath("batch " + dir + "/areas -o " + dir +
                             "/out --emit-jobs --camera sony-ilce-qx1 --altitude 60");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.out, "");  // no line at all, not the plain field's alone
  EXPECT_NE(r.err.find("control character"), std::string::npos) << r.err;
}

// A sweep that names a scheduler twice would print two job lines writing one -o: refused.
TEST(ShellText, ASweepThatNamesASchedulerTwiceIsRefused) {
  const std::string dir = fresh_dir("sweep-twice");
  fs::create_directories(dir);
  std::ofstream(dir + "/spec.yaml") << "app: hotspot\nworld: hotspot\ndrones: 2\n"
                                    << "schedulers: [sa, greedy, sa]\nseeds: {from: 1, to: 2}\n";
  const CliRun r = run_swath_fleet("sweep " + dir + "/spec.yaml --runs " + dir + "/runs");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("\"sa\" appears twice"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace swath::test
