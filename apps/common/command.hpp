#pragma once
// A subcommand of `swath` or `swath-energy`: setup() only declares options (parsing binds them to
// members), run() does the work. Each program registers its commands in its main.cpp.

#include <CLI/CLI.hpp>

#include <memory>
#include <vector>

#include "swath/base/input_error.hpp"

namespace swath::apps {

class Command {
 public:
  virtual ~Command() = default;
  virtual const char* name() const = 0;
  virtual const char* description() const = 0;
  virtual void setup(CLI::App& app) = 0;
  /// Throws base::InputError for bad input; returns the exit code otherwise.
  virtual int run() = 0;
};

/// Parses the command line into one of `commands` and runs it: --help, --version, usage errors
/// (exit 2), base::InputError (exit 2, "program command: message"), anything else (exit 1).
int run_program(const char* program, const char* description, const char* exit_codes,
                std::vector<std::unique_ptr<Command>>& commands, int argc, char** argv);

}  // namespace swath::apps
