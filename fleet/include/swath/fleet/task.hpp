#pragma once
// Writing swarm applications against virtual drones (paper 000 §3.1, Table 1; docs/swath-fleet.md):
// C++20 coroutines on one thread. A *task* is a virtual drone: its actions (`fly_to`, `sense`,
// `hover`, `custom`) are queued at once and return futures; `co_await` is the paper's blocking
// `.value`; `spawn` is `newTask`, `cancel` is `cancelTasks`. The runtime decides which real drone
// serves each task's next segment. One thread and a FIFO of ready coroutines make a run
// deterministic: the same seed gives the same interleaving, byte for byte.
//
//   const fleet::Kind kStep{"trace-step"};
//   fleet::Co<fleet::Reading> step(fleet::Ctx& t, fleet::Vec3 p) {
//     t.fly_to(p);                                // queued; returns at once
//     co_return co_await t.sense("road_camera");  // blocks this task only
//   }

#include <coroutine>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "swath/vehicle/random.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::fleet {

using vehicle::Vec3;

/// The "logic task" a spawn belongs to: the forecaster matches tasks of equal kinds
/// (docs/swath-fleet.md, 'Forecasting the next requests').
struct Kind {
  std::string name;
};

/// Binding (paper 000 §3.1.2). `same_drone`: every segment on the drone that took the first.
/// Not `interruptible`: the drone is reserved between segments (docs/swath-fleet.md).
struct Flags {
  bool same_drone = false;
  bool interruptible = true;
};

/// What an action returns. `values` are the sensor's (empty for flying and hovering).
struct Reading {
  double t_s = 0;      ///< when the action finished, seconds since the run began
  int drone = -1;      ///< the real drone that did it (index in the fleet file)
  Vec3 at;             ///< where, local metres (x east, y north, altitude above home)
  std::string sensor;  ///< the sensor, or the action's name ("fly_to", "hover", a custom name)
  std::vector<double> values;
  std::string ref;  ///< what the world says the values mean ("rssi_dbm", "x_m,y_m,heading_deg")
};

/// An action or task that failed (`reason`: drone_lost, no_feasible_drone, sensor_failure, ...).
struct ActionFailed : std::runtime_error {
  explicit ActionFailed(const std::string& why) : std::runtime_error(why), reason(why) {}
  std::string reason;
};
/// Awaiting a cancelled task.
struct TaskCancelled : std::runtime_error {
  TaskCancelled() : std::runtime_error("task cancelled") {}
};

class Ctx;

namespace detail {

class Core;

/// Where a suspended coroutine waits; `armed` is shared by the waiters of one `any`.
struct Waiter {
  int task;
  std::coroutine_handle<> handle;
  std::shared_ptr<bool> armed;
};

/// The shared state of a future or a task's result.
struct StateBase {
  bool ready = false;
  std::exception_ptr error;
  std::vector<Waiter> waiters;
  int task = -1;  ///< the task whose result (or action) this is
};
template <class T>
struct State : StateBase {
  std::optional<T> value;
};
template <>
struct State<void> : StateBase {};

/// The awaiter of every future-like object: ready → no suspension; else the runtime resumes the
/// coroutine when the state resolves.
template <class T>
struct StateAwaiter {
  std::shared_ptr<State<T>> state;
  Core* core;
  bool suspended = false;  ///< the await suspended (its script step is recorded then)
  bool await_ready() const noexcept;
  void await_suspend(std::coroutine_handle<> h);
  T await_resume();
};

}  // namespace detail

/// A value that a coroutine awaits: an action's reading.
template <class T>
class Future {
 public:
  Future() = default;
  Future(std::shared_ptr<detail::State<T>> state, detail::Core* core)
      : state_(std::move(state)), core_(core) {}
  bool ready() const { return state_ && state_->ready; }
  detail::StateAwaiter<T> operator co_await() const { return {state_, core_}; }
  const std::shared_ptr<detail::State<T>>& state() const { return state_; }

 private:
  std::shared_ptr<detail::State<T>> state_;
  detail::Core* core_ = nullptr;
};

/// A spawned task: await it for its result.
template <class T>
class TaskHandle {
 public:
  TaskHandle() = default;
  TaskHandle(int id, std::shared_ptr<detail::State<T>> state, detail::Core* core)
      : id_(id), state_(std::move(state)), core_(core) {}
  int id() const { return id_; }
  bool ready() const { return state_ && state_->ready; }
  detail::StateAwaiter<T> operator co_await() const { return {state_, core_}; }
  const std::shared_ptr<detail::State<T>>& state() const { return state_; }
  detail::Core* core() const { return core_; }

 private:
  int id_ = -1;
  std::shared_ptr<detail::State<T>> state_;
  detail::Core* core_ = nullptr;
};

/// A coroutine returning T: a task's body, or a helper a task awaits (`co_await helper(t)`).
/// Lazy: nothing runs until the runtime starts it or a coroutine awaits it.
template <class T = void>
class [[nodiscard]] Co {
 public:
  using value_type = T;
  struct promise_base {
    std::shared_ptr<detail::State<T>> result = std::make_shared<detail::State<T>>();
    std::coroutine_handle<> continuation;
    std::suspend_always initial_suspend() noexcept { return {}; }
    struct Final {
      bool await_ready() noexcept { return false; }
      template <class P>
      std::coroutine_handle<> await_suspend(std::coroutine_handle<P> h) noexcept {
        auto c = h.promise().continuation;
        return c ? c : std::noop_coroutine();
      }
      void await_resume() noexcept {}
    };
    Final final_suspend() noexcept { return {}; }
    void unhandled_exception() { result->error = std::current_exception(); }
  };
  struct promise_void : promise_base {
    void return_void() {}
  };
  struct promise_value : promise_base {
    template <class U>
    void return_value(U&& v) {
      this->result->value.emplace(std::forward<U>(v));
    }
  };
  struct promise_type : std::conditional_t<std::is_void_v<T>, promise_void, promise_value> {
    Co get_return_object() { return Co(std::coroutine_handle<promise_type>::from_promise(*this)); }
  };

  Co(Co&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
  Co& operator=(Co&& o) noexcept {
    if (this != &o) {
      if (h_) h_.destroy();
      h_ = std::exchange(o.h_, nullptr);
    }
    return *this;
  }
  Co(const Co&) = delete;
  ~Co() {
    if (h_) h_.destroy();
  }

  /// Awaiting a Co runs it now and resumes the awaiter when it returns (symmetric transfer).
  struct Awaiter {
    std::coroutine_handle<promise_type> child;
    bool await_ready() const noexcept { return false; }
    std::coroutine_handle<> await_suspend(std::coroutine_handle<> h) noexcept {
      child.promise().continuation = h;
      return child;
    }
    T await_resume() {
      auto& r = *child.promise().result;
      if (r.error) std::rethrow_exception(r.error);
      if constexpr (!std::is_void_v<T>) return std::move(*r.value);
    }
  };
  Awaiter operator co_await() & = delete;
  Awaiter operator co_await() && { return Awaiter{h_}; }

  /// For the runtime: the frame (now owned by the caller) and its result state.
  std::coroutine_handle<promise_type> release() { return std::exchange(h_, nullptr); }
  std::shared_ptr<detail::State<T>> result() const { return h_.promise().result; }

 private:
  explicit Co(std::coroutine_handle<promise_type> h) : h_(h) {}
  std::coroutine_handle<promise_type> h_;
};

/// Sensors and the space the applications act in (worlds/ implements it; docs/swath-fleet.md).
class World;

namespace detail {

/// What a task body needs from the runtime (implemented in runtime.cpp).
class Core {
 public:
  virtual ~Core() = default;
  virtual int current_task() const = 0;
  /// Queues an action of task `task`; the future resolves with its reading.
  virtual Future<Reading> act(int task, int type, const Vec3& to, const std::string& name,
                              double duration_s) = 0;
  /// Registers a new task and queues its first resumption; returns its id.
  virtual int spawn(int parent, const Kind& kind, Flags flags,
                    std::function<std::coroutine_handle<>(Ctx&)> start,
                    std::shared_ptr<StateBase> result) = 0;
  virtual void cancel(int issuer, int task) = 0;
  virtual Future<void> delay(int task, double cost_s) = 0;
  virtual void suspended(int task, StateBase& awaited, std::coroutine_handle<> h,
                         std::shared_ptr<bool> armed) = 0;
  /// The await of `awaited` by task `task` throws (the awaited task failed or was cancelled, or
  /// the action failed): the app sees the error there, which its script records.
  virtual void raised(int /*task*/, StateBase& /*awaited*/, bool /*suspended*/) {}
  virtual double now_s() const = 0;
  virtual const World& world() const = 0;
  virtual vehicle::SplitMix64& random() = 0;
  virtual void metric(const std::string& name, double value) = 0;
};

template <class T>
bool StateAwaiter<T>::await_ready() const noexcept {
  return state->ready;
}
template <class T>
void StateAwaiter<T>::await_suspend(std::coroutine_handle<> h) {
  suspended = true;
  core->suspended(core->current_task(), *state, h, nullptr);
}
template <class T>
T StateAwaiter<T>::await_resume() {
  if (state->error) {
    if (core) core->raised(core->current_task(), *state, suspended);
    std::rethrow_exception(state->error);
  }
  if constexpr (!std::is_void_v<T>) return *state->value;
}

}  // namespace detail

/// A task's handle on the runtime: acting (as a virtual drone), spawning, cancelling.
class Ctx {
 public:
  Ctx(detail::Core& core, int task, bool acts) : core_(&core), task_(task), acts_(acts) {}
  int task() const { return task_; }

  /// Flies there; the reading's `at` is where it arrived. Throws std::logic_error in the app's
  /// main, which is no virtual drone (docs/swath-fleet.md).
  Future<Reading> fly_to(const Vec3& to) { return act(0, to, "fly_to", 0); }
  /// Senses with `sensor` where the task's last fly_to took it; the world sets the time.
  Future<Reading> sense(const std::string& sensor) { return act(1, {}, sensor, 0); }
  /// Flies there reading `sensor` every `period_s` (> 0) of the flight (paper Table 1's
  /// fly_sensing): the reading's `values` are, per sample, x_m, y_m and the sensor's values.
  Future<Reading> fly_sensing(const Vec3& to, const std::string& sensor, double period_s) {
    return act(4, to, sensor, period_s);
  }
  /// Hovers in place for `seconds` (≥ 0).
  Future<Reading> hover(double seconds) { return act(2, {}, "hover", seconds); }
  /// An action of the application's own (drop a parcel, record video) lasting `seconds`.
  Future<Reading> custom(const std::string& name, double seconds) {
    return act(3, {}, name, seconds);
  }

  /// newTask (paper Table 1): starts `fn(ctx, args...)` as a new task; `fn` and the arguments are
  /// kept in the task record, so a coroutine may take them by reference.
  template <class F, class... Args>
  auto spawn(const Kind& kind, Flags flags, F fn, Args... args) {
    using C = std::invoke_result_t<F&, Ctx&, Args&...>;
    using T = typename C::value_type;
    auto kept = std::make_shared<std::tuple<F, Args...>>(std::move(fn), std::move(args)...);
    auto result = std::make_shared<detail::State<T>>();
    auto start = [kept, result](Ctx& c) -> std::coroutine_handle<> {
      C co = std::apply([&c](F& f, Args&... a) { return f(c, a...); }, *kept);
      auto h = co.release();
      h.promise().result = result;  // the body writes straight into the handle's state
      return h;
    };
    const int id = core_->spawn(task_, kind, flags, std::move(start), result);
    return TaskHandle<T>(id, result, core_);
  }

  /// cancelTasks: queued segments dropped, an action in progress aborted, the drone freed,
  /// awaiters get TaskCancelled. A finished task is left as it is.
  template <class T>
  void cancel(const TaskHandle<T>& h) {
    core_->cancel(task_, h.id());
  }
  template <class T>
  void cancel(const std::vector<TaskHandle<T>>& hs) {
    for (const auto& h : hs) core_->cancel(task_, h.id());
  }

  /// Heavy computation: `co_await c.compute(fn, cost_s)` returns fn() after `cost_s` of virtual
  /// time (inline in simulation; docs/swath-fleet.md).
  template <class F>
  Co<std::invoke_result_t<F&>> compute(F fn, double cost_s) {
    co_await core_->delay(task_, cost_s);
    co_return fn();
  }

  double now_s() const { return core_->now_s(); }
  const World& world() const { return core_->world(); }
  /// The application's own random stream (deterministic for the run's seed).
  vehicle::SplitMix64& random() { return core_->random(); }
  /// An application metric for summary.json (the last value of each name is kept).
  void metric(const std::string& name, double value) { core_->metric(name, value); }

 private:
  Future<Reading> act(int type, const Vec3& to, const std::string& name, double s) {
    if (!acts_) throw std::logic_error("the app's main is no virtual drone: spawn a task to act");
    return core_->act(task_, type, to, name, s);
  }
  detail::Core* core_;
  int task_;
  bool acts_;
};

/// Awaits every handle in order; their values in the same order (docs/swath-fleet.md `all`).
template <class T>
Co<std::vector<T>> all(std::vector<TaskHandle<T>> hs) {
  std::vector<T> out;
  out.reserve(hs.size());
  for (auto& h : hs) out.push_back(co_await h);
  co_return out;
}

namespace detail {
/// Suspends until the first of several states is ready; resumes once (a shared `armed` flag).
struct AnyAwaiter {
  std::vector<std::shared_ptr<StateBase>> states;
  Core* core;
  bool await_ready() const noexcept {
    for (const auto& s : states)
      if (s->ready) return true;
    return states.empty();
  }
  void await_suspend(std::coroutine_handle<> h) {
    auto armed = std::make_shared<bool>(true);
    for (const auto& s : states) core->suspended(core->current_task(), *s, h, armed);
  }
  std::size_t await_resume() const noexcept {
    for (std::size_t i = 0; i < states.size(); ++i)
      if (states[i]->ready) return i;
    return states.size();
  }
};
}  // namespace detail

/// Waits for the first of `hs` to end (done, failed or cancelled) and returns its index; await
/// that handle for its value or error. Returns hs.size() for an empty list.
template <class T>
Co<std::size_t> any(std::vector<TaskHandle<T>> hs) {
  detail::AnyAwaiter a;
  for (const auto& h : hs) {
    a.states.push_back(h.state());
    a.core = h.core();
  }
  co_return co_await a;
}

}  // namespace swath::fleet
