#pragma once
// The rotors as the control task sees them (docs/swath-control.md): where each one pushes, which
// way it spins, how thrust and drag torque follow its speed, and the ESC's PWM range. These are
// control's own inputs, a small value the caller fills from the vehicle description; they say
// nothing about the motor dynamics, which only the simulated airframe needs.

#include <array>
#include <cstddef>

#include "swath/vehicle/multirotor.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::control {

using vehicle::Quat;
using vehicle::Vec3;

/// The most rotors a layout may have (docs/swath-control.md: n ≤ 8).
inline constexpr std::size_t kMaxRotors = 8;

/// One rotor. Its thrust is `efficiency · thrust_coeff_n_s2 · Ω²` along body +z (up) and its drag
/// torque `−spin · torque_coeff_nm_s2 · Ω²` about body +z, spin = +1 for a counter-clockwise rotor
/// seen from above (s_i).
struct Rotor {
  Vec3 position_m;          ///< hub in body FLU about the centre of mass, m; |·| < 10
  bool ccw = true;          ///< true: spins counter-clockwise seen from above
  double efficiency = 1.0;  ///< η in (0, 1]: < 1 only for the lower rotor of a coaxial pair
};

/// ESC pulse mapping (`esc.mapping`, docs/swath-control.md, 'Vehicle, scheduler and environment
/// files'): `thrust_linear` commands Ω = Ω_max √u, so thrust is proportional to the normalised
/// pulse u; `linear` commands Ω = Ω_max u.
enum class EscMapping { thrust_linear, linear };

/// Everything the mixer needs. Valid when 4 ≤ count ≤ 8, coefficients > 0, pwm_min_us <
/// pwm_max_us, 0 < resolution_us ≤ pwm_max_us − pwm_min_us, and the effectiveness has rank 4.
struct MixerRotors {
  std::array<Rotor, kMaxRotors> rotors{};
  std::size_t count = 0;                ///< rotors in use, [4, 8]
  double thrust_coeff_n_s2 = 8.0e-6;    ///< k_T, N/(rad/s)², > 0 (the propeller)
  double torque_coeff_nm_s2 = 1.28e-7;  ///< k_Q, N m/(rad/s)², > 0
  double max_speed_rad_s = 1000.0;      ///< Ω_max, rad/s, > 0
  double pwm_min_us = 1000.0;           ///< pulse for u = 0, µs
  double pwm_max_us = 2000.0;           ///< pulse for u = 1, µs, > pwm_min_us
  double resolution_us = 1.0;           ///< PWM quantum, µs, (0, pwm_max_us − pwm_min_us]
  EscMapping mapping = EscMapping::thrust_linear;

  /// The largest thrust of one rotor at full efficiency, k_T Ω_max², N.
  double max_rotor_force_n() const { return thrust_coeff_n_s2 * max_speed_rad_s * max_speed_rad_s; }
};

/// The standard frames of `rotors.layout` (vehicle::RotorLayout, vehicle::rotor_layout: the plant's
/// own geometry and rotor order): quad_x and hexa_x arms every 90° / 60° from 45° / 30° left of
/// forward, spins alternating from `first_ccw`; y6 three arms at 60°, 180°, 300°, each an upper
/// rotor of `first_ccw` and a lower one of the other spin at `coaxial_lower_efficiency`, upper and
/// lower alternating.
MixerRotors standard_layout(vehicle::RotorLayout kind, double arm_m, bool first_ccw = true,
                            double coaxial_lower_efficiency = 0.8);

/// The layout of the plant's airframe and ESCs, as the controller believes them to be.
MixerRotors layout_of(const vehicle::Airframe& airframe, const vehicle::EscSettings& esc);

}  // namespace swath::control
