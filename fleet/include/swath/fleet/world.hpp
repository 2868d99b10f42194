#pragma once
// What the applications act in, as the runtime sees it (docs/swath-fleet.md: fleet sees worlds only
// through this interface): where apps start, the fence, and the sensors. Sensor noise is a hash
// of (seed, position), not of time, so a reading does not depend on the schedule.

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "swath/fleet/task.hpp"

namespace swath::fleet {

/// A sensor that could not read (an app's own sensor raised, or returned no list of numbers):
/// the task sensing fails with its sentence, the rest of the run goes on.
struct SensorError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class World {
 public:
  virtual ~World() = default;
  /// The world's kind ("hotspot", "road", ...).
  virtual std::string kind() const = 0;
  /// Where applications begin, local metres.
  virtual Vec3 start() const = 0;
  /// The fence, local metres (x, y), counter-clockwise; empty: none.
  virtual std::vector<std::array<double, 2>> fence() const { return {}; }
  /// Seconds a reading with `sensor` takes. Throws ActionFailed("unknown_sensor: NAME") for a
  /// sensor this world does not have.
  virtual double sense_time_s(const std::string& sensor) const = 0;
  /// The reading at `at` (t_s and drone are filled in by the runtime). May throw SensorError.
  virtual Reading sense(const std::string& sensor, const Vec3& at, double t_s) const = 0;
};

}  // namespace swath::fleet
