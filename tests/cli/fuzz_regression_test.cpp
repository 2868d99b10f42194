// Every input a fuzzer ever broke a reader with (tests/fuzz-regressions/<target>/), and every
// seed, goes through the same target again: bad input may only end in InputError.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_runner.hpp"
#include "targets.hpp"

namespace swath::test {
namespace {

TEST(FuzzRegressions, EveryCrashInputAndSeedIsReadOrRefusedCleanly) {
  std::size_t regressions = 0;
  for (const fuzz::Target& t : fuzz::targets()) {
    for (const char* seed : t.seeds) {
      ASSERT_TRUE(std::filesystem::exists(source_path(seed))) << t.name << ": " << seed;
      EXPECT_NO_THROW(t.run(read_text(source_path(seed)))) << t.name << ": " << seed;
    }
    const std::filesystem::path dir = source_path(std::string("tests/fuzz-regressions/") + t.name);
    if (!std::filesystem::is_directory(dir)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      EXPECT_NO_THROW(t.run(read_text(entry.path().string()))) << t.name << ": " << entry.path();
      ++regressions;
    }
  }
  EXPECT_GE(regressions, 4u);  // the four the first fuzz runs found
}

}  // namespace
}  // namespace swath::test
