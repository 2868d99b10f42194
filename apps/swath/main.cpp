// swath: survey planning from the command line.
#include <memory>
#include <vector>

#include "batch_command.hpp"
#include "cameras_command.hpp"
#include "classify_command.hpp"
#include "command.hpp"
#include "plan_command.hpp"
#include "render_command.hpp"
#include "verify_command.hpp"

int main(int argc, char** argv) {
  using namespace swath::apps;
  std::vector<std::unique_ptr<Command>> commands;
  commands.push_back(std::make_unique<ClassifyCommand>());
  commands.push_back(std::make_unique<PlanCommand>());
  commands.push_back(std::make_unique<BatchCommand>());
  commands.push_back(std::make_unique<RenderCommand>());
  commands.push_back(std::make_unique<VerifyCommand>());
  commands.push_back(std::make_unique<CamerasCommand>());
  return run_program("swath", "swath: drone area survey planner",
                     "Exit codes: 0 success; 2 bad input or usage (the message names the file, the "
                     "place and the problem; nothing is written); 3 batch: some areas could not "
                     "be planned (their rows in batch.csv say why); 4 swath verify: a check "
                     "fails; 1 unexpected failure.",
                     commands, argc, argv);
}
