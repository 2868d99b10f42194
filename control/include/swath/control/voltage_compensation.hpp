#pragma once
// Thrust compensation for a sagging battery, as ArduPilot's motors library does it
// (AP_MotorsMulticopter: MOT_BAT_VOLT_MAX / MOT_BAT_VOLT_MIN): the controller low-passes the
// battery voltage (0.5 Hz), clamps it to [volt_min_v, volt_max_v] and multiplies its thrust
// outputs by the lift it has lost, (volt_max_v / V)², so the loop gains stay those tuned at a full
// pack. (ArduPilot's lift_max is V/V_max mixed with its square by MOT_THST_EXPO; our ESCs are
// thrust-linear with the motor speed proportional to the voltage, so the square is exact.)

#include "swath/control/rotor_layout.hpp"
#include "swath/vehicle/battery.hpp"

namespace swath::control {

class ThrustCompensation {
 public:
  /// Off unless the battery models sag (cells > 0) and asks for it (thrust_compensation).
  ThrustCompensation(const vehicle::Battery& battery, double initial_voltage_v);
  /// A new terminal voltage `dt_s` after the previous one (first-order filter at 0.5 Hz).
  void measure(double voltage_v, double dt_s);
  /// The thrust gain now, (V_max / V)² (1 when off).
  double gain() const;
  /// A pulse with its thrust multiplied by gain() (at most pwm_max_us).
  double pwm_us(double pwm_us, const MixerRotors& rotors) const;
  double filtered_voltage_v() const { return filtered_v_; }

 private:
  bool on_;
  double volt_min_v_, volt_max_v_;
  double filtered_v_;
};

}  // namespace swath::control
