#pragma once
// One straight leg of a simulated drone, in closed form (docs/swath-fleet.md; paper 000 §4.2): a
// vertical change of altitude at constant climb or descent rate, then the horizontal flight with
// the speed limit of the paper (cruise, and the approach speed within `approach_within_m` of the
// target), bounded accelerations and a stop at the target. Within each piece v² is linear in the
// distance flown (constant acceleration) or v is constant, so times and positions are exact:
// t = 2 (v₂ − v₁) / β for v² = α + β s, and the inverse for the position at a time.

#include <vector>

#include "swath/vehicle/kinematics.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::fleet {

using vehicle::Vec3;

/// How a simulated drone flies. Defaults: paper 000 §4.2 (10 m/s, 2 m/s within 20 m); 2 m/s² and
/// 3 m/s climb are our values (the paper's profiled ones are in a lost figure;
/// docs/swath-fleet.md).
struct Kinematics {
  double cruise_m_s = 10.0;       ///< horizontal speed far from the target, > 0
  double approach_m_s = 2.0;      ///< horizontal speed within approach_within_m, (0, cruise]
  double approach_within_m = 20;  ///< ≥ 0; 0: no approach phase
  double accel_m_s2 = 2.0;        ///< horizontal acceleration and braking, > 0; 0: instantaneous
  double climb_m_s = 3.0;         ///< vertical speed up, > 0
  double descent_m_s = 3.0;       ///< vertical speed down, > 0
};

/// One piece of the horizontal profile: on [s0_m, s1_m] of the distance, v² = alpha + beta·s
/// (m²/s², m/s²·2), entered at t0_s after the horizontal part began.
struct LegPiece {
  double s0_m, s1_m, alpha, beta, t0_s, v0_m_s, v1_m_s;
};

class Leg {
 public:
  /// From `from` to `to` (local metres, z = altitude above home), entering the horizontal part at
  /// `initial_speed_m_s` (≥ 0; a retargeted drone's speed projected on the new course; clamped to
  /// what it can still brake from).
  Leg(const Vec3& from, const Vec3& to, const Kinematics& k, double initial_speed_m_s = 0.0);

  double duration_s() const { return vertical_s_ + horizontal_s_; }
  double vertical_s() const { return vertical_s_; }
  double horizontal_m() const { return length_m_; }
  /// Where the drone is `t_s` after the leg began (clamped to [0, duration]).
  Vec3 position_at(double t_s) const;
  /// Its horizontal ground speed then, m/s (0 while climbing or descending).
  double speed_at(double t_s) const;
  /// True while it climbs or descends.
  bool vertical_at(double t_s) const { return t_s < vertical_s_; }
  bool climbing() const { return to_.z > from_.z; }
  const std::vector<LegPiece>& pieces() const { return pieces_; }
  const Vec3& from() const { return from_; }
  const Vec3& to() const { return to_; }

 private:
  double distance_at(double horizontal_t_s) const;
  Vec3 from_, to_;
  double vertical_s_ = 0, horizontal_s_ = 0, length_m_ = 0;
  Vec3 unit_;  ///< horizontal direction
  std::vector<LegPiece> pieces_;
};

/// The leg a drone at `from` flies to `to` when told to at `t_on_s` after it began `current` (null:
/// it was not moving). A retarget keeps the speed along the new course (the component across it
/// is braked); a drone already at the target (within 1e-9 m) starts from rest. The runtime's
/// model and the simulated fleet both start their legs with it, so they agree to the bit.
Leg next_leg(const Leg* current, double t_on_s, const Vec3& from, const Vec3& to,
             const Kinematics& k);

/// The horizontal time alone for a leg of `length_m` from rest to rest under `k` (the closed form
/// the scheduler's ETA uses; equal to Leg(..).duration_s() without the vertical part).
double horizontal_time_s(double length_m, const Kinematics& k);

/// The same time in closed form without building the profile (the scheduler's ETA, evaluated for
/// every drone–request pair): vehicle::rest_to_rest_s (vehicle/kinematics.hpp).
using vehicle::rest_to_rest_s;

}  // namespace swath::fleet
