#include "swath/fleet/trace_replay.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>

#include "swath/base/input_error.hpp"

namespace swath::fleet {

namespace {

// What every replayed task shares: the graph and the handles of the tasks spawned so far (by
// node index; an unset handle: not spawned in this run).
struct TraceRun {
  Dtg dtg;
  std::vector<TaskHandle<void>> handles;
};

// A compute step's function (a pointer, not a lambda: the coroutine frame of compute<F> keeps F,
// and a lambda type of this unnamed namespace would give it no linkage).
int no_result() {
  return 0;
}

Future<Reading> replay_action(Ctx& c, const DtgStep& s) {
  switch (s.action) {
    case 0:
      return c.fly_to(s.to_m);
    case 1:
      return c.sense(s.name);
    case 2:
      return c.hover(s.seconds);
    case 3:
      return c.custom(s.name, s.seconds);
    default:
      return c.fly_sensing(s.to_m, s.name, s.seconds);
  }
}

// One recorded task's program, step by step. Awaited tasks that failed or were cancelled are
// passed over (the app went on) unless the recorded await threw and ended the task there; a
// failure of its own action ends this task as failed, as an app's body would. A step the app saw
// throw (`raised`: a call refused at the fence or out of reach, an await of a task that had
// failed) throws here too when the replay's does: at the last step of a task that failed, the
// error ends it (with this run's reason, the recorded one when nothing else changed), elsewhere
// the app caught it and went on.
Co<void> replay_task(Ctx& c, std::shared_ptr<TraceRun> run, int node) {
  const DtgNode& n = run->dtg.nodes[static_cast<std::size_t>(node)];
  std::vector<Future<Reading>> actions;     // by the recorded action's index ("aN")
  std::vector<Future<Reading>> unrecorded;  // calls refused then, queued in this run
  // The tasks it spawned, by their recorded end: an await of one already done left no step, so
  // before each step every child that had ended before it in the recording is awaited here (at
  // once when it is done here too, as then).
  std::vector<std::pair<std::int64_t, int>> children;
  for (const DtgStep& s : n.script)
    if (s.op == DtgStep::Op::spawn) {
      const std::int64_t end = run->dtg.nodes[static_cast<std::size_t>(s.tasks.front())].ended_seq;
      if (end >= 0) children.push_back({end, s.tasks.front()});
    }
  std::sort(children.begin(), children.end());
  std::size_t next_child = 0;
  const auto step_count = n.script.size();
  for (std::size_t i = 0; i <= step_count; ++i) {
    const std::int64_t before = i < step_count ? n.script[i].seq : n.ended_seq;
    while (next_child < children.size() && before >= 0 && children[next_child].first < before) {
      const TaskHandle<void> h =
          run->handles[static_cast<std::size_t>(children[next_child++].second)];
      // Done already: nothing to wait for (an await of it by the app is a step of its own).
      if (h.id() < 0 || h.ready()) continue;
      try {
        co_await h;
      } catch (const ActionFailed&) {
      } catch (const TaskCancelled&) {
      }
    }
    if (i == step_count) break;
    const DtgStep& s = n.script[i];
    // The recorded error ended the task here: this run's, if it has one, ends it too.
    const bool ends_here = s.raised && i + 1 == step_count && n.status == DtgStatus::failed;
    switch (s.op) {
      case DtgStep::Op::act:
        if (!s.raised) {
          actions.push_back(replay_action(c, s));
          break;
        }
        try {
          unrecorded.push_back(replay_action(c, s));
        } catch (...) {
          if (ends_here) throw;
        }
        break;
      case DtgStep::Op::spawn: {
        const int k = s.tasks.front();
        const DtgNode& m = run->dtg.nodes[static_cast<std::size_t>(k)];
        const Kind kind{m.kind};  // named first: GCC PR 100611 (README)
        const Flags flags{.same_drone = m.same_drone, .interruptible = m.interruptible};
        run->handles[static_cast<std::size_t>(k)] = c.spawn(kind, flags, replay_task, run, k);
        break;
      }
      case DtgStep::Op::cancel: {
        const TaskHandle<void>& h = run->handles[static_cast<std::size_t>(s.tasks.front())];
        if (h.id() >= 0) c.cancel(h);
        break;
      }
      case DtgStep::Op::delay:
        co_await c.compute(&no_result, s.seconds);
        break;
      case DtgStep::Op::await: {
        if (s.any) {
          detail::AnyAwaiter a;
          for (int k : s.tasks) {
            const TaskHandle<void>& h = run->handles[static_cast<std::size_t>(k)];
            if (h.id() >= 0) a.states.push_back(h.state()), a.core = h.core();
          }
          for (int k : s.actions) {
            const Future<Reading>& f = actions[static_cast<std::size_t>(k)];
            a.states.push_back(f.state());
          }
          if (a.core && !a.states.empty()) co_await a;
          break;
        }
        for (int k : s.actions) co_await actions[static_cast<std::size_t>(k)];
        for (int k : s.tasks) {
          const TaskHandle<void> h = run->handles[static_cast<std::size_t>(k)];
          if (h.id() < 0) continue;
          try {
            co_await h;
          } catch (const ActionFailed&) {
            if (ends_here) throw;
          } catch (const TaskCancelled&) {
            if (ends_here) throw;
          }
        }
        break;
      }
    }
  }
  // The recorded task ended after its last step: a body returns once its results are in.
  for (const Future<Reading>& f : actions) co_await f;
  for (const Future<Reading>& f : unrecorded) co_await f;
}

}  // namespace

App make_trace_app(const Dtg& dtg) {
  auto run = std::make_shared<TraceRun>();
  run->dtg = dtg;
  run->handles.resize(dtg.nodes.size());
  if (dtg.nodes.empty() || dtg.nodes.front().type != DtgNodeType::task ||
      dtg.nodes.front().number != 0)
    throw base::InputError("the task graph has no main task (t0) to replay");
  std::vector<char> spawned(dtg.nodes.size(), 0);
  for (const DtgNode& n : dtg.nodes) {
    if (n.type != DtgNodeType::task) continue;
    if (!n.has_script)
      throw base::InputError("task t" + std::to_string(n.number) +
                             " has no script: the dtg.json was written by a swath-fleet that "
                             "did not record tasks' programs; run the app again");
    // Each task spawned once at most, main never: a script cannot make the replay spawn forever.
    for (const DtgStep& s : n.script) {
      if (s.op != DtgStep::Op::spawn) continue;
      const auto k = static_cast<std::size_t>(s.tasks.front());
      if (k == 0 || spawned[k]++)
        throw base::InputError("task t" + std::to_string(n.number) + "'s script spawns t" +
                               std::to_string(dtg.nodes[k].number) +
                               (k == 0 ? ", the main task" : ", spawned before"));
    }
  }
  App app;
  app.name = dtg.app;
  app.description = "trace replay of a recorded " + dtg.app + " run";
  app.main = [run](Ctx& c) { return replay_task(c, run, 0); };
  return app;
}

std::string schedule_dependence(const std::string& app) {
  if (app == "wifi")
    return "the wifi app (case 2) cancels the cells its Gaussian process already knows from the "
           "readings taken so far, so which cells are cancelled depends on the order the "
           "schedule senses them; a trace can only repeat the recorded cancels (world replay, "
           "swath-fleet run or tune, re-runs the app instead)";
  return "";
}

}  // namespace swath::fleet
