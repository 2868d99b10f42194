#pragma once
// swath-fleet's faults file (docs/swath-fleet.md), YAML:
//   - {t_s: 40, drone: alpha, kind: link_loss, duration_s: 10}
//   - {t_s: 90, drone: bravo, kind: battery_drop, soc: 0.25}
//   - {t_s: 120, drone: alpha, kind: motor_failure}
//   - {t_s: 30, drone: bravo, kind: sensor_failure, duration_s: 20}
// or random ones:
//   random: {per_drone_per_hour: 6, kinds: [link_loss, motor_failure], seed: 3, duration_s: 10}
// Random faults are a Poisson process per drone from SplitMix64::stream(seed, "faults/" + name):
// a drone's faults do not change when drones are added or removed. A random battery_drop falls
// to a charge uniform in [0.05, 0.5].

#include <cstdint>
#include <string>
#include <vector>

#include "swath/fleet/runtime.hpp"

namespace swath::fleet {

/// The faults of `text` for drones named `drones` (indices in that order), up to `horizon_s`,
/// sorted by (t_s, drone). Throws base::InputError naming `source`, the line and the problem
/// (an unknown drone is named with the known ones).
std::vector<FaultEvent> parse_faults(const std::string& text, const std::string& source,
                                     const std::vector<std::string>& drones, double horizon_s);
std::vector<FaultEvent> read_faults(const std::string& path, const std::vector<std::string>& drones,
                                    double horizon_s);

/// Random faults without a file (the property tests' 1,000 schedules).
std::vector<FaultEvent> random_faults(std::uint64_t seed, double per_drone_per_hour,
                                      const std::vector<FaultKind>& kinds,
                                      const std::vector<std::string>& drones, double horizon_s,
                                      double duration_s = 10);

}  // namespace swath::fleet
