#include "cli_runner.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace swath::test {
namespace {

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::string fresh_dir(const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("swath-cli-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir.string();
}

std::string read_text(const std::string& path) {
  return slurp(path);
}

std::string source_path(const std::string& relative) {
  return std::string(SWATH_SOURCE_DIR) + "/" + relative;
}

std::map<std::string, std::string> directory_files(const std::string& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file())
      out[std::filesystem::relative(e.path(), dir).string()] = read_text(e.path().string());
  return out;
}

nlohmann::json qgc_item(int command, int id, double lat_deg, double lon_deg, double alt_m,
                        int frame) {
  return {{"autoContinue", true},
          {"command", command},
          {"doJumpId", id},
          {"frame", frame},
          {"params", {0, 0, 0, nullptr, lat_deg, lon_deg, alt_m}},
          {"type", "SimpleItem"}};
}

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

CliRun run_swath(const std::string& args) {
  return run_program(SWATH_BINARY, args);
}

CliRun run_swath_energy(const std::string& args) {
  return run_program(SWATH_ENERGY_BINARY, args);
}

CliRun run_swath_control(const std::string& args) {
  return run_program(SWATH_CONTROL_BINARY, args);
}

CliRun run_swath_fleet(const std::string& args) {
  return run_program(SWATH_FLEET_BINARY, args);
}

namespace {

CliRun run_named(const std::string& program, const std::string& args) {
  if (program == "swath") return run_swath(args);
  if (program == "swath-energy") return run_swath_energy(args);
  if (program == "swath-control") return run_swath_control(args);
  if (program == "swath-fleet") return run_swath_fleet(args);
  ADD_FAILURE() << "no program " << program << " is built for the tests";
  return {};
}

}  // namespace

void expect_users_file_survives(const std::string& program, const std::string& args,
                                const std::string& dir, const std::string& name) {
  const std::string mine = "MY OWN " + name + "\n", path = dir + "/" + name;
  std::filesystem::create_directories(dir);
  std::ofstream(path) << mine;
  const CliRun refused = run_named(program, args);
  EXPECT_EQ(refused.exit_code, 2);
  const std::string command = args.substr(0, args.find(' '));  // its list: .swath-fleet-run.files
  EXPECT_EQ(refused.err, program + " " + command + ": " + path +
                             ": a file swath did not write (no ." + program + "-" + command +
                             ".files here lists it) would be replaced; move it, or choose "
                             "another -o\n");
  EXPECT_EQ(read_text(path), mine);
  EXPECT_EQ(directory_files(dir).size(), 1u);
  std::filesystem::remove(path);
  ASSERT_EQ(run_named(program, args).exit_code, 0);
  const CliRun again = run_named(program, args);
  ASSERT_EQ(again.exit_code, 0) << "its own files are replaced: " << again.err;
}

CliRun run_program(const std::string& binary, const std::string& args) {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path dir = fs::temp_directory_path() / ("swath-cli-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path out = dir / ("out" + std::to_string(counter));
  const fs::path err = dir / ("err" + std::to_string(counter++));
  const std::string command = "cd '" + std::string(SWATH_SOURCE_DIR) + "' && '" + binary + "' " +
                              args + " >'" + out.string() + "' 2>'" + err.string() + "' </dev/null";
  const int status = std::system(command.c_str());
  CliRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = slurp(out);
  run.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return run;
}

}  // namespace swath::test
