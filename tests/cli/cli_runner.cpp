#include "cli_runner.hpp"

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
