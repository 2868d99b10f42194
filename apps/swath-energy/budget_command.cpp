#include "budget_command.hpp"

#include <iostream>

#include "swath/base/output_set.hpp"
#include "swath/energy/budget.hpp"
#include "swath/energy/energy_files.hpp"
#include "swath/energy/sim_config.hpp"

namespace swath::apps {

void BudgetCommand::setup(CLI::App& app) {
  app.add_option(
         "MISSION", mission_,
         "mission.geojson written by swath plan, a QGC .plan or a QGC WPL 110 .waypoints file")
      ->required();
  app.add_option("--drone", drone_,
                 "Drone profile YAML: speeds, battery, power (see share/drones/)")
      ->required();
  app.add_option("-o,--output", output_, "Also write budget.json and soc.csv into this directory");
  app.add_flag("--json", json_, "Print budget.json to stdout instead of the table");
}

int BudgetCommand::run() {
  const auto missions = energy::read_waypoint_missions(mission_);
  const energy::DroneProfile drone = energy::read_drone_profile(drone_);
  for (const std::string& w : drone.warnings)
    std::cerr << "swath-energy budget: warning: " << w << '\n';
  // A file of the user's in the way is refused before the budget, not after it.
  if (!output_.empty())
    base::check_output_names(output_, "energy-budget", {"budget.json", "soc.csv"});
  std::vector<energy::DroneBudget> budgets;
  for (const auto& m : missions) budgets.push_back(energy::budget(m, drone));
  const std::string json = energy::budget_json(budgets, drone);
  if (!output_.empty())
    base::write_files_atomically(output_,
                                 {{"budget.json", json}, {"soc.csv", energy::budget_csv(budgets)}},
                                 "energy-budget");
  std::cout << (json_ ? json : energy::budget_table(budgets, drone));
  for (const auto& b : budgets)
    if (!b.can_finish()) return base::kExitNotCompleted;
  return base::kExitSuccess;
}

}  // namespace swath::apps
