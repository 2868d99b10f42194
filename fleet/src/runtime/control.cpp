// Orders from outside the run (control.hpp, docs/swath-fleet.md "Abort and control"): pause,
// resume, and the abort — every airborne vehicle told to return (or land), the log closed as a
// complete record. Called from the loop between its steps, never from a signal handler.

#include <chrono>
#include <thread>

#include "runtime/runtime_impl.hpp"

namespace swath::fleet::rt {

namespace {
const char* action_name(AbortAction a) {
  return a == AbortAction::land ? "land" : "rtl";
}
}  // namespace

// The next order: one read while waiting for the wall clock first, else the source's.
ControlRequest Runtime::next_order() {
  if (waiting_order_.order != ControlOrder::none) return std::exchange(waiting_order_, {});
  return settings_.control ? settings_.control() : ControlRequest{};
}

bool Runtime::take_orders() {
  for (;;) {
    const ControlRequest r = next_order();
    switch (r.order) {
      case ControlOrder::none:
        return false;
      case ControlOrder::pause:
        pause_run(r.reason);
        break;
      case ControlOrder::resume:
        resume_run(r.reason);
        break;
      case ControlOrder::rtl_all:
        abort_run(r.reason, AbortAction::rtl, false);
        return true;
      case ControlOrder::land_all:
        abort_run(r.reason, AbortAction::land, false);
        return true;
    }
  }
}

// Not on the ground (landed or charging at home) and not out of the fleet: the vehicles an abort
// must bring down. A drone whose link is down is included: its command goes out when it answers.
bool Runtime::airborne(const Drone& d) {
  return d.mode != Mode::landed && d.mode != Mode::charging && d.mode != Mode::lost;
}

// Every airborne vehicle is told first (the backend's command before any bookkeeping that might
// fail), then the model follows. Also called after an exception, with the runtime's state in
// whatever shape the exception left it: each drone's bookkeeping is tried on its own.
void Runtime::abort_run(const std::string& reason, AbortAction action, bool by_error) {
  record_.aborted = reason;
  record_.aborted_by_error = by_error;
  record_.failure = "aborted (" + reason + ")";
  log(json{{"ev", "aborted"}, {"reason", reason}, {"action", action_name(action)}});
  for (Drone& d : drones_) {
    if (!airborne(d)) continue;
    if (action == AbortAction::land)
      backend_.land(d.index, now_);
    else if (!settings_.envelope.routes())
      backend_.return_home(d.index, now_);
    // With routes (a simulated fleet) model_abort commands the way home round the fence.
    try {
      integrate(d, now_);  // where it is now, for the record
    } catch (const std::exception&) {
    }
    log(at_json(json{{"ev", "abort_command"}, {"drone", d.index}}, d.pos,
                json{{"command", action_name(action)}}));
    try {
      model_abort(d, action);
    } catch (const std::exception&) {
      // The vehicle has its order; only the model's picture of it is left as it was.
    }
  }
}

// The model's side of an abort: its request requeued, a return leg (already returning: as it
// was) or, for a landing, stopped where it is.
void Runtime::model_abort(Drone& d, AbortAction action) {
  requeue(d, "aborted");
  leave_spot(d);
  d.relieving = -1;
  d.held_for = -1;
  d.land_retry_s = kInf;
  integrate(d, now_);
  if (action == AbortAction::rtl) {
    if (d.mode == Mode::returning) return;
    const Vec3 home{d.spec.home_m.x, d.spec.home_m.y, d.pos.z > 0 ? d.pos.z : d.layer_m};
    if (settings_.envelope.routes()) {
      start_leg(d, home, Mode::returning, now_);
      return;
    }
    const Leg* current = on_leg(d.mode) && d.leg ? &*d.leg : nullptr;
    d.leg = next_leg(current, now_ - d.leg_start, d.pos, home, d.spec.kinematics());
    d.leg_start = now_;
    set_mode(d, Mode::returning, now_);  // the backend was told already
    return;
  }
  d.leg.reset();
  d.route.clear();
  set_mode(d, Mode::hovering, now_);  // descending where it is; the run ends now
}

// Vehicles on their way to a request or a forecast place stop and hold; their requests wait
// again. Acting vehicles finish the action in hand; returning ones go on home.
void Runtime::pause_run(const std::string& reason) {
  if (paused_) return;
  paused_ = true;
  paused_since_s_ = now_;
  log(json{{"ev", "paused"}, {"reason", reason}});
  for (Drone& d : drones_) {
    if (d.mode != Mode::flying && d.mode != Mode::positioning) continue;
    requeue(d, "paused");
    leave_spot(d);
    d.relieving = -1;
    integrate(d, now_);
    d.leg.reset();
    d.route.clear();
    backend_.pause(d.index, now_);
    set_mode(d, Mode::hovering, now_);
  }
}

// Scheduling goes on; a request's no-feasible-drone clock does not count the pause.
void Runtime::resume_run(const std::string& reason) {
  if (!paused_) return;
  paused_ = false;
  const double paused_s = now_ - paused_since_s_;
  for (Task& t : tasks_)
    if (t.has_work() && t.serving < 0 && t.requested) {
      t.visible_since_s += paused_s;
      t.unserved_since_s += paused_s;  // infinity stays infinity
    }
  log(json{{"ev", "resumed"}, {"reason", reason}, {"paused_s", round6(paused_s)}});
  changed_ = true;
}

// settings.pace: sleeps until the wall clock reaches the run's time, in short slices so that an
// order is taken within 20 ms (it is kept for the loop, which carries it out).
void Runtime::wait_for_wall_clock() {
  using clock = std::chrono::steady_clock;
  if (!pace_start_) pace_start_ = clock::now();
  const auto due = *pace_start_ + std::chrono::duration_cast<clock::duration>(
                                      std::chrono::duration<double>(now_ / settings_.pace));
  while (clock::now() < due) {
    if (waiting_order_.order == ControlOrder::none && settings_.control)
      waiting_order_ = settings_.control();
    if (waiting_order_.order != ControlOrder::none) return;
    std::this_thread::sleep_until(std::min(due, clock::now() + std::chrono::milliseconds(20)));
  }
}

}  // namespace swath::fleet::rt
