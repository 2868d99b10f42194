#pragma once
// Bad input, and the exit codes every swath program uses.

#include <stdexcept>
#include <string>

namespace swath::base {

/// Bad input from a user's file or arguments. what() is one sentence naming the file, the place
/// (line, feature, key) and the problem; the command line turns it into exit code 2. Outcomes
/// that are not malformed input ("the fleet cannot fly it", "the battery ran empty") are results
/// with a status, not this exception.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// Exit codes, the same in every program (README "Exit codes").
enum ExitCode : int {
  kExitSuccess = 0,
  kExitFailure = 1,       ///< unexpected failure (a bug, or the system refused a write)
  kExitBadInput = 2,      ///< bad input or usage; nothing written
  kExitPartial = 3,       ///< a batch in which some items failed (their rows say why)
  kExitNotCompleted = 4,  ///< a simulated or real flight did not complete (battery, fleet)
  kExitLostControl = 5,   ///< swath-control: the simulated vehicle lost control
};

}  // namespace swath::base
