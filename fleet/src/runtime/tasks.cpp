// Tasks and coroutines: spawn, actions and their futures, awaits (each a step of the task's
// script), wake-ups, ends.

#include <algorithm>
#include <chrono>
#include <exception>
#include <stdexcept>
#include <string>

#include "runtime/runtime_impl.hpp"
#include "swath/base/number_text.hpp"

namespace swath::fleet::rt {

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
  count_created_at_instant();
  log(json{{"ev", "task_created"},
           {"task", t.id},
           {"kind", t.kind},
           {"parent", parent},
           {"same_drone", t.flags.same_drone},
           {"interruptible", t.flags.interruptible}});
  t.root = t.start(*t.ctx);
  ready_.push_back({t.id, t.root, nullptr});
  return t.id;
}

void Runtime::count_created_at_instant() {
  if (now_ != instant_s_) {
    instant_s_ = now_;
    created_at_instant_ = 0;
  }
  if (++created_at_instant_ > kMaxTasksPerInstant) instant_runaway_ = true;
}

namespace {
/// A metric's bytes in summary.json: its name escaped (a control character as \u00XX) and room
/// for the punctuation and the value.
std::size_t metric_json_bytes(const std::string& name) {
  std::size_t bytes = 32;
  for (const char c : name)
    bytes += static_cast<unsigned char>(c) < 0x20 ? 6 : (c == '"' || c == '\\') ? 2 : 1;
  return bytes;
}

/// The start of a metric's name for a message: control characters as \xNN (a NUL would end it).
std::string name_for_message(const std::string& name) {
  std::string shown;
  for (std::size_t i = 0; i < name.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    constexpr char hex[] = "0123456789abcdef";
    shown += c < 0x20 ? std::string{'\\', 'x', hex[c >> 4], hex[c & 15]} : std::string(1, name[i]);
  }
  return shown + (name.size() > 40 ? "..." : "");
}
}  // namespace

void Runtime::metric(const std::string& name, double value) {
  if (!record_.metrics.contains(name)) {
    const std::size_t bytes = metric_json_bytes(name);
    if (record_.metrics.size() >= kMaxMetrics || metric_bytes_ + bytes > kMaxMetricBytes)
      throw std::length_error(
          "metric \"" + name_for_message(name) + "\": more than " + std::to_string(kMaxMetrics) +
          " metric names or 2 MiB of them in "
          "summary.json, swath-fleet's limit for one run (so that collect, render and replay "
          "read it)");
    metric_bytes_ += bytes;
  }
  record_.metrics[name] = value;
}

// A fly_to inside the envelope or an error to the app, never flown: a height of 0 is the drone's
// own layer, else in (0, ceiling] and under the fence's height; the place inside the fence.
void Runtime::check_target(const Vec3& to) const {
  const auto at = [&] {
    return "fly_to (" + base::shortest_text(to.x) + ", " + base::shortest_text(to.y) + ", " +
           base::shortest_text(to.z) + ") m is ";
  };
  if (!(to.z >= 0)) throw ActionFailed(at() + "below home (heights are 0 < h ≤ the ceiling)");
  const std::string why = settings_.envelope.refusal(to);
  if (!why.empty()) throw ActionFailed(at() + why);
  check_reachable(to, at());
}

// A target is flown only by a drone with a way home from it inside the fence
// (Utility::pair_feasible); with no such drone the task fails now, saying why, rather than waiting
// for a drone that never comes. Round the fence when the runtime routes (LocalEnvelope::route),
// else straight: a drone must be able to turn straight home from anywhere on its legs.
void Runtime::check_reachable(const Vec3& to, const std::string& at) const {
  if (!settings_.envelope.fenced()) return;
  if (settings_.envelope.routes()) {
    for (const Drone& d : drones_)
      if (!settings_.envelope.route(d.spec.home_m, to).empty()) return;
    throw ActionFailed(at + "out of reach: no way to it inside the fence from any drone's home");
  }
  std::string why;
  for (const Drone& d : drones_) {
    why = settings_.envelope.leg_refusal(d.spec.home_m, to);
    if (why.empty()) return;
  }
  throw ActionFailed(at + "out of reach: the straight leg to it from every drone's home passes " +
                     why + " (legs are flown straight, not routed round the fence)");
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
  // The script keeps the call exactly (full precision), so a replay flies the same targets; a
  // call refused here is kept too (raised), so that a replay refuses it where the app saw it.
  ScriptStep step{ScriptStep::act, type >= 0 && type <= 4 ? type : 3, to, name, duration_s};
  try {
    if (type == 4) {  // fly_sensing: a fly_to that reads `name` every duration_s on the way
      world_.sense_time_s(name);  // an unknown sensor fails here, at the call
      if (!(duration_s > 0)) throw ActionFailed("fly_sensing needs a period > 0 s");
      a.sample_sensor = name;
      a.sample_period_s = duration_s;
    }
    if (a.type == ActionType::sense) a.duration_s = world_.sense_time_s(name);
    if (a.type == ActionType::fly_to) check_target(to);
  } catch (...) {
    step.raised = true;
    step.seq = script_seq_++;
    t.script.push_back(std::move(step));
    t.last_armed.reset();
    throw;
  }
  if (a.type == ActionType::fly_to) {
    t.location = to;
    t.has_location = true;
    if (!t.first_loc) t.first_loc = to;
  }
  t.actions.push_back(std::move(a));
  t.sync_node = -1;
  step.seq = script_seq_++;
  t.script.push_back(std::move(step));
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

// An await that throws is a step of the script even when it did not suspend (the awaited task
// had already failed): the app saw the error there, and a replay must see it at the same point.
void Runtime::raised(int task, detail::StateBase& awaited, bool suspended) {
  if (task < 0) return;
  Task& t = tasks_.at(static_cast<std::size_t>(task));
  std::optional<int> ref;
  if (awaited.task >= 0) ref = awaited.task;
  for (std::size_t a = 0; !ref && a < t.actions.size(); ++a)
    if (t.actions[a].result.get() == &awaited) ref = -static_cast<int>(a) - 1;
  if (!ref) return;
  if (suspended && !t.script.empty() && t.script.back().op == ScriptStep::await &&
      std::find(t.script.back().refs.begin(), t.script.back().refs.end(), *ref) !=
          t.script.back().refs.end()) {
    t.script.back().raised = true;  // the step its suspension recorded
    return;
  }
  t.script.push_back({ScriptStep::await, 0, {}, {}, 0, {*ref}, false, script_seq_++, true});
  t.last_armed.reset();
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
  auto began = std::chrono::steady_clock::now();
  while (!ready_.empty()) {
    // An app whose tasks wake each other without end never empties ready_ nor lets the clock
    // move: a waiting abort goes first (loop() takes it next), and max_time_s bounds the wall
    // time spent here too (loop() then ends the run as not completed).
    if (abort_waiting() || instant_runaway_) return;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count() >
        settings_.max_time_s) {
      wall_stalled_ = true;
      return;
    }
    const detail::Waiter w = ready_.front();
    ready_.pop_front();
    Task& t = tasks_.at(static_cast<std::size_t>(w.task));
    if (t.status != TaskStatus::running || t.frame_gone) continue;
    current_ = t.id;
    const auto resumed = std::chrono::steady_clock::now();
    w.handle.resume();
    current_ = -1;
    // One task that kept its turn past the bound (an app's busy loop, stopped and failed with its
    // own reason) is not the tasks waking each other: the bound starts again after it.
    if (const auto after = std::chrono::steady_clock::now();
        std::chrono::duration<double>(after - resumed).count() > settings_.max_time_s)
      began = after;
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
      d.task = -1;
      stop(d, now_);
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

}  // namespace swath::fleet::rt
