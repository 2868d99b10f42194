#pragma once
// What a swath-control flight is asked to be (the options `run`, `compare` and `sweep` share) and
// the checked simulation settings built from it: the vehicle, scheduler and environment files
// (bundled names or paths) with their --set overrides, the mission and its options.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swath/control/control_files.hpp"
#include "swath/control/simulation.hpp"

namespace swath::apps {

struct FlightRequest {
  std::string mission, vehicle = "quad-f450", scheduler = "tt-400", environment = "calm";
  std::string drone, start;
  std::vector<std::string> sets;  ///< FILE.KEY=VALUE
  std::uint64_t seed = 1;
  bool loop = false;
  std::optional<double> speed_m_s, altitude_m, max_time_s;
};

/// The options of a flight other than MISSION, -o and the files (each command words those).
void add_flight_options(CLI::App& app, FlightRequest& request);

struct PreparedFlight {
  control::SimulationSettings settings;
  control::SummaryInputs inputs;
  std::vector<std::string> warnings;
};

/// A vehicle, scheduler or environment file: given by path, or the bundled
/// share/<folder>/<given>.yaml when `given` is a bare name.
struct ConfigFile {
  std::string name;  ///< as summary.json names it
  std::string source, text;
};
/// Reads it; throws base::InputError naming `flag` (and the bundled names) when there is none.
ConfigFile config_file(const std::string& given, const std::string& folder, const std::string& what,
                       const std::string& flag);

/// Reads and checks everything the request names; throws base::InputError (one sentence naming
/// the flag or file and the problem).
PreparedFlight prepare_flight(const FlightRequest& request);

}  // namespace swath::apps
