#pragma once
// The sensors of docs/swath-control.md: gyro, accelerometer, magnetometer, barometer and a position
// fix (GPS or vision), each sampling on its own integer-nanosecond schedule with noise, a bias that
// walks, range and LSB of its converter, a first-order low-pass and a latency; and the driver's
// accumulation of Δθ and Δv between control executions, as ArduPilot's INS backend does, so
// that executions that are skipped lose no inertial data.

#include <cstdint>
#include <deque>
#include <string>

#include "swath/vehicle/clock.hpp"
#include "swath/vehicle/random.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::vehicle {

enum class SensorType { gyro, accel, mag, baro, position };

/// Units are the sensor's own: rad/s (gyro), m/s² (accel), unit field (mag), m (baro, position).
struct SensorSettings {
  std::string name = "gyro";
  SensorType type = SensorType::gyro;
  SimTime period_ns = 1'000'000;  ///< > 0
  SimTime phase_ns = 0;           ///< first sample at phase, then every period
  double noise = 0.0;             ///< white, standard deviation per sample
  double bias_constant = 0.0;
  double bias_random_walk_per_sqrt_s = 0.0;  ///< the bias's standard deviation grows as σ √t
  double lsb = 0.0;                          ///< converter step (0: none)
  double range = 0.0;                        ///< |value| clamped to it per axis (0: none)
  double latency_s = 0.0;                    ///< delivered this long after it is measured
  double lpf_hz = 0.0;                       ///< first-order low-pass cut-off (0: none)
  bool trigger = false;                      ///< has a logistic model (reactive mode)
  // Position fixes only.
  double velocity_noise_m_s = 0.0;
  double markov_sigma_m = 0.0;          ///< Gauss–Markov error, stationary standard deviation
  double markov_time_constant_s = 0.0;  ///< its correlation time (> 0 when sigma > 0)
};

/// What the sensors measure: the true motion at an instant.
struct Truth {
  Vec3 position_m, velocity_m_s;
  Vec3 accel_m_s2;  ///< world ENU, gravity not included
  Quat attitude;    ///< body FLU to world ENU
  Vec3 rate_rad_s;  ///< body FLU
};

/// The magnetic field direction used by `mag` (unit, world ENU): north, dipping 60° down.
Vec3 magnetic_field_unit();

struct SensorSample {
  SimTime measured_at = 0, delivered_at = 0;
  Vec3 value;       ///< body axes for gyro/accel/mag; world for position; z only for baro
  Vec3 velocity;    ///< position fixes: velocity, world ENU
  Vec3 unfiltered;  ///< the value before the low-pass (converted: LSB and range applied)
};

class Sensor {
 public:
  Sensor(const SensorSettings& settings, SplitMix64 random);
  const SensorSettings& settings() const { return settings_; }
  /// When the next sample is measured.
  SimTime next_measurement() const { return next_; }
  /// Measures the sample due now (now == next_measurement()) from the truth; it is delivered
  /// after the latency (see deliver()).
  void measure(SimTime now, const Truth& truth);
  /// The samples delivered by `now`, oldest first (removed from the queue).
  std::deque<SensorSample> deliver(SimTime now);
  /// The same samples, each handed to `take` (no container built: the plant calls this for every
  /// sensor at every event, mostly with nothing due).
  template <typename F>
  void deliver_each(SimTime now, F&& take) {
    while (!queue_.empty() && queue_.front().delivered_at <= now) {
      take(queue_.front());
      queue_.pop_front();
    }
  }
  /// The current bias (for tests and the oracle).
  const Vec3& bias() const { return bias_; }

 private:
  Vec3 ideal(const Truth& truth) const;
  double convert(double v) const;

  SensorSettings settings_;
  SplitMix64 random_;
  SimTime next_;
  Vec3 bias_, filtered_, markov_;
  bool filter_started_ = false;
  double walk_step_ = 0, markov_a_ = 0, markov_step_ = 0, lpf_alpha_ = 0;
  std::deque<SensorSample> queue_;
};

/// The driver's accumulation between executions: Δθ = Σ ω dt over gyro samples, Δv = Σ f dt over
/// accelerometer samples, each sample weighted by its own period.
class InertialAccumulator {
 public:
  void add_gyro(const Vec3& rate_rad_s, double dt_s);
  void add_accel(const Vec3& specific_force_m_s2, double dt_s);
  struct Deltas {
    Vec3 angle_rad, velocity_m_s;
    double gyro_s = 0, accel_s = 0;  ///< the time each sum covers
  };
  /// The sums since the previous take(), and reset.
  Deltas take();

 private:
  Deltas sums_;
};

}  // namespace swath::vehicle
