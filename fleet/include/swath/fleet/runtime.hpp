#pragma once
// The runtime (paper 000 §3, §4.1; docs/swath-fleet.md): runs one application against a fleet of
// drones behind a Backend (backend.hpp; the simulated fleet unless RuntimeSettings::backend says).
// Each task's head segment (a fly_to and the non-flying actions after it) is a *request*; every
// tick (0.1 s, the paper's heartbeat) the runtime applies what happened, resumes the coroutines
// that can go on, and — when something changed — asks the scheduler which drone serves which
// request. Time jumps from event to event on the tick grid, so an hour's mission takes
// milliseconds. Same settings and seed: the same bytes in every output.
//
// The simulated fleet (docs/swath-fleet.md, 'The simulated fleet') is exact per leg (see leg.hpp):
// climb to the drone's altitude layer (20 m + separation × index, the collision rule;
// envelope.hpp), level flight with the approach rule and bounded accelerations, power through
// energy::Battery (paper 004 eq. 12) from the drone's energy::PowerProfile (hover = airspeed 0).
// Faults (docs/swath-fleet.md, 'Faults'): every task ends exactly once, every result is delivered
// at most once.

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "swath/energy/battery.hpp"
#include "swath/energy/power_model.hpp"
#include "swath/fleet/backend.hpp"
#include "swath/fleet/control.hpp"
#include "swath/fleet/dtg.hpp"
#include "swath/fleet/envelope.hpp"
#include "swath/fleet/forecaster.hpp"
#include "swath/fleet/leg.hpp"
#include "swath/fleet/scheduler.hpp"
#include "swath/fleet/task.hpp"
#include "swath/fleet/vehicle_address.hpp"
#include "swath/fleet/world.hpp"
#include "swath/vehicle/drone.hpp"
#include "swath/vehicle/wind.hpp"

namespace swath::fleet {

/// An application: its main coroutine, registered by name (docs/swath-fleet.md).
struct App {
  std::string name;
  std::string description;
  std::function<Co<void>(Ctx&)> main;
};

/// swath-fleet's drone when nothing says otherwise: Kinematics' cruise, climb, descent and
/// acceleration (paper 000 §4.2 and ours; leg.hpp), not the planner's vehicle::Drone defaults.
vehicle::Drone default_flying_drone();

/// One simulated drone: what flies (vehicle::Drone: name, speeds, acceleration, as the fleet file
/// gives them) and what only swath-fleet's flights need beside it. A field vehicle::Drone already
/// has is never copied here (tests/fleet/drone_spec_test.cpp checks).
struct DroneSpec {
  vehicle::Drone drone = default_flying_drone();
  Vec3 home_m;  ///< take-off point, local metres (z = 0)
  /// Paper 000 §4.2's approach rule: this horizontal speed within approach_within_m of a target,
  /// m/s (0, cruise]; approach_within_m ≥ 0, 0: no approach phase.
  double approach_m_s = Kinematics{}.approach_m_s;
  double approach_within_m = Kinematics{}.approach_within_m;
  energy::Battery battery;  ///< initial_soc is where it starts; reserve_soc where it must land
  energy::PowerProfile power;
  /// Longest flight before it must be home, s (> 0; case 5's 60 s); infinity: the battery decides.
  double max_flight_time_s = std::numeric_limits<double>::infinity();
  double recharge_s = 30;  ///< from landing to a full battery at home (a swap or a charge), s (≥ 0)
  /// The real vehicle flying this drone with `run --backend mavlink` (the fleet file's
  /// `mavlink {url, sysid}`); absent: none given. The simulated fleet ignores it.
  std::optional<VehicleAddress> vehicle;

  /// How it flies, from `drone` and the approach rule (a drone without a cruise speed flies
  /// Kinematics' default).
  Kinematics kinematics() const;
};

enum class FaultKind { link_loss, battery_drop, motor_failure, sensor_failure };
const char* fault_name(FaultKind kind);

/// One injected fault (docs/swath-fleet.md).
struct FaultEvent {
  double t_s = 0;  ///< when, s since the run began (≥ 0)
  int drone = 0;   ///< index in the fleet
  FaultKind kind = FaultKind::link_loss;
  double duration_s = 10;  ///< link_loss and sensor_failure: how long, s (> 0)
  double soc = 0.1;        ///< battery_drop: the charge it falls to, [0, 1]
};

struct RuntimeSettings {
  std::string app_name;          ///< for the log
  std::string scheduler = "sa";  ///< sa | reactive | greedy | round-robin | hungarian
  std::uint64_t seed = 1;
  double tick_s = 0.1;           ///< the heartbeat (paper 000 §4.1), s, > 0
  double link_latency_s = 0.05;  ///< command and result latency, s, ≥ 0
  double hold_s = 10;            ///< non-interruptible tasks keep their drone this long, s
  double max_time_s = 3600;      ///< a run that has not completed by then ends (exit 4), s
  double state_period_s = 1.0;   ///< drone_state events, s (> 0)
  double no_feasible_s = 600;    ///< a request no free drone takes fails after this, s
  double layer_base_m = 20;      ///< altitude of drone 0's layer, m
  double layer_step_m = 5;       ///< between layers, m (at least envelope.separation_m is used)
  /// The safety envelope (envelope.hpp): ceiling, separation, fence. Every fly_to is checked
  /// against it, the layers must fit under the ceiling and the homes inside the fence.
  LocalEnvelope envelope;
  /// Where the local frame lies on the Earth (the world's origin, WGS84), logged in run_start so
  /// that the live and replay page draws the run on a map in lat/lon; unset: local metres only.
  std::optional<geometry::GeoPoint> origin;
  double disc_m = 5;  ///< radius a drone at or bound for a place reserves (first come), m
  /// A steady horizontal wind (vehicle::Wind; swath-fleet's --wind E,N gives its air velocity):
  /// the drones keep their ground tracks and speeds, the rotors work at the airspeed (hover: the
  /// wind speed), and the way home is costed into a headwind. Calm by default (the paper's
  /// experiments).
  vehicle::Wind wind = vehicle::Wind::from_velocity(0, 0);  // calm: +0 east and north
  Weights weights;
  std::vector<FaultEvent> faults;  ///< sorted or not; applied in (t_s, drone) order
  /// What forecasts the next requests and q (docs/swath-fleet.md): none, gmf or constant-velocity.
  /// The scheduler "reactive" is sa with none and the forecast weights at 0 (the paper's
  /// baseline); sa with none differs from it only by those weights, which then weigh nothing.
  std::string forecaster = "none";
  std::vector<Dtg> histories;  ///< past runs' DTGs (gmf's matches, q's counts)
  GmfSettings gmf;
  /// A speculative position is a hit when a request appears within this of it, m (> 0).
  double hit_within_m = 2;
  /// Relief (docs/swath-fleet.md, Example 5): a drone at work whose flight time or battery ends
  /// within the soonest idle drone's flight to its place plus relief_margin_s gets that drone as a
  /// stand-by there, which takes the next segment when it leaves. Off: the paper's baseline.
  bool relief = false;
  double relief_margin_s = 20;  ///< s, ≥ 0
  /// The vehicles (backend.hpp; not owned, outlives the run): null, run_app's own simulated
  /// fleet (event to event); else e.g. MavlinkFleet, whose vehicle i flies drone i: the runtime
  /// ticks every tick_s and takes arrivals, landings, positions and link state from its reports.
  Backend* backend = nullptr;
  /// Orders from outside (control.hpp), polled between steps; empty: none ever come.
  ControlSource control;
  /// True once an abort is waiting in `control` (a signal noted), without taking it: the runtime
  /// then stops resuming tasks, so an app that spawns without end cannot hold off the abort.
  std::function<bool()> abort_pending;
  /// What a signal's abort (ControlOrder::rtl_all from `control`) or an exception escaping the
  /// run tells the vehicles.
  AbortAction on_abort = AbortAction::rtl;
  /// The simulated fleet only: simulated seconds per wall-clock second (1: real time), so that a
  /// person or `swath-fleet ctl` can act during the run; 0: as fast as it computes.
  double pace = 0;
  /// Called with each line of events.jsonl (no newline) as it is logged, on the run's thread
  /// (swath-fleet run --live streams them; a wall-clock run reports take-offs); empty: nothing is
  /// called. It cannot change the run.
  std::function<void(const std::string&)> on_event;
};

/// What one drone did.
struct DroneRecord {
  std::string name;
  double distance_m = 0, flight_s = 0, idle_s = 0, energy_wh = 0, final_soc = 0;
  /// Positions over time (every state change and at state_period_s): t_s, x_m, y_m, alt_m.
  std::vector<std::array<double, 4>> track;
  /// What it was doing: [t0_s, t1_s) and the mode (flying, acting, hovering, held, returning,
  /// charging, lost, unreachable).
  struct Span {
    double t0_s, t1_s;
    std::string mode;
  };
  std::vector<Span> spans;
};

struct RunRecord {
  bool completed = false;
  double completion_time_s = 0;  ///< start to the app's main returning (return home not counted)
  double end_s = 0;              ///< when the run stopped
  std::string failure;           ///< why main failed or the run stopped, "" when completed
  std::string events_jsonl;      ///< events.jsonl (docs/swath-fleet.md)
  std::string dtg_json;          ///< dtg.json (docs/swath-fleet.md, `run`'s outputs)
  std::vector<DroneRecord> drones;
  std::map<std::string, int> tasks_by_outcome;  ///< done, cancelled, failed
  std::map<std::string, double> metrics;        ///< the app's (Ctx::metric)
  int schedules = 0, requeued = 0, duplicate_results = 0;
  int forecasts = 0;  ///< forecast rounds (the DTG had changed)
  /// Drones sent to forecast places; hits: a request appeared within hit_within_m while it was
  /// there or on its way; misses: it left (or the run ended) before one did.
  int speculative_positions = 0, speculative_hits = 0, speculative_misses = 0;
  int reliefs = 0;              ///< stand-bys sent (relief)
  int faults_happened = 0;      ///< faults applied during the run (a `fault` event each)
  int battery_exhausted = 0;    ///< drones down where their charge ran out (an event each)
  double decision_s_total = 0;  ///< wall time in the scheduler (timing.json only)
  double forecast_s_total = 0;  ///< wall time in the forecaster (timing.json only)
  /// Served and cancelled request places (t_s, x_m, y_m) for the pictures.
  std::vector<std::array<double, 3>> served, cancelled;
  /// Why the run was aborted (the `aborted` event's reason: "SIGINT", "ctl rtl-all", "exception:
  /// ..."); "" when it was not.
  std::string aborted;
  bool aborted_by_error = false;  ///< the abort was an exception escaping the run
};

/// Runs `app` in `world` with `drones` (at least one). Throws base::InputError for an unknown
/// scheduler name, a backend whose vehicle count differs from the fleet's, or a fleet outside
/// settings.envelope (layers above the ceiling, a home outside the fence); an exception escaping
/// the app's main ends the run as not completed.
RunRecord run_app(const App& app, const World& world, const std::vector<DroneSpec>& drones,
                  const RuntimeSettings& settings);

}  // namespace swath::fleet
