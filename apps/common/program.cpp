#include <iostream>
#include <string>

#include "command.hpp"
#include "remedy_text.hpp"
#include "swath/base/freed_memory.hpp"
#include "swath/base/input_error.hpp"

namespace swath::apps {

int run_program(const char* program, const char* description, const char* exit_codes,
                std::vector<std::unique_ptr<Command>>& commands, int argc, char** argv) {
  base::keep_freed_memory();
  CLI::App app{description};
  app.name(program);
  app.footer(exit_codes);
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(program) + " " + SWATH_VERSION);
  std::vector<std::pair<CLI::App*, Command*>> registered;
  for (auto& command : commands) {
    CLI::App* sub = app.add_subcommand(command->name(), command->description());
    sub->footer(exit_codes);
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
    std::cerr << program << ": " << e.what() << " (see " << program << " --help)\n";
    return base::kExitBadInput;
  }

  for (auto& [sub, command] : registered) {
    if (!sub->parsed()) continue;
    try {
      return command->run();
    } catch (const swath::base::InputError& e) {
      std::cerr << program << ' ' << command->name() << ": "
                << with_remedies(e.what(), e.remedies()) << '\n';
      return base::kExitBadInput;
    } catch (const std::exception& e) {
      std::cerr << program << ' ' << command->name() << ": unexpected failure: " << e.what()
                << '\n';
      return base::kExitFailure;
    }
  }
  return base::kExitBadInput;
}

}  // namespace swath::apps
