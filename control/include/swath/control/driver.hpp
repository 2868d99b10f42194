#pragma once
// The sensor driver (docs/swath-control.md): the samples the plant delivers between two
// executions, turned into one execution's estimator input — gyro and accelerometer integrated to
// Δθ and Δv (vehicle::InertialAccumulator), the latest magnetometer, barometer and position fix
// marked fresh until an execution has read them.

#include <optional>
#include <vector>

#include "swath/control/estimator.hpp"
#include "swath/vehicle/flight_model.hpp"

namespace swath::control {

class SensorDriver {
 public:
  /// `sensors`: the vehicle's, in file order (samples name them by index).
  explicit SensorDriver(std::vector<vehicle::SensorSettings> sensors)
      : sensors_(std::move(sensors)) {}

  /// One delivered sample.
  void deliver(const vehicle::DeliveredSample& delivered);
  /// The input of an execution starting at `now_ns` (fresh flags set for what arrived since the
  /// last take; a fresh fix's wait since its arrival, 0 without `now_ns`), and the accumulators
  /// reset.
  EstimatorInput take(std::optional<vehicle::SimTime> now_ns = std::nullopt);

 private:
  std::vector<vehicle::SensorSettings> sensors_;
  vehicle::InertialAccumulator imu_;
  EstimatorInput input_;
  vehicle::SimTime fix_delivered_ns_ = 0;
};

/// The estimator's measurement noise taken from the vehicle's sensors: the position sensor's
/// white noise and velocity noise, the barometer's noise (each floored at 1 mm or 1 mm/s so the
/// filter never trusts a fix absolutely), and the position sensor's latency as the fix delay
/// unless `base` sets one; `base`'s other settings kept.
EstimatorSettings with_sensor_noise(EstimatorSettings base,
                                    const std::vector<vehicle::SensorSettings>& sensors);

}  // namespace swath::control
