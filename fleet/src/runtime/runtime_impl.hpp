#pragma once
// The runtime's inside (runtime.hpp is its outside, run_app): one class whose parts live in
// runtime/ (the coroutine engine, tasks, the DTG, the drones' records, faults, the loop) and
// schedule/ (rounds, forecasts and speculation, relief). Private to fleet/src: nlohmann's json
// is the events' writer here.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "swath/fleet/runtime.hpp"

namespace swath::fleet::rt {

using json = nlohmann::ordered_json;
constexpr double kInf = std::numeric_limits<double>::infinity();
/// An app's metrics in summary.json: at most kMaxMetrics names taking at most kMaxMetricBytes
/// (escaped names and values), so that summary.json stays far below the 4 MiB its readers
/// (collect, render, replay) accept.
constexpr std::size_t kMaxMetrics = 10000;
constexpr std::size_t kMaxMetricBytes = std::size_t{2} << 20;
/// Tasks an app may create at one instant of simulated time: a task failing at once and retried
/// at once (a refused fly_to in a loop) would otherwise grow memory and the log without bound
/// while the clock stands still, where max_time_s cannot end it.
constexpr int kMaxTasksPerInstant = 20000;

enum class ActionType { fly_to = 0, sense = 1, hover = 2, custom = 3 };
enum class ActionState { pending, running, completed, delivered, dropped };
enum class TaskStatus { running, done, cancelled, failed };
// positioning: flying to a forecast place (speculation, docs/swath-fleet.md), serving nothing.
enum class Mode { landed, hovering, flying, positioning, acting, held, returning, charging, lost };

inline const char* mode_name(Mode m, bool link_up) {
  if (!link_up && m != Mode::lost) return "unreachable";
  switch (m) {
    case Mode::landed:
      return "landed";
    case Mode::hovering:
      return "hovering";
    case Mode::flying:
      return "flying";
    case Mode::positioning:
      return "positioning";
    case Mode::acting:
      return "acting";
    case Mode::held:
      return "held";
    case Mode::returning:
      return "returning";
    case Mode::charging:
      return "charging";
    case Mode::lost:
      return "lost";
  }
  return "?";
}

struct Action {
  ActionType type;
  Vec3 to;
  std::string name;
  double duration_s = 0;
  std::shared_ptr<detail::State<Reading>> result;
  ActionState state = ActionState::pending;
  std::string sample_sensor;   ///< fly_sensing: the sensor read on the way
  double sample_period_s = 0;  ///< fly_sensing: every so many seconds of the flight
};

// One step of a task's program (dtg.json "script"; written out by dtg_json()).
struct ScriptStep {
  enum Op : std::uint8_t { act, await, spawn, cancel, delay };
  Op op = act;
  int act_type = 0;  // Ctx's action types: fly_to 0, sense 1, hover 2, custom 3, fly_sensing 4
  Vec3 to;
  std::string name;
  double s = 0;                // hover/custom duration, fly_sensing period, delay cost
  std::vector<int> refs = {};  // await: task id, or -(action + 1); spawn, cancel: the task id
  bool any = false;
  std::uint64_t seq = 0;
  // act: the call threw (refused: outside the fence, out of reach, ...), no action queued;
  // await: it threw (the awaited task failed or was cancelled). The app saw the error there.
  bool raised = false;
};

struct Task {
  int id = 0;
  std::string kind;
  Flags flags;
  int parent = -1;
  std::function<std::coroutine_handle<>(Ctx&)> start;
  std::shared_ptr<detail::StateBase> result;
  std::unique_ptr<Ctx> ctx;
  std::coroutine_handle<> root;
  TaskStatus status = TaskStatus::running;
  bool frame_gone = false;
  std::vector<Action> actions;
  int serving = -1;          // the drone flying to or acting on its head segment
  std::optional<int> bound;  // same_drone / not interruptible
  Vec3 location;             // where its last fly_to goes
  bool has_location = false;
  double created_s = 0, ended_s = -1, visible_since_s = -1;
  // The no-feasible-drone clock: since when a round left a drone free and this request without
  // one (note_unserved); infinity while it is not running.
  double unserved_since_s = std::numeric_limits<double>::infinity();
  std::optional<Vec3> first_loc;
  std::vector<int> drones_used;
  int sync_node = -1;  // the sync node its latest awaits formed; -1 after it did something else
  // It spawned or cancelled since that sync node: edges still leave the node, but its next await
  // is a new one (an await after work is the next iteration's sync, docs/swath-fleet.md).
  bool issued_since_sync = false;
  bool requested = false;  // a request_visible logged for the current head
  int segment = -1;        // the head segment's index (0, 1, ...: each new head is the next)
  std::size_t segment_head = static_cast<std::size_t>(-1);  // its first action
  // Its program as the runtime saw it, in order (dtg.json "script", for trace replay): actions
  // queued or refused, awaits that suspended or threw, spawns, cancels and compute delays.
  std::vector<ScriptStep> script;
  std::shared_ptr<bool> last_armed;  // the `any` its latest await step belongs to
  std::int64_t ended_seq = -1;       // its end in the order of all script steps and ends

  // The first action not yet done by some drone.
  std::size_t head() const {
    std::size_t i = 0;
    while (i < actions.size() &&
           (actions[i].state == ActionState::completed ||
            actions[i].state == ActionState::delivered || actions[i].state == ActionState::dropped))
      ++i;
    return i;
  }
  bool has_work() const { return status == TaskStatus::running && head() < actions.size(); }
};

struct Pending {  // a result on its way to the app
  double deliver_s;
  int drone, task;
  std::size_t action;
  Reading reading;
  std::uint64_t seq;
};

struct Drone {
  DroneSpec spec;
  int index = 0;
  Mode mode = Mode::landed;
  Vec3 pos;           // at t_mark
  double t_mark = 0;  // energy and position are integrated up to here
  std::optional<Leg> leg;
  double leg_start = 0;
  // The stops after the leg's end on its way round the fence (LocalEnvelope::route), the target
  // last; empty when the leg ends at the target.
  std::vector<Vec3> route;
  double act_end = 0, charge_end = 0, hold_until = 0;
  int task = -1;  // flying to or acting for
  std::size_t action = 0;
  int held_for = -1;
  double soc = 1, energy_j = 0, distance_m = 0, flight_s = 0, idle_s = 0, airborne_since = 0;
  bool link_up = true, sensor_ok = true;
  double link_back = 0, sensor_back = 0;
  std::vector<Pending> buffered;  // results finished while the link was down
  double layer_m = 20;
  DroneRecord record;
  std::string span_mode;
  double span_start = 0;
  std::optional<Vec3> spot;  // the forecast place it was sent to (speculation)
  bool spot_hit = false;     // a request appeared there
  int relieving = -1;        // the drone it stands by for (docs/swath-fleet.md, 'Relief')
  // Vehicles read every tick (real ones): the last reported position; the leg above is then the
  // model's estimate (energy), the vehicle's report says where it is and when it arrived.
  std::optional<Vec3> reported;
  // Sent home but its way was not clear (separation.cpp): tries again then, for this reason.
  double home_retry_s = std::numeric_limits<double>::infinity();
  std::string home_why;
  // Over its home with its descent not clear (separation.cpp): holds there, tries again then.
  double land_retry_s = std::numeric_limits<double>::infinity();
};

// A drone's way: its leg, then a leg to each of the route's stops after it, each from rest (it
// stops at every bend); hovering at the last. Where it is `since_s` after the leg began.
inline Vec3 way_position(const Leg& leg, const std::vector<Vec3>& rest, double since_s,
                         const Kinematics& k) {
  if (rest.empty() || since_s <= leg.duration_s()) return leg.position_at(since_s);
  double t = since_s - leg.duration_s();
  Vec3 from = leg.to();
  for (const Vec3& stop : rest) {
    const Leg next(from, stop, k);
    if (t <= next.duration_s()) return next.position_at(t);
    t -= next.duration_s();
    from = stop;
  }
  return from;
}

// A way a drone may begin (runtime/separation.cpp): its first leg and the stops after it.
struct Way {
  Leg leg;
  std::vector<Vec3> rest;
};

inline bool on_leg(Mode m) {
  return m == Mode::flying || m == Mode::positioning || m == Mode::returning;
}

// In a steady wind the autopilot holds position and ground track: the rotors fly at the
// airspeed, ground velocity less wind (RuntimeSettings::wind, its air velocity).
inline double hover_power_w(const DroneSpec& s, const Vec3& wind) {
  return energy::level_flight_power_w(s.power.mechanical, std::hypot(wind.x, wind.y)) +
         s.power.payload_w;
}
// Cruise into a headwind: what the way home may cost at most (the feasibility checks).
inline double cruise_power_w(const DroneSpec& s, const Vec3& wind) {
  return energy::level_flight_power_w(s.power.mechanical,
                                      s.kinematics().cruise_m_s + std::hypot(wind.x, wind.y)) +
         s.power.payload_w;
}
inline double climb_power_w(const DroneSpec& s) {
  return energy::climbing_power_w(s.power) + s.power.payload_w;
}
inline double descent_power_w(const DroneSpec& s) {
  return energy::descending_power_w(s.power) + s.power.payload_w;
}

class Runtime final : public detail::Core {
 public:
  Runtime(const App& app, const World& world, const std::vector<DroneSpec>& specs,
          const RuntimeSettings& settings, Backend& backend);

  RunRecord run();

  // detail::Core
  int current_task() const override { return current_; }
  Future<Reading> act(int task, int type, const Vec3& to, const std::string& name,
                      double duration_s) override;
  int spawn(int parent, const Kind& kind, Flags flags,
            std::function<std::coroutine_handle<>(Ctx&)> start,
            std::shared_ptr<detail::StateBase> result) override;
  void cancel(int issuer, int task) override;
  Future<void> delay(int task, double cost_s) override;
  void suspended(int task, detail::StateBase& awaited, std::coroutine_handle<> h,
                 std::shared_ptr<bool> armed) override;
  void raised(int task, detail::StateBase& awaited, bool suspended) override;
  double now_s() const override { return now_; }
  const World& world() const override { return world_; }
  vehicle::SplitMix64& random() override { return app_rng_; }
  void metric(const std::string& name, double value) override;

 private:
  // Logging.
  void log(json e) {
    json line;
    line["t_s"] = round6(now_);
    for (auto& [k, v] : e.items()) line[k] = v;
    const std::string text = line.dump();
    record_.events_jsonl += text;
    record_.events_jsonl += '\n';
    if (settings_.on_event) settings_.on_event(text);
  }
  static double round6(double v) { return std::round(v * 1e6) / 1e6; }
  static json at_json(json e, const Vec3& p, json more = json::object()) {
    e["x_m"] = round6(p.x);
    e["y_m"] = round6(p.y);
    e["alt_m"] = round6(p.z);
    for (auto& [k, v] : more.items()) e[k] = v;
    return e;
  }

  // The DTG's sync nodes and edges (its task nodes are tasks_).
  struct SyncNode {
    int waiter = 0;  // task id
    double created_s = 0;
    std::vector<int> awaited;  // task ids
  };
  struct DtgRef {  // a node: task id or sync number
    bool sync = false;
    int number = 0;
  };
  struct Edge {
    DtgRef from, to;
    DtgEdgeType type;
  };
  static DtgRef issuer_node(const Task& t) {  // where its spawn and cancel edges leave
    return t.sync_node >= 0 ? DtgRef{true, t.sync_node} : DtgRef{false, t.id};
  }
  Dtg live_dtg() const;

  // One scheduling round's steps (schedule() runs them).
  Snapshot snapshot_base() const;
  void add_requests(Snapshot& s, std::vector<int>& req_task);
  void add_drones(Snapshot& s, const std::vector<int>& req_task, std::vector<int>& drone_of);
  void apply_assignment(const Snapshot& s, const Assignment& a, const std::vector<int>& req_task,
                        const std::vector<int>& drone_of);
  void update_forecasts();
  void add_forecasts(Snapshot& s, const std::vector<int>& req_task) const;
  void position(Drone& d, const ForecastRequest& f);
  void leave_spot(Drone& d);
  void note_hits(const Vec3& request_at, int task);
  // Relief (docs/swath-fleet.md).
  void relieve();
  bool working(const Drone& d) const;
  bool idle(const Drone& d) const;
  double must_leave_at(const Drone& d) const;
  double leave_from(const Drone& d, const Vec3& place, double airborne_s, double soc_s,
                    double extra_flight_s) const;
  void stand_by(Drone& e, const Drone& d, const Vec3& at, double leave_s);

  void check_envelope(const std::vector<DroneSpec>& specs) const;
  void check_reachable(const Vec3& to, const std::string& at) const;
  json envelope_json() const;
  void check_target(const Vec3& to) const;
  // Separation (runtime/separation.cpp): is the leg (none: hovering where it is) that d would
  // begin at t0 clear of every climb and, when it climbs, of every airborne drone?
  Way candidate_leg(const Drone& d, const Vec3& to, double t) const;
  bool clear_to_fly(const Drone& d, const std::optional<Way>& way, double t0) const;
  Vec3 dispatch_target(const Drone& d, const Task& t) const;
  double retry_s_ = kInf;  // a plan waited for separation: schedule again then

  // The run's steps (run() is their loop).
  Task& start_main();
  void fail_unserved();
  void note_unserved(const Snapshot& s, const Assignment& a, const std::vector<int>& req_task);
  double next_happening() const;
  bool advance_clock(double next, std::int64_t& tick_index);
  void step_drones_to_now();
  void deliver_due();
  void finish_run(const Task& main);
  std::string dtg_json() const;

  // Tasks and coroutines.
  void resume_ready();
  void fail_for_sensor(Task& tk, const SensorError& e);
  void finish_task(Task& t, TaskStatus status, const std::string& reason);
  void wake(detail::StateBase& s);
  void resolve_action(Task& t, std::size_t a, const Reading& r, int drone);
  void fail_action_futures(Task& t, std::exception_ptr e);
  /// Counts a task created now; past kMaxTasksPerInstant at one instant the run is to end.
  void count_created_at_instant();
  void destroy_frames();
  int dtg_sync_node(Task& t);

  // Drones.
  Vec3 position_at(const Drone& d, double t) const;
  void integrate(Drone& d, double t);
  double next_event(const Drone& d) const;
  void step_drone(Drone& d, double t);
  void recover(Drone& d, double t);
  void emit(Drone& d, Task& tk, std::size_t a, const Reading& r, double t);
  void sample_along(const Action& fa, const Leg& flown, double flown_from, Reading& r);
  void arrive(Drone& d, double t);
  void finish_action(Drone& d, double t);
  void descend(Drone& d, double t);
  void land_home(Drone& d, double t);
  void start_leg(Drone& d, const Vec3& to, Mode mode, double t);
  void fly_leg(Drone& d, const Vec3& to, Mode mode, double t);
  void next_stop(Drone& d, double t);
  /// Where the drone's way ends: the last stop of its route, else its leg's end.
  static Vec3 way_end(const Drone& d) { return d.route.empty() ? d.leg->to() : d.route.back(); }
  /// The stops of d's way from `from` to `to` (LocalEnvelope::route; the straight leg when the
  /// fence gives none, which the checks before the flight rule out).
  std::vector<Vec3> stops(const Vec3& from, const Vec3& to) const;
  /// The flight time of d's way from `from` to `to` along its stops, s.
  double way_s(const Drone& d, const Vec3& from, const Vec3& to) const;
  void start_action_or_release(Drone& d, double t);
  void release(Drone& d, double t);
  void go_home(Drone& d, double t, const std::string& why);
  void set_mode(Drone& d, Mode m, double t);
  void requeue(Drone& d, const std::string& reason);
  void unserve(Drone& d);
  bool must_go_home(const Drone& d, double t) const;
  /// When an airborne drone comes within a tick of running out of charge at the most it can
  /// draw (drone_energy.cpp); infinity on the ground.
  double exhausted_at(const Drone& d) const;
  void exhaust(Drone& d, double t);
  void lose_drone(Drone& d, const std::string& reason, double t);
  double leave_time(const Drone& d) const;  ///< when a hovering drone must head home
  bool available(const Drone& d) const;

  // Scheduling.
  void schedule();
  void dispatch(Drone& d, Task& t, double at);
  void apply_fault(const FaultEvent& f);
  void log_states();
  // Vehicles read every tick (Backend::reports_every_tick).
  void command_leg(Drone& d, const Vec3& to, Mode mode, double t);
  void stop(Drone& d, double t);
  void poll_backend();
  // Orders from outside (runtime/control.cpp).
  ControlRequest next_order();
  bool take_orders();  ///< true: an abort was carried out, the run ends
  /// An abort (a signal) noted but not yet taken (RuntimeSettings::abort_pending).
  bool abort_waiting() const { return settings_.abort_pending && settings_.abort_pending(); }
  static bool airborne(const Drone& d);
  void abort_run(const std::string& reason, AbortAction action, bool by_error);
  void model_abort(Drone& d, AbortAction action);
  void pause_run(const std::string& reason);
  void resume_run(const std::string& reason);
  void wait_for_wall_clock();
  bool loop(Task& main);  ///< false: aborted

  const App& app_;
  const World& world_;
  RuntimeSettings settings_;
  bool layer_step_is_separation_ = false;  // separation_m, not layer_step_m, spaces the layers
  std::shared_ptr<const LocalEnvelope> envelope_;  // settings_.envelope, shared with snapshots
  vehicle::SplitMix64 app_rng_, sched_rng_;
  std::unique_ptr<Scheduler> scheduler_;
  std::vector<Drone> drones_;
  std::deque<Task> tasks_;  // stable addresses, id = index
  std::vector<FaultEvent> faults_;
  std::size_t next_fault_ = 0;
  std::deque<detail::Waiter> ready_;
  std::vector<Pending> pending_;
  std::vector<std::pair<double, std::shared_ptr<detail::State<void>>>> delays_;
  double now_ = 0;
  int current_ = -1;
  bool changed_ = true;
  bool wall_stalled_ = false;  // resume_ready ran max_time_s of wall time without the clock moving
  // Tasks created at instant_s_ (kMaxTasksPerInstant); instant_runaway_ once past the bound.
  double instant_s_ = -1;
  int created_at_instant_ = 0;
  bool instant_runaway_ = false;
  std::size_t metric_bytes_ = 0;  // the app's metrics in summary.json (kMaxMetricBytes)
  std::uint64_t seq_ = 0;
  double next_state_log_ = 0;
  RunRecord record_;
  // The DTG as it grows (docs/swath-fleet.md): task nodes are tasks_, sync nodes and edges here.
  std::vector<SyncNode> syncs_;
  std::vector<Edge> edges_;
  bool dtg_changed_ = true;  // since the last forecast
  // Orders every script step and task end of the run: an await of a task already done leaves no
  // step, so replay needs to know which tasks had ended before each step (dtg.json "seq").
  std::uint64_t script_seq_ = 0;

  // Forecasting and speculation (docs/swath-fleet.md).
  std::unique_ptr<Forecaster> forecaster_;
  std::vector<ForecastRequest> forecasts_;
  Dtg live_;                     // the DTG at the last forecast (q reads its nodes)
  double next_relief_s_ = kInf;  // when relieve() has something to do next
  Backend& backend_;             // the vehicles: the simulated fleet or real ones
  // Orders from outside (runtime/control.cpp).
  bool paused_ = false;
  double paused_since_s_ = 0;
  ControlRequest waiting_order_;  // taken while waiting for the wall clock, not yet carried out
  std::optional<std::chrono::steady_clock::time_point> pace_start_;
};

}  // namespace swath::fleet::rt
