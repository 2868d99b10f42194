#include "swath/control/driver.hpp"

#include <algorithm>

namespace swath::control {

using vehicle::SensorType;

void SensorDriver::deliver(const vehicle::DeliveredSample& d) {
  const vehicle::SensorSettings& s = sensors_[d.sensor];
  const double dt = vehicle::seconds(s.period_ns);
  switch (s.type) {
    case SensorType::gyro:
      imu_.add_gyro(d.sample.value, dt);
      break;
    case SensorType::accel:
      imu_.add_accel(d.sample.value, dt);
      break;
    case SensorType::mag:
      input_.mag = {d.sample.value, true};
      break;
    case SensorType::baro:
      input_.baro = {d.sample.value.z, true};
      break;
    case SensorType::position:
      input_.fix = {d.sample.value, d.sample.velocity, true, true};
      fix_delivered_ns_ = d.sample.delivered_at;
      break;
  }
}

EstimatorInput SensorDriver::take(std::optional<vehicle::SimTime> now_ns) {
  const vehicle::InertialAccumulator::Deltas d = imu_.take();
  input_.imu = {d.angle_rad, d.velocity_m_s, d.gyro_s};
  input_.fix.waited_s =
      now_ns && input_.fix.position_fresh ? vehicle::seconds(*now_ns - fix_delivered_ns_) : 0.0;
  EstimatorInput out = input_;
  input_.mag.fresh = input_.baro.fresh = false;
  input_.fix.position_fresh = input_.fix.velocity_fresh = false;
  return out;
}

EstimatorSettings with_sensor_noise(EstimatorSettings base,
                                    const std::vector<vehicle::SensorSettings>& sensors) {
  for (const vehicle::SensorSettings& s : sensors) {
    if (s.type == SensorType::position) {
      base.position_noise_m = std::max(s.noise, 1e-3);
      base.velocity_noise_m_s = std::max(s.velocity_noise_m_s, 1e-3);
      if (!base.fix_delay_s) base.fix_delay_s = s.latency_s;
    } else if (s.type == SensorType::baro) {
      base.baro_noise_m = std::max(s.noise, 1e-3);
    }
  }
  return base;
}

}  // namespace swath::control
