// swath: survey planning from the command line.
#include <iostream>
#include <memory>
#include <vector>

#include "cameras_command.hpp"
#include "classify_command.hpp"
#include "command.hpp"
#include "plan_command.hpp"
#include "render_command.hpp"
#include "swath/geometry/input_error.hpp"

namespace {

constexpr const char* kExitCodes =
    "Exit codes: 0 success; 2 bad input or usage (the message names the file, the place and the "
    "problem); 1 unexpected failure.";

}  // namespace

int main(int argc, char** argv) {
  using namespace swath::apps;
  std::vector<std::unique_ptr<Command>> commands;
  commands.push_back(std::make_unique<ClassifyCommand>());
  commands.push_back(std::make_unique<PlanCommand>());
  commands.push_back(std::make_unique<RenderCommand>());
  commands.push_back(std::make_unique<CamerasCommand>());

  CLI::App app{"swath: drone area survey planner"};
  app.footer(kExitCodes);
  app.require_subcommand(1);
  app.set_version_flag("--version", "swath 0.1.0");
  std::vector<std::pair<CLI::App*, Command*>> registered;
  for (auto& command : commands) {
    CLI::App* sub = app.add_subcommand(command->name(), command->description());
    sub->footer(kExitCodes);
    command->setup(*sub);
    registered.emplace_back(sub, command.get());
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "swath: " << e.what() << " (see swath --help)\n";
    return kBadInput;
  }

  for (auto& [sub, command] : registered) {
    if (!sub->parsed()) continue;
    try {
      return command->run();
    } catch (const swath::geometry::InputError& e) {
      std::cerr << "swath " << command->name() << ": " << e.what() << '\n';
      return kBadInput;
    } catch (const std::exception& e) {
      std::cerr << "swath " << command->name() << ": unexpected failure: " << e.what() << '\n';
      return kUnexpectedFailure;
    }
  }
  return kBadInput;
}
