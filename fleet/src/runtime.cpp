#include "swath/fleet/runtime.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "swath/base/input_error.hpp"

namespace swath::fleet {

const char* fault_name(FaultKind kind) {
  switch (kind) {
    case FaultKind::link_loss:
      return "link_loss";
    case FaultKind::battery_drop:
      return "battery_drop";
    case FaultKind::motor_failure:
      return "motor_failure";
    case FaultKind::sensor_failure:
      return "sensor_failure";
  }
  return "?";
}

namespace {

using json = nlohmann::ordered_json;
constexpr double kInf = std::numeric_limits<double>::infinity();

enum class ActionType { fly_to = 0, sense = 1, hover = 2, custom = 3 };
enum class ActionState { pending, running, completed, delivered, dropped };
enum class TaskStatus { running, done, cancelled, failed };
// positioning: flying to a forecast place (speculation, docs/swath-fleet.md), serving nothing.
enum class Mode { landed, hovering, flying, positioning, acting, held, returning, charging, lost };

const char* mode_name(Mode m, bool link_up) {
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
  double s = 0;           // hover/custom duration, fly_sensing period, delay cost
  std::vector<int> refs;  // await: task id, or -(action + 1); spawn, cancel: the task id
  bool any = false;
  std::uint64_t seq = 0;
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
  std::optional<Vec3> first_loc;
  std::vector<int> drones_used;
  int sync_node = -1;  // the sync node its latest awaits formed; -1 after it did something else
  // It spawned or cancelled since that sync node: edges still leave the node, but its next await
  // is a new one (an await after work is the next iteration's sync, docs/swath-fleet.md).
  bool issued_since_sync = false;
  bool requested = false;  // a request_visible logged for the current head
  int segment = 0;         // head segments made visible so far
  // Its program as the runtime saw it, in order (dtg.json "script", for trace replay): actions
  // queued, awaits that suspended, spawns, cancels and compute delays.
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
  int relieving = -1;        // the drone it stands by for (relief, §18.5 Example 5)
  // External vehicles (RunSettings::backend): the last reported position; the leg above is then
  // the model's estimate (energy), the vehicle's report says where it is and when it arrived.
  std::optional<Vec3> reported;
};

bool on_leg(Mode m) {
  return m == Mode::flying || m == Mode::positioning || m == Mode::returning;
}

// In a steady wind the autopilot holds position and ground track: the rotors fly at the
// airspeed, ground velocity less wind (RunSettings::wind_m_s).
double hover_power_w(const DroneSpec& s, const Vec3& wind) {
  return energy::level_flight_power_w(s.power.mechanical, std::hypot(wind.x, wind.y)) +
         s.power.payload_w;
}
// Cruise into a headwind: what the way home may cost at most (the feasibility checks).
double cruise_power_w(const DroneSpec& s, const Vec3& wind) {
  return energy::level_flight_power_w(s.power.mechanical,
                                      s.kinematics.cruise_m_s + std::hypot(wind.x, wind.y)) +
         s.power.payload_w;
}
double climb_power_w(const DroneSpec& s) {
  return (s.power.climb_w > 0 ? s.power.climb_w : 1.3 * s.power.mechanical.cruise_w) +
         s.power.payload_w;
}
double descent_power_w(const DroneSpec& s) {
  return (s.power.descent_w > 0 ? s.power.descent_w : 0.8 * s.power.mechanical.cruise_w) +
         s.power.payload_w;
}

// ∫ f over [a, b] by 5-point Gauss–Legendre: exact for the polynomials of degree ≤ 9 that power
// is within a piece of constant acceleration (level power is cubic in speed, speed linear in t).
template <class F>
double gauss(F f, double a, double b) {
  static constexpr std::array<double, 5> x{0.0, -0.5384693101056831, 0.5384693101056831,
                                           -0.9061798459386640, 0.9061798459386640};
  static constexpr std::array<double, 5> w{0.5688888888888889, 0.4786286704993665,
                                           0.4786286704993665, 0.2369268850561891,
                                           0.2369268850561891};
  const double h = 0.5 * (b - a), m = 0.5 * (a + b);
  double s = 0;
  for (std::size_t i = 0; i < 5; ++i) s += w[i] * f(m + h * x[i]);
  return s * h;
}

class Runtime final : public detail::Core {
 public:
  Runtime(const App& app, const World& world, const std::vector<DroneSpec>& specs,
          const RunSettings& settings)
      : app_(app),
        world_(world),
        settings_(settings),
        app_rng_(vehicle::SplitMix64::stream(settings.seed, "app")),
        sched_rng_(vehicle::SplitMix64::stream(settings.seed, "scheduler")) {
    const bool reactive = settings.scheduler == "reactive";
    scheduler_ = make_scheduler(reactive ? "sa" : settings.scheduler);
    if (!scheduler_)
      throw base::InputError("unknown scheduler \"" + settings.scheduler +
                             "\": use sa, reactive, greedy, round-robin or hungarian");
    if (reactive) {  // the paper's baseline: SA without the forecast terms
      settings_.weights.speculative = 0;
      settings_.weights.avoid_mutual = 0;
    } else if (settings.forecaster != "none") {
      forecaster_ = make_forecaster(settings.forecaster, settings.histories, settings.gmf);
      if (!forecaster_)
        throw base::InputError("unknown forecaster \"" + settings.forecaster +
                               "\": use gmf, constant-velocity or none");
    }
    for (std::size_t i = 0; i < specs.size(); ++i) {
      Drone d;
      d.spec = specs[i];
      d.index = static_cast<int>(i);
      d.pos = specs[i].home_m;
      d.pos.z = 0;
      d.soc = specs[i].battery.initial_soc;
      d.layer_m = settings.layer_base_m + settings.layer_step_m * static_cast<double>(i);
      if (settings.backend) {  // an external vehicle is unreachable until first heard
        d.link_up = false;
        d.link_back = kInf;
      }
      d.record.name = specs[i].name;
      drones_.push_back(std::move(d));
    }
    ext_ = settings.backend;
    if (ext_ && ext_->vehicles() != static_cast<int>(specs.size()))
      throw base::InputError("the backend has " + std::to_string(ext_->vehicles()) +
                             " vehicles for a fleet of " + std::to_string(specs.size()) +
                             " drones");
    faults_ = settings.faults;
    std::stable_sort(faults_.begin(), faults_.end(), [](const FaultEvent& a, const FaultEvent& b) {
      return a.t_s != b.t_s ? a.t_s < b.t_s : a.drone < b.drone;
    });
  }

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
  double now_s() const override { return now_; }
  const World& world() const override { return world_; }
  vehicle::SplitMix64& random() override { return app_rng_; }
  void metric(const std::string& name, double value) override { record_.metrics[name] = value; }

 private:
  // Logging.
  void log(json e) {
    json line;
    line["t_s"] = round6(now_);
    for (auto& [k, v] : e.items()) line[k] = v;
    record_.events_jsonl += line.dump();
    record_.events_jsonl += '\n';
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
  // Relief (docs/swath-fleet.md, Example 5).
  void relieve();
  bool working(const Drone& d) const;
  bool idle(const Drone& d) const;
  double must_leave_at(const Drone& d) const;
  double leave_from(const Drone& d, const Vec3& place, double airborne_s, double soc_s,
                    double extra_flight_s) const;
  void stand_by(Drone& e, const Drone& d, const Vec3& at, double leave_s);

  // The run's steps (run() is their loop).
  Task& start_main();
  void fail_unserved();
  double next_happening() const;
  bool advance_clock(double next, std::int64_t& tick_index);
  void step_drones_to_now();
  void deliver_due();
  void finish_run(const Task& main);
  std::string dtg_json() const;

  // Tasks and coroutines.
  void resume_ready();
  void finish_task(Task& t, TaskStatus status, const std::string& reason);
  void wake(detail::StateBase& s);
  void resolve_action(Task& t, std::size_t a, const Reading& r, int drone);
  void fail_action_futures(Task& t, std::exception_ptr e);
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
  void land_home(Drone& d, double t);
  void start_leg(Drone& d, const Vec3& to, Mode mode, double t);
  void start_action_or_release(Drone& d, double t);
  void release(Drone& d, double t);
  void go_home(Drone& d, double t, const std::string& why);
  void set_mode(Drone& d, Mode m, double t);
  void requeue(Drone& d, const std::string& reason);
  void unserve(Drone& d);
  bool must_go_home(const Drone& d, double t) const;
  double leave_time(const Drone& d) const;  ///< when a hovering drone must head home
  bool available(const Drone& d) const;

  // Scheduling.
  void schedule();
  void dispatch(Drone& d, Task& t, double at);
  void apply_fault(const FaultEvent& f);
  void log_states();
  // External vehicles (RunSettings::backend).
  void command_leg(Drone& d, const Vec3& to, Mode mode);
  void poll_backend();

  const App& app_;
  const World& world_;
  RunSettings settings_;
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
  Backend* ext_ = nullptr;       // external vehicles, or null: the simulated fleet
};

// ---------------------------------------------------------------------------------------------
// Tasks

int Runtime::spawn(int parent, const Kind& kind, Flags flags,
                   std::function<std::coroutine_handle<>(Ctx&)> start,
                   std::shared_ptr<detail::StateBase> result) {
  Task& t = tasks_.emplace_back();
  t.id = static_cast<int>(tasks_.size()) - 1;
  t.kind = kind.name;
  t.flags = flags;
  t.parent = parent;
  t.start = std::move(start);
  t.result = std::move(result);
  t.result->task = t.id;
  t.ctx = std::make_unique<Ctx>(*this, t.id, t.id != 0);
  t.created_s = now_;
  t.location = world_.start();
  if (parent >= 0 && static_cast<std::size_t>(parent) < tasks_.size()) {
    Task& p = tasks_[static_cast<std::size_t>(parent)];
    t.location = p.location;
    p.issued_since_sync = true;
    edges_.push_back({issuer_node(p), {false, t.id}, DtgEdgeType::spawn});
    p.script.push_back({ScriptStep::spawn, 0, {}, {}, 0, {t.id}, false, script_seq_++});
    p.last_armed.reset();
  }
  dtg_changed_ = true;
  log(json{{"ev", "task_created"}, {"task", t.id}, {"kind", t.kind}, {"parent", parent}});
  t.root = t.start(*t.ctx);
  ready_.push_back({t.id, t.root, nullptr});
  return t.id;
}

Future<Reading> Runtime::act(int task, int type, const Vec3& to, const std::string& name,
                             double duration_s) {
  Task& t = tasks_.at(static_cast<std::size_t>(task));
  auto state = std::make_shared<detail::State<Reading>>();
  Action a{type == 4 ? ActionType::fly_to : static_cast<ActionType>(type),
           to,
           type == 4 ? std::string("fly_to") : name,
           type == 4 ? 0.0 : std::max(0.0, duration_s),
           state,
           ActionState::pending,
           {},
           0.0};
  if (type == 4) {  // fly_sensing: a fly_to that reads `name` every duration_s on the way
    world_.sense_time_s(name);  // an unknown sensor fails here, at the call
    if (!(duration_s > 0)) throw ActionFailed("fly_sensing needs a period > 0 s");
    a.sample_sensor = name;
    a.sample_period_s = duration_s;
  }
  if (a.type == ActionType::sense) a.duration_s = world_.sense_time_s(name);
  if (a.type == ActionType::fly_to) {
    t.location = to;
    t.has_location = true;
    if (!t.first_loc) t.first_loc = to;
  }
  t.actions.push_back(std::move(a));
  t.sync_node = -1;
  // The script keeps the call exactly (full precision), so a replay flies the same targets.
  t.script.push_back({ScriptStep::act,
                      type >= 0 && type <= 4 ? type : 3,
                      to,
                      name,
                      duration_s,
                      {},
                      false,
                      script_seq_++});
  t.last_armed.reset();
  if (t.serving < 0) changed_ = true;
  return Future<Reading>(state, this);
}

Future<void> Runtime::delay(int task, double cost_s) {
  auto state = std::make_shared<detail::State<void>>();
  Task& t = tasks_.at(static_cast<std::size_t>(task));
  t.sync_node = -1;
  t.script.push_back({ScriptStep::delay, 0, {}, {}, cost_s, {}, false, script_seq_++});
  t.last_armed.reset();
  if (!(cost_s > 0)) {
    state->ready = true;
  } else {
    delays_.push_back({now_ + cost_s, state});
  }
  return Future<void>(state, this);
}

int Runtime::dtg_sync_node(Task& t) {
  if (t.sync_node < 0 || t.issued_since_sync) {
    t.sync_node = static_cast<int>(syncs_.size());
    t.issued_since_sync = false;
    syncs_.push_back({t.id, now_, {}});
    dtg_changed_ = true;
  }
  return t.sync_node;
}

void Runtime::suspended(int task, detail::StateBase& awaited, std::coroutine_handle<> h,
                        std::shared_ptr<bool> armed) {
  if (task >= 0) {  // the script's await step: a task ("tN") or one of its own actions ("aN")
    Task& t = tasks_.at(static_cast<std::size_t>(task));
    std::optional<int> ref;
    if (awaited.task >= 0) ref = awaited.task;
    for (std::size_t a = 0; !ref && a < t.actions.size(); ++a)
      if (t.actions[a].result.get() == &awaited) ref = -static_cast<int>(a) - 1;
    if (ref) {
      if (armed && armed == t.last_armed && !t.script.empty()) {
        t.script.back().refs.push_back(*ref);  // one more state of the same `any`
      } else {
        t.script.push_back(
            {ScriptStep::await, 0, {}, {}, 0, {*ref}, armed != nullptr, script_seq_++});
      }
      t.last_armed = armed;
    }
  }
  awaited.waiters.push_back({task, h, std::move(armed)});
  if (awaited.task >= 0 && task >= 0) {  // awaiting a task: a sync node of the DTG
    Task& t = tasks_.at(static_cast<std::size_t>(task));
    const int node = dtg_sync_node(t);
    syncs_[static_cast<std::size_t>(node)].awaited.push_back(awaited.task);
    edges_.push_back({{false, awaited.task}, {true, node}, DtgEdgeType::sync});
    dtg_changed_ = true;
  }
}

void Runtime::wake(detail::StateBase& s) {
  s.ready = true;
  for (auto& w : s.waiters) {
    if (w.armed) {
      if (!*w.armed) continue;
      *w.armed = false;
    }
    ready_.push_back(w);
  }
  s.waiters.clear();
}

void Runtime::resume_ready() {
  while (!ready_.empty()) {
    const detail::Waiter w = ready_.front();
    ready_.pop_front();
    Task& t = tasks_.at(static_cast<std::size_t>(w.task));
    if (t.status != TaskStatus::running || t.frame_gone) continue;
    current_ = t.id;
    w.handle.resume();
    current_ = -1;
    if (t.root.done() && t.status == TaskStatus::running) {
      if (t.result->error) {
        std::string why = "exception";
        try {
          std::rethrow_exception(t.result->error);
        } catch (const ActionFailed& e) {
          why = e.reason;
        } catch (const TaskCancelled&) {
          why = "awaited_cancelled";
        } catch (const std::exception& e) {
          why = e.what();
        }
        finish_task(t, TaskStatus::failed, why);
      } else {
        finish_task(t, TaskStatus::done, "");
      }
    }
  }
}

void Runtime::fail_action_futures(Task& t, std::exception_ptr e) {
  for (auto& a : t.actions)
    if (!a.result->ready) {
      a.result->error = e;
      a.state = ActionState::dropped;
      wake(*a.result);
    }
}

void Runtime::finish_task(Task& t, TaskStatus status, const std::string& reason) {
  if (t.status != TaskStatus::running) return;
  t.status = status;
  t.ended_s = now_;
  t.ended_seq = static_cast<std::int64_t>(script_seq_++);
  const char* ev = status == TaskStatus::done        ? "task_done"
                   : status == TaskStatus::cancelled ? "task_cancelled"
                                                     : "task_failed";
  json e{{"ev", ev}, {"task", t.id}};
  if (!reason.empty()) e["reason"] = reason;
  log(e);
  record_.tasks_by_outcome[status == TaskStatus::done        ? "done"
                           : status == TaskStatus::cancelled ? "cancelled"
                                                             : "failed"] += 1;
  // A drone still serving it is freed; queued segments are dropped.
  if (t.serving >= 0) {
    Drone& d = drones_[static_cast<std::size_t>(t.serving)];
    t.serving = -1;
    if (d.task == t.id && (d.mode == Mode::flying || d.mode == Mode::acting)) {
      if (status == TaskStatus::cancelled && t.has_location) {
        record_.cancelled.push_back({round6(now_), round6(t.location.x), round6(t.location.y)});
        // After the task's terminal event (R4): the place only, for the pictures.
        log(at_json(json{{"ev", "request_cancelled"}}, t.location));
      }
      integrate(d, now_);
      d.task = -1;
      set_mode(d, Mode::hovering, now_);
    }
  }
  for (auto& d : drones_)
    if (d.held_for == t.id) {
      d.held_for = -1;
      if (d.mode == Mode::held) set_mode(d, Mode::hovering, now_);
    }
  for (auto& a : t.actions)
    if (a.state == ActionState::pending || a.state == ActionState::running)
      a.state = ActionState::dropped;
  if (status != TaskStatus::done) {
    if (!t.result->error)
      t.result->error = status == TaskStatus::cancelled
                            ? std::make_exception_ptr(TaskCancelled())
                            : std::make_exception_ptr(ActionFailed(reason));
  }
  wake(*t.result);
  changed_ = true;
  dtg_changed_ = true;
}

void Runtime::cancel(int issuer, int task) {
  if (task < 0 || static_cast<std::size_t>(task) >= tasks_.size()) return;
  Task& t = tasks_[static_cast<std::size_t>(task)];
  if (issuer >= 0) {  // the call, taking effect or not: a replay fires it at the same point
    Task& i = tasks_[static_cast<std::size_t>(issuer)];
    i.script.push_back({ScriptStep::cancel, 0, {}, {}, 0, {task}, false, script_seq_++});
    i.last_armed.reset();
  }
  if (t.status != TaskStatus::running) return;
  if (issuer >= 0) {
    Task& i = tasks_[static_cast<std::size_t>(issuer)];
    i.issued_since_sync = true;
    edges_.push_back({issuer_node(i), {false, task}, DtgEdgeType::cancel});
  }
  finish_task(t, TaskStatus::cancelled, "");
}

void Runtime::destroy_frames() {
  for (Task& t : tasks_)
    if (t.status != TaskStatus::running && !t.frame_gone && t.id != current_) {
      t.frame_gone = true;
      if (t.root) t.root.destroy();
    }
}

void Runtime::resolve_action(Task& t, std::size_t a, const Reading& r, int drone) {
  Action& act = t.actions[a];
  if (act.state == ActionState::delivered || t.status != TaskStatus::running ||
      act.state == ActionState::dropped) {
    log(json{{"ev", "duplicate_result"},
             {"drone", drone},
             {"task", t.id},
             {"action", static_cast<int>(a)}});
    ++record_.duplicate_results;
    return;
  }
  act.state = ActionState::delivered;
  act.result->value = r;
  json done{{"ev", "action_done"},
            {"drone", drone},
            {"task", t.id},
            {"action", static_cast<int>(a)},
            {"name", act.type == ActionType::fly_to ? std::string("fly_to") : act.name}};
  if (act.type == ActionType::sense) {
    record_.served.push_back({round6(r.t_s), round6(r.at.x), round6(r.at.y)});
    done = at_json(done, r.at, json{{"at_s", round6(r.t_s)}});  // where it sensed
  }
  log(done);
  wake(*act.result);
}

// ---------------------------------------------------------------------------------------------
// Drones

Vec3 Runtime::position_at(const Drone& d, double t) const {
  if (ext_ && d.reported && d.mode != Mode::charging && d.mode != Mode::landed) return *d.reported;
  if (on_leg(d.mode) && d.leg) return d.leg->position_at(t - d.leg_start);
  return d.pos;
}

void Runtime::integrate(Drone& d, double t) {
  if (t <= d.t_mark) return;
  const double a = d.t_mark, b = t;
  const DroneSpec& s = d.spec;
  double energy = 0, charge_as = 0;  // J, A·s
  auto constant = [&](double watts, double secs) {
    energy += watts * secs;
    charge_as += energy::battery_current_a(s.battery, watts) * secs;
  };
  switch (d.mode) {
    case Mode::landed:
    case Mode::lost:
      break;
    case Mode::charging:
      break;  // full when charge_end comes
    case Mode::hovering:
    case Mode::acting:
    case Mode::held:
      constant(hover_power_w(s, settings_.wind_m_s), b - a);
      d.idle_s += d.mode == Mode::acting ? 0.0 : b - a;
      break;
    case Mode::flying:
    case Mode::positioning:
    case Mode::returning: {
      const Leg& leg = *d.leg;
      const double la = a - d.leg_start, lb = b - d.leg_start;
      // Vertical part at the climb or descent power.
      const double v0 = std::clamp(la, 0.0, leg.vertical_s()),
                   v1 = std::clamp(lb, 0.0, leg.vertical_s());
      if (v1 > v0) constant(leg.climbing() ? climb_power_w(s) : descent_power_w(s), v1 - v0);
      // Level part, piece by piece (constant acceleration within each), at the airspeed.
      const auto& pieces = leg.pieces();
      const Vec3& wind = settings_.wind_m_s;
      const double run = std::hypot(leg.to().x - leg.from().x, leg.to().y - leg.from().y);
      const double ux = run > 0 ? (leg.to().x - leg.from().x) / run : 0.0;
      const double uy = run > 0 ? (leg.to().y - leg.from().y) / run : 0.0;
      for (std::size_t i = 0; i < pieces.size(); ++i) {
        const double p0 = leg.vertical_s() + pieces[i].t0_s;
        const double p1 =
            i + 1 < pieces.size() ? leg.vertical_s() + pieces[i + 1].t0_s : leg.duration_s();
        const double x0 = std::max(la, p0), x1 = std::min(lb, p1);
        if (x1 <= x0) continue;
        auto watts = [&](double tl) {
          const double v = leg.speed_at(tl);
          return energy::level_flight_power_w(s.power.mechanical,
                                              std::hypot(ux * v - wind.x, uy * v - wind.y)) +
                 s.power.payload_w;
        };
        energy += gauss(watts, x0, x1);
        charge_as += gauss(
            [&](double tl) { return energy::battery_current_a(s.battery, watts(tl)); }, x0, x1);
      }
      // Hovering at the end if the interval runs past the leg (it stops there).
      if (lb > leg.duration_s())
        constant(hover_power_w(s, settings_.wind_m_s), lb - std::max(la, leg.duration_s()));
      const Vec3 p0 = leg.position_at(la), p1 = leg.position_at(lb);
      d.distance_m += std::hypot(p1.x - p0.x, p1.y - p0.y);
      break;
    }
  }
  if (d.mode != Mode::landed && d.mode != Mode::lost && d.mode != Mode::charging)
    d.flight_s += b - a;
  d.energy_j += energy;
  d.soc -= charge_as / (3600.0 * s.battery.capacity_ah);
  d.pos = position_at(d, t);
  d.t_mark = t;
}

void Runtime::set_mode(Drone& d, Mode m, double t) {
  d.mode = m;
  const std::string name = mode_name(m, d.link_up);
  if (name != d.span_mode) {
    if (!d.span_mode.empty() && t > d.span_start)
      d.record.spans.push_back({round6(d.span_start), round6(t), d.span_mode});
    d.span_mode = name;
    d.span_start = t;
  }
  d.record.track.push_back({round6(t), round6(d.pos.x), round6(d.pos.y), round6(d.pos.z)});
  // Every point of the track and every change of mode, so that `swath-fleet render` redraws the
  // run from its events alone (the state's own time: a leg may end between ticks).
  log(at_json(json{{"ev", "drone_mode"}, {"drone", d.index}, {"at_s", round6(t)}}, d.pos,
              json{{"state", name}}));
}

double Runtime::next_event(const Drone& d) const {
  double e = kInf;
  switch (d.mode) {
    case Mode::flying:
    case Mode::positioning:
    case Mode::returning:
      if (!ext_) e = d.leg_start + d.leg->duration_s();  // else: the vehicle's report ends it
      break;
    case Mode::acting:
      e = d.act_end;
      break;
    case Mode::charging:
      e = d.charge_end;
      break;
    case Mode::held:
      e = d.hold_until;
      break;
    default:
      break;
  }
  if (!d.link_up) e = std::min(e, d.link_back);
  if (!d.sensor_ok) e = std::min(e, d.sensor_back);
  return std::min(e, leave_time(d));
}

void Runtime::start_leg(Drone& d, const Vec3& to, Mode mode, double t) {
  integrate(d, t);
  double v0 = 0;
  if (on_leg(d.mode) && d.leg) {
    // A retarget keeps the speed along the new course (the component across it is braked).
    const double along = d.leg->speed_at(t - d.leg_start);
    const Vec3 old_dir = d.leg->to() - d.leg->from(), new_dir = to - d.pos;
    const double n0 = std::hypot(old_dir.x, old_dir.y), n1 = std::hypot(new_dir.x, new_dir.y);
    if (n0 > 0 && n1 > 0)
      v0 = along * std::max(0.0, (old_dir.x * new_dir.x + old_dir.y * new_dir.y) / (n0 * n1));
  }
  if (d.mode == Mode::landed) d.airborne_since = t;
  d.leg.emplace(d.pos, to, d.spec.kinematics, v0);
  d.leg_start = t;
  set_mode(d, mode, t);
  command_leg(d, to, mode);
}

// An external vehicle is told to fly what the model just started (nothing for the simulation).
void Runtime::command_leg(Drone& d, const Vec3& to, Mode mode) {
  if (!ext_) return;
  if (mode == Mode::returning) {
    ext_->return_home(d.index);
    return;
  }
  const Kinematics& k = d.spec.kinematics;
  ext_->go_to(d.index, to, k.cruise_m_s, k.approach_m_s, k.approach_within_m);
}

bool Runtime::available(const Drone& d) const {
  return d.link_up && (d.mode == Mode::landed || d.mode == Mode::hovering || d.mode == Mode::held ||
                       d.mode == Mode::positioning || (d.mode == Mode::flying && d.task >= 0));
}

double Runtime::leave_time(const Drone& d) const {
  if (d.mode != Mode::hovering && d.mode != Mode::held) return kInf;
  return must_leave_at(d);
}

// When the drone must head home from where it is now: its flight time, or its battery drained at
// hover power down to what the way home takes (a hovering drone's exact limit; for one on a leg
// or acting, an estimate from its place at t_mark).
double Runtime::must_leave_at(const Drone& d) const {
  return std::max(leave_from(d, d.pos, d.airborne_since, d.t_mark, 0.0), d.t_mark);
}

// When drone `d`, waiting at `place`, must leave for home: airborne since `airborne_s`, its
// flight time less the way home; or, its charge d.soc draining at hover power from `soc_s`, when
// what is left just takes it home plus `extra_flight_s` of cruise (a flight still to make there).
double Runtime::leave_from(const Drone& d, const Vec3& place, double airborne_s, double soc_s,
                           double extra_flight_s) const {
  const Vec3 home{d.spec.home_m.x, d.spec.home_m.y, d.layer_m};
  const double back_s = Leg(place, home, d.spec.kinematics).duration_s() +
                        d.layer_m / d.spec.kinematics.descent_m_s + 2 * settings_.tick_s;
  const double cruise_w = cruise_power_w(d.spec, settings_.wind_m_s);
  const double need = d.spec.battery.reserve_soc +
                      energy::battery_current_a(d.spec.battery, cruise_w) *
                          (back_s + extra_flight_s) / (3600.0 * d.spec.battery.capacity_ah);
  return std::min(airborne_s + d.spec.max_flight_time_s - back_s,
                  soc_s + energy::seconds_to_soc(d.spec.battery, d.soc, need,
                                                 hover_power_w(d.spec, settings_.wind_m_s)));
}

bool Runtime::must_go_home(const Drone& d, double t) const {
  if (d.mode == Mode::landed || d.mode == Mode::charging || d.mode == Mode::lost ||
      d.mode == Mode::returning)
    return false;
  const Vec3 home{d.spec.home_m.x, d.spec.home_m.y, d.layer_m};
  const Leg back(d.pos, home, d.spec.kinematics);
  const double back_s = back.duration_s() + d.layer_m / d.spec.kinematics.descent_m_s;
  if (t - d.airborne_since + back_s + 2 * settings_.tick_s >= d.spec.max_flight_time_s) return true;
  const double cruise_w = cruise_power_w(d.spec, settings_.wind_m_s);
  const double landing =
      energy::soc_after(d.spec.battery, d.soc, cruise_w, back_s + 2 * settings_.tick_s);
  return !(landing >= d.spec.battery.reserve_soc);
}

void Runtime::requeue(Drone& d, const std::string& reason) {
  if (d.task < 0) return;
  Task& t = tasks_[static_cast<std::size_t>(d.task)];
  unserve(d);
  t.requested = false;
  log(json{{"ev", "requeued"}, {"task", t.id}, {"drone", d.index}, {"reason", reason}});
  ++record_.requeued;
  changed_ = true;
}

// The drone no longer serves its task: the segment it was on waits for a drone again.
void Runtime::unserve(Drone& d) {
  if (d.task < 0) return;
  Task& t = tasks_[static_cast<std::size_t>(d.task)];
  for (auto& a : t.actions)
    if (a.state == ActionState::running) a.state = ActionState::pending;
  t.serving = -1;
  d.task = -1;
}

void Runtime::go_home(Drone& d, double t, const std::string& why) {
  requeue(d, why);
  leave_spot(d);
  d.relieving = -1;
  if (d.held_for >= 0) d.held_for = -1;
  const Vec3 home{d.spec.home_m.x, d.spec.home_m.y, d.pos.z > 0 ? d.pos.z : d.layer_m};
  start_leg(d, home, Mode::returning, t);
  changed_ = true;
}

void Runtime::release(Drone& d, double t) {
  Task* t_ptr = d.task >= 0 ? &tasks_[static_cast<std::size_t>(d.task)] : nullptr;
  if (t_ptr) t_ptr->serving = -1;
  d.task = -1;
  if (t_ptr && !t_ptr->flags.interruptible && t_ptr->status == TaskStatus::running) {
    d.held_for = t_ptr->id;
    d.hold_until = t + settings_.hold_s;
    set_mode(d, Mode::held, t);
  } else {
    set_mode(d, Mode::hovering, t);
  }
  changed_ = true;
  if (must_go_home(d, t)) go_home(d, t, "battery");
}

// The drone is where its task's head segment is: do the next action, or finish the segment.
void Runtime::start_action_or_release(Drone& d, double t) {
  Task& tk = tasks_[static_cast<std::size_t>(d.task)];
  const std::size_t h = tk.head();
  if (tk.status != TaskStatus::running || h >= tk.actions.size() ||
      tk.actions[h].type == ActionType::fly_to || (tk.actions[h].state != ActionState::pending)) {
    release(d, t);
    return;
  }
  Action& a = tk.actions[h];
  if (a.type == ActionType::sense && !d.sensor_ok) {
    requeue(d, "sensor_failure");
    set_mode(d, Mode::hovering, t);
    return;
  }
  a.state = ActionState::running;
  d.action = h;
  d.act_end = t + a.duration_s;
  set_mode(d, Mode::acting, t);
  if (ext_) ext_->act(d.index, a.name, a.type == ActionType::sense);
}

// A link back or a sensor repaired by t.
void Runtime::recover(Drone& d, double t) {
  if (!d.link_up && t >= d.link_back) {
    d.link_up = true;
    for (Pending& p : d.buffered) {
      p.deliver_s = t + settings_.link_latency_s;
      pending_.push_back(p);
    }
    d.buffered.clear();
    set_mode(d, d.mode, t);
    changed_ = true;
  }
  if (!d.sensor_ok && t >= d.sensor_back) {
    d.sensor_ok = true;
    changed_ = true;
  }
}

// A result on its way to the app: after the link's latency, or buffered while the link is down.
void Runtime::emit(Drone& d, Task& tk, std::size_t a, const Reading& r, double t) {
  Pending p{t + settings_.link_latency_s, d.index, tk.id, a, r, seq_++};
  if (d.link_up)
    pending_.push_back(std::move(p));
  else
    d.buffered.push_back(std::move(p));
}

// fly_sensing: a reading every period along the leg that reached the target (x_m, y_m and the
// sensor's values per sample).
void Runtime::sample_along(const Action& fa, const Leg& flown, double flown_from, Reading& r) {
  r.sensor = fa.sample_sensor;
  std::string ref;
  for (double s_t = fa.sample_period_s;
       s_t <= flown.duration_s() + 1e-9 && r.values.size() < 3 * 100000;
       s_t += fa.sample_period_s) {
    const Vec3 at = flown.position_at(s_t);
    const Reading one = world_.sense(fa.sample_sensor, at, flown_from + s_t);
    r.values.push_back(at.x);
    r.values.push_back(at.y);
    r.values.insert(r.values.end(), one.values.begin(), one.values.end());
    ref = one.ref;
  }
  r.ref = "samples of x_m,y_m," + ref;
}

// The end of a leg to a task's place: the fly_to done (binding the task where its flags say),
// then its next action, or home when the link is down.
void Runtime::arrive(Drone& d, double t) {
  const Leg flown = *d.leg;
  const double flown_from = d.leg_start;
  d.pos = ext_ && d.reported ? *d.reported : d.leg->to();
  d.leg.reset();
  if (d.task < 0) {
    set_mode(d, Mode::hovering, t);
    return;
  }
  Task& tk = tasks_[static_cast<std::size_t>(d.task)];
  if (std::find(tk.drones_used.begin(), tk.drones_used.end(), d.index) == tk.drones_used.end())
    tk.drones_used.push_back(d.index);
  if ((tk.flags.same_drone || !tk.flags.interruptible) && !tk.bound) tk.bound = d.index;
  const std::size_t h = tk.head();
  if (h < tk.actions.size() && tk.actions[h].type == ActionType::fly_to) {
    tk.actions[h].state = ActionState::completed;
    Reading r;
    r.t_s = t;
    r.drone = d.index;
    r.at = d.pos;
    r.sensor = "fly_to";
    if (tk.actions[h].sample_period_s > 0) sample_along(tk.actions[h], flown, flown_from, r);
    emit(d, tk, h, r, t);
  }
  if (!d.link_up) {  // the vehicle's own failsafe takes it home
    requeue(d, "link_loss");
    go_home(d, t, "link_loss");
    return;
  }
  start_action_or_release(d, t);
}

// The end of an action: its reading, then the next action, or home (link down, battery).
void Runtime::finish_action(Drone& d, double t) {
  Task& tk = tasks_[static_cast<std::size_t>(d.task)];
  Action& a = tk.actions[d.action];
  a.state = ActionState::completed;
  Reading r;
  if (a.type == ActionType::sense) r = world_.sense(a.name, d.pos, t);
  r.t_s = t;
  r.drone = d.index;
  r.at = d.pos;
  if (r.sensor.empty()) r.sensor = a.name;
  emit(d, tk, d.action, r, t);
  if (!d.link_up) {
    go_home(d, t, "link_loss");
    return;
  }
  if (must_go_home(d, t)) {
    go_home(d, t, "battery");
    return;
  }
  start_action_or_release(d, t);
}

// Home reached: the descent from the layer is part of the flight, then the recharge (a swap or a
// charge to full, case 5's 30 s).
void Runtime::land_home(Drone& d, double t) {
  d.pos = d.leg->to();
  d.leg.reset();
  const double down = d.pos.z / d.spec.kinematics.descent_m_s;
  d.energy_j += descent_power_w(d.spec) * down;
  d.soc -= energy::battery_current_a(d.spec.battery, descent_power_w(d.spec)) * down /
           (3600.0 * d.spec.battery.capacity_ah);
  d.flight_s += down;
  d.pos.z = 0;
  d.charge_end = t + d.spec.recharge_s;
  set_mode(d, Mode::charging, t);
  changed_ = true;
}

// Everything that happens to drone d at time t (an event of next_event(d)).
void Runtime::step_drone(Drone& d, double t) {
  integrate(d, t);
  recover(d, t);
  switch (d.mode) {
    case Mode::flying:
    case Mode::positioning:
      if (t >= d.leg_start + d.leg->duration_s()) arrive(d, t);
      break;
    case Mode::acting:
      if (t >= d.act_end) finish_action(d, t);
      break;
    case Mode::returning:
      if (t >= d.leg_start + d.leg->duration_s()) land_home(d, t);
      break;
    case Mode::charging:
      if (t >= d.charge_end) {
        d.soc = 1.0;
        set_mode(d, Mode::landed, t);
        changed_ = true;
      }
      break;
    case Mode::hovering:
      if (t >= leave_time(d) - 1e-9) go_home(d, t, "battery");
      break;
    case Mode::held:
      if (t >= leave_time(d) - 1e-9) {
        go_home(d, t, "battery");
        break;
      }
      if (t >= d.hold_until) {  // the hold is over: the task may go to any drone again
        Task& tk = tasks_[static_cast<std::size_t>(d.held_for)];
        if (!tk.flags.same_drone) tk.bound.reset();
        d.held_for = -1;
        set_mode(d, Mode::hovering, t);
        changed_ = true;
      }
      break;
    default:
      break;
  }
}

void Runtime::dispatch(Drone& d, Task& t, double at) {
  t.serving = d.index;
  d.task = t.id;
  if (d.held_for == t.id) d.held_for = -1;
  const std::size_t h = t.head();
  Vec3 to = t.location;
  if (h < t.actions.size() && t.actions[h].type == ActionType::fly_to) to = t.actions[h].to;
  // Earlier non-flying actions happen where the task's previous fly_to went.
  for (std::size_t i = h; i-- > 0;)
    if (t.actions[i].type == ActionType::fly_to) {
      if (h < t.actions.size() && t.actions[h].type != ActionType::fly_to) to = t.actions[i].to;
      break;
    }
  if (!(to.z > 0)) to.z = d.layer_m;
  for (std::size_t i = h; i < t.actions.size(); ++i) {
    if (i > h && t.actions[i].type == ActionType::fly_to) break;
    if (t.actions[i].state == ActionState::pending && t.actions[i].type == ActionType::fly_to)
      t.actions[i].state = ActionState::running;
  }
  log(at_json(
      json{{"ev", "dispatch"}, {"drone", d.index}, {"task", t.id}, {"segment", t.segment - 1}},
      to));
  const Vec3 here = position_at(d, at);
  if (std::hypot(here.x - to.x, here.y - to.y) < 1e-9 && std::abs(here.z - to.z) < 1e-9 &&
      d.mode != Mode::landed) {
    integrate(d, at);
    d.leg.emplace(here, to, d.spec.kinematics, 0.0);
    d.leg_start = at;
    set_mode(d, Mode::flying, at);
    command_leg(d, to, Mode::flying);
    return;
  }
  if (d.mode == Mode::landed) {
    integrate(d, at);
    d.airborne_since = at;
    // Take off: climb at home, then the leg climbs to the layer and flies.
  }
  start_leg(d, to, Mode::flying, at);
}

// The scheduler's view of the fleet's kinematics and energy (the first drone's, eq. 12).
Snapshot Runtime::snapshot_base() const {
  Snapshot s;
  const DroneSpec& first = drones_.front().spec;
  s.eta.cruise_m_s = first.kinematics.cruise_m_s;
  s.eta.accel_m_s2 = first.kinematics.accel_m_s2 > 0 ? first.kinematics.accel_m_s2 : 1e9;
  s.eta.approach_m_s = first.kinematics.approach_m_s;
  s.eta.approach_within_m = first.kinematics.approach_within_m;
  s.weights = settings_.weights;
  s.fence = world_.fence();
  // Charge: there, serve, home above the reserve.
  EnergyFeasibility e;
  e.battery = first.battery;
  e.cruise_power_w = cruise_power_w(first, settings_.wind_m_s);
  e.hover_power_w = hover_power_w(first, settings_.wind_m_s);
  s.energy = e;
  return s;
}

// Requests: every running task with work whose head is not being acted on; `req_task` gets their
// task ids. First come, first served (§18.3): a drone acting, held or bound for a place reserves a
// 5 m disc around it; other tasks' requests inside wait until it leaves.
void Runtime::add_requests(Snapshot& s, std::vector<int>& req_task) {
  std::vector<std::pair<Vec3, int>> discs;
  for (const Drone& d : drones_) {
    if (d.mode == Mode::acting || d.mode == Mode::held)
      discs.push_back({d.pos, d.mode == Mode::acting ? d.task : d.held_for});
    if (d.mode == Mode::flying && d.task >= 0 && d.leg) discs.push_back({d.leg->to(), d.task});
  }
  for (Task& t : tasks_) {
    if (!t.has_work()) continue;
    if (t.serving >= 0 && drones_[static_cast<std::size_t>(t.serving)].mode != Mode::flying)
      continue;
    const std::size_t h = t.head();
    Request r;
    r.location_m = t.actions[h].type == ActionType::fly_to ? t.actions[h].to : t.location;
    if (std::any_of(discs.begin(), discs.end(), [&](const std::pair<Vec3, int>& disc) {
          return disc.second != t.id &&
                 std::hypot(disc.first.x - r.location_m.x, disc.first.y - r.location_m.y) <
                     settings_.disc_m;
        }))
      continue;
    for (std::size_t i = h; i < t.actions.size(); ++i) {
      if (i > h && t.actions[i].type == ActionType::fly_to) break;
      r.service_s += t.actions[i].duration_s;
      if (t.actions[i].type == ActionType::sense) r.needs_sensor = true;
    }
    if (!t.requested) {
      t.requested = true;
      t.visible_since_s = now_;
      log(at_json(json{{"ev", "request_visible"}, {"task", t.id}, {"segment", t.segment++}},
                  r.location_m, json{{"service_s", round6(r.service_s)}}));
      note_hits(r.location_m, t.id);
    }
    r.waiting_s = now_ - t.visible_since_s;
    if (t.bound) r.bound_drone = *t.bound;
    req_task.push_back(t.id);
    s.requests.push_back(r);
  }
}

// Drones available to the scheduler; `drone_of` maps snapshot drones to fleet indices. Bound
// requests are renumbered from fleet indices to snapshot positions.
void Runtime::add_drones(Snapshot& s, const std::vector<int>& req_task,
                         std::vector<int>& drone_of) {
  for (Drone& d : drones_) {
    if (!available(d) || d.relieving >= 0) continue;  // a stand-by is pinned to its place
    DroneState ds;
    ds.position_m = position_at(d, now_);
    if (!(ds.position_m.z > 0)) ds.position_m.z = d.layer_m;
    ds.home_m = {d.spec.home_m.x, d.spec.home_m.y, d.layer_m};
    ds.soc = d.soc;
    ds.can_sense = d.sensor_ok;
    if (std::isfinite(d.spec.max_flight_time_s)) {
      // What is left once the descent at home and two ticks of margin are set aside.
      const double used = d.mode == Mode::landed ? 0.0 : now_ - d.airborne_since;
      const double climb = d.mode == Mode::landed ? d.layer_m / d.spec.kinematics.climb_m_s : 0.0;
      ds.remaining_flight_s = d.spec.max_flight_time_s - used - climb -
                              d.layer_m / d.spec.kinematics.descent_m_s - 2 * settings_.tick_s;
    }
    if (d.mode == Mode::held) ds.only_request = -1;
    for (std::size_t r = 0; r < req_task.size(); ++r) {
      if (req_task[r] == d.task) ds.target = static_cast<int>(r);
      if (d.mode == Mode::held && req_task[r] == d.held_for) ds.only_request = static_cast<int>(r);
    }
    if (d.spot) {  // speculating: the forecast at its place is its target (commitment)
      double nearest = settings_.hit_within_m;
      for (std::size_t f = 0; f < s.forecasts.size(); ++f)
        if (const double g = vehicle::horizontal_distance(s.forecasts[f].location_m, *d.spot);
            g <= nearest) {
          nearest = g;
          ds.target = static_cast<int>(req_task.size() + f);
        }
    }
    drone_of.push_back(d.index);
    s.drones.push_back(ds);
  }
  for (Request& r : s.requests)
    if (r.bound_drone) {
      auto it = std::find(drone_of.begin(), drone_of.end(), *r.bound_drone);
      r.bound_drone = it == drone_of.end() ? -1 : static_cast<int>(it - drone_of.begin());
    }
}

// Applies the difference to the fleet. Two requests of this round inside one disc: the first (by
// drone) goes. Drones that lost their request to another and got nothing stop where they are.
void Runtime::apply_assignment(const Snapshot& s, const Assignment& a,
                               const std::vector<int>& req_task, const std::vector<int>& drone_of) {
  std::vector<Vec3> claimed;
  const auto visible = static_cast<int>(req_task.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    Drone& d = drones_[static_cast<std::size_t>(drone_of[i])];
    if (a[i] && *a[i] >= visible) {  // speculation: only a place to wait at
      const ForecastRequest& f = s.forecasts[static_cast<std::size_t>(*a[i] - visible)];
      if (d.spot && vehicle::horizontal_distance(*d.spot, f.location_m) < 1e-6) continue;
      unserve(d);
      position(d, f);
      continue;
    }
    leave_spot(d);
    int want = a[i] ? req_task[static_cast<std::size_t>(*a[i])] : -1;
    if (want >= 0) {
      const Vec3 at = s.requests[static_cast<std::size_t>(*a[i])].location_m;
      if (std::any_of(claimed.begin(), claimed.end(), [&](const Vec3& c) {
            return std::hypot(c.x - at.x, c.y - at.y) < settings_.disc_m;
          })) {
        want = d.task;  // keeps what it had; the request waits for the disc
        changed_ = true;
      } else {
        claimed.push_back(at);
      }
    }
    if (want == d.task) continue;
    if (d.task >= 0) {  // retargeted or stopped on the way
      unserve(d);
      if (want < 0) {
        integrate(d, now_);
        d.leg.reset();
        set_mode(d, Mode::hovering, now_);
      }
    }
    if (want >= 0) {
      Task& t = tasks_[static_cast<std::size_t>(want)];
      if (t.serving >= 0 && t.serving != d.index) {
        Drone& other = drones_[static_cast<std::size_t>(t.serving)];
        if (other.task == t.id) other.task = -1;
      }
      dispatch(d, t, now_);
    }
  }
  for (Drone& d : drones_)
    if ((d.mode == Mode::flying && d.task < 0) ||
        (d.mode == Mode::positioning && !d.spot && d.relieving < 0)) {
      integrate(d, now_);
      d.leg.reset();
      set_mode(d, Mode::hovering, now_);
    }
}

// One scheduling round (§18.5): the snapshot, the scheduler's assignment (timed), its log line,
// its application.
void Runtime::schedule() {
  Snapshot s = snapshot_base();
  std::vector<int> req_task, drone_of;
  update_forecasts();
  add_requests(s, req_task);
  add_forecasts(s, req_task);
  add_drones(s, req_task, drone_of);
  if (s.requests.empty() && s.forecasts.empty() &&
      std::none_of(s.drones.begin(), s.drones.end(),
                   [](const DroneState& x) { return x.target.has_value(); }))
    return;
  const auto clock0 = std::chrono::steady_clock::now();
  const Assignment a = s.drones.empty() ? Assignment{} : scheduler_->assign(s, sched_rng_);
  record_.decision_s_total +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  ++record_.schedules;
  json assignment = json::array();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i]) continue;
    const auto k = static_cast<std::size_t>(*a[i]);
    if (k < req_task.size())
      assignment.push_back(json{{"drone", drone_of[i]}, {"task", req_task[k]}});
    else  // a forecast place (its `position` event follows)
      assignment.push_back(json{{"drone", drone_of[i]}, {"forecast", k - req_task.size()}});
  }
  log(json{{"ev", "schedule"}, {"assignment", assignment}});
  apply_assignment(s, a, req_task, drone_of);
}

// Forecasts again when the DTG changed (§18.3 step 4); a `forecast` event when they differ.
void Runtime::update_forecasts() {
  if (!forecaster_ || !dtg_changed_) return;
  dtg_changed_ = false;
  const auto clock0 = std::chrono::steady_clock::now();
  live_ = live_dtg();
  std::vector<ForecastRequest> next = forecaster_->forecast(live_, now_);
  record_.forecast_s_total +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  ++record_.forecasts;
  auto same = [](const std::vector<ForecastRequest>& a, const std::vector<ForecastRequest>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& x, const auto& y) {
      return x.kind == y.kind && x.p == y.p && x.location_m.x == y.location_m.x &&
             x.location_m.y == y.location_m.y;
    });
  };
  const bool changed = !same(next, forecasts_);
  forecasts_ = std::move(next);  // kept even when only the expected times moved
  if (!changed) return;
  json list = json::array();
  for (const ForecastRequest& f : forecasts_)
    list.push_back(at_json(json{{"kind", f.kind}}, f.location_m,
                           json{{"p", round6(f.p)}, {"expected_s", round6(f.expected_s)}}));
  log(json{{"ev", "forecast"}, {"forecasts", list}});
}

// The forecasts not already shown by a visible request, and q between the visible requests
// (§18.5's avoid-mutual; pairs below 0.01 left out, as the scheduler's neighbour lists).
void Runtime::add_forecasts(Snapshot& s, const std::vector<int>& req_task) const {
  if (!forecaster_) return;
  for (const ForecastRequest& f : forecasts_)
    if (f.p > 0 && std::none_of(s.requests.begin(), s.requests.end(), [&](const Request& r) {
          return vehicle::horizontal_distance(r.location_m, f.location_m) <= settings_.hit_within_m;
        })) {
      ForecastRequest g = f;
      g.location_m.z = 0;  // each drone flies at its layer
      s.forecasts.push_back(g);
    }
  for (std::size_t i = 0; i < req_task.size(); ++i)
    for (std::size_t j = 0; j < req_task.size(); ++j) {
      if (i == j) continue;
      const auto ti = static_cast<std::size_t>(req_task[i]),
                 tj = static_cast<std::size_t>(req_task[j]);
      if (ti >= live_.nodes.size() || tj >= live_.nodes.size()) continue;
      const double q = forecaster_->cancel_probability(live_.nodes[ti], live_.nodes[tj]);
      if (q > 0.01) s.mutual.push_back({static_cast<int>(i), static_cast<int>(j), q});
    }
}

// Speculation positions a drone only (§18.5): it flies to the forecast place at its layer and
// waits there; it serves what appears only when the scheduler gives it that request.
void Runtime::position(Drone& d, const ForecastRequest& f) {
  leave_spot(d);
  d.spot = f.location_m;
  d.spot_hit = false;
  ++record_.speculative_positions;
  Vec3 to = f.location_m;
  to.z = d.layer_m;
  log(at_json(json{{"ev", "position"}, {"drone", d.index}}, to,
              json{{"kind", f.kind}, {"p", round6(f.p)}}));
  start_leg(d, to, Mode::positioning, now_);
}

// ---- relief (docs/swath-fleet.md, Example 5) ---------------------------------------------------
// A drone at work that must soon head home is relieved: the idle drone that gets to its place
// soonest is sent there when the working drone's leave time is within that flight plus
// relief_margin_s, and waits there, out of the scheduler's hands, until the working drone leaves
// (home, lost, link down). Then the stand-by is the drone nearest the work it left (requeued on
// the way home): the scheduler gives it the next segment without a flight from home.

bool Runtime::working(const Drone& d) const {
  return d.link_up && (d.task >= 0 || d.held_for >= 0) &&
         (d.mode == Mode::flying || d.mode == Mode::acting || d.mode == Mode::held ||
          d.mode == Mode::hovering);
}

bool Runtime::idle(const Drone& d) const {
  return d.link_up && d.sensor_ok && d.task < 0 && d.held_for < 0 && !d.spot && d.relieving < 0 &&
         (d.mode == Mode::landed || d.mode == Mode::hovering);
}

void Runtime::relieve() {
  next_relief_s_ = kInf;
  for (Drone& e : drones_) {  // stand-bys whose drone has left are free again
    if (e.relieving < 0) continue;
    const Drone& d = drones_[static_cast<std::size_t>(e.relieving)];
    if (!d.link_up || d.mode == Mode::returning || d.mode == Mode::landed ||
        d.mode == Mode::charging || d.mode == Mode::lost) {
      e.relieving = -1;
      changed_ = true;
    }
  }
  for (const Drone& d : drones_) {
    if (!working(d) || std::any_of(drones_.begin(), drones_.end(),
                                   [&](const Drone& e) { return e.relieving == d.index; }))
      continue;
    const double leave_s = must_leave_at(d);
    if (!std::isfinite(leave_s)) continue;
    Vec3 at = d.leg && on_leg(d.mode) ? d.leg->to() : position_at(d, now_);
    Drone* best = nullptr;
    double best_eta = kInf;
    for (Drone& e : drones_) {
      if (&e == &d || !idle(e)) continue;
      const Vec3 to{at.x, at.y, e.layer_m};
      Vec3 from = position_at(e, now_);
      if (e.mode == Mode::landed) from.z = 0;
      const double eta = Leg(from, to, e.spec.kinematics).duration_s();
      // Worth it only when it can stay at least the margin beyond the hand-over.
      const double airborne_s = e.mode == Mode::landed ? now_ : e.airborne_since;
      if (leave_from(e, to, airborne_s, now_, eta) < leave_s + settings_.relief_margin_s) continue;
      if (eta < best_eta) best_eta = eta, best = &e;
    }
    if (!best) continue;
    const double when = leave_s - best_eta - settings_.relief_margin_s;
    if (when <= now_ + 1e-9)
      stand_by(*best, d, {at.x, at.y, best->layer_m}, leave_s);
    else
      next_relief_s_ = std::min(next_relief_s_, when);
  }
}

void Runtime::stand_by(Drone& e, const Drone& d, const Vec3& at, double leave_s) {
  e.relieving = d.index;
  ++record_.reliefs;
  log(at_json(json{{"ev", "relief"}, {"drone", e.index}, {"for", d.index}}, at,
              json{{"leave_s", round6(leave_s)}}));
  start_leg(e, at, Mode::positioning, now_);
}

// The drone leaves its forecast place (another target, home, the run's end): a miss unless a
// request appeared there.
void Runtime::leave_spot(Drone& d) {
  if (!d.spot) return;
  if (!d.spot_hit) ++record_.speculative_misses;
  d.spot.reset();
  d.spot_hit = false;
}

// A request appeared: a hit for each drone sent to within hit_within_m of it.
void Runtime::note_hits(const Vec3& request_at, int task) {
  for (Drone& d : drones_)
    if (d.spot && !d.spot_hit &&
        vehicle::horizontal_distance(*d.spot, request_at) <= settings_.hit_within_m) {
      d.spot_hit = true;
      ++record_.speculative_hits;
      log(json{{"ev", "speculation_hit"}, {"drone", d.index}, {"task", task}});
    }
}

void Runtime::apply_fault(const FaultEvent& f) {
  if (f.drone < 0 || static_cast<std::size_t>(f.drone) >= drones_.size()) return;
  Drone& d = drones_[static_cast<std::size_t>(f.drone)];
  integrate(d, now_);
  log(json{{"ev", "fault"},
           {"drone", d.index},
           {"fault", fault_name(f.kind)},
           {"duration_s", round6(f.duration_s)},
           {"soc", round6(std::max(0.0, d.soc))}});
  if (d.mode == Mode::lost) return;
  switch (f.kind) {
    case FaultKind::link_loss:
      if (!d.link_up) {
        d.link_back = std::max(d.link_back, now_ + f.duration_s);
        break;
      }
      d.link_up = false;
      d.link_back = now_ + f.duration_s;
      if (d.mode == Mode::flying || d.mode == Mode::positioning || d.mode == Mode::hovering ||
          d.mode == Mode::held) {
        requeue(d, "link_loss");
        go_home(d, now_, "link_loss");
      } else {
        set_mode(d, d.mode, now_);  // acting: it finishes, then its failsafe takes it home
      }
      changed_ = true;
      break;
    case FaultKind::battery_drop:
      d.soc = std::min(d.soc, f.soc);
      if (must_go_home(d, now_)) go_home(d, now_, "battery");
      changed_ = true;
      break;
    case FaultKind::motor_failure: {
      if (d.task >= 0) {
        Task& t = tasks_[static_cast<std::size_t>(d.task)];
        requeue(d, "motor_failure");
        if (t.flags.same_drone && t.bound && *t.bound == d.index) {
          fail_action_futures(t, std::make_exception_ptr(ActionFailed("drone_lost")));
          finish_task(t, TaskStatus::failed, "drone_lost");
        }
      }
      for (Task& t : tasks_)
        if (t.status == TaskStatus::running && t.bound && *t.bound == d.index) {
          if (t.flags.same_drone) {
            fail_action_futures(t, std::make_exception_ptr(ActionFailed("drone_lost")));
            finish_task(t, TaskStatus::failed, "drone_lost");
          } else {
            t.bound.reset();
          }
        }
      d.held_for = -1;
      leave_spot(d);
      d.leg.reset();
      for (const Pending& p : d.buffered) {
        Action& a = tasks_[static_cast<std::size_t>(p.task)].actions[p.action];
        if (a.state == ActionState::completed) a.state = ActionState::pending;
      }
      d.buffered.clear();
      set_mode(d, Mode::lost, now_);
      changed_ = true;
      break;
    }
    case FaultKind::sensor_failure:
      d.sensor_ok = false;
      d.sensor_back = std::max(d.sensor_back, now_ + f.duration_s);
      if (d.mode == Mode::acting && d.task >= 0) {
        Task& t = tasks_[static_cast<std::size_t>(d.task)];
        if (t.actions[d.action].type == ActionType::sense) {
          requeue(d, "sensor_failure");
          set_mode(d, Mode::hovering, now_);
        }
      }
      changed_ = true;
      break;
  }
}

void Runtime::log_states() {
  for (Drone& d : drones_) {
    integrate(d, now_);
    log(at_json(json{{"ev", "drone_state"}, {"drone", d.index}}, d.pos,
                json{{"soc", round6(d.soc)}, {"state", mode_name(d.mode, d.link_up)}}));
    d.record.track.push_back({round6(now_), round6(d.pos.x), round6(d.pos.y), round6(d.pos.z)});
  }
}

// What the external vehicles did since the last tick, in drone order: positions, a link lost
// (§18.7: after the backend's silence rule the drone is unavailable, its request requeued and the
// vehicle's own failsafe takes it home, as for an injected link_loss) or up (first heard, or
// back: buffered results go out; landed, it rejoins), a target reached, home reached, a vehicle
// refusing to fly.
void Runtime::poll_backend() {
  ext_->advance_to(now_);
  for (Drone& d : drones_) {
    const VehicleReport r = ext_->report(d.index);
    if (r.position_known) d.reported = r.position_m;
    integrate(d, now_);
    if (d.mode == Mode::lost) continue;
    if (!r.refusal.empty()) {  // it will not fly: out of the fleet, its work requeued
      log(json{{"ev", "vehicle_refused"}, {"drone", d.index}, {"reason", r.refusal}});
      requeue(d, "vehicle_refused");
      leave_spot(d);
      d.leg.reset();
      // Refused in the air (a target outside the fence): it still goes home and lands; the
      // backend does nothing for a vehicle already down.
      if (d.mode != Mode::landed && d.mode != Mode::charging) ext_->return_home(d.index);
      set_mode(d, Mode::lost, now_);
      changed_ = true;
      continue;
    }
    if (d.link_up && !r.link_up) {
      log(at_json(json{{"ev", "link_lost"}, {"drone", d.index}}, d.pos));
      d.link_up = false;
      d.link_back = kInf;  // until the backend hears it again
      if (d.mode == Mode::flying || d.mode == Mode::positioning || d.mode == Mode::hovering ||
          d.mode == Mode::held) {
        requeue(d, "link_loss");
        go_home(d, now_, "link_loss");
      } else {
        set_mode(d, d.mode, now_);  // acting: it finishes, then goes home (finish_action)
      }
      changed_ = true;
    } else if (!d.link_up && r.link_up) {
      log(at_json(json{{"ev", "link_up"}, {"drone", d.index}}, d.pos));
      d.link_back = now_;
      recover(d, now_);
    }
    if ((d.mode == Mode::flying || d.mode == Mode::positioning) && r.arrived)
      arrive(d, now_);
    else if (d.mode == Mode::returning && r.landed_home)
      land_home(d, now_);
  }
}

// Logs run_start and spawns the app's main, whose body writes into its own promise state.
Task& Runtime::start_main() {
  json drones = json::array();
  for (const Drone& d : drones_)
    drones.push_back(json{{"drone", d.index}, {"name", d.spec.name}, {"soc", round6(d.soc)}});
  log(json{{"ev", "run_start"},
           {"app", settings_.app_name},
           {"seed", settings_.seed},
           {"scheduler", settings_.scheduler},
           {"max_time_s", settings_.max_time_s},
           {"drones", drones}});
  for (Drone& d : drones_) set_mode(d, Mode::landed, 0);
  auto main_state = std::make_shared<detail::State<void>>();
  const App& app = app_;
  spawn(
      -1, Kind{"main"}, Flags{},
      [&app](Ctx& c) -> std::coroutine_handle<> { return app.main(c).release(); }, main_state);
  Task& main = tasks_.front();  // mirror the main body's promise state
  main.result = main_state;
  main.result->task = -1;  // awaiting main is not a sync of the DTG
  auto h = std::coroutine_handle<Co<void>::promise_type>::from_address(main.root.address());
  h.promise().result = main_state;
  return main;
}

// Requests waiting too long for any drone fail visibly (docs/swath-fleet.md).
void Runtime::fail_unserved() {
  for (Task& t : tasks_)
    if (t.has_work() && t.serving < 0 && t.requested &&
        now_ - t.visible_since_s >= settings_.no_feasible_s) {
      fail_action_futures(t, std::make_exception_ptr(ActionFailed("no_feasible_drone")));
      finish_task(t, TaskStatus::failed, "no_feasible_drone");
    }
}

// The time of the next thing that happens: a drone's event, a result's delivery, a delay's end, a
// fault, a request's no-feasible-drone deadline; infinity when nothing can.
double Runtime::next_happening() const {
  double next = kInf;
  for (const Drone& d : drones_) next = std::min(next, next_event(d));
  for (const Pending& p : pending_) next = std::min(next, p.deliver_s);
  for (const auto& [t, s] : delays_) next = std::min(next, t);
  if (next_fault_ < faults_.size()) next = std::min(next, faults_[next_fault_].t_s);
  next = std::min(next, next_relief_s_);
  for (const Task& t : tasks_)
    if (t.has_work() && t.serving < 0 && t.requested)
      next = std::min(next, t.visible_since_s + settings_.no_feasible_s);
  // External vehicles report at any time: every tick (§18.3 step 1, "real runs sleep to the
  // next tick").
  if (ext_) next = std::min(next, now_ + settings_.tick_s);
  return next;
}

// Moves the clock to `next` rounded up to the tick grid, logging drone_state on the way; false
// (with the failure set) past max_time_s.
bool Runtime::advance_clock(double next, std::int64_t& tick_index) {
  const double tick = settings_.tick_s;
  if (next > settings_.max_time_s) next = std::min(next, settings_.max_time_s + tick);
  std::int64_t k = static_cast<std::int64_t>(std::ceil(next / tick - 1e-9));
  k = std::max(k, tick_index + (next > now_ ? 0 : 1));
  if (k <= tick_index) k = tick_index + 1;
  while (next_state_log_ < static_cast<double>(k) * tick - 1e-12) {
    now_ = next_state_log_;
    log_states();
    next_state_log_ += settings_.state_period_s;
  }
  tick_index = k;
  now_ = static_cast<double>(k) * tick;
  if (now_ <= settings_.max_time_s) return true;
  record_.failure = "not completed within max_time_s (" +
                    std::to_string(static_cast<long long>(settings_.max_time_s)) + " s)";
  now_ = settings_.max_time_s;
  return false;
}

// Drones, in (time, drone) order, each through every event up to now.
void Runtime::step_drones_to_now() {
  for (;;) {
    double best = kInf;
    Drone* who = nullptr;
    for (Drone& d : drones_) {
      const double e = next_event(d);
      if (e <= now_ + 1e-12 && e < best) best = e, who = &d;
    }
    if (!who) return;
    step_drone(*who, best);
  }
}

// Faults, results and delays due by now, in (time, drone, sequence) order.
void Runtime::deliver_due() {
  while (next_fault_ < faults_.size() && faults_[next_fault_].t_s <= now_ + 1e-12)
    apply_fault(faults_[next_fault_++]);
  std::stable_sort(pending_.begin(), pending_.end(), [](const Pending& a, const Pending& b) {
    return a.deliver_s != b.deliver_s ? a.deliver_s < b.deliver_s
           : a.drone != b.drone       ? a.drone < b.drone
                                      : a.seq < b.seq;
  });
  std::size_t n = 0;
  while (n < pending_.size() && pending_[n].deliver_s <= now_ + 1e-12) ++n;
  std::vector<Pending> due(pending_.begin(), pending_.begin() + static_cast<long>(n));
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<long>(n));
  for (const Pending& p : due)
    resolve_action(tasks_[static_cast<std::size_t>(p.task)], p.action, p.reading, p.drone);
  for (auto it = delays_.begin(); it != delays_.end();)
    if (it->first <= now_ + 1e-12) {
      wake(*it->second);
      it = delays_.erase(it);
    } else {
      ++it;
    }
}

// The record: outcome, every task ended exactly once (what still runs is cancelled with the
// run), each drone's figures, run_end.
void Runtime::finish_run(const Task& main) {
  record_.completed = main.status == TaskStatus::done;
  if (main.status == TaskStatus::failed && record_.failure.empty())
    record_.failure = "the app's main failed";
  record_.completion_time_s = record_.completed ? main.ended_s : now_;
  record_.end_s = now_;
  for (Task& t : tasks_)
    if (t.status == TaskStatus::running) finish_task(t, TaskStatus::cancelled, "run_ended");
  destroy_frames();
  for (Drone& d : drones_) {
    leave_spot(d);
    integrate(d, now_);
    set_mode(d, d.mode, now_);
    if (!d.span_mode.empty() && now_ > d.span_start)
      d.record.spans.push_back({round6(d.span_start), round6(now_), d.span_mode});
    d.record.distance_m = d.distance_m;
    d.record.flight_s = d.flight_s;
    d.record.idle_s = d.idle_s;
    d.record.energy_wh = d.energy_j / 3600.0;
    d.record.final_soc = d.soc;
    record_.drones.push_back(d.record);
  }
  log(json{{"ev", "run_end"},
           {"completed", record_.completed},
           {"completion_time_s", round6(record_.completion_time_s)}});
}

// dtg.json: task nodes, sync nodes, edges (docs/swath-fleet.md).
std::string Runtime::dtg_json() const {
  auto id = [](const DtgRef& r) { return (r.sync ? "s" : "t") + std::to_string(r.number); };
  json nodes = json::array();
  for (const Task& t : tasks_) {
    json n{{"id", "t" + std::to_string(t.id)},
           {"type", "task"},
           {"kind", t.kind},
           {"created_s", round6(t.created_s)},
           {"ended_s", round6(t.ended_s)},
           {"status", t.status == TaskStatus::done        ? "done"
                      : t.status == TaskStatus::cancelled ? "cancelled"
                                                          : "failed"},
           {"actions", t.actions.size()},
           {"drones", t.drones_used},
           {"ended_seq", t.ended_seq},
           {"same_drone", t.flags.same_drone},
           {"interruptible", t.flags.interruptible}};
    json script = json::array();
    for (const ScriptStep& st : t.script) {
      static const char* const kActs[] = {"fly_to", "sense", "hover", "custom", "fly_sensing"};
      json step;
      switch (st.op) {
        case ScriptStep::act:
          step["act"] = kActs[st.act_type];
          if (st.act_type == 0 || st.act_type == 4) step["to"] = {st.to.x, st.to.y, st.to.z};
          if (st.act_type == 1 || st.act_type == 4) step["sensor"] = st.name;
          if (st.act_type == 3) step["name"] = st.name;
          if (st.act_type == 2 || st.act_type == 3) step["s"] = st.s;
          if (st.act_type == 4) step["period_s"] = st.s;
          break;
        case ScriptStep::await: {
          json refs = json::array();
          for (int r : st.refs)
            refs.push_back(r >= 0 ? "t" + std::to_string(r) : "a" + std::to_string(-r - 1));
          step["await"] = std::move(refs);
          if (st.any) step["any"] = true;
          break;
        }
        case ScriptStep::spawn:
          step["spawn"] = "t" + std::to_string(st.refs.front());
          break;
        case ScriptStep::cancel:
          step["cancel"] = "t" + std::to_string(st.refs.front());
          break;
        case ScriptStep::delay:
          step["delay_s"] = st.s;
          break;
      }
      step["seq"] = st.seq;
      script.push_back(std::move(step));
    }
    n["script"] = std::move(script);
    if (t.first_loc)
      n["first_loc"] = {round6(t.first_loc->x), round6(t.first_loc->y), round6(t.first_loc->z)};
    nodes.push_back(std::move(n));
  }
  for (std::size_t k = 0; k < syncs_.size(); ++k)
    nodes.push_back(json{{"id", "s" + std::to_string(k)},
                         {"type", "sync"},
                         {"waiter", syncs_[k].waiter},
                         {"created_s", round6(syncs_[k].created_s)},
                         {"awaited", syncs_[k].awaited}});
  json edges = json::array();
  for (const Edge& e : edges_)
    edges.push_back(json{{"from", id(e.from)},
                         {"to", id(e.to)},
                         {"type", e.type == DtgEdgeType::spawn  ? "spawn"
                                  : e.type == DtgEdgeType::sync ? "sync"
                                                                : "cancel"}});
  return json{{"app", settings_.app_name},
              {"seed", settings_.seed},
              {"nodes", nodes},
              {"edges", edges}}
             .dump(1) +
         "\n";
}

// The DTG as it stands now, as a value (the forecaster's input): tasks still running are its
// frontier. Node indices as parse_dtg makes them: tasks by id, then sync nodes by number.
Dtg Runtime::live_dtg() const {
  Dtg g;
  g.app = settings_.app_name;
  g.nodes.reserve(tasks_.size() + syncs_.size());
  for (const Task& t : tasks_) {
    DtgNode n;
    n.number = t.id;
    n.kind = t.kind;
    n.created_s = round6(t.created_s);
    if (t.status != TaskStatus::running) {
      n.ended_s = round6(t.ended_s);
      n.status = t.status == TaskStatus::done        ? DtgStatus::done
                 : t.status == TaskStatus::cancelled ? DtgStatus::cancelled
                                                     : DtgStatus::failed;
    }
    if (t.first_loc)
      n.first_loc_m = Vec3{round6(t.first_loc->x), round6(t.first_loc->y), round6(t.first_loc->z)};
    g.nodes.push_back(std::move(n));
  }
  for (std::size_t k = 0; k < syncs_.size(); ++k) {
    DtgNode n;
    n.type = DtgNodeType::sync;
    n.number = static_cast<int>(k);
    n.waiter = syncs_[k].waiter;
    n.kind = tasks_[static_cast<std::size_t>(n.waiter)].kind;
    n.created_s = round6(syncs_[k].created_s);
    g.nodes.push_back(std::move(n));
  }
  const int tasks = static_cast<int>(tasks_.size());
  auto index = [&](const DtgRef& r) { return r.sync ? tasks + r.number : r.number; };
  for (const Edge& e : edges_) g.edges.push_back({index(e.from), index(e.to), e.type});
  return g;
}

// The tick loop (docs/swath-fleet.md): resume what is ready, schedule when inputs changed, jump to
// the next thing that happens, let it happen.
RunRecord Runtime::run() {
  Task& main = start_main();
  std::int64_t tick_index = 0;
  for (;;) {
    resume_ready();
    destroy_frames();
    if (main.status != TaskStatus::running) break;
    fail_unserved();
    if (!ready_.empty()) continue;
    if (settings_.relief) relieve();
    if (changed_) {
      changed_ = false;
      schedule();
    }
    const double next = next_happening();
    if (!std::isfinite(next)) {
      record_.failure = "the app waits for something that cannot happen (no drone can serve it)";
      break;
    }
    if (!advance_clock(next, tick_index)) break;
    step_drones_to_now();
    if (ext_) poll_backend();
    deliver_due();
  }
  if (ext_) ext_->end_run();
  finish_run(main);
  record_.dtg_json = dtg_json();
  return std::move(record_);
}

}  // namespace

RunRecord run_app(const App& app, const World& world, const std::vector<DroneSpec>& drones,
                  const RunSettings& settings) {
  if (drones.empty()) throw base::InputError("the fleet has no drones");
  Runtime rt(app, world, drones, settings);
  return rt.run();
}

}  // namespace swath::fleet
