#pragma once
// The seam between the runtime and vehicles that fly outside it (DESIGN.md §18.6): real or
// emulated autopilots — MavlinkFleet (mavlink_fleet.hpp) implements it over swath::mavlink.
//
// What this seam is, honestly: the simulated fleet is NOT behind it. The runtime keeps its exact
// per-leg simulation (leg.hpp, event to event on the tick grid) when RunSettings::backend is null,
// byte for byte as before. With a backend, the runtime keeps its own drone records (modes,
// reservations, the energy estimate) but hands every *movement* to the backend and learns its
// outcome from it: it ticks every tick_s on its clock, calls advance_to(now), and reads each
// vehicle's report — where it is, whether it reached the last target, whether it is down at home
// after a return, and whether its link is alive. Action durations (sense, hover, custom) stay on
// the runtime's clock while the vehicle holds its place; a sense also asks the backend for its
// photo, and the reading comes from the world's sensors at the reported position.

#include <string>

#include "swath/fleet/task.hpp"

namespace swath::fleet {

/// What the runtime knows of one external vehicle after Backend::advance_to.
struct VehicleReport {
  bool link_up = false;  ///< telemetry heard lately (a backend's own rule: MAVLink 3 s)
  bool position_known = false;
  Vec3 position_m;           ///< local metres at the world's origin, z above home (if known)
  bool arrived = false;      ///< at the target of the latest go_to, holding there
  bool landed_home = false;  ///< after return_home: on the ground (disarmed)
  /// Why the vehicle cannot fly (a step refused three times, with its STATUSTEXT, or a target
  /// outside the fence); "" when it can. A refused vehicle can still be sent home.
  std::string refusal;
};

class Backend {
 public:
  virtual ~Backend() = default;
  /// Number of vehicles; the runtime's drone i is vehicle i.
  virtual int vehicles() const = 0;
  /// Flies vehicle `drone` to `to_m` (local metres, z: altitude above home, > 0): taking off
  /// first when on the ground. The approach rule (`approach_m_s` within `approach_within_m` of
  /// the target, `cruise_m_s` before, m/s and m) is the vehicle's speed setting.
  virtual void go_to(int drone, const Vec3& to_m, double cruise_m_s, double approach_m_s,
                     double approach_within_m) = 0;
  /// Starts action `name` where the vehicle holds (a sense: a photo); its duration is the
  /// runtime's.
  virtual void act(int drone, const std::string& name, bool sense) = 0;
  /// Home and land (a return to launch).
  virtual void return_home(int drone) = 0;
  /// Brings the backend to time `t_s` (s since the run began, non-decreasing): its I/O and
  /// timers; a real backend waits for the wall clock to reach it.
  virtual void advance_to(double t_s) = 0;
  virtual VehicleReport report(int drone) const = 0;
  /// The app's main returned: every airborne vehicle goes home (not counted in completion).
  /// Returns once they are down, or after the backend's own deadline: the caller may then close
  /// the links.
  virtual void end_run() = 0;
};

}  // namespace swath::fleet
