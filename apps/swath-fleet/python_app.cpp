// Fleet apps in Python (python_app.hpp). Each Python task runs on a thread of its own, mapped onto
// a runtime task whose coroutine hands that thread a baton and waits until the Python code blocks
// on a future (the coroutine then awaits that future for it) or returns. Exactly one side runs
// at a time, and every hand-over happens at a point the runtime chose, so a run's events do not
// depend on the threads' timing: the runtime stays single-threaded and deterministic.

#include "python_app.hpp"

#include <pybind11/embed.h>
#include <pybind11/stl.h>

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <variant>
#include <vector>

#include "../../fleet/apps/src/gaussian_process.hpp"  // the wifi app's, for wifi.py's parity
#include "fleet_inputs.hpp"
#include "fleet_main.hpp"
#include "python_baton.hpp"
#include "run_control.hpp"
#include "swath/base/number_text.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/worlds/worlds.hpp"

namespace py = pybind11;

namespace {
/// The longest a hover or a custom action, and a reading of the app's own sensors, may take: as a
/// static world's tables allow (worlds.cpp: hover and custom up to a day, a sensor an hour).
constexpr double kMaxActionS = 86400;
constexpr double kMaxSenseS = 3600;
constexpr std::size_t kMaxNameBytes = 256;
constexpr std::size_t kMaxMessageBytes = 1000;
constexpr int kMaxLiveTasks = 2000;
/// How long a task stopped by a signal or --max-time may go on ignoring TaskKilled (a bare
/// except) before the runtime abandons its thread: stopping must not depend on the app.
constexpr double kStopGraceS = 2;
}  // namespace

namespace swath::apps {
namespace {

using fleet::Co;
using fleet::Ctx;
using fleet::Reading;

/// What a Python task's future refers to: an action's reading or a task's end.
using Awaited = std::variant<fleet::Future<Reading>, fleet::TaskHandle<void>>;

/// How a Python task handed the baton back.
enum class Yield { awaiting, returned, raised, action_failed, cancelled };

class Host;

/// One Python task: its thread and what it last asked of the runtime. Owned by the Host for the
/// whole process, so Python objects are only released with the interpreter's lock held.
struct PyTask {
  int slot = 0;
  bool is_main = false;
  Ctx* ctx = nullptr;
  py::object fn, args, result;  // touched only with the GIL held
  std::thread thread;
  std::condition_variable turn_cv;  // the Baton wakes this task's thread through it
  unsigned long python_thread = 0;  // PyThread_get_thread_ident() of the thread
  bool started = false;
  std::atomic<bool> finished = false, killed = false;
  bool abandoned = false;  // runtime side: the thread ignored TaskKilled past kStopGraceS
  /// Why the runtime stopped the task while it kept its turn (a signal, the wall-clock bound);
  /// set before the exception is raised in its thread, read there (its task_failed reason).
  std::string stopped_why;
  std::string spawned_at;  // "app.py line N" of its newTask call
  std::chrono::steady_clock::time_point stopped_at, first_stopped_at;
  Yield yield = Yield::returned;
  Awaited awaited;
  std::string error;        // the sentence of a Python exception, or an ActionFailed reason
  bool propagated = false;  // the error is another task's, already reported
};

/// A Python exception that escaped a task (the runtime's task_failed reason is its sentence).
struct PythonError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

thread_local PyTask* current_task = nullptr;

struct ErrorTypes {
  py::object action_failed, task_cancelled, task_failed, task_killed;
};
ErrorTypes& error_types() {
  static ErrorTypes types;
  return types;
}

class Host {
 public:
  std::string path;  // the app file as given on the command line
  py::object app_fn;
  Baton baton;
  double max_wall_s = 3600;  // --max-time: also the wall time a task may keep its turn

  PyTask& new_task() {
    tasks_.push_back(std::make_unique<PyTask>());
    tasks_.back()->slot = static_cast<int>(tasks_.size()) - 1;
    return *tasks_.back();
  }
  PyTask& task(int slot) { return *tasks_.at(static_cast<std::size_t>(slot)); }

  /// Runtime side: runs the task until it blocks or ends (its thread starts on the first turn).
  void step(PyTask& t) {
    if (!t.started) {
      // A thread per task: past kMaxLiveTasks the task fails instead of starting (an app that
      // spawns without end would otherwise take the machine's threads).
      const std::string too_many = t.spawned_at + ": bee.newTask: more than " +
                                   std::to_string(kMaxLiveTasks) +
                                   " tasks alive at once, swath-fleet's limit for a Python app "
                                   "(each runs on a thread of its own)";
      if (threads_alive_ >= kMaxLiveTasks) return refuse_start(t, too_many);
      try {
        t.thread = std::thread([this, &t] { thread_main(t); });
      } catch (const std::system_error&) {  // the system's own limit came first
        return refuse_start(t, too_many);
      }
      t.started = true;
      ++threads_alive_;
    }
    run_turn(t);
    join_if_finished(t);
  }
  /// Runtime side: a task whose frame is gone (cancelled, or the run over) unwinds its Python
  /// code: every wait and action raises TaskKilled until the function returns.
  void kill(PyTask& t) {
    if (!t.started || t.finished || t.abandoned) return;
    t.killed = true;
    run_turn(t);
    join_if_finished(t);
  }
  /// After the runs, GIL released: ends every thread still waiting.
  void kill_all() {
    for (auto& t : tasks_) kill(*t);
    for (auto& t : tasks_)
      if (t->thread.joinable() && !t->abandoned) t->thread.join();
  }
  /// A task was abandoned: its thread may run on, so the process must end without joining it
  /// or finalising Python under it.
  bool any_abandoned() const {
    return std::any_of(tasks_.begin(), tasks_.end(), [](const auto& t) { return t->abandoned; });
  }
  /// With the GIL held: drops the Python objects.
  void clear() {
    tasks_.clear();
    app_fn = py::object();
  }

  /// The sentence for a Python exception: the app file, the line in it, the type and message.
  std::string sentence(py::error_already_set& e) const;
  /// Where in the app file a Python exception was raised: "app.py line 9" (or the file alone).
  std::string where(py::error_already_set& e) const;

 private:
  void thread_main(PyTask& t);
  void run_turn(PyTask& t);
  /// A task that cannot start fails at once with `why`.
  static void refuse_start(PyTask& t, const std::string& why) {
    t.yield = Yield::raised;
    t.error = why;
  }
  /// A thread whose function has returned is joined at once: an ended thread's stack stays
  /// mapped until it is joined, and an app of many short tasks would run out of them.
  static void join_if_finished(PyTask& t) {
    if (t.finished && t.thread.joinable()) t.thread.join();
  }
  std::atomic<int> threads_alive_{0};
  bool stop_if_due(PyTask& t, std::chrono::steady_clock::time_point turn_began);
  void abandon(PyTask& t);
  std::deque<std::unique_ptr<PyTask>> tasks_;
};

Host* host = nullptr;
std::string one_line(const std::string& message);

// The runtime waits for a task's turn to end; a task that keeps it (a loop that never blocks)
// is stopped when a signal asks for the abort or after max_wall_s, so neither hangs the run.
void Host::run_turn(PyTask& t) {
  const auto began = std::chrono::steady_clock::now();
  baton.run(t.slot, t.turn_cv, [&] { return stop_if_due(t, began); });
  if (t.abandoned) abandon(t);
}

// The turn is the runtime's again (Baton::run): the task fails with why it was stopped, and its
// thread, which may be anywhere in Python or C code, is never waited for again.
void Host::abandon(PyTask& t) {
  t.killed = true;  // any call it still makes into swath_fleet raises TaskKilled
  t.yield = Yield::raised;
  t.error = path + ": " + t.stopped_why + "; abandoned " + base::shortest_text(kStopGraceS) +
            " s later (it went on, catching TaskKilled or inside a C call)";
}

// Raises TaskKilled in the task's thread (at its next Python line); again each second, as an app
// may catch the first in a bare except. Its task then fails with `stopped_why`. True (abandon
// it) once it has kept its turn kStopGraceS past the first TaskKilled.
bool Host::stop_if_due(PyTask& t, std::chrono::steady_clock::time_point turn_began) {
  const auto now = std::chrono::steady_clock::now();
  std::string why;
  if (const int s = noted_signal(); s != 0)
    why = std::string("stopped by ") + (s == SIGINT ? "SIGINT" : "SIGTERM") +
          " while it kept its turn";
  else if (std::chrono::duration<double>(now - turn_began).count() > max_wall_s)
    why = "kept its turn (never waited on a future) for more than --max-time, " +
          base::shortest_text(max_wall_s) + " s of wall-clock time";
  if (why.empty()) return false;
  if (!t.stopped_why.empty() &&
      std::chrono::duration<double>(now - t.first_stopped_at).count() > kStopGraceS)
    return t.abandoned = true;
  if (t.python_thread == 0) return false;
  if (!t.stopped_why.empty() && now - t.stopped_at < std::chrono::seconds(1)) return false;
  py::gil_scoped_acquire gil;  // the task's thread lets it go at its switch interval
  if (t.finished) return false;
  if (t.stopped_why.empty()) t.first_stopped_at = now;
  t.stopped_why = why;
  t.stopped_at = now;
  PyThreadState_SetAsyncExc(t.python_thread, error_types().task_killed.ptr());
  return false;
}

// The message is cut to kMaxMessageBytes (at a character's start): it is a task_failed reason,
// and a line of events.jsonl holds at most 1 MiB.
std::string Host::sentence(py::error_already_set& e) const {
  const std::string type = py::str(e.type().attr("__name__"));
  std::string message = one_line(py::str(e.value()));
  if (message.size() > kMaxMessageBytes) {
    std::size_t cut = kMaxMessageBytes;
    while (cut > 0 && (static_cast<unsigned char>(message[cut]) & 0xC0) == 0x80) --cut;
    message = message.substr(0, cut) + "... (" + std::to_string(message.size()) + " bytes)";
  }
  return where(e) + ": " + type + (message.empty() ? "" : ": " + message);
}

// A reason is one line of events.jsonl and the same for the same seed: pybind11's messages span
// lines and name objects by their memory address ("<swath_fleet.Bee object at 0x7f...>").
std::string one_line(const std::string& message) {
  static const std::regex address(" at 0x[0-9a-fA-F]+>"), breaks(R"(\s*[\r\n]\s*)");
  std::string s = std::regex_replace(message, address, ">");
  s = std::regex_replace(s, breaks, " ");
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  return s;
}

std::string Host::where(py::error_already_set& e) const {
  std::string where = path;
  try {
    const py::list frames =
        e.trace() ? py::list(py::module_::import("traceback").attr("extract_tb")(e.trace()))
                  : py::list();
    const std::string file = std::filesystem::absolute(path).lexically_normal().string();
    for (const py::handle f : frames) {
      const std::string name = py::str(f.attr("filename"));
      if (name == path || name == file)
        where = path + " line " + py::str(f.attr("lineno")).cast<std::string>();
    }
  } catch (const std::exception&) {
    // no traceback to read: the file alone
  }
  // A file Python cannot decode has no line (lineno None): the file alone.
  if (e.matches(PyExc_SyntaxError) && py::hasattr(e.value(), "lineno") &&
      !e.value().attr("lineno").is_none())
    where = path + " line " + py::str(e.value().attr("lineno")).cast<std::string>();
  return where;
}

void Host::thread_main(PyTask& t) {
  baton.wait_turn(t.slot, t.turn_cv);
  Yield yield = Yield::returned;
  std::string error;
  bool propagated = false;
  {
    py::gil_scoped_acquire gil;
    current_task = &t;
    t.python_thread = PyThread_get_thread_ident();
    try {
      if (!t.killed) {
        py::object bee =
            py::module_::import("swath_fleet").attr("Bee")(py::capsule(&t, "swath_fleet.task"));
        t.result = t.is_main ? app_fn(bee) : t.fn(bee, *py::tuple(t.args));
      }
    } catch (py::error_already_set& e) {
      const ErrorTypes& types = error_types();
      if (t.killed) {
        yield = Yield::returned;
      } else if (!t.stopped_why.empty()) {
        yield = Yield::raised;
        error = where(e) + ": " + t.stopped_why;
      } else if (e.matches(types.action_failed)) {
        yield = Yield::action_failed;
        error = one_line(py::str(e.value()));
      } else if (e.matches(types.task_cancelled)) {
        yield = Yield::cancelled;
      } else {
        yield = Yield::raised;
        propagated = e.matches(types.task_failed);
        // A task_failed exception carries the sentence of the task it came from.
        error = propagated ? py::str(e.value()).cast<std::string>() : sentence(e);
      }
    }
    current_task = nullptr;
  }
  --threads_alive_;
  baton.finish(t.slot, [&] {
    t.yield = yield;
    t.error = error;
    t.propagated = propagated;
    t.finished = true;
  });
  t.finished = true;
}

/// Ends a task's Python thread when its frame is destroyed with the thread still waiting.
struct KillGuard {
  PyTask* t;
  ~KillGuard() { host->kill(*t); }
};

/// The runtime task of a Python task: runs it, awaiting what it awaits.
Co<void> run_task(Ctx& ctx, int slot) {
  PyTask& t = host->task(slot);
  t.ctx = &ctx;
  KillGuard guard{&t};
  for (;;) {
    host->step(t);
    if (t.yield != Yield::awaiting) break;
    const Awaited awaited = t.awaited;
    try {
      if (const auto* f = std::get_if<fleet::Future<Reading>>(&awaited))
        co_await *f;
      else
        co_await std::get<fleet::TaskHandle<void>>(awaited);
    } catch (const std::exception&) {
      // The Python side reads the error from the future's state.
    }
  }
  if (t.yield == Yield::raised) {
    if (!t.propagated) std::cerr << "swath-fleet: " << t.error << "\n";
    throw PythonError(t.error);
  }
  if (t.yield == Yield::action_failed) throw fleet::ActionFailed(t.error);
  if (t.yield == Yield::cancelled) throw fleet::TaskCancelled();
}

// ---- the Python side: swath_fleet.Bee, Future, Reading ---------------------------------------

[[noreturn]] void raise(const py::object& type, const std::string& message) {
  PyErr_SetString(type.ptr(), message.c_str());
  throw py::error_already_set();
}

/// The calling task, which must be the bee's own and alive.
PyTask& acting(PyTask* t) {
  if (current_task != t)
    raise(py::module_::import("builtins").attr("RuntimeError"),
          "a bee is used only by the task it was given to");
  if (t->killed) raise(error_types().task_killed, "the task's run is over");
  return *t;
}

struct PyFuture {
  Awaited awaited;
  PyTask* task = nullptr;  // the task's record, for a task's future

  bool ready() const {
    return std::visit([](const auto& a) { return a.ready(); }, awaited);
  }
  std::exception_ptr error() const {
    return std::visit([](const auto& a) { return a.state()->error; }, awaited);
  }

  /// Blocks the calling task until the action or task is done (BeeCluster's `.value`).
  py::object value() {
    PyTask* me = current_task;
    if (me == nullptr)
      raise(py::module_::import("builtins").attr("RuntimeError"),
            "Future.value is read inside a task");
    if (me->killed) raise(error_types().task_killed, "the task's run is over");
    if (!ready()) {
      {
        py::gil_scoped_release nogil;
        host->baton.yield(me->slot, me->turn_cv, [&] {
          me->awaited = awaited;
          me->yield = Yield::awaiting;
        });
      }
      if (me->killed) raise(error_types().task_killed, "the task's run is over");
    }
    if (const std::exception_ptr e = error()) {
      try {
        std::rethrow_exception(e);
      } catch (const fleet::ActionFailed& f) {
        raise(error_types().action_failed, f.reason);
      } catch (const fleet::TaskCancelled&) {
        raise(error_types().task_cancelled, "task cancelled");
      } catch (const std::exception& x) {
        raise(error_types().task_failed, x.what());
      }
    }
    if (const auto* f = std::get_if<fleet::Future<Reading>>(&awaited))
      return py::cast(*f->state()->value);
    return task->result ? task->result : py::none();
  }
};

// The arguments of the app's calls, each checked with a sentence naming the call and the
// argument (the task then fails on the app's line), not pybind11's "Unable to cast".

std::string type_name(const py::handle h) {
  return py::str(h.get_type().attr("__name__"));
}

/// A real number as Python and NumPy give them (int, float, numpy.float32, numpy.int64, ...): a
/// number that converts to float, not a bool, a complex or a string.
bool is_real_number(const py::handle h) {
  return PyNumber_Check(h.ptr()) && !py::isinstance<py::bool_>(h) && !PyComplex_Check(h.ptr()) &&
         !py::isinstance<py::str>(h) && !py::isinstance<py::bytes>(h);
}

double number_arg(const py::handle h, const std::string& call, const std::string& name) {
  if (!is_real_number(h))
    throw py::type_error(call + ": " + name + " must be a number, not a " + type_name(h));
  const double v = PyFloat_AsDouble(h.ptr());
  if (v == -1.0 && PyErr_Occurred()) throw py::error_already_set();
  if (!std::isfinite(v))
    throw py::value_error(call + ": " + name + " must be finite, not " + base::shortest_text(v));
  return v;
}

/// A duration: a number of seconds from 0 to kMaxActionS.
double seconds_arg(const py::handle h, const std::string& call, const std::string& name) {
  const double s = number_arg(h, call, name);
  if (s < 0 || s > kMaxActionS)
    throw py::value_error(call + ": " + name + " must be from 0 to " +
                          base::shortest_text(kMaxActionS) + " s, not " + base::shortest_text(s));
  return s;
}

/// A name the log carries (a sensor, a custom action, a task's kind): a string of at most
/// kMaxNameBytes, so that every event stays far below the 1 MiB a line of events.jsonl may hold.
std::string name_arg(const py::handle h, const std::string& call, const std::string& name) {
  if (!py::isinstance<py::str>(h))
    throw py::type_error(call + ": " + name + " must be a string, not a " + type_name(h));
  std::string s = h.cast<std::string>();
  if (s.size() > kMaxNameBytes)
    throw py::value_error(call + ": " + name + " must be at most " + std::to_string(kMaxNameBytes) +
                          " bytes long, not " + std::to_string(s.size()));
  return s;
}

fleet::Vec3 point(const py::tuple& a, std::size_t from) {
  const std::string call = "bee.act(\"fly_to\", x_m, y_m[, z_m])";
  if (a.size() < from + 2 || a.size() > from + 3) throw py::value_error(call);
  return {number_arg(a[from], call, "x_m"), number_arg(a[from + 1], call, "y_m"),
          a.size() == from + 3 ? number_arg(a[from + 2], call, "z_m") : 0.0};
}

PyFuture act_on(Ctx& ctx, const std::string& name, const py::tuple& a) {
  if (name == "fly_to") return {ctx.fly_to(point(a, 0))};
  if (name == "sense") {
    const std::string call = "bee.act(\"sense\", sensor)";
    if (a.size() != 1) throw py::value_error(call);
    return {ctx.sense(name_arg(a[0], call, "sensor"))};
  }
  if (name == "hover") {
    const std::string call = "bee.act(\"hover\", seconds)";
    if (a.size() != 1) throw py::value_error(call);
    return {ctx.hover(seconds_arg(a[0], call, "seconds"))};
  }
  if (name == "custom") {
    const std::string call = "bee.act(\"custom\", name, seconds)";
    if (a.size() != 2) throw py::value_error(call);
    return {ctx.custom(name_arg(a[0], call, "name"), seconds_arg(a[1], call, "seconds"))};
  }
  throw py::value_error("bee.act: unknown action \"" + name + "\" (fly_to, sense, hover, custom)");
}

/// bee.act(name, *args): what the runtime refuses at the call (a fly_to outside the fence, an
/// unknown sensor) raises ActionFailed, as the future of a failed action does.
PyFuture act(PyTask* t, const py::args& a) {
  Ctx& ctx = *acting(t).ctx;
  const std::string call = "bee.act(name, *args)";
  if (a.empty())
    throw py::type_error(call + ": the action's name is missing (fly_to, sense, hover, custom)");
  const std::string name = name_arg(a[0], call, "name");
  try {
    return act_on(ctx, name, py::tuple(a[py::slice(1, static_cast<py::ssize_t>(a.size()), 1)]));
  } catch (const fleet::ActionFailed& e) {
    raise(error_types().action_failed, e.reason);
  }
}

PyFuture new_task(PyTask* t, const py::object& fn, const py::args& a, bool same_drone,
                  bool interruptible, const py::object& kind) {
  Ctx& ctx = *acting(t).ctx;
  if (py::module_::import("inspect").attr("iscoroutinefunction")(fn).cast<bool>())
    throw py::type_error("bee.newTask: fn must be a plain function (def), not an async one");
  PyTask& child = host->new_task();
  PyFrameObject* frame = PyEval_GetFrame();  // the app's line calling newTask
  child.spawned_at =
      host->path + (frame ? " line " + std::to_string(PyFrame_GetLineNumber(frame)) : "");
  child.fn = fn;
  child.args = py::tuple(a);
  const std::string kind_name =
      name_arg(kind.is_none() ? py::str(fn.attr("__name__")) : kind, "bee.newTask", "kind");
  auto h = ctx.spawn(fleet::Kind{kind_name},
                     fleet::Flags{.same_drone = same_drone, .interruptible = interruptible},
                     run_task, child.slot);
  return {h, &child};
}

void cancel_tasks(PyTask* t, const py::iterable& futures) {
  Ctx& ctx = *acting(t).ctx;
  for (const py::handle f : futures) {
    if (!py::isinstance<PyFuture>(f))
      throw py::type_error("bee.cancelTasks: each item must be a task's Future, not a " +
                           type_name(f));
    const PyFuture& fut = f.cast<const PyFuture&>();
    const auto* h = std::get_if<fleet::TaskHandle<void>>(&fut.awaited);
    if (h == nullptr) throw py::value_error("bee.cancelTasks: the future of an action, not a task");
    ctx.cancel(*h);
  }
}

py::tuple xyz(const fleet::Vec3& v) {
  return py::make_tuple(v.x, v.y, v.z);
}

/// A world with the app's own sensors (SENSORS = {name: (time_s, fn(x_m, y_m, t_s) -> values)})
/// beside the file's: read by the runtime, which holds the baton, so the GIL is free to take.
/// "app.py line N" of a Python function's definition (the file alone for a builtin).
std::string definition_of(const py::object& fn) {
  if (!py::hasattr(fn, "__code__")) return host->path;
  return host->path + " line " +
         py::str(fn.attr("__code__").attr("co_firstlineno")).cast<std::string>();
}

/// The app's sensor `fn` called at `at`: its values, or a SensorError naming the file and line.
std::vector<double> read_values(const std::string& sensor, const py::object& fn,
                                const fleet::Vec3& at, double t_s) {
  std::string why;
  try {
    const py::object got = fn(at.x, at.y, t_s);
    const auto type_of = [](const py::handle h) {
      return py::str(h.get_type().attr("__name__")).cast<std::string>();
    };
    if (py::isinstance<py::str>(got) || py::isinstance<py::bytes>(got) ||
        !py::isinstance<py::sequence>(got))
      why = definition_of(fn) + ": sensor \"" + sensor +
            "\" must return a list of numbers, not a " + type_of(got);
    else
      for (const py::handle v : got)
        if (why.empty() && !is_real_number(v))
          why = definition_of(fn) + ": sensor \"" + sensor +
                "\" must return a list of numbers; it holds a " + type_of(v);
    if (why.empty()) {
      std::vector<double> values;
      for (const py::handle v : got) {
        values.push_back(PyFloat_AsDouble(v.ptr()));
        if (values.back() == -1.0 && PyErr_Occurred()) throw py::error_already_set();
      }
      return values;
    }
  } catch (py::error_already_set& e) {
    why = host->sentence(e);
  }
  std::cerr << "swath-fleet: " << why << "\n";
  throw fleet::SensorError(why);
}

class PythonSensorsWorld final : public worlds::BaseWorld {
 public:
  PythonSensorsWorld(std::unique_ptr<worlds::BaseWorld> inner, py::dict sensors)
      : worlds::BaseWorld(*inner), inner_(std::move(inner)), sensors_(std::move(sensors)) {}
  ~PythonSensorsWorld() override {
    py::gil_scoped_acquire gil;
    sensors_.release().dec_ref();  // here, with the GIL held
  }
  const worlds::BaseWorld& inner() const { return *inner_; }
  double sense_time_s(const std::string& sensor) const override {
    py::gil_scoped_acquire gil;
    if (!sensors_.contains(sensor)) return inner_->sense_time_s(sensor);
    return py::tuple(sensors_[py::str(sensor)])[0].cast<double>();
  }
  /// An app's sensor that raises, or returns anything but a list of numbers, fails the task
  /// sensing (fleet::SensorError) with the file and line.
  Reading sense(const std::string& sensor, const fleet::Vec3& at, double t_s) const override {
    {
      py::gil_scoped_acquire gil;
      if (sensors_.contains(sensor)) {
        const py::object fn = py::tuple(sensors_[py::str(sensor)])[1];
        Reading r;
        r.sensor = sensor;
        r.ref = sensor;
        r.values = read_values(sensor, fn, at, t_s);
        return r;
      }
    }
    return inner_->sense(sensor, at, t_s);
  }

 private:
  std::unique_ptr<worlds::BaseWorld> inner_;
  py::dict sensors_;
};

/// The world's parameters an app reads (worlds.hpp), as attributes.
py::object world_view(const fleet::World& outer) {
  const auto* wrapped = dynamic_cast<const PythonSensorsWorld*>(&outer);
  const fleet::World& w = wrapped ? wrapped->inner() : outer;
  py::dict d;
  d["kind"] = w.kind();
  d["start"] = xyz(w.start());
  d["fence"] = w.fence();
  if (const auto* h = dynamic_cast<const worlds::HotspotWorld*>(&w)) {
    d["steps"] = h->steps, d["side_m"] = h->side_m, d["step_m"] = h->step_m;
    d["source_m"] = xyz(h->source_m);
  } else if (const auto* r = dynamic_cast<const worlds::RoadWorld*>(&w)) {
    d["steps"] = r->steps, d["step_m"] = r->step_m, d["road_m"] = r->road_m;
  } else if (const auto* s = dynamic_cast<const worlds::SitesWorld*>(&w)) {
    py::dict sites;
    for (const auto& [name, p] : s->sites) sites[py::str(name)] = xyz(p);
    d["sites"] = sites, d["handling_s"] = s->handling_s;
    d["delivery_interruptible"] = s->delivery_interruptible;
  } else if (const auto* f = dynamic_cast<const worlds::RfFieldWorld*>(&w)) {
    d["cell_m"] = f->cell_m, d["width_m"] = f->width_m, d["height_m"] = f->height_m;
    d["gp_length_m"] = f->gp_length_m, d["gp_sigma_f"] = f->gp_sigma_f;
    d["gp_sigma_n_db"] = f->gp_sigma_n_db, d["cancel_below_db"] = f->cancel_below_db;
  } else if (const auto* k = dynamic_cast<const worlds::TrackingWorld*>(&w)) {
    d["duration_s"] = k->duration_s, d["walker_speed_m_s"] = k->walker_speed_m_s;
    d["camera_range_m"] = k->camera_range_m;
  }
  return py::module_::import("types").attr("SimpleNamespace")(**d);
}

PyTask* task_of(const py::capsule& c) {
  return static_cast<PyTask*>(c.get_pointer());
}

}  // namespace
}  // namespace swath::apps

PYBIND11_EMBEDDED_MODULE(swath_fleet, m) {
  using namespace swath::apps;
  m.doc() = "swath-fleet's Python apps: BeeCluster's API (docs/swath-fleet.md)";
  ErrorTypes& types = error_types();
  types.action_failed = py::exception<void>(m, "ActionFailed");
  types.task_cancelled = py::exception<void>(m, "TaskCancelled");
  types.task_failed = py::exception<void>(m, "TaskFailed");
  types.task_killed = py::exception<void>(m, "TaskKilled", PyExc_BaseException);

  // os._exit would end swath-fleet itself, exit 0 with no file written: an app's os._exit(n)
  // raises SystemExit instead, as sys.exit does (its task fails; the run's files are written). A
  // child the app forked (multiprocessing ends its children with os._exit) exits as asked.
  static const pid_t swath_pid = getpid();
  m.def("_exit", [](int status) {
    if (getpid() != swath_pid) _exit(status);
    PyErr_SetString(PyExc_SystemExit, ("os._exit(" + std::to_string(status) +
                                       "): an app ends by returning from APP, not the process")
                                          .c_str());
    throw py::error_already_set();
  });

  // C's hypot, as the C++ apps use it (math.hypot rounds its own way): for parity of results.
  m.def("hypot", [](double x, double y) { return std::hypot(x, y); });

  py::class_<Reading>(m, "Reading")
      .def_readonly("t_s", &Reading::t_s)
      .def_readonly("drone", &Reading::drone)
      .def_property_readonly("at", [](const Reading& r) { return xyz(r.at); })
      .def_readonly("sensor", &Reading::sensor)
      .def_readonly("values", &Reading::values)
      .def_readonly("ref", &Reading::ref);

  // The built-in wifi app's Gaussian process (RBF kernel; prior mean the readings' mean).
  py::class_<swath::fleet::GaussianProcess>(m, "GaussianProcess")
      .def(py::init<double, double, double>(), py::arg("length_m"), py::arg("sigma_f"),
           py::arg("sigma_n"))
      .def("add", &swath::fleet::GaussianProcess::add)
      .def("predict", [](const swath::fleet::GaussianProcess& gp, double x, double y) {
        const auto p = gp.predict(x, y);
        return py::make_tuple(p[0], p[1]);  // mean, standard deviation
      });

  py::class_<PyFuture>(m, "Future")
      .def_property_readonly("value", &PyFuture::value)
      .def("done", [](const PyFuture& f) {
        if (current_task != nullptr && current_task->killed)  // its run is over or abandoned
          raise(error_types().task_killed, "the task's run is over");
        return f.ready();
      });

  py::class_<PyTask, std::unique_ptr<PyTask, py::nodelete>>(m, "Bee")
      .def(py::init(
          [](const py::capsule& c) { return std::unique_ptr<PyTask, py::nodelete>(task_of(c)); }))
      .def("act", [](PyTask* t, const py::args& a) { return act(t, a); })
      .def(
          "newTask",
          [](PyTask* t, const py::object& fn, const py::args& a, bool same_drone,
             bool interruptible, const py::object& kind) {
            return new_task(t, fn, a, same_drone, interruptible, kind);
          },
          py::arg("fn"), py::kw_only(), py::arg("same_drone") = false,
          py::arg("interruptible") = true, py::arg("kind") = py::none())
      .def("cancelTasks", &cancel_tasks)
      .def("metric",
           [](PyTask* t, const py::object& name, const py::object& v) {
             const std::string call = "bee.metric(name, value)";
             acting(t).ctx->metric(name_arg(name, call, "name"), number_arg(v, call, "value"));
           })
      .def_property_readonly("now_s", [](PyTask* t) { return acting(t).ctx->now_s(); })
      .def_property_readonly("world", [](PyTask* t) { return world_view(acting(t).ctx->world()); })
      .def_property_readonly("task", [](PyTask* t) { return acting(t).ctx->task(); });
  py::object bee = m.attr("Bee");
  bee.attr("new_task") = bee.attr("newTask");
  bee.attr("cancel_tasks") = bee.attr("cancelTasks");
}

namespace swath::apps {
namespace {

/// The first argument naming a .py file that is no option's value: the app.
int python_app_arg(int argc, char** argv) {
  // The options of run and compare that take no value.
  const std::vector<std::string> flags{"--render", "--relief", "--allow-no-gcs-failsafe"};
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i], before = argv[i - 1];
    const bool value_of_option = i > 2 && before.starts_with("-") &&
                                 before.find('=') == std::string::npos &&
                                 std::find(flags.begin(), flags.end(), before) == flags.end();
    if (a.size() > 3 && a.ends_with(".py") && a[0] != '-' && !value_of_option) return i;
  }
  return -1;
}

/// SENSORS = {name: (time_s, fn)}: each entry checked at load (std::invalid_argument names the
/// entry), so that a run never meets a bad one mid-flight.
void check_sensors(const py::object& sensors) {
  const std::string form = " must be (time_s, fn(x_m, y_m, t_s))";
  if (!py::isinstance<py::dict>(sensors))
    throw std::invalid_argument("SENSORS must be a dict {name: (time_s, fn(x_m, y_m, t_s))}");
  for (const auto& [key, entry] : py::reinterpret_borrow<py::dict>(sensors)) {
    if (!py::isinstance<py::str>(key))
      throw std::invalid_argument("SENSORS: a sensor's name must be a string, not " +
                                  py::repr(key).cast<std::string>());
    const std::string at = "SENSORS[\"" + key.cast<std::string>() + "\"]";
    if (!py::isinstance<py::tuple>(entry) && !py::isinstance<py::list>(entry))
      throw std::invalid_argument(at + form);
    const auto pair = py::reinterpret_borrow<py::sequence>(entry);
    if (pair.size() != 2) throw std::invalid_argument(at + form);
    const py::object time = pair[0];
    const bool number = (py::isinstance<py::float_>(time) || py::isinstance<py::int_>(time)) &&
                        !py::isinstance<py::bool_>(time);
    const double time_s = number ? time.cast<double>() : 0;
    if (!number || !std::isfinite(time_s) || time_s < 0 || time_s > kMaxSenseS)
      throw std::invalid_argument(at + ": time_s must be a number of seconds from 0 to " +
                                  base::shortest_text(kMaxSenseS) + ", not " +
                                  py::repr(time).cast<std::string>());
    if (!PyCallable_Check(pair[1].ptr()))
      throw std::invalid_argument(at + ": its reading must be a function fn(x_m, y_m, t_s), not " +
                                  py::repr(pair[1]).cast<std::string>());
  }
}

/// --max-time's seconds, if given and a number (run refuses a bad one itself): also the wall
/// time a Python task may keep its turn.
double max_time_arg(int argc, char** argv, double fallback) {
  for (int i = 1; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "--max-time") {
      char* end = nullptr;
      const double v = std::strtod(argv[i + 1], &end);
      if (end != argv[i + 1] && *end == '\0' && std::isfinite(v) && v > 0) return v;
    }
  return fallback;
}

/// The world kind the app runs in: its WORLD, else the kind of the --world file.
std::string world_kind_of(const py::dict& globals, int argc, char** argv) {
  if (globals.contains("WORLD")) {
    const py::object world = globals["WORLD"];
    const std::vector<std::string>& kinds = worlds::world_kinds();
    if (py::isinstance<py::str>(world) &&
        std::find(kinds.begin(), kinds.end(), world.cast<std::string>()) != kinds.end())
      return world.cast<std::string>();
    std::string names;
    for (const std::string& k : kinds) names += (names.empty() ? "" : ", ") + k;
    throw std::invalid_argument("WORLD must name a world kind (" + names + "), not " +
                                py::repr(world).cast<std::string>());
  }
  for (int i = 1; i + 1 < argc; ++i)
    if (std::string(argv[i]) == "--world") try {
        const std::string file = world_path(argv[i + 1]);
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        return worlds::parse_world(text.str(), file, {})->kind();
      } catch (const std::exception&) {
        // run reports the world's error itself
      }
  return "static";
}

/// A file name as Python spells it (os.fsdecode): any bytes the system allows, not only UTF-8.
py::object file_name(const std::string& path) {
  return py::module_::import("os").attr("fsdecode")(py::bytes(path));
}

/// The app file read here (its bytes, whatever its name's characters) and run in `globals`,
/// compiled under its own name so that tracebacks and SyntaxErrors name it.
void run_file(const std::string& path, py::dict& globals) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw std::invalid_argument("cannot be read");
  const py::module_ builtins = py::module_::import("builtins");
  builtins.attr("exec")(builtins.attr("compile")(py::bytes(text.str()), file_name(path), "exec"),
                        globals);
}

/// APP must be a plain function: an async one (or a generator) would run nothing when called.
void check_app(const py::dict& globals) {
  if (!globals.contains("APP") || !PyCallable_Check(globals["APP"].ptr()))
    throw std::invalid_argument("defines no function APP(bee)");
  const py::module_ inspect = py::module_::import("inspect");
  for (const char* test : {"iscoroutinefunction", "isasyncgenfunction", "isgeneratorfunction"})
    if (inspect.attr(test)(globals["APP"]).cast<bool>())
      throw std::invalid_argument(
          "APP must be a plain function (def APP(bee): ...), not an async function or a "
          "generator, which would run nothing when called");
}

/// NAME: a non-empty string (the name the runs log).
std::string app_name(const py::object& name) {
  if (!py::isinstance<py::str>(name) || name.cast<std::string>().empty())
    throw std::invalid_argument("NAME must be a non-empty string, not " +
                                py::repr(name).cast<std::string>());
  return name.cast<std::string>();
}

}  // namespace

int fleet_main_with_python(int argc, char** argv) {
  const int at = python_app_arg(argc, argv);
  if (at < 0) return fleet_main(argc, argv);
  const std::string path = argv[at];
  if (!std::filesystem::is_regular_file(path)) {
    std::cerr << "swath-fleet: " << path << ": no such Python app file\n";
    return 2;
  }
  // Sets and dicts of strings iterate in one order from run to run (same seed, same bytes).
  setenv("PYTHONHASHSEED", "0", 0);
  // File names and files in UTF-8 (Python's UTF-8 mode) whatever the process's locale: swath-fleet
  // never sets one, so Python would take ASCII, and an app in a folder named in any other
  // characters could not import the modules beside it.
  PyPreConfig preconfig;
  PyPreConfig_InitPythonConfig(&preconfig);
  preconfig.utf8_mode = 1;
  if (PyStatus status = Py_PreInitialize(&preconfig); PyStatus_Exception(status)) {
    std::cerr << "swath-fleet: " << path << ": Python cannot start: "
              << (status.err_msg ? status.err_msg : "preinitialisation failed") << "\n";
    return 2;
  }
  // swath-fleet's own SIGINT and SIGTERM handling stays (the run's abort, exit 130 and 143).
  py::scoped_interpreter interpreter(false);
  Host h;
  h.path = path;
  h.max_wall_s = max_time_arg(argc, argv, h.max_wall_s);
  std::string name;
  host = &h;
  try {
    py::dict globals;
    globals["__name__"] = "__swath_app__";
    globals["__file__"] = file_name(path);
    globals["__builtins__"] = py::module_::import("builtins");
    const py::module_ fleet_module = py::module_::import("swath_fleet");
    for (const char* module : {"os", "posix"})
      py::module_::import(module).attr("_exit") = fleet_module.attr("_exit");
    // The app's folder on the path: an app may import modules of its own from beside it.
    py::module_::import("sys").attr("path").attr("insert")(
        0, file_name(std::filesystem::absolute(path).parent_path().string()));
    run_file(path, globals);
    check_app(globals);
    h.app_fn = globals["APP"];
    if (globals.contains("SENSORS")) {
      check_sensors(globals["SENSORS"]);
      py::dict sensors = globals["SENSORS"];
      world_wrapper() = [sensors](std::unique_ptr<worlds::BaseWorld> w) {
        py::gil_scoped_acquire gil;
        return std::unique_ptr<worlds::BaseWorld>(
            std::make_unique<PythonSensorsWorld>(std::move(w), sensors));
      };
    }
    const std::string kind = world_kind_of(globals, argc, argv);
    // NAME: the name the runs log (a built-in app's, for the same events and histories).
    name = globals.contains("NAME") ? app_name(globals["NAME"]) : path;
    fleet::register_app({name, "Python app " + path,
                         [](Ctx& c) {
                           PyTask& t = host->new_task();
                           t.is_main = true;
                           return run_task(c, t.slot);
                         }},
                        kind, name != path);
  } catch (py::error_already_set& e) {
    std::cerr << "swath-fleet: " << h.sentence(e) << "\n";
    return 2;
  } catch (const std::exception& e) {  // whatever else loading throws is bad input too
    std::cerr << "swath-fleet: " << path << ": " << one_line(e.what()) << "\n";
    return 2;
  }
  std::vector<char*> args(argv, argv + argc);
  args[static_cast<std::size_t>(at)] = name.data();
  int code = 0;
  {
    py::gil_scoped_release nogil;  // the tasks' threads take it in turn
    code = fleet_main(argc, args.data());
    h.kill_all();
    if (h.any_abandoned()) {  // the files are written; its thread may hold Python for ever
      std::cout.flush();
      std::cerr.flush();
      std::_Exit(code);
    }
  }
  world_wrapper() = nullptr;  // its dict goes with the GIL held
  h.clear();
  host = nullptr;
  return code;
}

}  // namespace swath::apps
