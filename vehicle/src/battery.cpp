#include "swath/vehicle/battery.hpp"

#include <cmath>
#include <limits>

namespace swath::vehicle {

double battery_current_a(const Battery& b, double power_w) {
  const double v = b.voltage_v;
  const double disc = v * v - 4.0 * b.resistance_ohm * b.stabilised_voltage_v * power_w / v;
  if (disc < 0.0) return std::numeric_limits<double>::quiet_NaN();
  // (V - sqrt(disc)) / 2R loses digits when R is small; the conjugate form does not.
  return 2.0 * b.stabilised_voltage_v * power_w / v / (v + std::sqrt(disc));
}

double max_power_w(const Battery& b) {
  return b.voltage_v * b.voltage_v * b.voltage_v /
         (4.0 * b.resistance_ohm * b.stabilised_voltage_v);
}

double soc_of_charge(const Battery& b, double charge_as) {
  return charge_as / (3600.0 * b.capacity_ah);
}

double soc_after_charge(const Battery& b, double soc, double charge_as) {
  return soc - soc_of_charge(b, charge_as);
}

double soc_after(const Battery& b, double soc, double power_w, double seconds) {
  return soc_after_charge(b, soc, battery_current_a(b, power_w) * seconds);
}

double seconds_to_soc(const Battery& b, double soc, double target_soc, double power_w) {
  if (soc <= target_soc) return 0.0;
  const double current = battery_current_a(b, power_w);
  if (!(current > 0.0)) return std::numeric_limits<double>::infinity();
  return (soc - target_soc) * 3600.0 * b.capacity_ah / current;
}

double usable_energy_j(const Battery& b, double soc, double target_soc, double power_w) {
  return power_w * seconds_to_soc(b, soc, target_soc, power_w);
}

}  // namespace swath::vehicle
