#pragma once
// A subcommand of `swath`: setup() only declares options (parsing binds them to members),
// run() does the work. Commands are registered in main.cpp.

#include <CLI/CLI.hpp>

namespace swath::apps {

/// Exit codes of every swath program (documented in --help and the README).
enum ExitCode : int {
  kSuccess = 0,
  kUnexpectedFailure = 1,  ///< a bug or an environment failure (disk full, ...)
  kBadInput = 2,           ///< bad input file or usage; the message says what and where
};

class Command {
 public:
  virtual ~Command() = default;
  virtual const char* name() const = 0;
  virtual const char* description() const = 0;
  virtual void setup(CLI::App& app) = 0;
  /// Throws geometry::InputError for bad input; returns the exit code otherwise.
  virtual int run() = 0;
};

}  // namespace swath::apps
