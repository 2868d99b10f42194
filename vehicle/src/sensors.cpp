#include "swath/vehicle/sensors.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "swath/vehicle/multirotor.hpp"

namespace swath::vehicle {

Vec3 magnetic_field_unit() {
  const double dip = 60.0 * std::numbers::pi / 180.0;
  return {0.0, std::cos(dip), -std::sin(dip)};
}

Sensor::Sensor(const SensorSettings& settings, SplitMix64 random)
    : settings_(settings), random_(random), next_(settings.phase_ns) {
  // The per-sample constants, computed once (measure() runs at up to a few kHz).
  const double dt = seconds(settings_.period_ns);
  walk_step_ = settings_.bias_random_walk_per_sqrt_s * std::sqrt(dt);
  markov_a_ = std::exp(-dt / settings_.markov_time_constant_s);
  markov_step_ = settings_.markov_sigma_m * std::sqrt(1 - markov_a_ * markov_a_);
  lpf_alpha_ = 1 - std::exp(-2 * std::numbers::pi * settings_.lpf_hz * dt);
  bias_ = Vec3{1, 1, 1} * settings.bias_constant;
  if (settings_.type == SensorType::position && settings_.markov_sigma_m > 0)
    markov_ = Vec3{random_.normal(), random_.normal(), random_.normal()} *
              settings_.markov_sigma_m;  // started stationary
}

Vec3 Sensor::ideal(const Truth& t) const {
  switch (settings_.type) {
    case SensorType::gyro:
      return t.rate_rad_s;
    case SensorType::accel:  // specific force: what the proof mass feels, in body axes
      return rotate_inverse(t.attitude, t.accel_m_s2 + Vec3{0, 0, kStandardGravity_m_s2});
    case SensorType::mag:
      return rotate_inverse(t.attitude, magnetic_field_unit());
    case SensorType::baro:
      return {0, 0, t.position_m.z};
    case SensorType::position:
      return t.position_m;
  }
  return {};
}

double Sensor::convert(double v) const {
  if (settings_.range > 0) v = std::clamp(v, -settings_.range, settings_.range);
  if (settings_.lsb > 0) v = std::round(v / settings_.lsb) * settings_.lsb;
  return v;
}

void Sensor::measure(SimTime now, const Truth& truth) {
  // The bias walks between samples; the noise is white per sample.
  if (settings_.bias_random_walk_per_sqrt_s > 0)
    bias_ += Vec3{random_.normal(), random_.normal(), random_.normal()} * walk_step_;
  Vec3 raw = ideal(truth) + bias_ +
             Vec3{random_.normal(), random_.normal(), random_.normal()} * settings_.noise;
  if (settings_.type == SensorType::position && settings_.markov_sigma_m > 0) {
    // Gauss–Markov, discretised exactly: e_{k+1} = a e_k + σ √(1 − a²) n.
    markov_ = markov_ * markov_a_ +
              Vec3{random_.normal(), random_.normal(), random_.normal()} * markov_step_;
    raw += markov_;
  }
  if (settings_.type == SensorType::baro) raw.x = raw.y = 0;
  const Vec3 converted{convert(raw.x), convert(raw.y), convert(raw.z)};
  if (settings_.lpf_hz > 0 && filter_started_) {
    filtered_ += (converted - filtered_) * lpf_alpha_;
  } else {
    filtered_ = converted;
    filter_started_ = true;
  }
  SensorSample sample;
  sample.measured_at = now;
  sample.delivered_at = now + from_seconds(settings_.latency_s);
  sample.value = filtered_;
  sample.unfiltered = converted;
  if (settings_.type == SensorType::position)
    sample.velocity =
        truth.velocity_m_s +
        Vec3{random_.normal(), random_.normal(), random_.normal()} * settings_.velocity_noise_m_s;
  queue_.push_back(sample);
  next_ = now + settings_.period_ns;
}

std::deque<SensorSample> Sensor::deliver(SimTime now) {
  std::deque<SensorSample> out;
  deliver_each(now, [&](const SensorSample& s) { out.push_back(s); });
  return out;
}

void InertialAccumulator::add_gyro(const Vec3& rate, double dt) {
  sums_.angle_rad += rate * dt;
  sums_.gyro_s += dt;
}

void InertialAccumulator::add_accel(const Vec3& force, double dt) {
  sums_.velocity_m_s += force * dt;
  sums_.accel_s += dt;
}

InertialAccumulator::Deltas InertialAccumulator::take() {
  const Deltas d = sums_;
  sums_ = {};
  return d;
}

}  // namespace swath::vehicle
