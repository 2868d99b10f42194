#pragma once
// The seam between the runtime and the vehicles it flies (docs/swath-fleet.md). The runtime talks
// to a Backend only: the simulated fleet (backends/, SimulatedFleet: legs in closed form, made by
// run_app when RuntimeSettings::backend is null) and real or emulated autopilots (MavlinkFleet,
// mavlink_fleet.hpp) implement it.
//
// The runtime keeps its own drone records for every backend (modes, reservations, the energy
// estimate from the same leg model the simulated fleet flies) and hands every *movement* to the
// backend. Two kinds of backend differ in how the runtime learns the outcome:
//  - a model (reports_every_tick() false) knows ahead when each vehicle arrives (arrival_s):
//    time jumps from event to event on the tick grid, byte for byte the same every run;
//  - real vehicles (reports_every_tick() true) are read every tick_s: the runtime calls
//    advance_to(now) and reads each vehicle's report — where it is, whether it reached the last
//    target, whether it is down at home after a return, and whether its link is alive.
// Action durations (sense, hover, custom) stay on the runtime's clock while the vehicle holds its
// place; a sense also asks the backend for its photo, and the reading comes from the world's
// sensors at the vehicle's position. Commands carry the time they are given at (s since the run
// began, never before the last advance_to): a model starts its legs then; real vehicles act at
// once.

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
  /// The vehicle's own battery report (MAVLink BATTERY_STATUS), state of charge [0, 1]; < 0: none.
  double battery_soc = -1;
};

class Backend {
 public:
  virtual ~Backend() = default;
  /// Number of vehicles; the runtime's drone i is vehicle i.
  virtual int vehicles() const = 0;
  /// Flies vehicle `drone` to `to_m` (local metres, z: altitude above home, > 0): taking off
  /// first when on the ground. The approach rule (`approach_m_s` within `approach_within_m` of
  /// the target, `cruise_m_s` before, m/s and m) is the vehicle's speed setting.
  virtual void go_to(int drone, double t_s, const Vec3& to_m, double cruise_m_s,
                     double approach_m_s, double approach_within_m) = 0;
  /// Starts action `name` where the vehicle holds (a sense: a photo); its duration is the
  /// runtime's.
  virtual void act(int drone, const std::string& name, bool sense) = 0;
  /// Home and land (a return to launch): how real vehicles end a way home. A model's way home
  /// is flown with go_to to above home and landed with land(), so that the runtime can hold it
  /// there until its descent is clear of the other drones.
  virtual void return_home(int drone, double t_s) = 0;
  /// Lands where it is (an abort with `--on-abort land`, `swath-fleet ctl land-all`; a model's
  /// landing over home); a model's arrival_s is then its touch-down.
  virtual void land(int drone, double t_s) = 0;
  /// A pause (`swath-fleet ctl pause`): the vehicle stops where it is and holds there. By
  /// default what hold() does.
  virtual void pause(int drone, double t_s) { hold(drone, t_s); }
  /// The runtime took the vehicle's request away and gave it nothing else: it stops where it is.
  virtual void hold(int drone, double t_s) = 0;
  /// Brings the backend to time `t_s` (s since the run began, non-decreasing): its I/O and
  /// timers; a real backend waits for the wall clock to reach it.
  virtual void advance_to(double t_s) = 0;
  virtual VehicleReport report(int drone) const = 0;
  /// The app's main returned: every airborne vehicle goes home (not counted in completion).
  /// Returns once they are down, or after the backend's own deadline: the caller may then close
  /// the links.
  virtual void end_run() = 0;
  /// The run was aborted after every airborne vehicle was told to return or land: returns once
  /// each has taken the order (or after the backend's own deadline). By default end_run().
  virtual void end_abort() { end_run(); }
  /// When vehicle `drone` reaches the target of its latest go_to or return_home (landed, for the
  /// latter), s, when the backend knows it ahead (a model); infinity when only its report will say.
  virtual double arrival_s(int drone) const = 0;
  /// True: the runtime ticks every tick_s and reads the reports (real vehicles); false: it jumps
  /// to the next event, arrival_s among them, and reads no report.
  virtual bool reports_every_tick() const = 0;
};

}  // namespace swath::fleet
