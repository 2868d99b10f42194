// swath-control: a simulated multirotor and its control task flying missions (paper 002).
#include <memory>
#include <vector>

#include "ardupilot_json_command.hpp"
#include "command.hpp"
#include "compare_command.hpp"
#include "fit_command.hpp"
#include "response_command.hpp"
#include "run_command.hpp"
#include "sweep_command.hpp"

int main(int argc, char** argv) {
  using namespace swath::apps;
  std::vector<std::unique_ptr<Command>> commands;
  commands.push_back(std::make_unique<ControlRunCommand>());
  commands.push_back(std::make_unique<ControlCompareCommand>());
  commands.push_back(std::make_unique<ControlSweepCommand>());
  commands.push_back(std::make_unique<ControlFitCommand>());
  commands.push_back(std::make_unique<ControlResponseCommand>());
  commands.push_back(std::make_unique<ControlArduPilotJsonCommand>());
  return run_program("swath-control",
                     "swath-control: fly missions with a simulated multirotor and its control task",
                     "Exit codes: 0 the flight ended as asked (completed, the reserve reached with "
                     "--loop, or the time limit); 2 bad input or usage, or an output directory "
                     "that cannot be used (the message names the file, the place and the "
                     "problem; nothing is written); 4 the battery ran empty before the end of the "
                     "mission; 5 the vehicle lost control (tilt, ground, or 50 m off for 5 s; the "
                     "files are still written); 1 unexpected failure.",
                     commands, argc, argv);
}
