#pragma once
// Setpoints along a mission (docs/swath-control.md): a carrot that moves along each leg with
// a trapezoid speed profile — accelerate at max_accel_m_s2, cruise at the leg's speed, brake to a
// stop at the waypoint — sampled at 50 Hz, with the yaw along the leg, slewed to each new
// heading at a limited rate with its rate as feed-forward (a step would make every waypoint an
// attitude transient of up to 180°). The control task advances the held sample to its own time
// (extrapolated), as a flight stack's position controller advances its target every loop.

#include <cstddef>
#include <vector>

#include "swath/vehicle/clock.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::control {

using vehicle::SimTime;
using vehicle::Vec3;

/// What the control task is asked to do at one instant.
struct Setpoint {
  Vec3 position_m;     ///< world ENU, m
  Vec3 velocity_m_s;   ///< feed-forward, world ENU, m/s
  double yaw_rad = 0;  ///< heading of body +x, counter-clockwise from east (ENU), rad, (−π, π]
  double yaw_rate_rad_s = 0;  ///< the slew's rate: feed-forward, world up, rad/s
  std::size_t leg = 0;        ///< the leg being flown; legs() once the path has ended
  std::size_t segment = 0;    ///< the segment of that leg (points segment → segment + 1)
  /// When the carrot was sampled (its latest update), ns, on the clock of the execution that
  /// reads it (TaskInput::time_ns).
  SimTime sampled_ns = 0;
};

/// The setpoint advanced from its sample to `t_ns` along its own feed-forward: position +
/// velocity · (t − sampled), yaw + yaw rate · (t − sampled) (wrapped to [−π, π]); unchanged when
/// t ≤ sampled. A carrot held between 50 Hz updates would otherwise fall behind by up to one
/// period's travel (0.1 m at 5 m/s) and jump back at each update: a sawtooth the position and
/// velocity gains turn into ~1° of pitch at 50 Hz.
Setpoint extrapolated(const Setpoint& sp, SimTime t_ns);

/// Limits of the carrot's motion (`controller.limits`, docs/swath-control.md, 'Vehicle, scheduler
/// and environment files').
struct CarrotLimits {
  double max_speed_m_s = 3.0;   ///< along the leg, m/s, > 0
  double max_climb_m_s = 1.5;   ///< vertical component, m/s, > 0
  double max_accel_m_s2 = 1.0;  ///< along the leg, m/s², > 0
  double update_hz = 50.0;      ///< the carrot moves at this rate (`run.setpoint_rate_hz`), > 0
  /// The heading turns to each new segment's at this rate, rad/s (`limits.yaw_slew_dps`); 0 or
  /// less: at once (a step).
  double yaw_slew_rad_s = 45 * 3.14159265358979323846 / 180;
};

/// The trapezoid of one leg: time to cover `length_m` (≥ 0) starting and ending at rest with
/// speed ≤ `speed_m_s` and |acceleration| ≤ `accel_m_s2`; and the distance covered after `t_s`
/// seconds (0 before the start, length_m after the end).
double trapezoid_duration_s(double length_m, double speed_m_s, double accel_m_s2);
double trapezoid_distance_m(double t_s, double length_m, double speed_m_s, double accel_m_s2);

/// A carrot along legs (world ENU). A leg is a polyline flown without stopping (a waypoint
/// mission's leg has two points; a stage plan's guided path is one long leg); the carrot starts
/// each leg at rest and stops at its end. The flight starts at rest at the first leg's first point
/// at time 0; each leg starts when the previous one ends. A leg's speed is max_speed_m_s, lowered
/// so that the vertical component of its steepest segment stays within max_climb_m_s. Zero-length
/// legs take no time.
class CarrotPath {
 public:
  /// Legs between consecutive `waypoints` (at least one point); `limits` valid as documented.
  CarrotPath(const std::vector<Vec3>& waypoints, const CarrotLimits& limits);
  /// `legs`: each at least one point (a leg's start should be the previous leg's end; the carrot
  /// jumps otherwise); at least one leg.
  CarrotPath(std::vector<std::vector<Vec3>> legs, const CarrotLimits& limits);

  /// The setpoint in force at `t_ns` (≥ 0): the carrot as of the latest update at or before t
  /// (sampled_ns; extrapolated() advances it to t).
  /// Yaw points along the segment flown, slewed from the previous segment's heading (the
  /// shorter way) at yaw_slew_rad_s from the moment the carrot enters the segment; on a vertical
  /// segment it keeps the previous one's (0 at first).
  Setpoint at(SimTime t_ns) const;
  /// When the carrot reaches the end of the last leg, ns (rounded once, never accumulated).
  SimTime end_ns() const { return leg_start_ns_.back(); }
  std::size_t legs() const { return legs_.size(); }
  /// The points of leg `k` (< legs()).
  const std::vector<Vec3>& leg(std::size_t k) const { return legs_[k].points; }
  /// The path's length, m.
  double length_m() const;

 private:
  struct Leg {
    std::vector<Vec3> points;
    std::vector<double> arc_m;         // cumulative length at each point (arc_m[0] = 0)
    std::vector<double> yaw_rad;       // per segment
    std::vector<double> from_yaw_rad;  // per segment: the heading its slew starts from
    std::vector<double> enter_s;       // per segment: when the carrot enters it, s after the start
    double speed_m_s = 0;
  };
  double time_at_distance(double s_m, const Leg& leg) const;
  void slew(Setpoint& sp, double from_rad, double to_rad, double since_s) const;

  std::vector<Leg> legs_;
  std::vector<SimTime> leg_start_ns_;  // per leg, plus the end
  CarrotLimits limits_;
  SimTime update_period_ns_;
};

}  // namespace swath::control
