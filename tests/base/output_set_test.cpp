// The output set (docs/swath-plan.md): whole sets switched in, nothing foreign
// replaced, stale files of swath's own previous set removed, planted names refused, nothing left
// behind by a refusal.
#include "swath/base/output_set.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>

#include "swath/base/input_error.hpp"

namespace swath::base {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("swath-output-set-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// Every name in the directory, swath's manifests included.
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

TEST(OutputSet, AFailedWriteLeavesTheOldFilesAndNoTemporaries) {
  const fs::path dir = fresh("failed");
  write_files_atomically(dir, {{"a.txt", "old a"}, {"b.txt", "old b"}});
  // The second name is not a plain file name: nothing may change, no temporary stays.
  EXPECT_THROW(write_files_atomically(dir, {{"a.txt", "new a"}, {"missing/b.txt", "new b"}}),
               InputError);
  EXPECT_EQ(slurp(dir / "a.txt"), "old a");
  EXPECT_EQ(listing(dir), (std::set<std::string>{".swath-files.files", "a.txt", "b.txt"}));
  write_files_atomically(dir, {{"a.txt", "new a"}});
  EXPECT_EQ(slurp(dir / "a.txt"), "new a");
}

// A user's directory named like a file of the set: refused before anything changes, as bad input.
TEST(OutputSet, ADirectoryInTheWayIsRefusedBeforeAnythingChanges) {
  const fs::path dir = fresh("in-the-way");
  write_files_atomically(dir, {{"a.txt", "old a"}, {"c.txt", "old c"}}, "plan");
  fs::create_directories(dir / "b.txt" / "inside");
  try {
    write_files_atomically(dir, {{"a.txt", "new a"}, {"b.txt", "new b"}, {"c.txt", "new c"}},
                           "plan");
    FAIL() << "a file renamed onto a directory";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("b.txt: a directory of that name is in the way"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(slurp(dir / "a.txt"), "old a");
  EXPECT_EQ(slurp(dir / "c.txt"), "old c");
  EXPECT_TRUE(fs::is_directory(dir / "b.txt" / "inside"));
  EXPECT_EQ(listing(dir), (std::set<std::string>{".swath-plan.files", "a.txt", "b.txt", "c.txt"}));
}

// The k-th rename of a set fails (as a file system may: EIO): the renames before it are undone,
// each file its old self again or gone where it had none, nothing of the set left behind (no
// temporary, no kept second name), the manifest the old one.
TEST(OutputSet, ARenameFailingPartWayIsUndoneTheOldSetAsItWas) {
  const fs::path dir = fresh("undone");
  write_files_atomically(dir, {{"a.txt", "old a"}, {"c.txt", "old c"}}, "plan");
  const std::string manifest = slurp(dir / ".swath-plan.files");
  const std::set<std::string> before = listing(dir);
  // The set renames a.txt, b.txt (new), c.txt, d.txt (new), its manifest: each k fails in turn.
  for (int failing = 1; failing <= 5; ++failing) {
    int renames = 0;
    testing::set_rename_function([&](const char* from, const char* to) {
      if (++renames == failing) {
        errno = EIO;
        return -1;
      }
      return std::rename(from, to);
    });
    try {
      write_files_atomically(
          dir, {{"a.txt", "new a"}, {"b.txt", "new b"}, {"c.txt", "new c"}, {"d.txt", "new d"}},
          "plan");
      ADD_FAILURE() << "rename " << failing << " failed, yet the set was committed";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("the old files are as they were"), std::string::npos)
          << e.what();
    }
    testing::set_rename_function({});
    EXPECT_EQ(listing(dir), before) << "rename " << failing;
    EXPECT_EQ(slurp(dir / "a.txt"), "old a") << failing;
    EXPECT_EQ(slurp(dir / "c.txt"), "old c") << failing;
    EXPECT_EQ(slurp(dir / ".swath-plan.files"), manifest) << failing;
  }
  // And the set switches in whole once renames work, the kept second names gone.
  write_files_atomically(dir, {{"a.txt", "new a"}, {"b.txt", "new b"}}, "plan");
  EXPECT_EQ(slurp(dir / "a.txt"), "new a");
  EXPECT_EQ(listing(dir), (std::set<std::string>{".swath-plan.files", "a.txt", "b.txt"}));
}

TEST(OutputSet, StaleFilesOfTheSameKindGoFilesOfOthersStay) {
  const fs::path dir = fresh("stale");
  fs::create_directories(dir);
  std::ofstream(dir / "notes.txt") << "the user's own file";
  write_files_atomically(dir, {{"summary.json", "1"}, {"drone-1.plan", "1"}, {"drone-2.plan", "1"}},
                         "plan");
  // A re-plan with one drone: drone-2.plan was the old set's and goes; notes.txt was never ours.
  write_files_atomically(dir, {{"summary.json", "2"}, {"drone-1.plan", "2"}}, "plan");
  EXPECT_EQ(listing(dir), (std::set<std::string>{".swath-plan.files", "drone-1.plan", "notes.txt",
                                                 "summary.json"}));
  EXPECT_EQ(slurp(dir / "notes.txt"), "the user's own file");
  // Amending adds to the set without removing anything.
  {
    OutputSet amend(dir, "plan", {OutputSet::Mode::amend, 10.0});
    amend.add("coverage.png", "png");
    amend.commit();
  }
  write_files_atomically(dir, {{"summary.json", "3"}}, "plan");
  EXPECT_FALSE(fs::exists(dir / "coverage.png")) << "amended files belong to the set too";
  EXPECT_FALSE(fs::exists(dir / "drone-1.plan"));
}

// What a run killed by SIGKILL (no handler runs) leaves: its temporaries and the old files' second
// names, of the set's own files and of the set before. The next run removes them once its set
// is in; hidden names of other forms, or of files swath did not write, are the user's.
TEST(OutputSet, LeftoversOfAKilledRunGoTheUsersHiddenFilesStay) {
  const fs::path dir = fresh("leftovers");
  write_files_atomically(dir, {{"summary.json", "1"}, {"drone-2.plan", "1"}}, "plan");
  const std::set<std::string> leftovers{
      ".summary.json.tmp-0123456789abcdef", ".summary.json.old-fedcba9876543210",
      ".drone-2.plan.tmp-00000000deadbeef",        // of the set before (one drone now)
      "..swath-plan.files.tmp-0a0b0c0d0e0f0102"};  // the manifest's (its name begins with a dot)
  const std::set<std::string> users{".summary.json.old-backup",  // not a suffix swath draws
                                    ".summary.json.tmp-0123456789ABCDEF",  // upper case: not either
                                    ".notes.txt.tmp-0123456789abcdef",  // a file swath never wrote
                                    "summary.json.tmp-0123456789abcdef",     // not hidden
                                    ".summary.json.tmp-0123456789abcdef0"};  // one digit too many
  for (const std::string& name : leftovers) std::ofstream(dir / name) << "left";
  for (const std::string& name : users) std::ofstream(dir / name) << "mine";
  write_files_atomically(dir, {{"summary.json", "2"}}, "plan");
  std::set<std::string> expected{".swath-plan.files", "summary.json"};
  expected.insert(users.begin(), users.end());
  EXPECT_EQ(listing(dir), expected);
  for (const std::string& name : users) EXPECT_EQ(slurp(dir / name), "mine") << name;
  EXPECT_EQ(slurp(dir / "summary.json"), "2");
}

TEST(OutputSet, ANameAnotherKindWroteIsRefusedBeforeAnythingIsWritten) {
  const fs::path dir = fresh("foreign");
  write_files_atomically(dir, {{"summary.json", "plan"}}, "plan");
  OutputSet run(dir, "energy-run");
  run.add("energy.csv", "t");
  try {
    run.add("summary.json", "run");
    FAIL() << "replaced the plan's summary.json";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("summary.json belongs to the files of a swath plan"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(slurp(dir / "summary.json"), "plan");
  EXPECT_THROW(run.add("energy.csv", "again"), InputError) << "a name twice in one set";
}

// A file no manifest lists (the user's summary.json, or an older swath's that wrote none) is never
// replaced by default, by any kind of set: refused naming it, with the set's remedy, nothing
// written. A set told to replace it (a file the user named) does; check_output_names() refuses
// the same names, another kind's included, and writes or creates nothing.
TEST(OutputSet, AFileNoManifestListsIsKeptUnlessTheSetIsToldOtherwise) {
  const fs::path dir = fresh("unlisted");
  fs::create_directories(dir);
  std::ofstream(dir / "summary.json") << "mine";
  const auto refusal = [&](const std::function<void()>& write) {
    try {
      write();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("not refused");
  };
  const std::string sentence = (dir / "summary.json").string() +
                               ": a file swath did not write (no .swath-energy-run.files here "
                               "lists it) would be replaced; ";
  EXPECT_EQ(refusal([&] {
              write_files_atomically(dir, {{"summary.json", "run"}}, "energy-run");
            }),
            sentence + "move it, or choose another -o");
  OutputSet::Options options;
  options.unlisted_remedy = "move it";
  EXPECT_EQ(refusal([&] {
              check_output_names(dir, "energy-run", {"a.csv", "summary.json"}, options);
            }),
            sentence + "move it");
  EXPECT_EQ(listing(dir), std::set<std::string>{"summary.json"});
  EXPECT_EQ(slurp(dir / "summary.json"), "mine");
  EXPECT_EQ(refusal([&] { check_output_names(dir / "not-there", "energy-run", {"summary.json"}); }),
            "not refused");
  EXPECT_FALSE(fs::exists(dir / "not-there"));
  // Told to replace it: replaced, and listed from now on, so a set of that kind replaces it again.
  options.keep_unlisted = false;
  {
    OutputSet set(dir, "energy-run", options);
    set.add("summary.json", "run 1");
    set.commit();
  }
  write_files_atomically(dir, {{"summary.json", "run 2"}}, "energy-run");
  EXPECT_EQ(slurp(dir / "summary.json"), "run 2");
  // Another kind's file is refused as ever, by the check too.
  EXPECT_NE(refusal([&] {
              check_output_names(dir, "control-run", {"summary.json"});
            }).find("summary.json belongs to the files of a swath energy-run"),
            std::string::npos);
}

TEST(OutputSet, ARefusalAfterOpeningLeavesNoDirectoryBehind) {
  const fs::path dir = fresh("refused") / "deeper";
  {
    OutputSet set(dir, "plan");
    set.add("a.txt", "a");
    EXPECT_TRUE(fs::exists(dir));
  }  // destroyed without commit, as when a refusal is thrown after opening
  EXPECT_FALSE(fs::exists(dir));
}

TEST(OutputSet, StreamsWriteLargeFilesPieceByPiece) {
  const fs::path dir = fresh("stream");
  OutputSet set(dir, "energy-run");
  OutputSet::Stream& rows = set.stream("rows.csv");
  std::string expected;
  for (int i = 0; i < 100000; ++i) {
    const std::string row = std::to_string(i) + "," + std::to_string(long{i} * i) + "\n";
    rows << row;
    expected += row;
  }
  EXPECT_EQ(rows.size(), expected.size());
  EXPECT_FALSE(fs::exists(dir / "rows.csv")) << "nothing in place before commit";
  set.commit();
  EXPECT_EQ(slurp(dir / "rows.csv"), expected);
}

// Temporary names are random; the test makes them predictable, plants a symlink (to a file
// outside the directory) or a file at each of the first names the set will draw, and checks that
// every planted name is refused, nothing outside changes and the set still lands.
TEST(OutputSet, PlantedNamesAtTheTemporariesAreNeverOpened) {
  const fs::path dir = fresh("planted");
  const fs::path outside = fresh("planted-victim");
  fs::create_directories(dir);
  fs::create_directories(outside);
  std::ofstream(outside / "victim") << "precious";
  int drawn = 0;
  testing::set_temporary_suffix_source([&] { return "n" + std::to_string(drawn++); });
  for (int k = 0; k < 20; ++k) {
    const fs::path planted = dir / (".summary.json.tmp-n" + std::to_string(k));
    if (k % 2 == 0)
      fs::create_symlink(outside / "victim", planted);
    else
      std::ofstream(planted) << "planted";
  }
  write_files_atomically(dir, {{"summary.json", "ours"}}, "plan");
  EXPECT_EQ(slurp(outside / "victim"), "precious");
  EXPECT_EQ(slurp(dir / "summary.json"), "ours");
  EXPECT_EQ(drawn, 22)
      << "20 planted names refused, then one for the file and one for the manifest";
  // Every name planted: the set is refused with a system error, and nothing outside changes.
  drawn = 0;
  testing::set_temporary_suffix_source([&] { return "n" + std::to_string(drawn++ % 20); });
  EXPECT_THROW(write_files_atomically(dir, {{"summary.json", "again"}}, "plan"),
               std::runtime_error);
  testing::set_temporary_suffix_source({});
  EXPECT_EQ(slurp(outside / "victim"), "precious");
  EXPECT_EQ(slurp(dir / "summary.json"), "ours");
}

// A second set into a locked directory waits, then is refused naming the holder.
TEST(OutputSet, ASecondRunWaitsForTheLockThenIsRefusedNamingTheHolder) {
  const fs::path dir = fresh("locked");
  OutputSet holder(dir, "plan");
  const pid_t child = ::fork();
  if (child == 0) {
    int code = 3;
    try {
      OutputSet second(dir, "plan", {OutputSet::Mode::replace, 0.2});
      code = 4;
    } catch (const InputError& e) {
      const std::string what = e.what();
      code = what.find("another swath run (process " + std::to_string(::getppid()) + ")") !=
                     std::string::npos
                 ? 0
                 : 5;
    }
    ::_exit(code);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: threw another error, 4: not refused, 5: wrong message";
}

}  // namespace
}  // namespace swath::base
