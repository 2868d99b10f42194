#pragma once
// Bad input, and the exit codes every swath program uses.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace swath::base {

/// What a user can change to get past a refusal. Libraries name it (a fact about the plan, no
/// option names); each program words it in its own options (apps/common/remedy_text.cpp).
enum class Remedy : std::uint8_t {
  add_drones_or_battery,  ///< more drones, or more range per drone
  allow_partial,          ///< accept a plan that leaves part of the area unflown
  far_home,               ///< accept a home up to the far limit
  far_home_limit,         ///< (beyond even the far limit: nothing to change but the home)
  repair,           ///< fix the outline's order, or plan the areas a crossing outline encloses
  concave_hull,     ///< fly the convex hull instead
  simplify_zones,   ///< merge or simplify holes and no-fly zones
  lower_clearance,  ///< keep less clearance from zones and the boundary
  origin,           ///< place an area in local metres on the map
  local_csv,        ///< read a CSV area as x,y metres
  endurance,        ///< give the drones an endurance
  sorties,          ///< cut each drone's flight into battery-sized sorties
  higher_altitude,  ///< fly higher: a wider footprint, fewer lines, a shorter flight
};

/// Bad input from a user's file or arguments. what() is one sentence naming the file, the place
/// (line, feature, key) and the problem; remedies() what would get past it, for the program to
/// word; the command line turns it into exit code 2. Outcomes that are not malformed input ("the
/// fleet cannot fly it", "the battery ran empty") are results with a status, not this exception.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message, std::vector<Remedy> remedies = {})
      : std::runtime_error(message), remedies_(std::move(remedies)) {}
  const std::vector<Remedy>& remedies() const { return remedies_; }

 private:
  std::vector<Remedy> remedies_;
};

/// Exit codes, the same in every program (docs/reliability.md, "Exit codes and errors").
enum ExitCode : int {
  kExitSuccess = 0,
  kExitFailure = 1,       ///< unexpected failure (a bug, or the system refused a write)
  kExitBadInput = 2,      ///< bad input or usage; nothing written
  kExitPartial = 3,       ///< a batch in which some items failed (their rows say why)
  kExitNotCompleted = 4,  ///< a simulated or real flight did not complete (battery, fleet)
  kExitLostControl = 5,   ///< swath-control: the simulated vehicle lost control
};

}  // namespace swath::base
