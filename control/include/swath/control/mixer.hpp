#pragma once
// The mixer (docs/swath-control.md): the rotor forces that produce a collective thrust and a
// body torque, by the pseudo-inverse of the layout's effectiveness matrix; under saturation yaw is
// given up first, then the collective, and roll and pitch last (attitude authority kept, as
// ArduPilot and PX4 do); then normalised pulses quantised to the ESC's resolution.

#include <array>
#include <optional>

#include "swath/control/rotor_layout.hpp"

namespace swath::control {

/// The wrench of the rotors in body FLU: collective thrust along +z and torque.
struct Wrench {
  double thrust_n = 0;  ///< N, along body +z
  Vec3 torque_nm;       ///< N m, body FLU
};

/// The layout's effectiveness A (4 × n) and its pseudo-inverse A⁺ (n × 4). The unknowns are the
/// rotor forces f_i = k_T Ω_i² (N, before efficiency), so A's column i is
/// [η_i, η_i y_i, −η_i x_i, −s_i k_Q / k_T]: thrust, roll, pitch and yaw torque per newton.
struct MixerMatrices {
  std::array<std::array<double, kMaxRotors>, 4> effectiveness{};   ///< A, rows T, τx, τy, τz
  std::array<std::array<double, 4>, kMaxRotors> pseudo_inverse{};  ///< A⁺ = Aᵀ (A Aᵀ)⁻¹
  std::size_t count = 0;
};

/// A and A⁺ of `layout`, or nullopt when the layout is invalid (count outside [4, 8], a coefficient
/// not positive) or A has rank < 4 (the frame cannot control all four axes: refused).
std::optional<MixerMatrices> mixer_matrices(const MixerRotors& layout);

/// What one mix produced.
struct MixerOutput {
  std::array<double, kMaxRotors> force_n{};          ///< f_i = k_T Ω_i², N, in [0, k_T Ω_max²]
  std::array<double, kMaxRotors> speed_cmd_rad_s{};  ///< Ω the pulse commands (after quantising)
  std::array<double, kMaxRotors> pwm_us{};           ///< pwm_min_us + resolution_us · level, µs
  Wrench achieved;                                   ///< the wrench of the unquantised forces, A f
  double yaw_scale = 1;         ///< share of the requested yaw torque kept, [0, 1]
  double roll_pitch_scale = 1;  ///< share of the requested roll/pitch torque kept, [0, 1]
  bool thrust_clipped = false;  ///< the collective was moved from the request (out of reach, or
                                ///< to make room for roll and pitch)
};

/// Mixes `request` for `layout` (whose matrices are `m`), keeping attitude authority first as
/// ArduPilot's and PX4's mixers do:
/// 1. roll and pitch, f_RP = A⁺[0, τx, τy, 0], with the largest scale k ≤ 1 (their ratio kept)
///    for which some collective keeps every force in [0, f_max];
/// 2. the collective f_T = A⁺[T, 0, 0, 0] nearest the request within the collectives that leave
///    room for k·f_RP: reduced when a rotor would saturate high, raised when one would stop
///    (`thrust_clipped`);
/// 3. yaw, f_Y = A⁺[0, 0, 0, τz], with the largest scale ≤ 1 left over;
/// 4. the pulse u_i = f_i / f_max (thrust_linear) or √(f_i / f_max) (linear) is quantised to the
///    nearest level.
/// So a request within reach is produced exactly (A f = w), and one beyond it loses yaw first,
/// then collective, and roll and pitch only when no collective makes room for them.
MixerOutput mix(const MixerRotors& layout, const MixerMatrices& m, const Wrench& request);

/// The nearest quantised pulse for normalised command u (clamped to [0, 1]), µs.
double quantise_pwm_us(const MixerRotors& layout, double u);

}  // namespace swath::control
