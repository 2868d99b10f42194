#pragma once
// Runs the built command-line programs the way a user does and captures what they say.

#include <map>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace swath::test {

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Runs `binary <args>` (args are passed to /bin/sh as written) from the source directory.
CliRun run_program(const std::string& binary, const std::string& args);
/// run_program() of the built `swath`.
CliRun run_swath(const std::string& args);
/// run_program() of the built `swath-energy`.
CliRun run_swath_energy(const std::string& args);

/// run_program() of the built `swath-control`.
CliRun run_swath_control(const std::string& args);

/// run_program() of the built `swath-fleet`.
CliRun run_swath_fleet(const std::string& args);

/// A file of the user's in -o `dir`, `name` there, that the run `args` of `program` ("swath-fleet",
/// its command the first word of `args`) would write: the run is refused in one sentence naming
/// it, exit 2, the file as it was and nothing else in `dir`. The file taken away, the run writes,
/// and again (its own files are replaced). Fatal failures: call it in ASSERT_NO_FATAL_FAILURE.
void expect_users_file_survives(const std::string& program, const std::string& args,
                                const std::string& dir, const std::string& name);

/// A fresh empty directory under the system's temporary directory (removed first if present).
std::string fresh_dir(const std::string& name);

/// Whole content of a file ("" if missing).
std::string read_text(const std::string& path);

/// Path of a file in the source tree.
std::string source_path(const std::string& relative);

/// Every file under `dir` (recursively) by its path relative to `dir`, with its bytes.
std::map<std::string, std::string> directory_files(const std::string& dir);

/// A QGroundControl .plan mission item (a SimpleItem) of MAV_CMD `command`, `id` its doJumpId,
/// at lat/lon and `alt_m` metres in MAV_FRAME `frame` (3: above home; 0: above mean sea level),
/// its other parameters 0 (yaw none).
nlohmann::json qgc_item(int command, int id, double lat_deg, double lon_deg, double alt_m,
                        int frame = 3);

/// CSV text read back: a row per line (the header first), cells split at commas.
std::vector<std::vector<std::string>> csv_rows(const std::string& text);

}  // namespace swath::test
