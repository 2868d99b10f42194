#pragma once
// What the headless-browser tests of the pages share (plan_page_test.cpp, live_page_test.cpp):
// running a command, a scratch directory per test binary, finding Chromium and reading the
// page's self-check (#swath-check) back from the DOM it dumped.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace swath::html_test {

namespace fs = std::filesystem;

inline std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct ShellRun {
  int exit_code = -1;
  std::string out;
};

// `command` through /bin/sh from the source directory; standard output (and error, when the
// command does not send it elsewhere).
inline ShellRun run(const std::string& command) {
  const std::string full = "cd '" SWATH_SOURCE_DIR "' && " + command + " 2>&1";
  ShellRun r;
  FILE* pipe = ::popen(full.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
    r.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// One per test binary and process: the two binaries may run at once.
inline fs::path scratch_root() {
  return fs::temp_directory_path() /
         (std::string(program_invocation_short_name) + "-" + std::to_string(::getpid()));
}

// The plans, runs and Chromium's profiles (some MB each) go when every test passed; kept to look
// at otherwise.
class RemoveScratch : public ::testing::Environment {
 public:
  void TearDown() override {
    if (!::testing::UnitTest::GetInstance()->Failed()) fs::remove_all(scratch_root());
  }
};
inline const auto* const kRemoveScratch = ::testing::AddGlobalTestEnvironment(new RemoveScratch);

// A fresh path `name` in the scratch directory; its parent exists, it does not (a plan's -o
// directory must be absent to tell that a refused plan wrote nothing).
inline fs::path scratch(const std::string& name) {
  const fs::path dir = scratch_root() / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

inline std::string chromium() {
  const char* env = std::getenv("SWATH_CHROMIUM");
  const std::string path = env && *env ? env : "/usr/bin/chromium";
  return fs::exists(path) ? path : "";
}

#define REQUIRE_CHROMIUM()                                                                  \
  if (::swath::html_test::chromium().empty())                                               \
  GTEST_SKIP() << "no Chromium at /usr/bin/chromium or $SWATH_CHROMIUM: the browser tests " \
                  "of the pages need it (scripts/setup installs it)"

// The page's self-check (#swath-check), read from the DOM Chromium dumped; null when absent.
inline nlohmann::json self_check(const std::string& dom_text) {
  const std::string open = "<pre id=\"swath-check\" hidden=\"\">";
  const std::size_t at = dom_text.find(open);
  if (at == std::string::npos) return nlohmann::json();
  const std::size_t end = dom_text.find("</pre>", at);
  std::string text = dom_text.substr(at + open.size(), end - at - open.size());
  for (const auto& [entity, c] : std::map<std::string, std::string>{
           {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&amp;", "&"}})
    for (std::size_t k; (k = text.find(entity)) != std::string::npos;)
      text.replace(k, entity.size(), c);
  return nlohmann::json::parse(text, nullptr, false);
}

}  // namespace swath::html_test
