#include "swath/vehicle/battery.hpp"

#include <algorithm>
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

double lipo_cell_ocv_v(double soc) {
  const double s = std::clamp(soc, 0.0, 1.0);
  return -1.031 * std::exp(-35.0 * s) + 3.685 + s * (0.2156 + s * (-0.1178 + s * 0.3201));
}

double open_circuit_voltage_v(const Battery& b, double soc) {
  return b.cells * lipo_cell_ocv_v(soc);
}

double pack_resistance_ohm(const Battery& b) {
  return b.cells * b.internal_resistance_ohm;
}

double terminal_voltage_v(const Battery& b, double soc, double current_a) {
  return open_circuit_voltage_v(b, soc) - current_a * pack_resistance_ohm(b);
}

double sag_current_a(const Battery& b, double soc, double power_w) {
  const double e = open_circuit_voltage_v(b, soc);
  const double r = pack_resistance_ohm(b);
  const double disc = e * e - 4.0 * r * power_w;
  if (disc < 0.0) return std::numeric_limits<double>::quiet_NaN();
  // (E − √disc) / 2R in the conjugate form: exact digits for small R, and R = 0 allowed.
  return 2.0 * power_w / (e + std::sqrt(disc));
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
