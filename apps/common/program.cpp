#include <cctype>
#include <cstring>
#include <iostream>
#include <string>

#include "command.hpp"
#include "remedy_text.hpp"
#include "swath/base/freed_memory.hpp"
#include "swath/base/input_error.hpp"

namespace swath::apps {
namespace {

// Whether `token` is what strtod reads as NaN or an infinity ("nan", "-inf", "Infinity",
// "nan(0x1)"): CLI11 converts those to doubles, and a range check (x < lo || x > hi) lets NaN
// through (`--max-time nan` ran with a time limit of -9223372036854775808 s).
bool non_finite(std::string token) {
  for (char& c : token) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (!token.empty() && (token[0] == '+' || token[0] == '-')) token.erase(0, 1);
  return token == "nan" || token == "inf" || token == "infinity" || token.rfind("nan(", 0) == 0;
}

// Refuses any option of `app` (and of its parsed subcommands) given NaN or an infinity, alone or
// as part of a pair such as LAT,LON: no option of swath's takes one.
void refuse_non_finite(const CLI::App& app) {
  for (const CLI::Option* option : app.get_options())
    for (const std::string& value : option->results()) {
      std::string token;
      for (const char c : value + ",") {
        if (c != ',' && c != ';' && c != ':' && c != ' ') {
          token += c;
          continue;
        }
        if (non_finite(token))
          throw base::InputError(option->get_name() + " '" + value + "': not a finite number");
        token.clear();
      }
    }
  for (const CLI::App* sub : app.get_subcommands()) refuse_non_finite(*sub);
}

// Whether `name` is one of the arguments.
bool named(const char* name, int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], name) == 0) return true;
  return false;
}

}  // namespace

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
    // Only a command named on the command line can be parsed (by its exact name), so only those
    // declare their options: `swath plan`'s ~120 took 30 % of `swath --version`'s instructions
    // (CLI11 checks each new option's names against all before it). The program's own help
    // lists the commands by name and description alone.
    if (named(command->name(), argc, argv)) command->setup(*sub);
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
      refuse_non_finite(*sub);
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
