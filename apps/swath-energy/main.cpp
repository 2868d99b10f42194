// swath-energy: energy of flight plans: simulation with the periodic energy model, and budgets of
// waypoint missions.
#include <memory>
#include <vector>

#include "budget_command.hpp"
#include "command.hpp"
#include "run_command.hpp"

int main(int argc, char** argv) {
  using namespace swath::apps;
  std::vector<std::unique_ptr<Command>> commands;
  commands.push_back(std::make_unique<RunCommand>());
  commands.push_back(std::make_unique<BudgetCommand>());
  return run_program("swath-energy", "swath-energy: energy of drone flight plans",
                     "Exit codes: 0 success; 2 bad input or usage (the message names the file, the "
                     "place and the problem); 4 a drone cannot finish its mission on its battery "
                     "(run: the simulation ended before the last triggering point; budget: a drone "
                     "would land below its reserve); 1 unexpected failure.",
                     commands, argc, argv);
}
