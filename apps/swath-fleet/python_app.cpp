// Fleet apps in Python (python_app.hpp). Each Python task runs on a thread of its own, mapped onto
// a runtime task whose coroutine hands that thread a baton and waits until the Python code blocks
// on a future (the coroutine then awaits that future for it) or returns. Exactly one side runs
// at a time, and every hand-over happens at a point the runtime chose, so a run's events do not
// depend on the threads' timing: the runtime stays single-threaded and deterministic.

#include "python_app.hpp"

#include <pybind11/embed.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "../../fleet/apps/src/gaussian_process.hpp"  // the wifi app's, for wifi.py's parity
#include "fleet_inputs.hpp"
#include "fleet_main.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/worlds/worlds.hpp"

namespace py = pybind11;

namespace swath::apps {
namespace {

using fleet::Co;
using fleet::Ctx;
using fleet::Reading;

/// Who may run: the runtime (kRuntime) or one Python task (its slot).
class Baton {
 public:
  static constexpr int kRuntime = -1;
  /// Runtime side: lets task `slot` run and waits until it hands the baton back.
  void run(int slot) {
    std::unique_lock lock(m_);
    turn_ = slot;
    cv_.notify_all();
    cv_.wait(lock, [&] { return turn_ == kRuntime; });
  }
  /// Python side: hands the baton back and waits for this task's next turn.
  void yield(int slot) {
    std::unique_lock lock(m_);
    turn_ = kRuntime;
    cv_.notify_all();
    cv_.wait(lock, [&] { return turn_ == slot; });
  }
  void wait_turn(int slot) {
    std::unique_lock lock(m_);
    cv_.wait(lock, [&] { return turn_ == slot; });
  }
  /// Python side, when the task's function has returned.
  void finish() {
    std::lock_guard lock(m_);
    turn_ = kRuntime;
    cv_.notify_all();
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  int turn_ = kRuntime;
};

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
  bool started = false, finished = false, killed = false;
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

  PyTask& new_task() {
    tasks_.push_back(std::make_unique<PyTask>());
    tasks_.back()->slot = static_cast<int>(tasks_.size()) - 1;
    return *tasks_.back();
  }
  PyTask& task(int slot) { return *tasks_.at(static_cast<std::size_t>(slot)); }

  /// Runtime side: runs the task until it blocks or ends (its thread starts on the first turn).
  void step(PyTask& t) {
    if (!t.started) {
      t.started = true;
      t.thread = std::thread([this, &t] { thread_main(t); });
    }
    baton.run(t.slot);
  }
  /// Runtime side: a task whose frame is gone (cancelled, or the run over) unwinds its Python
  /// code: every wait and action raises TaskKilled until the function returns.
  void kill(PyTask& t) {
    if (!t.started || t.finished) return;
    t.killed = true;
    baton.run(t.slot);
  }
  /// After the runs, GIL released: ends every thread still waiting.
  void kill_all() {
    for (auto& t : tasks_) kill(*t);
    for (auto& t : tasks_)
      if (t->thread.joinable()) t->thread.join();
  }
  /// With the GIL held: drops the Python objects.
  void clear() {
    tasks_.clear();
    app_fn = py::object();
  }

  /// The sentence for a Python exception: the app file, the line in it, the type and message.
  std::string sentence(py::error_already_set& e) const;

 private:
  void thread_main(PyTask& t);
  std::deque<std::unique_ptr<PyTask>> tasks_;
};

Host* host = nullptr;

std::string Host::sentence(py::error_already_set& e) const {
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
  if (e.matches(PyExc_SyntaxError) && py::hasattr(e.value(), "lineno"))
    where = path + " line " + py::str(e.value().attr("lineno")).cast<std::string>();
  const std::string type = py::str(e.type().attr("__name__"));
  const std::string message = py::str(e.value());
  return where + ": " + type + (message.empty() ? "" : ": " + message);
}

void Host::thread_main(PyTask& t) {
  baton.wait_turn(t.slot);
  {
    py::gil_scoped_acquire gil;
    current_task = &t;
    try {
      if (!t.killed) {
        py::object bee =
            py::module_::import("swath_fleet").attr("Bee")(py::capsule(&t, "swath_fleet.task"));
        t.result = t.is_main ? app_fn(bee) : t.fn(bee, *py::tuple(t.args));
      }
      t.yield = Yield::returned;
    } catch (py::error_already_set& e) {
      const ErrorTypes& types = error_types();
      if (t.killed) {
        t.yield = Yield::returned;
      } else if (e.matches(types.action_failed)) {
        t.yield = Yield::action_failed;
        t.error = py::str(e.value());
      } else if (e.matches(types.task_cancelled)) {
        t.yield = Yield::cancelled;
      } else {
        t.yield = Yield::raised;
        t.propagated = e.matches(types.task_failed);
        // A task_failed exception carries the sentence of the task it came from.
        t.error =
            e.matches(types.task_failed) ? py::str(e.value()).cast<std::string>() : sentence(e);
      }
    }
    current_task = nullptr;
  }
  t.finished = true;
  baton.finish();
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
      me->awaited = awaited;
      me->yield = Yield::awaiting;
      {
        py::gil_scoped_release nogil;
        host->baton.yield(me->slot);
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

fleet::Vec3 point(const py::args& a, std::size_t from) {
  if (a.size() < from + 2 || a.size() > from + 3)
    throw py::value_error("bee.act(\"fly_to\", x_m, y_m[, z_m])");
  return {a[from].cast<double>(), a[from + 1].cast<double>(),
          a.size() == from + 3 ? a[from + 2].cast<double>() : 0.0};
}

PyFuture act(PyTask* t, const std::string& name, const py::args& a) {
  Ctx& ctx = *acting(t).ctx;
  if (name == "fly_to") return {ctx.fly_to(point(a, 0))};
  if (name == "sense") {
    if (a.size() != 1) throw py::value_error("bee.act(\"sense\", sensor)");
    return {ctx.sense(a[0].cast<std::string>())};
  }
  if (name == "hover") {
    if (a.size() != 1) throw py::value_error("bee.act(\"hover\", seconds)");
    return {ctx.hover(a[0].cast<double>())};
  }
  if (name == "custom") {
    if (a.size() != 2) throw py::value_error("bee.act(\"custom\", name, seconds)");
    return {ctx.custom(a[0].cast<std::string>(), a[1].cast<double>())};
  }
  throw py::value_error("bee.act: unknown action \"" + name + "\" (fly_to, sense, hover, custom)");
}

PyFuture new_task(PyTask* t, const py::object& fn, const py::args& a, bool same_drone,
                  bool interruptible, const py::object& kind) {
  Ctx& ctx = *acting(t).ctx;
  PyTask& child = host->new_task();
  child.fn = fn;
  child.args = py::tuple(a);
  const std::string kind_name =
      kind.is_none() ? py::str(fn.attr("__name__")).cast<std::string>() : kind.cast<std::string>();
  auto h = ctx.spawn(fleet::Kind{kind_name},
                     fleet::Flags{.same_drone = same_drone, .interruptible = interruptible},
                     run_task, child.slot);
  return {h, &child};
}

void cancel_tasks(PyTask* t, const py::iterable& futures) {
  Ctx& ctx = *acting(t).ctx;
  for (const py::handle f : futures) {
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
  Reading sense(const std::string& sensor, const fleet::Vec3& at, double t_s) const override {
    {
      py::gil_scoped_acquire gil;
      if (sensors_.contains(sensor)) try {
          const py::object fn = py::tuple(sensors_[py::str(sensor)])[1];
          Reading r;
          r.sensor = sensor;
          r.ref = sensor;
          r.values = fn(at.x, at.y, t_s).cast<std::vector<double>>();
          return r;
        } catch (py::error_already_set& e) {
          const std::string why = host->sentence(e);
          std::cerr << "swath-fleet: " << why << "\n";
          throw std::runtime_error(why);
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
      .def("done", &PyFuture::ready);

  py::class_<PyTask, std::unique_ptr<PyTask, py::nodelete>>(m, "Bee")
      .def(py::init(
          [](const py::capsule& c) { return std::unique_ptr<PyTask, py::nodelete>(task_of(c)); }))
      .def("act",
           [](PyTask* t, const std::string& name, const py::args& a) { return act(t, name, a); })
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
           [](PyTask* t, const std::string& name, double v) { acting(t).ctx->metric(name, v); })
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

/// The world kind the app runs in: its WORLD, else the kind of the --world file.
std::string world_kind_of(const py::dict& globals, int argc, char** argv) {
  if (globals.contains("WORLD")) return py::str(globals["WORLD"]);
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
  // swath-fleet's own SIGINT and SIGTERM handling stays (the run's abort, exit 130 and 143).
  py::scoped_interpreter interpreter(false);
  Host h;
  h.path = path;
  std::string name;
  host = &h;
  try {
    py::dict globals;
    globals["__name__"] = "__swath_app__";
    globals["__file__"] = path;
    globals["__builtins__"] = py::module_::import("builtins");
    py::module_::import("swath_fleet");
    // The app's folder on the path: an app may import modules of its own from beside it.
    py::module_::import("sys").attr("path").attr("insert")(
        0, std::filesystem::absolute(path).parent_path().string());
    py::eval_file(path, globals);
    if (!globals.contains("APP") || !PyCallable_Check(globals["APP"].ptr())) {
      std::cerr << "swath-fleet: " << path << ": defines no function APP(bee)\n";
      return 2;
    }
    h.app_fn = globals["APP"];
    if (globals.contains("SENSORS")) {
      py::dict sensors = globals["SENSORS"];
      world_wrapper() = [sensors](std::unique_ptr<worlds::BaseWorld> w) {
        py::gil_scoped_acquire gil;
        return std::unique_ptr<worlds::BaseWorld>(
            std::make_unique<PythonSensorsWorld>(std::move(w), sensors));
      };
    }
    const std::string kind = world_kind_of(globals, argc, argv);
    // NAME: the name the runs log (a built-in app's, for the same events and histories).
    name = globals.contains("NAME") ? py::str(globals["NAME"]).cast<std::string>() : path;
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
  } catch (const std::invalid_argument& e) {
    std::cerr << "swath-fleet: " << path << ": " << e.what() << "\n";
    return 2;
  }
  std::vector<char*> args(argv, argv + argc);
  args[static_cast<std::size_t>(at)] = name.data();
  int code = 0;
  {
    py::gil_scoped_release nogil;  // the tasks' threads take it in turn
    code = fleet_main(argc, args.data());
    h.kill_all();
  }
  world_wrapper() = nullptr;  // its dict goes with the GIL held
  h.clear();
  host = nullptr;
  return code;
}

}  // namespace swath::apps
