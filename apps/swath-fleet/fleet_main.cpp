// swath-fleet's command line (fleet_main.hpp).
#include "fleet_main.hpp"

#include <memory>
#include <vector>

#include "command.hpp"
#include "ctl_command.hpp"
#include "forecasts_command.hpp"
#include "replay_command.hpp"
#include "run_command.hpp"
#include "scale_out_command.hpp"
#include "tune_command.hpp"
#include "view_command.hpp"

namespace swath::apps {

int fleet_main(int argc, char** argv) {
  std::vector<std::unique_ptr<Command>> commands;
  commands.push_back(std::make_unique<FleetRunCommand>());
  commands.push_back(std::make_unique<FleetCompareCommand>());
  commands.push_back(std::make_unique<FleetForecastsCommand>());
  commands.push_back(std::make_unique<FleetReplayCommand>());
  commands.push_back(std::make_unique<FleetTuneCommand>());
  commands.push_back(std::make_unique<FleetCheckCommand>());
  commands.push_back(std::make_unique<FleetAppsCommand>());
  commands.push_back(std::make_unique<FleetWorldsCommand>());
  commands.push_back(std::make_unique<FleetRenderCommand>());
  commands.push_back(std::make_unique<FleetSweepCommand>());
  commands.push_back(std::make_unique<FleetCollectCommand>());
  commands.push_back(std::make_unique<FleetCtlCommand>());
  commands.push_back(std::make_unique<FleetViewCommand>());
  return run_program(
      "swath-fleet", "swath-fleet: swarm applications on a simulated fleet (paper 000)",
      "Exit codes: 0 the application completed; 2 bad input or usage (the message "
      "names the file, the place and the problem; nothing is written); 4 the "
      "application did not complete (time limit, no drone could serve it, its "
      "main failed, an abort by `ctl rtl-all` or `ctl land-all`; the files are still written; "
      "check: a rule is broken); 130 and 143 run aborted by SIGINT and SIGTERM (every airborne "
      "vehicle told to return, or land, the files written); 1 unexpected failure (an exception "
      "during a run aborts it the same way first).",
      commands, argc, argv);
}

}  // namespace swath::apps
