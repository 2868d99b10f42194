#include "swath/control/rotor_layout.hpp"

#include "swath/vehicle/multirotor.hpp"

namespace swath::control {

MixerRotors layout_of(const vehicle::Airframe& airframe, const vehicle::EscSettings& esc) {
  MixerRotors layout;
  layout.count = std::min(airframe.rotors.size(), kMaxRotors);
  for (std::size_t i = 0; i < layout.count; ++i) {
    const vehicle::Rotor& r = airframe.rotors[i];
    layout.rotors[i] = Rotor{r.position_m, r.spin > 0, r.efficiency};
  }
  const vehicle::Propulsion& p = airframe.propulsion;
  layout.thrust_coeff_n_s2 = p.thrust_coeff_n_s2;
  layout.torque_coeff_nm_s2 = p.torque_coeff_nm_s2;
  layout.max_speed_rad_s = p.max_speed_rad_s;
  layout.pwm_min_us = esc.pwm_min_us;
  layout.pwm_max_us = esc.pwm_max_us;
  // An ESC that does not quantise (resolution 0): the mixer's own finest quantum.
  layout.resolution_us = esc.resolution_us > 0 ? esc.resolution_us : 1e-6;
  layout.mapping = esc.thrust_linear ? EscMapping::thrust_linear : EscMapping::linear;
  return layout;
}

MixerRotors standard_layout(vehicle::RotorLayout kind, double arm_m, bool first_ccw,
                            double coaxial_lower_efficiency) {
  // One geometry for the plant and the controller: vehicle's layouts.
  vehicle::Airframe airframe;
  airframe.rotors =
      vehicle::rotor_layout(kind, arm_m, first_ccw ? +1 : -1, coaxial_lower_efficiency);
  return layout_of(airframe, vehicle::EscSettings{});
}

}  // namespace swath::control
