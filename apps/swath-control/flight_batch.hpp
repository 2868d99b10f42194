#pragma once
// Many flights at once (compare, sweep): each on its own settings, flown on `jobs` threads, the
// results at their own index so the files do not depend on the number of threads; and their
// table, runs.csv.

#include <string>
#include <vector>

#include "swath/control/simulation.hpp"

namespace swath::apps {

struct BatchFlight {
  std::string environment, vehicle, mode, value;  ///< value: the swept parameter's (sweep)
  std::uint64_t seed = 1;
  control::SimulationSettings settings;
  control::SimulationSummary summary;
};

/// Paper 002 §7's mission in `environment` (lab, rugby, arch): the lab's 20 m x 20 m room, a
/// rugby pitch, the arch's square (`paper` as MISSION of compare and sweep).
std::string paper_mission(const std::string& environment);

/// Flies every flight; rethrows the first failure after all threads have stopped.
void fly_all(std::vector<BatchFlight>& flights, unsigned jobs, bool progress);

/// runs.csv: a row per flight; `value_column` non-empty adds that column (sweep).
std::string runs_csv(const std::vector<BatchFlight>& flights, const std::string& value_column = "");

}  // namespace swath::apps
